// rtpbr shader library: Smith masking-shadowing.
//
// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs".
// Lambda(w) is the Smith auxiliary function of direction w; G1(w) = 1 / (1 + Lambda(w));
// the separable G2 = G1(o) G1(i), the height-correlated G2 = 1 / (1 + Lambda(o) + Lambda(i)).
// The visibility form V = G2 / (4 NoL NoV) folds the BRDF's denominator in.
// Directions are given by their cosine to the normal (isotropic) or in the local frame with
// n = +z (anisotropic). Directions at or below the horizon have G1 = 0 (Lambda is capped at
// RTPBR_LAMBDA_MAX instead of Inf). All of this assumes the microfacet normal faces the
// direction (the chi+(w.h) factor is the caller's job).
#ifndef RTPBR_SMITH_H
#define RTPBR_SMITH_H

#include "lang.h"
#include "config.h"
#include "ndf.h"

RTPBR_NAMESPACE_BEGIN

RTPBR_CONST float RTPBR_LAMBDA_MAX = 1e30f;

// Complementary error function, fractional error < 1.2e-7 everywhere (Chebyshev fit from
// Press et al., Numerical Recipes in C, 2nd ed., sec. 6.2, erfcc).
RTPBR_FN float rtpbr_erfc(float x) {
    float z = abs(x);
    float t = 1.0f / (1.0f + 0.5f * z);
    float p = -1.26551223f + t * (1.00002368f + t * (0.37409196f + t * (0.09678418f +
              t * (-0.18628806f + t * (0.27886807f + t * (-1.13520398f + t * (1.48851587f +
              t * (-0.82215223f + t * 0.17087277f))))))));
    float r = t * exp(-z * z + p);
    return x >= 0.0f ? r : 2.0f - r;
}

// Near 0, 1 - erfc(x) cancels (only absolute accuracy): the Maclaurin series there
// (Abramowitz & Stegun 7.1.5; truncation < 1e-9 relative for |x| < 0.5).
RTPBR_FN float rtpbr_erf(float x) {
    if (abs(x) < 0.5f) {
        float x2 = x * x;
        return 1.12837916709551257390f * x *
               (1.0f + x2 * (-1.0f / 3.0f + x2 * (0.1f + x2 * (-1.0f / 42.0f + x2 * (1.0f / 216.0f +
               x2 * (-1.0f / 1320.0f + x2 * (1.0f / 9360.0f)))))));
    }
    return 1.0f - rtpbr_erfc(x);
}

// ---- GGX ------------------------------------------------------------------------------------

// GGX Lambda for a direction with cosine cosTheta to the normal (Heitz 2014, eq. 72):
// Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2.
RTPBR_FN float Lambda_GGX(float cosTheta, float alpha) {
    if (!(cosTheta > 0.0f))
        return RTPBR_LAMBDA_MAX;
    float c = min(cosTheta, 1.0f);
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    float s = sqrt(a2 + (1.0f - a2) * c * c); // = c sqrt(1 + a2 tan^2)
    return 0.5f * (s - c) / c;
}

// Anisotropic GGX Lambda of the local direction w (n = +z) (Heitz 2014, eq. 86 with
// alpha_o^2 = ax^2 cos^2 phi + ay^2 sin^2 phi).
RTPBR_FN float Lambda_GGX_Aniso(rtpbr_float3 w, float alphaX, float alphaY) {
    if (!(w.z > 0.0f))
        return RTPBR_LAMBDA_MAX;
    float A = rtpbr_sq(Alpha_Clamp(alphaX) * w.x) + rtpbr_sq(Alpha_Clamp(alphaY) * w.y);
    float z2 = w.z * w.z;
    float s = sqrt(z2 + A); // = z sqrt(1 + A / z^2)
    return 0.5f * (s - w.z) / w.z;
}

// G1 for GGX written without the Lambda division: G1 = 2c / (c + sqrt(a^2 + (1 - a^2) c^2)).
RTPBR_FN float G1_GGX(float cosTheta, float alpha) {
    if (!(cosTheta > 0.0f))
        return 0.0f;
    float c = min(cosTheta, 1.0f);
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    return 2.0f * c / (c + sqrt(a2 + (1.0f - a2) * c * c));
}

