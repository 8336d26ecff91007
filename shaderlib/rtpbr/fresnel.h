// rtpbr shader library: Fresnel reflectance.
//
// Conventions: cosines are measured against the microfacet normal (VoH = LoH for reflection).
// eta is the relative index of refraction n_transmitted / n_incident; k the extinction
// coefficient of a conductor (complex IOR eta + i k), both per RGB channel for conductors.
#ifndef RTPBR_FRESNEL_H
#define RTPBR_FRESNEL_H

#include "lang.h"
#include "config.h"

RTPBR_NAMESPACE_BEGIN

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering".
// F = f0 + (f90 - f0) (1 - cos)^5; cos is clamped to [0, 1].
RTPBR_FN float F_Schlick1(float f0, float f90, float VoH) {
    float m = 1.0f - (VoH > 0.0f ? min(VoH, 1.0f) : 0.0f); // NaN-safe clamp
    float m2 = m * m;
    return f0 + (f90 - f0) * (m2 * m2 * m);
}

RTPBR_FN rtpbr_float3 F_Schlick(rtpbr_float3 f0, float f90, float VoH) {
    float m = 1.0f - (VoH > 0.0f ? min(VoH, 1.0f) : 0.0f); // NaN-safe clamp
    float m2 = m * m;
    return f0 + (RTPBR_F3(f90) - f0) * (m2 * m2 * m);
}

// Normal-incidence reflectance of a dielectric interface: ((eta - 1) / (eta + 1))^2.
RTPBR_FN float F0_FromIor(float eta) {
    return rtpbr_sq((eta - 1.0f) / (eta + 1.0f));
}

// Exact unpolarised Fresnel reflectance of a dielectric interface (Born & Wolf, Principles of
// Optics, sec. 1.5.2; arrangement as in Walter et al. 2007 / pbrt-v4 FrDielectric).
// cosThetaI < 0 means the ray arrives from the transmitted side: the interface is flipped.
// Past the critical angle (total internal reflection) the result is 1.
// eta is clamped to [1e-3, 1e3]; NaN eta behaves as eta = 1e-3.
RTPBR_FN float F_Dielectric(float cosThetaI, float eta) {
    float c = cosThetaI > -1.0f ? min(cosThetaI, 1.0f) : -1.0f; // NaN-safe clamp
    float e = eta > 1e-3f ? min(eta, 1e3f) : 1e-3f;
    if (c < 0.0f) {
        e = 1.0f / e;
        c = -c;
    }
    // cos^2(theta_t) = 1 - (1 - c^2) / e^2 = (c^2 + (e - 1)(e + 1)) / e^2: this form keeps its
    // precision for e near 1 at grazing angles, where 1 - sin^2 cancels.
    float cos2T = (c * c + (e - 1.0f) * (e + 1.0f)) / (e * e);
    if (cos2T <= 0.0f)
        return 1.0f;
    float cosT = sqrt(cos2T);
    float rPar = (e * c - cosT) / (e * c + cosT);
    float rPerp = (c - e * cosT) / (c + e * cosT);
    return 0.5f * (rPar * rPar + rPerp * rPerp);
}

