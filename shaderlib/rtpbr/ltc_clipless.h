// rtpbr shader library: the clipless sphere proxy of a polygon's LTC integral.
//
// Hill & Heitz 2016, "Real-Time Area Lighting: a Journey from Research to Production": instead
// of clipping the polygon to the horizon (ltc.h), integrate the unclipped polygon's vector form
// factor F (Arvo 1995) and replace the polygon by the sphere with the same F, whose
// horizon-clipped form factor is tabled (ltc2.w, at LTC_SphereLutCoord(F)) or approximated.
// Cheaper than clipping, but blind to which part of a polygon is under the horizon (errors
// measured in shaderlib/luts/ltc.md). Under RTPBR_LTC_CLIPLESS 1 this header, not ltc.h,
// defines LTC_EvaluatePolygon, through the proxy.
//
// Public functions
//   LTC_SphereLutCoord              the coordinate of ltc2.w for a vector form factor F
//   LTC_PolygonToLocalUnclipped     a polygon relative to P, local, not clipped
//   LTC_FormFactorVector            an unclipped polygon's vector form factor under M^-1
//   LTC_SphereFormFactor            the horizon-clipped sphere form factor, from ltc2.w
//   LTC_SphereFormFactorApprox      the same without a table
//   LTC_EvaluatePolygon             (RTPBR_LTC_CLIPLESS 1) ltc.h's one call, through the proxy
#ifndef RTPBR_LTC_CLIPLESS_H
#define RTPBR_LTC_CLIPLESS_H

#include "ltc.h"

RTPBR_NAMESPACE_BEGIN

// Column = cos of F's elevation mapped to [0, 1], row = |F| (= sin^2 of the sphere's angular
// radius), at texel centres as LTC_LutCoord.
RTPBR_FN rtpbr_float2 LTC_SphereLutCoord(rtpbr_float3 F) {
    float len = length(F);
    float z = len > 0.0f ? F.z / len : 0.0f;
    float scale = (float(RTPBR_LTC_SIZE) - 1.0f) / float(RTPBR_LTC_SIZE);
    float bias = 0.5f / float(RTPBR_LTC_SIZE);
    return rtpbr_float2(rtpbr_saturate(z * 0.5f + 0.5f) * scale + bias, rtpbr_saturate(len) * scale + bias);
}

// LTC_PolygonRelative (ltc.h) without the horizon clip.
RTPBR_FN LtcLocalPolygon LTC_PolygonToLocalUnclipped(rtpbr_float3x3 frame, rtpbr_float3 P, LtcPolygon poly, bool twoSided) {
    return LTC_PolygonRelative(frame, P, poly, twoSided);
}

// F = (1 / 2pi) sum of the edge vectors of M^-1 P for P from LTC_PolygonToLocalUnclipped,
// pointing toward the polygon: |F| is its form factor seen head-on, F.z its (signed,
// unclipped) form factor against the LTC's cosine (Arvo 1995).
RTPBR_FN rtpbr_float3 LTC_FormFactorVector(LtcLocalPolygon local, rtpbr_float4 ltc1) {
    rtpbr_float3 F = RTPBR_F3(0.0f);
    if (local.count < 3)
        return F;
    rtpbr_float3x3 minv = LTC_InverseMatrix(ltc1);
    for (int i = 0; i < RTPBR_LTC_CLIP_VERTICES; i++) {
        if (i < local.count) {
            rtpbr_float3 b = i + 1 < local.count ? local.v[i + 1] : local.v[0];
            F += LTC_EdgeIntegral(LTC_SafeNormalize(rtpbr_mul(minv, local.v[i])), LTC_SafeNormalize(rtpbr_mul(minv, b)));
        }
    }
    // Local polygons appear clockwise from P, which makes F point toward them; a transform
    // with a negative determinant mirrors the orientation.
    float det = ltc1.x * ltc1.w - ltc1.y * ltc1.z;
    return det < 0.0f ? -F : F;
}

// Hill & Heitz 2016: the horizon-clipped form factor of the sphere whose vector form factor
// is F, from sphereLut = ltc2.w fetched at LTC_SphereLutCoord(F).
RTPBR_FN float LTC_SphereFormFactor(rtpbr_float3 F, float sphereLut) {
    return min(rtpbr_pos(length(F) * sphereLut), 1.0f);
}

// Hill & Heitz 2016 (the cheap form of their course code): max((|F|^2 + F.z) / (|F| + 1), 0).
// Exact for a sphere centred on the normal (F.z = |F|) and as spheres get small; an off-axis
// sphere above the horizon reads high (30 degrees wide, centre 60 degrees off the normal: 0.15
// against 0.125). LTC_SphereCapFormFactor (ltc_shapes.h) is exact.
RTPBR_FN float LTC_SphereFormFactorApprox(rtpbr_float3 F) {
    float l = length(F);
    return min(rtpbr_pos((l * l + F.z) / (l + 1.0f)), 1.0f);
}

#if RTPBR_LTC_CLIPLESS
// ltc.h's LTC_EvaluatePolygon through the proxy: the sphere's form factor over the LTC's
// horizon mass (LTC_HorizonFraction).
RTPBR_FN float LTC_EvaluatePolygon(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, LtcPolygon poly, rtpbr_float4 ltc1, bool twoSided) {
    rtpbr_float3x3 frame = LTC_Frame(N, V);
    return LTC_HorizonFraction(LTC_SphereFormFactorApprox(LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(frame, P, poly, twoSided), ltc1)),
                               LTC_HorizonMass(LTC_InverseMatrix(ltc1)));
}
#endif

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_CLIPLESS_H