RTPBR_FN float G1_GGX_Aniso(rtpbr_float3 w, float alphaX, float alphaY) {
    if (!(w.z > 0.0f))
        return 0.0f;
    float A = rtpbr_sq(Alpha_Clamp(alphaX) * w.x) + rtpbr_sq(Alpha_Clamp(alphaY) * w.y);
    return 2.0f * w.z / (w.z + sqrt(w.z * w.z + A));
}

// ---- Beckmann -------------------------------------------------------------------------------

// Beckmann Lambda from a = 1 / (alpha tan theta) (Walter et al. 2007, eq. 27; Heitz 2014, eq. 80):
// Lambda = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), evaluated with erfc to keep the
// cancellation of two small terms accurate at large a.
RTPBR_FN float Lambda_Beckmann_FromA(float a) {
    if (!(a > 0.0f))
        return RTPBR_LAMBDA_MAX;
    if (a > 9.0f) // Lambda < 1e-37: 0 in float.
        return 0.0f;
    float lam = 0.5f * (exp(-a * a) / (a * RTPBR_SQRT_PI) - rtpbr_erfc(a));
    return min(max(lam, 0.0f), RTPBR_LAMBDA_MAX);
}

RTPBR_FN float Lambda_Beckmann(float cosTheta, float alpha) {
    if (!(cosTheta > 0.0f))
        return RTPBR_LAMBDA_MAX;
    float c = min(cosTheta, 1.0f);
    float s = rtpbr_safe_sqrt(1.0f - c * c);
    if (s <= 0.0f)
        return 0.0f;
    return Lambda_Beckmann_FromA(c / (Alpha_Clamp(alpha) * s));
}

RTPBR_FN float Lambda_Beckmann_Aniso(rtpbr_float3 w, float alphaX, float alphaY) {
    if (!(w.z > 0.0f))
        return RTPBR_LAMBDA_MAX;
    float d = sqrt(rtpbr_sq(Alpha_Clamp(alphaX) * w.x) + rtpbr_sq(Alpha_Clamp(alphaY) * w.y));
    if (d <= 0.0f)
        return 0.0f;
    return Lambda_Beckmann_FromA(w.z / d);
}

// Walter et al. 2007, eq. 27: the rational approximation of the Beckmann G1 (the fast path).
RTPBR_FN float G1_Beckmann_Fast(float cosTheta, float alpha) {
    if (!(cosTheta > 0.0f))
        return 0.0f;
    float c = min(cosTheta, 1.0f);
    float s = rtpbr_safe_sqrt(1.0f - c * c);
    if (s <= 0.0f)
        return 1.0f;
    float a = c / (Alpha_Clamp(alpha) * s);
    if (a >= 1.6f)
        return 1.0f;
    return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

RTPBR_FN float G1_Beckmann(float cosTheta, float alpha) {
    if (!(cosTheta > 0.0f))
        return 0.0f;
    return 1.0f / (1.0f + Lambda_Beckmann(cosTheta, alpha));
}

// ---- generic combinations ------------------------------------------------------------------

RTPBR_FN float G1_FromLambda(float lambda) { return 1.0f / (1.0f + lambda); }

RTPBR_FN float G2_Separable(float lambdaO, float lambdaI) {
    return 1.0f / ((1.0f + lambdaO) * (1.0f + lambdaI));
}

RTPBR_FN float G2_HeightCorrelated(float lambdaO, float lambdaI) {
    return 1.0f / (1.0f + lambdaO + lambdaI);
}

// The Lambda of the NDF selected by RTPBR_NDF, anisotropic form (local direction w, n = +z).
// GTR has no closed-form Smith Lambda for gamma != 2: it uses the GGX Lambda, as Burley 2012
// does for the clearcoat lobe.
RTPBR_FN float Lambda_Microfacet(rtpbr_float3 w, float alphaX, float alphaY) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return Lambda_Beckmann_Aniso(w, alphaX, alphaY);
#else
    return Lambda_GGX_Aniso(w, alphaX, alphaY);
#endif
}

