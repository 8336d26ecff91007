// rtpbr shader library: line and tube (capsule) lights with Linearly Transformed Cosines.
//
// Heitz & Hill 2017, "Real-Time Line- and Disk-Light Shading with Linearly Transformed
// Cosines" (SIGGRAPH course): a line light is a quad of small width W along a segment, turned
// to face the shading point (its width across the plane that holds the point and the line).
// To first order in W its LTC integral is W times a line integral, and a linear map keeps it a
// line: the LTC's M^-1 takes it to a segment in the clamped cosine's space whose width is
// scaled by |det M^-1| |a x b| / |M^-1 a x M^-1 b| (a, b: two points of the line; the strip's
// width across the new plane). The cosine's line integral is in closed form: Golubev 2023,
// "New Implementation of LTC Line Lights" (the term along the line is -n / (n^2 + t^2), his
// corrected Eq. 1.23; one angle instead of two arc tangents). A tube of radius r (a capsule:
// the cylinder around a segment closed by two hemispheres) is a quad for the cylinder (Heitz &
// Hill's facing quad, as wide and as long as the cylinder's silhouette between the points where
// the two planes through P tangent to it touch the end spheres) integrated as a polygon (ltc.h),
// plus its two end spheres (ltc_shapes.h), each weighted by the share of its disk outside the
// quad.
//
// Conventions: those of ltc.h and ltc_shapes.h (local frame, ltc1 from the tables, results are
// form factors in [0, 1]: the fraction of the LTC's mass above the horizon that falls on the
// light, so times ltc2's integrals they never exceed the albedo). A line or a tube faces every
// point (always two-sided). The segment is clipped to the horizon (z >= 0) before the transform
// and to the LTC's support after it, both exactly (a segment stays a segment): a light just
// below the ground gives exactly 0, where a clip in the cosine's space alone lets a sheared
// lobe see it (Golubev's leak; measured up to 4e-3 of the lobe's mass in the test).
//
// Accuracy (measured against double-precision quadrature: tests/shaderlib/ltc/test_ltc_lines.cpp)
//   - LTC_EvaluateLine: exact for an infinitely thin line (the limit W -> 0 of the facing
//     quad), up to float rounding (within 1.5e-5 relative, the Lambert and GGX lobes, across
//     and below both horizons); a real quad of width W differs from it by O((W / distance)^2)
//     (1.3e-4 at W / distance = 7e-3 under GGX at roughness 0.25);
//   - LTC_EvaluateTube: approximate. Exact (up to rounding) where one end sphere hides the rest
//     (seen end-on) and at length 0 (LTC_EvaluateSphere's value), and tends to the line of
//     width 2r as r -> 0 (relative difference under 2 r / distance). The cylinder's quad spans
//     its silhouette exactly; the approximation is the ends: each sphere is counted whole,
//     weighted by the area share of its disk outside the quad, where only that part shows.
//     Measured against the capsule (Lambert, GGX 0.25 to 0.75): within 7e-3 for far, long,
//     oblique, broadside and nearly end-on tubes and across the horizon, 9.5e-3 at 1.9 radii
//     from the axis; a sharp lobe (GGX 0.25) that looks at the ends errs more: up to 4.4e-2
//     on tubes seen nearly or half end-on, 0.26 where the length is about the radius (2.3e-3
//     under Lambert).
//
// Public functions
//   LTC_LineCosineIntegral   the clamped cosine's integral over a unit-width strip along a
//                            segment above the horizon (Golubev 2023's closed form)
//   LTC_LineWidthFactor      the width a strip across a line keeps under M^-1
//   LTC_IntegrateLineLocal   a local segment's form factor for any M^-1, clipped exactly
//   LTC_EvaluateLine         one call: a world-space line's form factor at P for ltc1
//   LTC_TubeWeights          the weights of a tube's cylinder quad and end spheres
//   LTC_TubeHalfWidth        the half-width of a tube's cylinder seen from P
//   LTC_TubeQuad             the quad that stands for a tube's cylinder seen from P
//   LTC_EvaluateTube         one call: a tube's (capsule's) form factor at P for ltc1
#ifndef RTPBR_LTC_LINES_H
#define RTPBR_LTC_LINES_H

#include "lang.h"
#include "config.h"
#include "ltc.h"
#include "ltc_shapes.h"

// LTC_EvaluateTube integrates a cylinder's quad narrower than this (its angular width in the
// cosine's space) as a line: see there.
#ifndef RTPBR_LTC_TUBE_THIN
#define RTPBR_LTC_TUBE_THIN 1e-2f
#endif

