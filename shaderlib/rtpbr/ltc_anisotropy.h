// rtpbr shader library: anisotropic LTC lobes, by stretching an isotropic one.
//
// Ours, from the LTC construction of Heitz, Dupuy, Hill & Neubelt 2016: an anisotropic GGX lobe
// (at, ab) is the isotropic lobe of alpha = sqrt(at ab) stretched about its centre c (the mirror
// direction) by k = sqrt(at / ab) along the anisotropy direction e1 (made orthogonal to c) and by
// 1 / k across it (GGX and Beckmann are stretch invariant; near c directions follow slopes
// linearly): M_aniso = A M_iso, A = k e1 e1^T + (1 / k) e2 e2^T + c c^T, e2 = c x e1, det A = 1.
// The lobe's inverse matrix is M^-1 A^-1, which LTC_LobeBegin (ltc.h) takes like any other, over
// polygons already clipped to the horizon. Accuracy against Monte Carlo: shaderlib/luts/ltc.md.
//
// Public functions
//   LTC_AnisotropicUnstretch        A^-1 v for the stretch A
//   LTC_AnisotropicInverseMatrix    M^-1 A^-1, the stretched lobe's matrix
//   LTC_AnisotropicAlbedoScale      the stretched lobe's albedo over the isotropic one's
#ifndef RTPBR_LTC_ANISOTROPY_H
#define RTPBR_LTC_ANISOTROPY_H

#include "ltc.h"

RTPBR_NAMESPACE_BEGIN

// c, e1 unit and orthogonal; k >= 1 when at >= ab (NaN or <= 0: no stretch).
RTPBR_FN rtpbr_float3 LTC_AnisotropicUnstretch(rtpbr_float3 v, rtpbr_float3 c, rtpbr_float3 e1, float k) {
    float kk = k > 0.0f ? k : 1.0f;
    rtpbr_float3 e2 = cross(c, e1);
    return e1 * (dot(e1, v) / kk) + e2 * (dot(e2, v) * kk) + c * dot(c, v);
}

// Rows of M^-1 times the symmetric A^-1, for LTC_LobeBegin.
RTPBR_FN rtpbr_float3x3 LTC_AnisotropicInverseMatrix(rtpbr_float4 ltc1, rtpbr_float3 c, rtpbr_float3 e1, float k) {
    return rtpbr_mat3_rows(LTC_AnisotropicUnstretch(rtpbr_float3(ltc1.x, 0.0f, ltc1.y), c, e1, k),
                           LTC_AnisotropicUnstretch(rtpbr_float3(0.0f, 1.0f, 0.0f), c, e1, k),
                           LTC_AnisotropicUnstretch(rtpbr_float3(ltc1.z, 0.0f, ltc1.w), c, e1, k));
}

// The stretched LTC's mass above the horizon over the isotropic LTC's, capped at 1: LTC_LobeEnd
// normalises each lobe to its own mass, but a stretch that leans the lobe under the horizon
// loses that part of the BRDF's albedo too (masking). Capped, the energy bound stays.
RTPBR_FN float LTC_AnisotropicAlbedoScale(rtpbr_float4 ltc1, rtpbr_float3x3 stretchedMinv) {
    float iso = LTC_HorizonMass(LTC_InverseMatrix(ltc1));
    float stretched = LTC_HorizonMass(stretchedMinv);
    return iso > 0.0f ? min(stretched / iso, 1.0f) : 0.0f;
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_ANISOTROPY_H
