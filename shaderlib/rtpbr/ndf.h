// rtpbr shader library: normal distribution functions.
//
// Conventions: the shading frame has the normal n along +z; NoH = cos(theta_h) of the
// microfacet normal h. Anisotropic variants also take ToH, BoH (tangent and bitangent
// components of h) and (alphaX, alphaY) along the tangent and bitangent.
// Every D is normalised so that  integral D(h) (n.h) dw_h = 1  over the hemisphere, and is 0
// for NoH <= 0.
// Roughness: materials carry perceptual roughness r in [0, 1]; alpha = r^2 (Burley 2012),
// clamped below at RTPBR_MIN_ALPHA (config.h).
#ifndef RTPBR_NDF_H
#define RTPBR_NDF_H

#include "lang.h"
#include "config.h"

RTPBR_NAMESPACE_BEGIN

// Clamps alpha to [RTPBR_MIN_ALPHA, 1]; NaN becomes RTPBR_MIN_ALPHA.
RTPBR_FN float Alpha_Clamp(float alpha) {
    return alpha > RTPBR_MIN_ALPHA ? min(alpha, 1.0f) : RTPBR_MIN_ALPHA;
}

// Burley 2012, "Physically-Based Shading at Disney": alpha = perceptual roughness squared.
// Any input: r clamped to [0, 1] (NaN, negatives: 0), alpha to [RTPBR_MIN_ALPHA, 1]. The
// library squares a roughness Material_Resolve has clamped directly, without this.
RTPBR_FN float Alpha_FromPerceptual(float perceptualRoughness) {
    float r = rtpbr_saturate(perceptualRoughness > 0.0f ? perceptualRoughness : 0.0f);
    return Alpha_Clamp(r * r);
}

// Burley 2012, "Physically-Based Shading at Disney", addenda: anisotropic aspect ratio
// aspect = sqrt(1 - 0.9 anisotropic), alphaX = alpha / aspect, alphaY = alpha * aspect.
RTPBR_FN rtpbr_float2 Alpha_Anisotropic(float alpha, float anisotropic) {
    float aspect = sqrt(1.0f - 0.9f * rtpbr_saturate(anisotropic));
    return rtpbr_float2(Alpha_Clamp(alpha / aspect), Alpha_Clamp(alpha * aspect));
}

// Trowbridge & Reitz 1975; Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces" (GGX). D = alpha^2 / (pi ((alpha^2 - 1) NoH^2 + 1)^2).
RTPBR_FN float D_GGX(float NoH, float alpha) {
    if (!(NoH > 0.0f))
        return 0.0f;
    float c = min(NoH, 1.0f);
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    // (a2 - 1) c^2 + 1 written as (c a2 - c) c + 1 keeps precision near c = 1 (Filament).
    float d = (c * a2 - c) * c + 1.0f;
    return a2 / (RTPBR_PI * d * d);
}

// Anisotropic GGX (Burley 2012, appendix B.2, GTR2_aniso):
// D = 1 / (pi ax ay (ToH^2/ax^2 + BoH^2/ay^2 + NoH^2)^2).
RTPBR_FN float D_GGX_Aniso(float NoH, float ToH, float BoH, float alphaX, float alphaY) {
    if (!(NoH > 0.0f))
        return 0.0f;
    float ax = Alpha_Clamp(alphaX);
    float ay = Alpha_Clamp(alphaY);
    float d = rtpbr_sq(ToH / ax) + rtpbr_sq(BoH / ay) + NoH * NoH;
    return 1.0f / (RTPBR_PI * ax * ay * d * d);
}

// Beckmann 1963; Walter et al. 2007, eq. 25. D = exp(-tan^2/alpha^2) / (pi alpha^2 NoH^4).
RTPBR_FN float D_Beckmann(float NoH, float alpha) {
    if (!(NoH > 0.0f))
        return 0.0f;
    float c2 = rtpbr_sq(min(NoH, 1.0f));
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    float e = (1.0f - c2) / (c2 * a2);
    if (e > 80.0f) // exp(-80) ~ 2e-35: the lobe is 0 in float, and c2^2 may underflow.
        return 0.0f;
    return exp(-e) / (RTPBR_PI * a2 * c2 * c2);
}