// G2 of the selected NDF and RTPBR_SMITH combination (local directions, n = +z).
RTPBR_FN float G2_Microfacet(rtpbr_float3 wo, rtpbr_float3 wi, float alphaX, float alphaY) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f))
        return 0.0f;
    float lo = Lambda_Microfacet(wo, alphaX, alphaY);
    float li = Lambda_Microfacet(wi, alphaX, alphaY);
#if RTPBR_SMITH == RTPBR_SMITH_SEPARABLE
    return G2_Separable(lo, li);
#else
    return G2_HeightCorrelated(lo, li);
#endif
}

// ---- visibility V = G2 / (4 NoL NoV) ------------------------------------------------------

// Height-correlated Smith GGX visibility (Heitz 2014, eq. 99; the form of Filament's
// V_SmithGGXCorrelated): V = 0.5 / (NoL sqrt(NoV^2 (1 - a^2) + a^2) + NoV sqrt(NoL^2 (1 - a^2) + a^2)).
RTPBR_FN float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = min(NoV, 1.0f);
    float l = min(NoL, 1.0f);
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    float lambdaV = l * sqrt(v * v * (1.0f - a2) + a2);
    float lambdaL = v * sqrt(l * l * (1.0f - a2) + a2);
    return 0.5f / (lambdaV + lambdaL);
}

// Hammon 2017, "PBR Diffuse Lighting for GGX+Smith Microsurfaces": the fast approximation of
// the height-correlated GGX visibility, V ~ 0.5 / rtpbr_lerp(2 NoL NoV, NoL + NoV, alpha).
RTPBR_FN float V_SmithGGXCorrelated_Fast(float NoV, float NoL, float alpha) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = min(NoV, 1.0f);
    float l = min(NoL, 1.0f);
    float a = Alpha_Clamp(alpha);
    return 0.5f / rtpbr_lerp(2.0f * l * v, l + v, a);
}

// Separable Smith GGX visibility: G1(V) G1(L) / (4 NoL NoV).
RTPBR_FN float V_SmithGGXSeparable(float NoV, float NoL, float alpha) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = min(NoV, 1.0f);
    float l = min(NoL, 1.0f);
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    // G1(c) / (2c) = 1 / (c + sqrt(a2 + (1 - a2) c^2))
    return 1.0f / ((v + sqrt(a2 + (1.0f - a2) * v * v)) * (l + sqrt(a2 + (1.0f - a2) * l * l)));
}

// Beckmann visibility with the selected Smith combination (exact Lambda, or Walter's G1 when
// RTPBR_SMITH_FAST).
RTPBR_FN float V_SmithBeckmann(float NoV, float NoL, float alpha) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = min(NoV, 1.0f);
    float l = min(NoL, 1.0f);
#if RTPBR_SMITH_FAST
    float G = G1_Beckmann_Fast(v, alpha) * G1_Beckmann_Fast(l, alpha);
#elif RTPBR_SMITH == RTPBR_SMITH_SEPARABLE
    float G = G2_Separable(Lambda_Beckmann(v, alpha), Lambda_Beckmann(l, alpha));
#else
    float G = G2_HeightCorrelated(Lambda_Beckmann(v, alpha), Lambda_Beckmann(l, alpha));
#endif
    return G / (4.0f * v * l);
}

// The visibility of the NDF and Smith variant selected by RTPBR_NDF / RTPBR_SMITH /
// RTPBR_SMITH_FAST (isotropic).
RTPBR_FN float V_Microfacet(float NoV, float NoL, float alpha) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return V_SmithBeckmann(NoV, NoL, alpha);
#elif RTPBR_SMITH == RTPBR_SMITH_SEPARABLE
    return V_SmithGGXSeparable(NoV, NoL, alpha);
#elif RTPBR_SMITH_FAST
    return V_SmithGGXCorrelated_Fast(NoV, NoL, alpha);
#else
    return V_SmithGGXCorrelated(NoV, NoL, alpha);
#endif
}

RTPBR_NAMESPACE_END

#endif // RTPBR_SMITH_H