RTPBR_NAMESPACE_BEGIN

// The integral of the clamped cosine D_o = max(z, 0) / pi over the strip of unit width along
// the segment a -> b (relative to the shading point, both ends at z >= 0), the strip facing
// the origin: (1 / pi) int n z / |p|^4 dt over p = n N + t T (N the unit foot of the line,
// T its unit direction). In closed form (Heitz & Hill 2017, Eq. 1.20; Golubev 2023):
//   (1 / 2 pi) [ N.z (t2 / s2 - t1 / s1 + angle / n) - T.z n (1 / s2 - 1 / s1) ],  s = n^2 + t^2,
// written without cancellation: t2 / s2 - t1 / s1 = (t2 - t1)(n^2 - t1 t2) / (s1 s2) and
// 1 / s2 - 1 / s1 = -(t2 - t1)(t1 + t2) / (s1 s2); the angle between a and b is atan2 of
// n (t2 - t1) and n^2 + t1 t2 (an arc cosine of their cosine loses angles below ~3e-4 in
// float: a short line far away). 0 for a degenerate segment or one through the origin.
RTPBR_FN float LTC_LineCosineIntegral(rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 ab = b - a;
    float len2 = dot(ab, ab);
    if (!(len2 > 0.0f))
        return 0.0f;
    float dt = sqrt(len2); // t2 - t1
    rtpbr_float3 T = ab / dt;
    float t1 = dot(a, T), t2 = t1 + dt;
    rtpbr_float3 foot = a - T * t1; // n N
    float n2 = dot(foot, foot);
    if (!(n2 > 0.0f))
        return 0.0f;
    float n = sqrt(n2);
    float s1 = n2 + t1 * t1, s2 = n2 + t2 * t2;
    float angle = rtpbr_atan2(n * dt, n2 + t1 * t2);
    float nz = foot.z / n; // N.z
    float i12 = dt * (nz * (n2 - t1 * t2) + T.z * n * (t1 + t2)) / (s1 * s2);
    float i3 = angle * nz / n;
    return rtpbr_pos(i12 + i3) * (0.5f * RTPBR_INV_PI);
}

// The width that a strip across the line through a and b (its width along cross(a, b), the
// normal of the plane through the origin and the line) keeps in the space of minv, measured
// across the image plane: |det minv| |a x b| / |minv a x minv b| (since (M a) x (M b) =
// det(M) M^-T (a x b); Heitz & Hill 2017's 1 / |M^-T o| for the unit normal o). 0 when the
// line passes through the origin.
RTPBR_FN float LTC_LineWidthFactor(rtpbr_float3x3 minv, rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 cx = rtpbr_mul(minv, rtpbr_float3(1.0f, 0.0f, 0.0f));
    rtpbr_float3 cy = rtpbr_mul(minv, rtpbr_float3(0.0f, 1.0f, 0.0f));
    rtpbr_float3 cz = rtpbr_mul(minv, rtpbr_float3(0.0f, 0.0f, 1.0f));
    float det = abs(dot(cx, cross(cy, cz)));
    float image = length(cross(rtpbr_mul(minv, a), rtpbr_mul(minv, b)));
    return image > 0.0f ? det * length(cross(a, b)) / image : 0.0f;
}

// The form factor of the line a -> b (relative to the shading point, local frame) of the given
// width, facing the point, for the LTC minv: the part above the horizon, then the part of its
// image inside the LTC's support (both clips exact), the cosine's closed form times the width
// kept. In [0, 1] (LTC_HorizonFraction); with LTC_Identity()'s matrix the Lambertian form
// factor.
RTPBR_FN float LTC_IntegrateLineLocal(rtpbr_float3x3 minv, rtpbr_float3 a, rtpbr_float3 b, float width) {
    LtcClipper unused = LTC_ClipperBegin();
    LtcSegment s = LTC_ClipEdge(unused, a, b);
    if (!s.valid)
        return 0.0f;
    rtpbr_float3 ma = rtpbr_mul(minv, s.a), mb = rtpbr_mul(minv, s.b);
    LtcSegment m = LTC_ClipEdge(unused, ma, mb);
    if (!m.valid)
        return 0.0f;
    float ff = width * LTC_LineWidthFactor(minv, s.a, s.b) * LTC_LineCosineIntegral(m.a, m.b);
    return LTC_HorizonFraction(ff, LTC_HorizonMass(minv));
}