// Anisotropic Beckmann (Walter et al. 2007; pbrt-v3 BeckmannDistribution::D):
// D = exp(-(ToH^2/ax^2 + BoH^2/ay^2) / NoH^2) / (pi ax ay NoH^4).
RTPBR_FN float D_Beckmann_Aniso(float NoH, float ToH, float BoH, float alphaX, float alphaY) {
    if (!(NoH > 0.0f))
        return 0.0f;
    float ax = Alpha_Clamp(alphaX);
    float ay = Alpha_Clamp(alphaY);
    float c2 = rtpbr_sq(min(NoH, 1.0f));
    float e = (rtpbr_sq(ToH / ax) + rtpbr_sq(BoH / ay)) / c2;
    if (e > 80.0f)
        return 0.0f;
    return exp(-e) / (RTPBR_PI * ax * ay * c2 * c2);
}

// Generalized Trowbridge-Reitz (Burley 2012, appendix B.2):
// D = c / (1 + (alpha^2 - 1) NoH^2)^gamma, with the normalisation
// c = (gamma - 1)(alpha^2 - 1) / (pi (1 - (alpha^2)^(1 - gamma)))  (gamma != 1),
// c = (alpha^2 - 1) / (pi ln(alpha^2))                             (gamma == 1).
// gamma = 2 is GGX, gamma = 1 is Burley's clearcoat lobe (GTR1). gamma is clamped to
// [0.5, 10]. Isotropic only.
RTPBR_FN float D_GTR(float NoH, float alpha, float gamma) {
    if (!(NoH > 0.0f))
        return 0.0f;
    float c = min(NoH, 1.0f);
    float g = gamma > 0.5f ? min(gamma, 10.0f) : 0.5f;
    float ac = Alpha_Clamp(alpha);
    float x = (ac - 1.0f) * (ac + 1.0f); // alpha^2 - 1 without cancellation
    if (abs(x) < 1e-5f) // alpha = 1: the uniform distribution of normals, D = 1/pi.
        return RTPBR_INV_PI;
    // L = log(alpha^2) = log1p(x); near alpha = 1 by its series (GPU log is only absolutely
    // accurate near 1, and x / L must stay accurate there).
    float L = abs(x) < 1e-2f ? x * (1.0f - x * (0.5f - x * (1.0f / 3.0f - 0.25f * x))) : log(ac * ac);
    // (gamma - 1) / (1 - exp((1 - gamma) L)) -> 1 / L as gamma -> 1; series for small y
    // (1 - exp(-y) = y (1 - y/2 + y^2/6 - y^3/24 + y^4/120 ...), truncation < 2e-8 at 0.1).
    float y = (g - 1.0f) * L;
    float ratio;
    if (abs(y) < 0.1f)
        ratio = 1.0f / (L * (1.0f - y * (0.5f - y * (1.0f / 6.0f - y * (1.0f / 24.0f - y / 120.0f)))));
    else
        ratio = (g - 1.0f) / (1.0f - exp(-y));
    float norm = ratio * x / RTPBR_PI;
    float t = 1.0f + x * c * c;
    return norm / pow(t, g);
}

// The isotropic NDF selected by RTPBR_NDF (GTR uses RTPBR_GTR_GAMMA).
RTPBR_FN float D_Microfacet(float NoH, float alpha) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return D_Beckmann(NoH, alpha);
#elif RTPBR_NDF == RTPBR_NDF_GTR
    return D_GTR(NoH, alpha, RTPBR_GTR_GAMMA);
#else
    return D_GGX(NoH, alpha);
#endif
}

// The anisotropic NDF selected by RTPBR_NDF (GTR has no anisotropic form here: GTR falls
// back to its isotropic lobe with alpha = sqrt(alphaX alphaY)).
RTPBR_FN float D_Microfacet_Aniso(float NoH, float ToH, float BoH, float alphaX, float alphaY) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return D_Beckmann_Aniso(NoH, ToH, BoH, alphaX, alphaY);
#elif RTPBR_NDF == RTPBR_NDF_GTR
    // h is a unit vector, so NoH alone fixes it up to the azimuth GTR ignores; ToH and BoH
    // only enter through the normalisation check below (keeps the signature uniform).
    float azimuthWeight = (ToH * ToH + BoH * BoH + NoH * NoH) > 0.0f ? 1.0f : 0.0f;
    return azimuthWeight * D_GTR(NoH, sqrt(Alpha_Clamp(alphaX) * Alpha_Clamp(alphaY)), RTPBR_GTR_GAMMA);
#else
    return D_GGX_Aniso(NoH, ToH, BoH, alphaX, alphaY);
#endif
}

RTPBR_NAMESPACE_END

#endif // RTPBR_NDF_H