// Exact unpolarised Fresnel reflectance of a conductor with complex IOR eta + i k, seen from a
// dielectric of index 1, per channel. Real-arithmetic form of the complex Fresnel equations
// (Lagarde 2013, "Memo on Fresnel equations"; after Born & Wolf sec. 14.2).
// At normal incidence: ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2); at grazing: 1.
RTPBR_FN rtpbr_float3 F_Conductor(float cosThetaI, rtpbr_float3 eta, rtpbr_float3 k) {
    float c = cosThetaI > 0.0f ? min(cosThetaI, 1.0f) : 0.0f; // NaN-safe clamp
    float cos2 = c * c;
    float sin2 = 1.0f - cos2;
    rtpbr_float3 eta2 = eta * eta;
    rtpbr_float3 etak2 = eta2 * (k * k);
    // a + i b = sqrt(eta^2 - k^2 - sin^2 + 2 i eta k): a^2 + b^2 = |t0 + 2 i eta k|, a b = eta k.
    // The larger of a^2, b^2 comes from the sum, the smaller from the product, and the
    // differences below are written as sums of squares: no cancellation in float (the
    // textbook form loses up to 1e-3 when t0 < 0 with small k, or when F is small).
    rtpbr_float3 t0 = eta2 - (k * k) - RTPBR_F3(sin2);
    rtpbr_float3 a2plusb2 = sqrt(t0 * t0 + 4.0f * etak2);
    rtpbr_float3 hi = 0.5f * (a2plusb2 + abs(t0));
    rtpbr_float3 lo = etak2 / max(hi, RTPBR_F3(1e-30f));
    // a^2 >= b^2 where t0 >= 0 (a select per channel: HLSL has no vector ternary, and lerp
    // would round the small one against the large one).
    rtpbr_float3 a2 = rtpbr_float3(t0.x >= 0.0f ? hi.x : lo.x, t0.y >= 0.0f ? hi.y : lo.y, t0.z >= 0.0f ? hi.z : lo.z);
    rtpbr_float3 b2 = rtpbr_float3(t0.x >= 0.0f ? lo.x : hi.x, t0.y >= 0.0f ? lo.y : hi.y, t0.z >= 0.0f ? lo.z : hi.z);
    rtpbr_float3 a = sqrt(a2);
    rtpbr_float3 am = a - RTPBR_F3(c);
    rtpbr_float3 ap = a + RTPBR_F3(c);
    // rs = (a^2 + b^2 + cos^2 - 2 a cos) / (a^2 + b^2 + cos^2 + 2 a cos)
    rtpbr_float3 rs = (am * am + b2) / max(ap * ap + b2, RTPBR_F3(1e-30f));
    // rp = rs (cos^2 (a^2 + b^2) + sin^4 - 2 a cos sin^2) / (... + 2 a cos sin^2)
    rtpbr_float3 em = c * a - RTPBR_F3(sin2);
    rtpbr_float3 ep = c * a + RTPBR_F3(sin2);
    rtpbr_float3 bc2 = b2 * cos2;
    rtpbr_float3 rp = rs * (em * em + bc2) / max(ep * ep + bc2, RTPBR_F3(1e-30f));
    return rtpbr_saturate(0.5f * (rp + rs));
}

// The parameters of whichever Fresnel model RTPBR_FRESNEL selects, so that generic code
// (BRDF_Specular, ...) can take one argument. Build it with one of the Fresnel_* functions.
struct FresnelParams {
    rtpbr_float3 f0;  // normal-incidence reflectance (Schlick); filled by every constructor
    float f90;  // grazing reflectance (Schlick), usually 1
    rtpbr_float3 eta; // relative IOR (dielectric: eta.x; conductor: per channel)
    rtpbr_float3 k;   // conductor extinction per channel (0 for dielectrics)
};

RTPBR_FN FresnelParams Fresnel_FromF0(rtpbr_float3 f0) {
    FresnelParams p;
    p.f0 = f0;
    p.f90 = 1.0f;
    // The dielectric with this normal reflectance (from the mean of f0): eta = (1 + sqrt f0) / (1 - sqrt f0).
    float s = sqrt(rtpbr_saturate((f0.x + f0.y + f0.z) / 3.0f));
    p.eta = RTPBR_F3((1.0f + s) / max(1.0f - s, 1e-3f));
    p.k = RTPBR_F3(0.0f);
    return p;
}

RTPBR_FN FresnelParams Fresnel_FromDielectric(float eta) {
    FresnelParams p;
    p.f0 = RTPBR_F3(F0_FromIor(eta));
    p.f90 = 1.0f;
    p.eta = RTPBR_F3(eta);
    p.k = RTPBR_F3(0.0f);
    return p;
}

RTPBR_FN FresnelParams Fresnel_FromConductor(rtpbr_float3 eta, rtpbr_float3 k) {
    FresnelParams p;
    p.f0 = F_Conductor(1.0f, eta, k);
    p.f90 = 1.0f;
    p.eta = eta;
    p.k = k;
    return p;
}

// The Fresnel model selected by RTPBR_FRESNEL, at cosine VoH to the microfacet normal.
RTPBR_FN rtpbr_float3 F_Microfacet(FresnelParams p, float VoH) {
#if RTPBR_FRESNEL == RTPBR_FRESNEL_DIELECTRIC
    return RTPBR_F3(F_Dielectric(VoH, p.eta.x));
#elif RTPBR_FRESNEL == RTPBR_FRESNEL_CONDUCTOR
    return F_Conductor(VoH, p.eta, p.k);
#else
    return F_Schlick(p.f0, p.f90, VoH);
#endif
}

RTPBR_NAMESPACE_END

#endif // RTPBR_FRESNEL_H