// The form factor at P (normal N, view V) of the line light P1 -> P2 (world space) of the given
// width, for the lobe ltc1 (LTC_Identity() for Lambert). For a light of radiance Le the
// reflected radiance is Le times it (times LTC_FresnelScale for the specular lobe), as for a
// polygon; the line's emitted power is Le times its area, width times length, times pi.
RTPBR_FN float LTC_EvaluateLine(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, rtpbr_float3 P1, rtpbr_float3 P2,
                                float width, rtpbr_float4 ltc1) {
    rtpbr_float3x3 frame = LTC_Frame(N, V);
    return LTC_IntegrateLineLocal(LTC_InverseMatrix(ltc1), rtpbr_mul(frame, P1 - P), rtpbr_mul(frame, P2 - P), width);
}

// A capsule's silhouette seen from P is the convex hull of its two end spheres' cones (angular
// radii s1, s2, centres theta apart). Where one cone holds the other, it is that sphere alone:
// (0, 1, 0) or (0, 0, 1) (and at length 0 the first). Otherwise it is LTC_TubeQuad (weight 1)
// and, beyond its ends, the part of each sphere's facing disk outside the quad's end: the
// weights are those parts' shares of the disks' areas, (1, share1, share2); for a thin far
// tube seen broadside (1, 1/2, 1/2).
RTPBR_FN rtpbr_float3 LTC_TubeWeights(rtpbr_float3 P, rtpbr_float3 P1, rtpbr_float3 P2, float radius) {
    rtpbr_float3 c1 = P1 - P, c2 = P2 - P;
    float d1 = length(c1), d2 = length(c2);
    float s1 = asin(clamp(radius / max(d1, 1e-30f), 0.0f, 1.0f));
    float s2 = asin(clamp(radius / max(d2, 1e-30f), 0.0f, 1.0f));
    float theta = rtpbr_atan2(length(cross(c1, c2)), dot(c1, c2));
    if (!(theta > abs(s1 - s2)))
        return s1 >= s2 ? rtpbr_float3(0.0f, 1.0f, 0.0f) : rtpbr_float3(0.0f, 0.0f, 1.0f);
    // The tangent planes touch sphere i at the axial position of P_i, at the chord whose
    // midpoint is P_i moved toward P by r^2 / d (d: P's distance from the axis); seen from P
    // that chord cuts the sphere's facing disk (radius rho) at the signed offset u rho toward
    // the outside, which leaves (acos u - u sqrt(1 - u^2)) / pi of the disk outside the quad.
    rtpbr_float3 ab = P2 - P1;
    rtpbr_float3 toP = P - (P1 + ab * (dot(P - P1, ab) / dot(ab, ab)));
    rtpbr_float3 shift = toP * (radius * radius / max(dot(toP, toP), 1e-30f));
    rtpbr_float2 u = rtpbr_float2(0.0f, 0.0f);
    for (int i = 0; i < 2; ++i) {
        rtpbr_float3 c = i == 0 ? c1 : c2, m = c + shift;
        float dd = dot(c, c);
        rtpbr_float3 offset = m * (dd / dot(c, m)) - c;
        float rho = radius * sqrt(dd / (dd - radius * radius));
        float side = dot(offset, i == 0 ? -ab : ab) >= 0.0f ? 1.0f : -1.0f;
        float ui = clamp(side * length(offset) / rho, -1.0f, 1.0f);
        if (i == 0)
            u.x = ui;
        else
            u.y = ui;
    }
    rtpbr_float2 share = (rtpbr_float2(acos(u.x), acos(u.y)) -
                          u * rtpbr_float2(rtpbr_safe_sqrt(1.0f - u.x * u.x), rtpbr_safe_sqrt(1.0f - u.y * u.y))) *
                         RTPBR_INV_PI;
    return rtpbr_float3(1.0f, share.x, share.y);
}

// The half-width of LTC_TubeQuad: r d / sqrt(d^2 - r^2), d the distance of P from the axis'
// line (P1, P2); 0 when P is on that line or within the radius of it.
RTPBR_FN float LTC_TubeHalfWidth(rtpbr_float3 P, rtpbr_float3 P1, rtpbr_float3 P2, float radius) {
    rtpbr_float3 ab = P2 - P1;
    rtpbr_float3 o = cross(P1 - P, ab); // |o| = d |ab|
    float d2 = dot(o, o) / max(dot(ab, ab), 1e-30f), r2 = radius * radius;
    return d2 > r2 ? radius * sqrt(d2 / (d2 - r2)) : 0.0f;
}

