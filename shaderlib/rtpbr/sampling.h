// rtpbr shader library: importance sampling.
//
// All directions are in the local shading frame (n = +z, tangent = +x). u is a pair of
// uniform numbers in [0, 1). Visible-normal samplers return a microfacet normal wm distributed
// as D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z  (Heitz & d'Eon 2014); the PDF_* functions
// return that density (per solid angle of wm), and the *_Reflection pdfs the density of the
// reflected direction wi = reflect(-wo, wm): D_wo(wm) / (4 |wo.wm|).
// wo must be above the horizon (wo.z > 0); otherwise the samplers return +z and the pdfs 0.
#ifndef RTPBR_SAMPLING_H
#define RTPBR_SAMPLING_H

#include "lang.h"
#include "config.h"
#include "ndf.h"
#include "smith.h"

RTPBR_NAMESPACE_BEGIN

// Inverse error function, single-precision fit of Giles 2010, "Approximating the erfinv
// function" (GPU Computing Gems Jade). Input clamped to (-1, 1).
RTPBR_FN float rtpbr_erfinv(float x) {
    float xc = clamp(x, -0.99999994f, 0.99999994f);
    float w = -log((1.0f - xc) * (1.0f + xc));
    float p;
    if (w < 5.0f) {
        w = w - 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = sqrt(w) - 3.0f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * xc;
}

// Reflects wo about the microfacet normal wm: wi = 2 (wo.wm) wm - wo.
RTPBR_FN rtpbr_float3 Reflect_About(rtpbr_float3 wo, rtpbr_float3 wm) {
    return 2.0f * dot(wo, wm) * wm - wo;
}

// The Jacobian of reflection, d(wm) / d(wi) = 1 / (4 |wo.wm|), and the half vector wm of
// (wo, wi); 0 when wi is below the horizon or wm faces away from wo.
RTPBR_FN float Reflection_Jacobian(rtpbr_float3 wo, rtpbr_float3 wi, RTPBR_OUT(rtpbr_float3) wm) {
    rtpbr_float3 hs = wo + wi;
    float l2 = dot(hs, hs);
    wm = rtpbr_float3(0.0f, 0.0f, 1.0f);
    if (!(wi.z > 0.0f) || !(l2 > 1e-20f))
        return 0.0f;
    wm = hs * rtpbr_rsqrt(l2);
    float woDotWm = dot(wo, wm);
    return woDotWm > 0.0f ? 1.0f / (4.0f * woDotWm) : 0.0f;
}

// ---- GGX ------------------------------------------------------------------------------------

// Dupuy & Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps": in the
// configuration stretched to alpha = 1, the visible normals are c + wo_std with c uniform on
// the spherical cap z >= -wo_std.z; unstretching gives the GGX visible normal
// (equivalent to Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
RTPBR_FN rtpbr_float3 Sample_GGX_VNDF(rtpbr_float3 wo, float alphaX, float alphaY, rtpbr_float2 u) {
    if (!(wo.z > 0.0f))
        return rtpbr_float3(0.0f, 0.0f, 1.0f);
    float ax = Alpha_Clamp(alphaX);
    float ay = Alpha_Clamp(alphaY);
    rtpbr_float3 wStd = normalize(rtpbr_float3(wo.x * ax, wo.y * ay, wo.z));
    float phi = RTPBR_TWO_PI * u.x;
    // c is uniform on the cap z >= -wStd.z: z = (1 - u.y) (1 + wStd.z) - wStd.z, written so
    // that nothing cancels near the cap's poles: 1 - z = u.y (1 + wStd.z) and
    // 1 + z = (1 - wStd.z) + (1 - u.y) (1 + wStd.z), with 1 - wStd.z = (x^2 + y^2) / (1 + wStd.z).
    float onePlusW = 1.0f + wStd.z;
    float oneMinusW = (wStd.x * wStd.x + wStd.y * wStd.y) / onePlusW;
    float sinTheta = rtpbr_safe_sqrt(u.y * onePlusW * (oneMinusW + (1.0f - u.y) * onePlusW));
    // hStd = c + wStd, c = (sinTheta cos phi, sinTheta sin phi, z); hStd.z = z + wStd.z.
    rtpbr_float3 hStd = rtpbr_float3(sinTheta * cos(phi) + wStd.x, sinTheta * sin(phi) + wStd.y,
                         (1.0f - u.y) * (1.0f + wStd.z));
    rtpbr_float3 h = rtpbr_float3(hStd.x * ax, hStd.y * ay, max(hStd.z, 0.0f));
    float l2 = dot(h, h);
    if (!(l2 > 1e-20f))
        return rtpbr_float3(0.0f, 0.0f, 1.0f);
    return h * rtpbr_rsqrt(l2);
}

RTPBR_FN float PDF_GGX_VNDF(rtpbr_float3 wo, rtpbr_float3 wm, float alphaX, float alphaY) {
    if (!(wo.z > 0.0f) || !(wm.z > 0.0f))
        return 0.0f;
    float woDotWm = dot(wo, wm);
    if (!(woDotWm > 0.0f))
        return 0.0f;
    return G1_GGX_Aniso(wo, alphaX, alphaY) * woDotWm *
           D_GGX_Aniso(wm.z, wm.x, wm.y, alphaX, alphaY) / wo.z;
}

RTPBR_FN float PDF_GGX_Reflection(rtpbr_float3 wo, rtpbr_float3 wi, float alphaX, float alphaY) {
    rtpbr_float3 wm;
    float jacobian = Reflection_Jacobian(wo, wi, wm);
    return jacobian > 0.0f ? PDF_GGX_VNDF(wo, wm, alphaX, alphaY) * jacobian : 0.0f;
}

// ---- Beckmann -------------------------------------------------------------------------------

// Visible Beckmann normals by the slope-space method of Heitz & d'Eon 2014, "Importance
// Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals": stretch to
// alpha = 1; there the visible slopes (x, y) seen from a direction at angle theta (rotated to
// phi = 0) have density proportional to (mu - x) exp(-x^2 - y^2), x < mu, mu = cot(theta).
// y is Gaussian (variance 1/2); x inverts the marginal CDF
//   C(x) = (mu erfc(-x) + exp(-x^2) / sqrt(pi)) / (mu erfc(-mu) + exp(-mu^2) / sqrt(pi))
// by safeguarded Newton iteration.
RTPBR_FN float Beckmann_SampleSlopeX(float mu, float u) {
    float uc = clamp(u, 1e-6f, 1.0f - 1e-6f);
    if (mu > 1e3f) // normal incidence: the marginal is the Gaussian itself
        return rtpbr_erfinv(2.0f * uc - 1.0f);
    float norm = mu * rtpbr_erfc(-mu) + exp(-mu * mu) / RTPBR_SQRT_PI;
    float target = uc * norm;
    float lo = -6.0f;
    float hi = min(mu, 6.0f);
    float x = clamp(rtpbr_erfinv(2.0f * uc - 1.0f), lo, hi);
    for (int i = 0; i < 24; i++) {
        float g = mu * rtpbr_erfc(-x) + exp(-x * x) / RTPBR_SQRT_PI - target;
        if (g > 0.0f)
            hi = x;
        else
            lo = x;
        float dg = 2.0f * (mu - x) * exp(-x * x) / RTPBR_SQRT_PI;
        float xn = x - g / dg;
        // Newton left the bracket (or dg = 0): bisect. The bounds are inclusive: at an exact
        // root (g = 0) the bracket closes on x itself, and x must be kept.
        if (!(xn >= lo && xn <= hi))
            xn = 0.5f * (lo + hi);
        if (abs(xn - x) < 1e-6f) {
            x = xn;
            break;
        }
        x = xn;
    }
    return x;
}

RTPBR_FN rtpbr_float3 Sample_Beckmann_VNDF(rtpbr_float3 wo, float alphaX, float alphaY, rtpbr_float2 u) {
    if (!(wo.z > 0.0f))
        return rtpbr_float3(0.0f, 0.0f, 1.0f);
    float ax = Alpha_Clamp(alphaX);
    float ay = Alpha_Clamp(alphaY);
    rtpbr_float3 wStd = normalize(rtpbr_float3(wo.x * ax, wo.y * ay, wo.z));
    // sin(theta) from the tangential components (1 - z^2 cancels near the normal, where it
    // would lose the azimuth of wo).
    float sinTheta = sqrt(wStd.x * wStd.x + wStd.y * wStd.y);
    float mu = sinTheta > 1e-6f ? wStd.z / sinTheta : 1e6f;
    float sx = Beckmann_SampleSlopeX(mu, u.x);
    float sy = rtpbr_erfinv(2.0f * clamp(u.y, 1e-6f, 1.0f - 1e-6f) - 1.0f);
    float cosPhi = 1.0f;
    float sinPhi = 0.0f;
    if (sinTheta > 0.0f) {
        cosPhi = wStd.x / sinTheta;
        sinPhi = wStd.y / sinTheta;
    }
    float x = (cosPhi * sx - sinPhi * sy) * ax;
    float y = (sinPhi * sx + cosPhi * sy) * ay;
    return normalize(rtpbr_float3(-x, -y, 1.0f));
}

RTPBR_FN float PDF_Beckmann_VNDF(rtpbr_float3 wo, rtpbr_float3 wm, float alphaX, float alphaY) {
    if (!(wo.z > 0.0f) || !(wm.z > 0.0f))
        return 0.0f;
    float woDotWm = dot(wo, wm);
    if (!(woDotWm > 0.0f))
        return 0.0f;
    float G1 = G1_FromLambda(Lambda_Beckmann_Aniso(wo, alphaX, alphaY));
    return G1 * woDotWm * D_Beckmann_Aniso(wm.z, wm.x, wm.y, alphaX, alphaY) / wo.z;
}

RTPBR_FN float PDF_Beckmann_Reflection(rtpbr_float3 wo, rtpbr_float3 wi, float alphaX, float alphaY) {
    rtpbr_float3 wm;
    float jacobian = Reflection_Jacobian(wo, wi, wm);
    return jacobian > 0.0f ? PDF_Beckmann_VNDF(wo, wm, alphaX, alphaY) * jacobian : 0.0f;
}

// ---- cosine-weighted hemisphere ------------------------------------------------------------

// Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", then Malley's method.
RTPBR_FN rtpbr_float3 Sample_CosineHemisphere(rtpbr_float2 u) {
    rtpbr_float2 d = 2.0f * u - RTPBR_F2(1.0f);
    float r = 0.0f;
    float phi = 0.0f;
    if (d.x != 0.0f || d.y != 0.0f) {
        if (abs(d.x) > abs(d.y)) {
            r = d.x;
            phi = (RTPBR_PI / 4.0f) * (d.y / d.x);
        } else {
            r = d.y;
            phi = (RTPBR_PI / 2.0f) - (RTPBR_PI / 4.0f) * (d.x / d.y);
        }
    }
    float x = r * cos(phi);
    float y = r * sin(phi);
    // z = sqrt(1 - r^2), not sqrt(1 - x^2 - y^2): no cancellation at the rim.
    return rtpbr_float3(x, y, rtpbr_safe_sqrt((1.0f - abs(r)) * (1.0f + abs(r))));
}

RTPBR_FN float PDF_CosineHemisphere(rtpbr_float3 w) {
    return w.z > 0.0f ? w.z * RTPBR_INV_PI : 0.0f;
}

RTPBR_NAMESPACE_END

#endif // RTPBR_SAMPLING_H
