// rtpbr shader library: the microfacet specular BRDF.
//
// Cook & Torrance 1982; Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces", eq. 20:   f(i, o) = F(i.h) G2(i, o) D(h) / (4 |n.i| |n.o|),  h = normalize(i + o).
// Visibility form (Filament): f = D V F with V = G2 / (4 NoL NoV).
// The models are picked by RTPBR_NDF, RTPBR_SMITH, RTPBR_SMITH_FAST and RTPBR_FRESNEL.
// f does not include the cosine factor NoL. Directions below the horizon give 0.
#ifndef RTPBR_MICROFACET_H
#define RTPBR_MICROFACET_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "ndf.h"
#include "smith.h"

RTPBR_NAMESPACE_BEGIN

// Isotropic specular BRDF from the usual dot products (n, v, l, h = normalize(v + l)).
RTPBR_FN rtpbr_float3 BRDF_Specular(float NoV, float NoL, float NoH, float VoH, float alpha,
                              FresnelParams fresnel) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return RTPBR_F3(0.0f);
    float D = D_Microfacet(NoH, alpha);
    float V = V_Microfacet(NoV, NoL, alpha);
    return (D * V) * F_Microfacet(fresnel, VoH);
}

// The general form in the local shading frame (n = +z, tangent = +x): anisotropic
// (alphaX along x, alphaY along y), G2 from RTPBR_SMITH with the exact Lambda.
// Symmetric in (wo, wi): reciprocal.
RTPBR_FN rtpbr_float3 BRDF_SpecularLocal(rtpbr_float3 wo, rtpbr_float3 wi, float alphaX, float alphaY,
                                   FresnelParams fresnel) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f))
        return RTPBR_F3(0.0f);
    rtpbr_float3 hs = wo + wi;
    float hl2 = dot(hs, hs);
    if (!(hl2 > 1e-12f))
        return RTPBR_F3(0.0f);
    rtpbr_float3 h = hs * rtpbr_rsqrt(hl2);
    float D = D_Microfacet_Aniso(h.z, h.x, h.y, alphaX, alphaY);
    float G = G2_Microfacet(wo, wi, alphaX, alphaY);
    rtpbr_float3 F = F_Microfacet(fresnel, dot(wo, h));
    // Both cosines tiny: the BRDF grows like 1 / (alpha (NoL + NoV)); the floor keeps it finite.
    return (D * G / max(4.0f * wo.z * wi.z, 1e-30f)) * F;
}

RTPBR_NAMESPACE_END

#endif // RTPBR_MICROFACET_H