// The quad (world space) that stands for the cylinder of a tube (axis P1 -> P2) seen from P: in
// the plane of the axis that faces P, of half-width LTC_TubeHalfWidth, so that its long edges
// lie in the two planes through P tangent to the cylinder, and its corners on the rays from P
// through the points where those planes touch the end spheres (at P_i's place along the axis:
// the quad reaches k = d^2 / (d^2 - r^2) times as far from P's foot on the axis). Seen from P,
// the cylinder's silhouette between the spheres exactly. Count 0 when the half-width is.
RTPBR_FN LtcPolygon LTC_TubeQuad(rtpbr_float3 P, rtpbr_float3 P1, rtpbr_float3 P2, float radius) {
    rtpbr_float3 ab = P2 - P1;
    rtpbr_float3 o = cross(P1 - P, ab);
    float halfWidth = LTC_TubeHalfWidth(P, P1, P2, radius);
    LtcPolygon q = LTC_Quad(P1, P2, P2, P1);
    if (!(halfWidth > 0.0f)) {
        q.count = 0;
        return q;
    }
    rtpbr_float3 foot = P1 + ab * (dot(P - P1, ab) / dot(ab, ab));
    rtpbr_float3 toFoot = P - foot;
    float d2 = dot(toFoot, toFoot);
    float k = d2 / (d2 - radius * radius);
    rtpbr_float3 e1 = foot + (P1 - foot) * k, e2 = foot + (P2 - foot) * k;
    rtpbr_float3 h = o * (halfWidth * rtpbr_rsqrt(dot(o, o)));
    return LTC_Quad(e1 + h, e2 + h, e2 - h, e1 - h);
}

// The form factor at P (normal N, view V) of the tube (capsule) of the given radius around the
// segment P1 -> P2 (world space), for the lobe ltc1 (LTC_Identity() for Lambert): the quad of
// LTC_TubeQuad (integrated as a polygon, ltc.h: exact for the quad whatever its width, where the
// line's first order in the width is not: a 0.2-wide tube in a GGX 0.25 lobe read 35 % high
// as a line) and the two end spheres (LTC_EvaluateSphere), weighted by LTC_TubeWeights. Inside
// the capsule, 1. With P1 = P2, LTC_EvaluateSphere's value; as radius -> 0, the line's of
// width 2 radius. Costs a polygon (4 edges) and up to two ellipses.
RTPBR_FN float LTC_EvaluateTube(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, rtpbr_float3 P1, rtpbr_float3 P2,
                                float radius, rtpbr_float4 ltc1) {
    rtpbr_float3 axis = P2 - P1;
    float len2 = dot(axis, axis);
    float h = len2 > 0.0f ? rtpbr_saturate(dot(P - P1, axis) / len2) : 0.0f;
    rtpbr_float3 nearest = P1 + axis * h - P;
    if (!(dot(nearest, nearest) > radius * radius))
        return 1.0f;
    rtpbr_float3 w = LTC_TubeWeights(P, P1, P2, radius);
    float sum = 0.0f;
    if (w.x > 0.0f) {
        rtpbr_float3x3 frame = LTC_Frame(N, V), minv = LTC_InverseMatrix(ltc1);
        rtpbr_float3 a = rtpbr_mul(frame, P1 - P), b = rtpbr_mul(frame, P2 - P);
        rtpbr_float3 ma = rtpbr_mul(minv, a), mb = rtpbr_mul(minv, b);
        float width = 2.0f * LTC_TubeHalfWidth(P, P1, P2, radius);
        // The quad's angular width in the cosine's space: the width it keeps
        // (LTC_LineWidthFactor) over the image line's distance, |A x B| / |B - A|. Thinner than
        // RTPBR_LTC_TUBE_THIN, the quad's corners (P1 +- h) and edge sums lose the width to float
        // rounding (measured: up to 1.7e-2 relative error at a radius of 1e-5 of the distance),
        // and the line's closed form is the quad's limit (off by O(thin^2)).
        float thin = width * LTC_LineWidthFactor(minv, a, b) * length(mb - ma) / max(length(cross(ma, mb)), 1e-30f);
        if (thin < RTPBR_LTC_TUBE_THIN)
            sum += w.x * LTC_IntegrateLineLocal(minv, a, b, width);
        else
            sum += w.x * LTC_IntegrateLocalMatrix(LTC_PolygonToLocal(frame, P, LTC_TubeQuad(P, P1, P2, radius), true), minv);
    }
    if (w.y > 0.0f)
        sum += w.y * LTC_EvaluateSphere(N, V, P, P1, radius, ltc1);
    if (w.z > 0.0f)
        sum += w.z * LTC_EvaluateSphere(N, V, P, P2, radius, ltc1);
    return rtpbr_saturate(sum);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_LINES_H
