// rtpbr shader library: corrections to the LTC result of a microfacet lobe. EXPERIMENTAL.
//
// EXPERIMENTAL: the functions, their arguments and the tuning constants of this header may
// change between releases, with new measurements, without a deprecation period. The stable
// polygon integration is ltc.h (which this header includes).
//
// A single LTC (Heitz, Dupuy, Hill & Neubelt 2016) cannot follow a GGX / Beckmann lobe
// everywhere: near the horizon and on the viewer's side it puts light where the BRDF has almost
// none, and it is exactly 0 beyond its own horizon where the true lobe has a long tail. Three
// estimates, each computed from quantities the streamed LTC integration already has, correct
// the specular lobe's result (before the table's Fresnel scale):
//   - the point correction: the LTC result times the ratio of the true lobe to the LTC at the
//     centre of the part of the light the LTC sees (for lights holding a small part of the lobe);
//   - the tail estimate: the midpoint rule f(c) pi F.z for a light in the LTC's tail;
//   - the streak estimate (GGX): for a light near the horizon on the mirror side of a grazing
//     view, the lobe across the plane of incidence integrated in closed form, along it by Gauss.
// How they are combined: shaderlib/luts/ltc.md ("Evaluation"); how they were found and what
// they gain: ltc.md ("How the corrections were found"). The engine applies them under
// RTPBR_LTC_POINT_CORRECTION and RTPBR_LTC_STREAK (config.h).
//
// Public functions
//   point correction   LTC_LobePoint, LTC_LobePointInvMass, LTC_PointWidthRatio, LTC_PointFactor
//   tail estimate      LTC_PointTail, LTC_PointTailWeight, LTC_PointCombine
//   streak, streamed   LTC_StreakBegin, LTC_StreakEdge, LTC_StreakNodes, LTC_StreakChordEdge,
//                      LTC_StreakEnd, LTC_StreakWeight, LTC_StreakVoH, LTC_StreakCandidate,
//                      LTC_StreakCandidateSquared,
//                      LTC_StreakSpan, LTC_StreakSpanTrusted (no trust: the chords pass skipped)
//   streak, culling    LTC_StreakOutside, LTC_StreakSteep, LTC_StreakSteepNoV
//   streak, stored     LTC_StreakLocal (a polygon from LTC_PolygonToLocal; tools and tests)
//   helpers            LTC_StreakCross, LTC_StreakNodePoint, LTC_StreakNode, LTC_Atan,
//                      LTC_StreakLateral, LTC_StreakSlope, LTC_StreakRamp
//   types              LtcPoint, LtcStreak
#ifndef RTPBR_LTC_CORRECTIONS_H
#define RTPBR_LTC_CORRECTIONS_H

#include "ltc.h"
#include "smith.h"

// ---- tuning constants ---------------------------------------------------------------------
// Each may be defined before including this header. A ramp "from A over W" is 0 at A and 1 at
// A + W (smoothstep between); "from A to B" the same between A and B.
// The point correction (LTC_PointFactor, LTC_PointWidthRatio):
#ifndef RTPBR_LTC_POINT_K_MAX
#define RTPBR_LTC_POINT_K_MAX 16.0f // the largest factor on the LTC result (no fireflies)
#endif
#ifndef RTPBR_LTC_POINT_GATE0
#define RTPBR_LTC_POINT_GATE0 1.0f // a factor above 1 is let through by the width ratio from GATE0 ...
#endif
#ifndef RTPBR_LTC_POINT_GATE_WIDTH
#define RTPBR_LTC_POINT_GATE_WIDTH 0.5f // ... over GATE_WIDTH (fully from GATE0 + GATE_WIDTH)
#endif
#ifndef RTPBR_LTC_POINT_SIDE0
#define RTPBR_LTC_POINT_SIDE0 0.6f // |V + w| from which a light is taken off the streak ...
#endif
#ifndef RTPBR_LTC_POINT_SIDE_WIDTH
#define RTPBR_LTC_POINT_SIDE_WIDTH 0.4f // ... over this (its width ratio raised to the open gate)
#endif
// (The fade exponent 16 of LTC_PointFactor, t = (1 - ff)^16, is written out there as four
// squarings: the same loop over a macro compiles to a different schedule on RADV.)
// The tail estimate (LTC_PointTailWeight):
#ifndef RTPBR_LTC_TAIL_COS0
#define RTPBR_LTC_TAIL_COS0 0.2f // distrusted as the LTC lobe vector's cosine rises from COS0 ...
#endif
#ifndef RTPBR_LTC_TAIL_COS_WIDTH
#define RTPBR_LTC_TAIL_COS_WIDTH 0.2f // ... over COS_WIDTH (none left from 0.4)
#endif
#ifndef RTPBR_LTC_TAIL_RATIO0
#define RTPBR_LTC_TAIL_RATIO0 0.5f // and as the LTC's over the cosine's form factor rises from RATIO0 ...
#endif
#ifndef RTPBR_LTC_TAIL_RATIO_WIDTH
#define RTPBR_LTC_TAIL_RATIO_WIDTH 1.5f // ... over RATIO_WIDTH (none left from 2)
#endif
// The streak estimate (LTC_StreakEnd's trust, LTC_StreakWeight, LTC_StreakCandidate):
#ifndef RTPBR_LTC_STREAK_Q0
#define RTPBR_LTC_STREAK_Q0 0.5f // the lobe's span over the light's elevations (q), trusted up to Q0 ...
#endif
#ifndef RTPBR_LTC_STREAK_Q1
#define RTPBR_LTC_STREAK_Q1 1.0f // ... not from Q1
#endif
#ifndef RTPBR_LTC_STREAK_R0
#define RTPBR_LTC_STREAK_R0 0.4f // the two Gauss nodes' ratio, trusted from R1, not below R0 ...
#endif
#ifndef RTPBR_LTC_STREAK_R1
#define RTPBR_LTC_STREAK_R1 0.7f // ... (a light's edge between the nodes)
#endif
#ifndef RTPBR_LTC_STREAK_W0
#define RTPBR_LTC_STREAK_W0 1.0f // the light's width across the plane in lobe widths: none below W0 ...
#endif
#ifndef RTPBR_LTC_STREAK_W1
#define RTPBR_LTC_STREAK_W1 2.0f // ... full trust from W1
#endif
#ifndef RTPBR_LTC_STREAK_V0
#define RTPBR_LTC_STREAK_V0 0.35f // the estimate's weight: 1 up to |V + c| = V0 ...
#endif
#ifndef RTPBR_LTC_STREAK_V1
#define RTPBR_LTC_STREAK_V1 0.75f // ... 0 from V1 (the mirror side near the horizon only)
#endif

RTPBR_NAMESPACE_BEGIN

// ---- the point correction -----------------------------------------------------------------
// For a light that holds a small part of the lobe, the integral is about the lobe's value at
// the light times the light's size, so the LTC's error there is the ratio k of the two lobes'
// values at the light: the LTC result is multiplied by k, taken at the centre of the part of
// the light the LTC sees, faded out as the light holds more of the LTC's mass (the LTC integral
// itself is then right by construction). A k above 1 is trusted only where the true lobe is not
// much narrower than the light or is no streak: a view and a light both near the horizon on
// the mirror side make the lobe a streak across the plane of incidence about alpha |V + L|
// wide (the half vector turns by dL / |V + L|), and one point at the streak's centre
// overstates a light wider than that (LTC_PointWidthRatio).

// The centre of the part of a light an isotropic LTC lobe (ltc1) sees: w = M F / |M F|, F its
// vector form factor in the LTC's space (LTC_LobeEndVector, z >= 0), and the LTC's density
// there per unit of its mass above the horizon (Heitz et al. 2016, eq. 1 with the cosine
// D_o = z / pi, over LTC_HorizonMass, as LTC_LobeEnd's form factor):
// D(w) = D_o(F / |F|) |det M^-1| / |M^-1 w|^3 = F.z |u|^3 / (pi |F|^4 det^2), u = det M F.
// density 0 when F is (nearly) zero: nothing seen, no correction.
struct LtcPoint {
    rtpbr_float3 dir;
    float density;
};

// LTC_LobePoint with 1 / the lobe's LTC_HorizonMass given (invMass: LTC_InverseHorizonMass, taken
// once per point by a caller evaluating many lights, AreaLightPixel.specularInvMass).
RTPBR_FN LtcPoint LTC_LobePointInvMass(rtpbr_float3 F, rtpbr_float4 ltc1, float invMass) {
    // M^-1 = [[a, 0, b], [0, 1, 0], [c, 0, d]] (rows): det M F = (d Fx - b Fz, det Fy, a Fz - c Fx)
    float det = ltc1.x * ltc1.w - ltc1.y * ltc1.z;
    float f2 = dot(F, F);
    rtpbr_float3 u = rtpbr_float3(ltc1.w * F.x - ltc1.y * F.z, det * F.y, ltc1.x * F.z - ltc1.z * F.x);
    float fd = f2 * det;
    float den = RTPBR_PI * (fd * fd); // (the mass's factor a product: density x invMass / den)
    float uu = dot(u, u);
    LtcPoint p;
    float ru = rtpbr_rsqrt(max(uu, 1e-30f)); // (|u|^3 = uu uu ru: one root for both)
    p.dir = u * ((det < 0.0f ? -1.0f : 1.0f) * ru);
    p.density = f2 > 1e-16f && den > 0.0f && invMass > 0.0f ? max(F.z, 0.0f) * (uu * uu * ru) * invMass / den : 0.0f;
    return p;
}

RTPBR_FN LtcPoint LTC_LobePoint(rtpbr_float3 F, rtpbr_float4 ltc1) {
    return LTC_LobePointInvMass(F, ltc1, LTC_InverseHorizonMass(LTC_InverseMatrix(ltc1)));
}

// The lobe's width across the plane of incidence over the light's angular radius: alpha |V + w|
// (vPlusW = the length of V + LtcPoint.dir, both unit) over sqrt(|F|), F the light's
// (horizon-clipped) vector form factor, whose length is about the solid angle / pi of a small
// light (so sqrt(|F|) about its angular radius). For LTC_PointFactor. The streak it guards
// against needs |V + w| small (both directions near the horizon on opposite sides: |V + w| =
// 2 V.h): from |V + w| = RTPBR_LTC_POINT_SIDE0 over RTPBR_LTC_POINT_SIDE_WIDTH the ratio is
// raised to at least the open gate (LTC_PointFactor's), so that a light beside or behind a
// lobe, however much wider than it, gets its ratio.
RTPBR_FN float LTC_PointWidthRatio(float alpha, float vPlusW, float formFactorLength) {
    float noStreak = vPlusW > RTPBR_LTC_POINT_SIDE0
                         ? min((vPlusW - RTPBR_LTC_POINT_SIDE0) * (1.0f / RTPBR_LTC_POINT_SIDE_WIDTH), 1.0f) *
                               (RTPBR_LTC_POINT_GATE0 + RTPBR_LTC_POINT_GATE_WIDTH)
                         : 0.0f; // NaN -> 0
    return max(alpha * vPlusW * rtpbr_rsqrt(max(formFactorLength, 1e-12f)), noStreak);
}

// The factor on the LTC result: fCos = the true f NoL at LtcPoint.dir (F = 1, the lobe the
// table was fitted to), ltcValue = norm x LtcPoint.density (the table's scale, ltc2.x, times
// the density), ff = the LTC's form factor of the light (LTC_LobeEnd), widthRatio =
// LTC_PointWidthRatio. With k = fCos / ltcValue: k below 1 as it is; above 1 (at most
// RTPBR_LTC_POINT_K_MAX), 1 + (k - 1) smoothstep(GATE0, GATE0 + GATE_WIDTH, widthRatio); then
// faded, k t + (1 - t) with t = (1 - ff)^16. 1 for NaN or zero values.
RTPBR_FN float LTC_PointFactor(float fCos, float ltcValue, float ff, float widthRatio) {
    float k = ltcValue > 0.0f && fCos >= 0.0f ? min(fCos / ltcValue, RTPBR_LTC_POINT_K_MAX) : 1.0f; // NaN: 1
    if (k > 1.0f) {
        float x = widthRatio > RTPBR_LTC_POINT_GATE0
                      ? min((widthRatio - RTPBR_LTC_POINT_GATE0) * (1.0f / RTPBR_LTC_POINT_GATE_WIDTH), 1.0f)
                      : 0.0f; // NaN: 0
        k = 1.0f + (k - 1.0f) * (x * x * (3.0f - 2.0f * x));
    }
    // k t + (1 - t), t = u^16, u = 1 - ff; 1 - t = ff (1 + u)(1 + u^2)(1 + u^4)(1 + u^8) without
    // the cancellation of 1 - t (a factor near 0 keeps its relative precision)
    // (latency: the products as a tree, not a chain)
    float f = rtpbr_saturate(ff);
    float u = 1.0f - f;
    float u2 = u * u;
    float p1 = f * (1.0f + u);
    float u4 = u2 * u2;
    float p2 = p1 * (1.0f + u2);
    float u8 = u4 * u4;
    float p3 = (1.0f + u4) * (1.0f + u8);
    return k * (u8 * u8) + p2 * p3;
}

// ---- the tail estimate --------------------------------------------------------------------
// An LTC is a transformed clamped cosine: it is exactly 0 beyond its own horizon, while the
// GGX / Beckmann lobe has a long tail. A light far from the lobe's peak (beside it, or beyond
// it on a grazing floor) gets little or nothing from the LTC, and the point correction cannot
// scale nothing up. There the true lobe varies slowly across the light, so the midpoint rule
// holds: the integral is about f (F = 1, without the cosine) at the direction c = F / |F| of
// the light's (horizon-clipped) vector form factor F, times pi F.z (the light's cosine-weighted
// solid angle). The corrected result is the larger of that and the point-corrected LTC, where
// the light lies in the LTC's own tail and the LTC is thin over it (LTC_PointTailWeight).

// The tail estimate in units of the LTC result before the table's scale: f pi formFactor /
// norm (norm = ltc2.x, as LTC_PointFactor's ltcValue), f = D V at c (the BRDF with F = 1),
// formFactor = F.z. 0 for NaN, negative or zero inputs.
RTPBR_FN float LTC_PointTail(float f, float formFactor, float norm) {
    float t = norm > 0.0f && f > 0.0f && formFactor > 0.0f ? f * RTPBR_PI * formFactor / norm : 0.0f;
    return t < 3.0e38f ? t : 0.0f; // +Inf (f overflowing) -> 0
}

// How much of the tail estimate to trust: where the light lies in the LTC's tail, and the LTC
// is thin over it. From the lobe's vector form factor Fl (LTC_LobeEndVector: the mean direction
// of the LTC's mass over the light, in the LTC's original space): 1 where its cosine
// Fl.z / |Fl| is at most RTPBR_LTC_TAIL_COS0 (and where the LTC sees nothing), falling over
// RTPBR_LTC_TAIL_COS_WIDTH; times 1 where the LTC's form factor ltcFF is at most
// RTPBR_LTC_TAIL_RATIO0 times the light's cosine form factor formFactor, falling over
// RTPBR_LTC_TAIL_RATIO_WIDTH (ratio ltcFF / formFactor): a light close below a narrow lobe's
// peak has a small cosine there but a dense LTC, and the midpoint rule overstates it.
RTPBR_FN float LTC_PointTailWeight(rtpbr_float3 lobeVector, float ltcFF, float formFactor) {
    float l2 = dot(lobeVector, lobeVector);
    float c = l2 > 1e-30f ? lobeVector.z * rtpbr_rsqrt(l2) : 0.0f;
    float x = c > RTPBR_LTC_TAIL_COS0 ? min((c - RTPBR_LTC_TAIL_COS0) * (1.0f / RTPBR_LTC_TAIL_COS_WIDTH), 1.0f)
                                      : 0.0f; // NaN -> 0
    float rho = formFactor > 0.0f ? ltcFF / formFactor : 0.0f; // NaN ltcFF -> 0 below
    float y = rho > RTPBR_LTC_TAIL_RATIO0
                  ? min((rho - RTPBR_LTC_TAIL_RATIO0) * (1.0f / RTPBR_LTC_TAIL_RATIO_WIDTH), 1.0f)
                  : 0.0f;
    return (1.0f - x * x * (3.0f - 2.0f * x)) * (1.0f - y * y * (3.0f - 2.0f * y));
}

// The corrected LTC result (before the table's scale): the larger of the point-corrected LTC
// (LTC result x LTC_PointFactor) and the weighted tail estimate. NaN in either: the other.
RTPBR_FN float LTC_PointCombine(float corrected, float tail, float weight) {
    float a = corrected >= 0.0f ? corrected : 0.0f;
    float b = tail * weight;
    return b > a ? b : a;
}

// ---- the streak estimate ------------------------------------------------------------------
// A view and a light both near the horizon on the mirror side make the GGX lobe a streak:
// narrow across the plane of incidence, long along it. A light seen there is a thin sliver
// (a wide panel seen edge-on), much wider than the streak, and neither one LTC nor one point
// (the point correction, the tail estimate) follows the lobe across it. But across the plane
// of incidence the lobe is simple: with h = V + L unnormalised and both unit, its slopes are
// (sx, sy) = (h.x, h.y) / h.z, and at a fixed elevation e of L, h.z = V.z + sin e and the
// visibility term (NoL = sin e) stay fixed while sy = L.y / h.z runs across the light. GGX's D
// in slopes is (alpha^2 / pi) (c + sy^2)^2 / (a^2 + sy^2)^2 (c = 1 + sx^2, a^2 = alpha^2 +
// sx^2), whose integral over sy has a closed form (LTC_StreakLateral), and the solid angle is
// d omega = h.z dsy de / cos(phi) (phi the azimuth off the plane; 1 is taken). So the light's
// integral of f NoL (F = 1) is one integral over elevation, taken with 2 Gauss points over the
// light's elevations in the plane of incidence (where it crosses that plane, else those of its
// vertices projected on it: LTC_StreakEdge), over the segment p(s) between the two extreme
// directions d0, d1 with de = |d0 x d1| ds / |p(s)|^2 (no trigonometry: a GPU's is off by 1e-4):
//   sum over nodes of |d0 x d1| / (2 |p|^2) Vis(NoV, sin e) sin e h.z (alpha^2 / pi) [H(s2) - H(s1)]
// with sx that of the node's direction q in the plane of incidence, and s1, s2 = y / h.z at the
// ends of the light's chord through q along y (in the plane spanned by q and y: the light's
// lateral extent there). Ours. Streamed like LtcLobe over the (horizon-clipped) edges: one
// pass for the elevations (LTC_StreakEdge; it can share the pass that sums the light's vector
// form factor F), LTC_StreakNodes(F), one pass for the chords (LTC_StreakChordEdge), then
// LTC_StreakEnd.
struct LtcStreak {
    rtpbr_float4 ends;  // the lowest and highest directions of the light in the plane of
                        // incidence: (x, z) and (x, z), unit (LTC_StreakEdge, LTC_StreakNodes)
    rtpbr_float2 crossing; // (min, max) of x / |x| where the polygon's edges cross y = 0
    float side;         // -1: the light on the mirror side (F.x < 0), 1: the viewer's side
    rtpbr_float4 lim;   // the chords' lateral limits: (low, high) at node 0, at node 1 (unit y)
};

RTPBR_FN LtcStreak LTC_StreakBegin() {
    LtcStreak s;
    s.ends = rtpbr_float4(1.0f, -1.0f, 0.0f, 0.0f); // (min, max) of x / sqrt(x^2 + z^2): empty
    s.crossing = rtpbr_float2(1.0f, -1.0f);         // empty
    s.side = 1.0f;
    s.lim = rtpbr_float4(1.0f, -1.0f, 1.0f, -1.0f); // empty
    return s;
}

// The point where a -> b crosses the plane through the origin of normal n, if it does.
RTPBR_FN bool LTC_StreakCross(rtpbr_float3 n, rtpbr_float3 a, rtpbr_float3 b, RTPBR_OUT(rtpbr_float3) x) {
    float da = dot(a, n), db = dot(b, n);
    bool crosses = (da <= 0.0f) != (db <= 0.0f); // NaN: no
    x = a + (b - a) * (crosses ? da / (da - db) : 0.0f);
    return crosses;
}

// The elevations pass: each segment a -> b of the horizon-clipped polygon (as handed to
// LTC_LobeEdge, the clipper's closing segment included). The elevation that matters is that
// of a direction's projection on the plane of incidence (the chords along y are there,
// LTC_StreakChordEdge): the angle psi from the light's side of the horizon, cos psi = side x /
// sqrt(x^2 + z^2). Kept: the range of x / sqrt(x^2 + z^2) over the vertices (a segment's
// projection is a segment, along which psi is monotonic: the extremes are vertices), and over
// the points where the edges cross the plane of incidence (y = 0). Where the light crosses the
// plane, the streak (narrow across it) sees the light's elevations there, not those of its
// far corners (a light turned about the normal: a range widened by its corners would put the
// nodes' chords over elevations the streak does not reach).
RTPBR_FN void LTC_StreakEdge(RTPBR_INOUT(LtcStreak) s, rtpbr_float3 a, rtpbr_float3 b) {
    float r2 = a.x * a.x + a.z * a.z;
    float u = r2 > 1e-30f ? a.x * rtpbr_rsqrt(r2) : 0.0f;
    s.ends.x = min(s.ends.x, u);
    s.ends.y = max(s.ends.y, u);
    rtpbr_float3 x;
    if (LTC_StreakCross(rtpbr_float3(0.0f, 1.0f, 0.0f), a, b, x)) {
        float x2 = x.x * x.x + x.z * x.z;
        float ux = x2 > 1e-30f ? x.x * rtpbr_rsqrt(x2) : 0.0f;
        s.crossing.x = min(s.crossing.x, ux);
        s.crossing.y = max(s.crossing.y, ux);
    }
}

// After the elevations pass: the light's side from its vector form factor F (either
// orientation), and the range (the crossings' where there are two, else the vertices') made
// the two extreme directions (x, z) in the plane of incidence, lowest (from the light's side of
// the horizon) first; (0, 0, 0, 0) when nothing was seen (NaN included).
RTPBR_FN void LTC_StreakNodes(RTPBR_INOUT(LtcStreak) s, rtpbr_float3 F) {
    s.side = (F.z < 0.0f ? -F.x : F.x) < 0.0f ? -1.0f : 1.0f;
    if (s.crossing.y > s.crossing.x) // the light crosses the plane of incidence: its range there
        s.ends = rtpbr_float4(s.crossing.x, s.crossing.y, s.ends.z, s.ends.w);
    bool seen = s.ends.y >= s.ends.x;
    float lo = clamp(s.side > 0.0f ? s.ends.y : s.ends.x, -1.0f, 1.0f); // x of the lowest
    float hi = clamp(s.side > 0.0f ? s.ends.x : s.ends.y, -1.0f, 1.0f);
    s.ends = seen ? rtpbr_float4(lo, sqrt(max(1.0f - lo * lo, 0.0f)), hi, sqrt(max(1.0f - hi * hi, 0.0f)))
                  : RTPBR_F4(0.0f);
}

// Node k of the quadrature: the point at s = 0.5 -+ 0.5 / sqrt 3 of the segment between the
// two extreme directions (x, z) (the integral over psi taken over s: d psi / ds = |d0 x d1| /
// |p(s)|^2, no trigonometry), unnormalised.
RTPBR_FN rtpbr_float2 LTC_StreakNodePoint(LtcStreak s, int k) {
    float t = k == 0 ? 0.21132487f : 0.78867513f;
    return rtpbr_float2(s.ends.x + (s.ends.z - s.ends.x) * t, s.ends.y + (s.ends.w - s.ends.y) * t);
}

// Its direction, unit, in the plane of incidence.
RTPBR_FN rtpbr_float3 LTC_StreakNode(LtcStreak s, int k) {
    rtpbr_float2 p = LTC_StreakNodePoint(s, k);
    float pp = dot(p, p);
    return pp > 1e-30f ? rtpbr_float3(p.x, 0.0f, p.y) * rtpbr_rsqrt(pp) : rtpbr_float3(0.0f, 0.0f, 1.0f);
}

// The chords pass: the same segments again. Widens each node's lateral limits by where the
// segment crosses the plane spanned by the node's direction q and y (normal q x y = (-q.z, 0,
// q.x)), on q's side.
RTPBR_FN void LTC_StreakChordEdge(RTPBR_INOUT(LtcStreak) s, rtpbr_float3 a, rtpbr_float3 b) {
    for (int k = 0; k < 2; k++) {
        rtpbr_float3 q = LTC_StreakNode(s, k);
        rtpbr_float3 x;
        if (LTC_StreakCross(rtpbr_float3(-q.z, 0.0f, q.x), a, b, x) && dot(x, q) > 0.0f) {
            float y = x.y * rtpbr_rsqrt(max(dot(x, x), 1e-30f));
            if (k == 0) {
                s.lim.x = min(s.lim.x, y);
                s.lim.y = max(s.lim.y, y);
            } else {
                s.lim.z = min(s.lim.z, y);
                s.lim.w = max(s.lim.w, y);
            }
        }
    }
}

// atan(x) within ~1e-7 relative in float: x P(x^2) on [0, 1] (P fitted by
// tools/fits/fit_atan.py: largest relative error 1.5e-8), pi / 2 - atan(1 / x) beyond. GPUs'
// atan (lavapipe's) is off by up to ~1e-4 relative. NaN -> 0, +-Inf -> +-pi / 2.
RTPBR_FN float LTC_Atan(float x) {
    float ax = abs(x);
    bool inv = ax > 1.0f;
    float t = inv ? 1.0f / ax : ax;
    float t2 = t * t;
    float p = 0.00285044225f;
    p = p * t2 - 0.0160709702f;
    p = p * t2 + 0.0426956009f;
    p = p * t2 - 0.075046718f;
    p = p * t2 + 0.106411324f;
    p = p * t2 - 0.142037035f;
    p = p * t2 + 0.199926287f;
    p = p * t2 - 0.33333074f;
    p = p * t2 + 0.999999985f;
    float r = p * t;
    r = inv ? 1.57079632679f - r : r;
    return x < 0.0f ? -r : (x >= 0.0f ? r : 0.0f);
}

// Integral over sy of (c + sy^2)^2 / (a^2 + sy^2)^2 from s1 to s2, m = c - a^2 = 1 - alpha^2.
// The differences are taken in closed form (atan x2 - atan x1 = atan((x2 - x1) / (1 + x1 x2))
// when x1 x2 > -1; s2 / (a^2 + s2^2) - s1 / (a^2 + s1^2) = (s2 - s1)(a^2 - s1 s2) / (...)):
// a range far from 0 on one side would otherwise cancel (and lose 1e-4 with a GPU's atan).
RTPBR_FN float LTC_StreakLateral(float s1, float s2, float a2, float m) {
    float a = sqrt(a2);
    float x1 = s1 / a, x2 = s2 / a;
    float at = x1 * x2 > -1.0f ? LTC_Atan((x2 - x1) / (1.0f + x1 * x2)) : LTC_Atan(x2) - LTC_Atan(x1);
    float r = (s2 - s1) * (a2 - s1 * s2) / ((a2 + s1 * s1) * (a2 + s2 * s2));
    return (s2 - s1) + (2.0f * m / a + m * m / (2.0f * a2 * a)) * at + m * m / (2.0f * a2) * r;
}

// The slope sx = h.x / h.z of the unit direction (x, z) in the plane of incidence.
RTPBR_FN float LTC_StreakSlope(float x, float z, rtpbr_float3 vLocal) {
    return (vLocal.x + x) / max(vLocal.z + z, 1e-6f);
}

// smoothstep(lo, hi, x); NaN -> 1.
RTPBR_FN float LTC_StreakRamp(float x, float lo, float hi) {
    float t = x > lo ? min((x - lo) / (hi - lo), 1.0f) : (x <= lo ? 0.0f : 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// The lobe's span over the light's elevations, q = |sx1 - sx0| / a (LTC_StreakEnd's first
// trust factor), from the ends alone (after LTC_StreakNodes): the estimate's trust is 0 unless
// q < RTPBR_LTC_STREAK_Q1 (LTC_StreakSpanTrusted; NaN: not), which a caller can test before the
// chords pass and skip it and LTC_StreakEnd (AreaLight_StreakEstimate: a narrow lobe seen across
// a tall light, as on a glossy floor under a tall panel).
RTPBR_FN float LTC_StreakSpan(LtcStreak s, rtpbr_float3 vLocal, float alpha) {
    float al = max(alpha, 1e-3f);
    float sx0 = LTC_StreakSlope(s.ends.x, s.ends.y, vLocal), sx1 = LTC_StreakSlope(s.ends.z, s.ends.w, vLocal);
    float near2 = sx0 * sx1 <= 0.0f ? 0.0f : min(sx0 * sx0, sx1 * sx1);
    return abs(sx1 - sx0) * rtpbr_rsqrt(al * al + near2);
}

RTPBR_FN bool LTC_StreakSpanTrusted(float q) { return q < RTPBR_LTC_STREAK_Q1; }

// The estimate: the integral of D V NoL (F = 1: the lobe the tables were fitted to, with
// the configured Smith term) over the light, from both passes (.x), and how far to trust it
// (.y, in [0, 1]), the product of three factors, each 0 below its first constant, 1 above its
// second, smoothstep between:
//   - two Gauss points follow the lobe along the light's elevations: it spans slopes sx from
//     one end to the other of q = |sx1 - sx0| / a (a = sqrt(alpha^2 + sx^2) at the end nearer
//     the peak, alpha when the range crosses it), trusted up to q = RTPBR_LTC_STREAK_Q0, not
//     from RTPBR_LTC_STREAK_Q1 (a narrow lobe seen across a tall light);
//   - the two nodes' terms are within a factor of each other: their ratio from
//     RTPBR_LTC_STREAK_R0 to R1 (a light's edge across the streak between them makes the
//     integrand a step that two points miss);
//   - the light is wider than the lobe across the plane (a streak to follow): (hi - lo) /
//     (h.z alpha) from RTPBR_LTC_STREAK_W0 to W1 (a light within the lobe's width is the
//     point correction's case).
// vLocal = V in the LTC frame (x toward V), alpha >= 1e-3 taken. (-1, 0) when nothing was seen
// (keep the other result). GGX only (RTPBR_NDF_GGX: the closed form is GGX's); other NDFs
// get (-1, 0).
RTPBR_FN rtpbr_float2 LTC_StreakEnd(LtcStreak s, rtpbr_float3 vLocal, float alpha) {
    if (!(s.ends.y > 0.0f || s.ends.w > 0.0f) || RTPBR_NDF != RTPBR_NDF_GGX)
        return rtpbr_float2(-1.0f, 0.0f);
    float al = max(alpha, 1e-3f);
    float al2 = al * al, m = 1.0f - al2;
    float span = abs(s.ends.x * s.ends.w - s.ends.y * s.ends.z); // |d0 x d1|
    float term[2];
    float widest = 0.0f; // the light's widest chord in lobe widths, (hi - lo) / (h.z alpha)
    for (int k = 0; k < 2; k++) {
        rtpbr_float2 p = LTC_StreakNodePoint(s, k);
        float pp = max(dot(p, p), 1e-30f);
        rtpbr_float3 q = rtpbr_float3(p.x, 0.0f, p.y) * rtpbr_rsqrt(pp);
        float lo = k == 0 ? s.lim.x : s.lim.z, hi = k == 0 ? s.lim.y : s.lim.w;
        float se = q.z;
        float hz = vLocal.z + se;
        term[k] = 0.0f;
        if (hi > lo && se > 0.0f && hz > 0.0f) {
            float sx = (vLocal.x + q.x) / hz;
            float a2 = al2 + sx * sx;
            term[k] = V_Microfacet(vLocal.z, se, al) * se * hz * LTC_StreakLateral(lo / hz, hi / hz, a2, m) / pp;
            widest = max(widest, (hi - lo) / (hz * al));
        }
    }
    float sum = (term[0] + term[1]) * (0.5f * span * (al2 * RTPBR_INV_PI));
    float q = LTC_StreakSpan(s, vLocal, alpha);
    float rho = max(term[0], term[1]) > 0.0f ? min(term[0], term[1]) / max(term[0], term[1]) : 0.0f;
    float trust = (1.0f - LTC_StreakRamp(q, RTPBR_LTC_STREAK_Q0, RTPBR_LTC_STREAK_Q1)) *
                  LTC_StreakRamp(rho, RTPBR_LTC_STREAK_R0, RTPBR_LTC_STREAK_R1) *
                  LTC_StreakRamp(widest, RTPBR_LTC_STREAK_W0, RTPBR_LTC_STREAK_W1);
    bool finite = sum >= 0.0f && sum < 3.0e38f;
    return finite ? rtpbr_float2(sum, trust) : RTPBR_F2(0.0f);
}

// V.h at the middle of the light's elevation range in the plane of incidence (after
// LTC_StreakNodes): where the streak's Fresnel is taken (the tables' Fresnel scale averages it
// over the whole lobe, low for a metal's streak at grazing).
RTPBR_FN float LTC_StreakVoH(LtcStreak s, rtpbr_float3 vLocal) {
    rtpbr_float3 q = rtpbr_float3(s.ends.x + s.ends.z, 0.0f, s.ends.y + s.ends.w);
    rtpbr_float3 h = vLocal + q * rtpbr_rsqrt(max(dot(q, q), 1e-30f));
    return rtpbr_saturate(dot(vLocal, h) * rtpbr_rsqrt(max(dot(h, h), 1e-30f)));
}

// How much of the streak estimate to take: 1 - smoothstep(RTPBR_LTC_STREAK_V0, V1, |V + c|),
// c = +-F / |F| the direction of the light's vector form factor (turned to z >= 0; |V + c| =
// 2 V.h is small only on the mirror side near the horizon). 0 for NaN or zero F.
RTPBR_FN float LTC_StreakWeight(rtpbr_float3 vLocal, rtpbr_float3 F) {
    float l2 = dot(F, F);
    float v = l2 > 1e-30f ? length(vLocal + F * ((F.z < 0.0f ? -1.0f : 1.0f) * rtpbr_rsqrt(l2))) : 1.0f;
    return 1.0f - LTC_StreakRamp(v, RTPBR_LTC_STREAK_V0, RTPBR_LTC_STREAK_V1); // NaN -> 1 -> weight 0
}

// Whether a light can get any trust (LTC_StreakEnd's third factor): its extent across the
// plane of incidence, at most its angular diameter (bounding sphere of radius r at distance d:
// 2 r / sqrt(d^2 - r^2) = 2 tan(asin(r / d)), above the angle), must reach RTPBR_LTC_STREAK_W0
// lobe widths h.z alpha, and h.z >= NoV. A cheap test before the passes (the engine's); false
// only where the estimate's trust would be 0. LTC_StreakCandidateSquared: from distance^2, the
// comparison squared (radius >= 0; no root: the engine's, issue 32).
RTPBR_FN bool LTC_StreakCandidateSquared(float radius, float distance2, float alpha, float NoV) {
    float d2 = distance2 - radius * radius;
    float w = RTPBR_LTC_STREAK_W0 * max(alpha, 1e-3f) * NoV;
    return !(d2 > 0.0f) || 4.0f * (radius * radius) >= (w * w) * d2;
}
RTPBR_FN bool LTC_StreakCandidate(float radius, float distance, float alpha, float NoV) {
    return LTC_StreakCandidateSquared(radius, distance * distance, alpha, NoV);
}

// Whether the streak estimate's weight (LTC_StreakWeight) is 0 for every view direction within
// the angle viewSpread of viewAxis and every light direction within lightSpread of lightAxis
// (axes of any non-zero length; spreads in radians, >= 0; false for a lightSpread above pi / 2,
// whose cone is not convex: the mean of its directions may lie outside it). The weight needs
// |V + c| < RTPBR_LTC_STREAK_V1 (V, c unit: V.c < V1^2 / 2 - 1), an angle between V and c above
// acos(V1^2 / 2 - 1) = 136 degrees for 0.75; two directions of the cones are at most the axes'
// angle plus both spreads apart. c, the direction of a horizon-clipped polygon's vector form
// factor, is the normalised mean of the directions to its points (F = (1 / pi) int w dw,
// either orientation), so it lies in any cone (of half-angle <= pi / 2) that holds the light.
// 1e-2 radians are kept as a margin for rounding (a small light's vector form factor is a sum
// of nearly opposite edge terms: float rounding turns its direction by about 1e-7 radians over
// the light's angular size). A cheap test for a host's culling (the engine's, per screen tile
// and light, with the cones from the tile's box to the camera and to the light's bounding
// sphere): where it holds for all of a point's lights, AreaLight_End's streak estimate changes
// nothing (RTPBR_AREA_LIGHT_STREAK_ON 0 gives the same result). NaN: false.
RTPBR_FN bool LTC_StreakOutside(rtpbr_float3 viewAxis, float viewSpread, rtpbr_float3 lightAxis, float lightSpread) {
    float c = dot(viewAxis, lightAxis) * rtpbr_rsqrt(max(dot(viewAxis, viewAxis) * dot(lightAxis, lightAxis), 1e-30f));
    float axes = acos(clamp(c, -1.0f, 1.0f));
    float limit = acos(0.5f * RTPBR_LTC_STREAK_V1 * RTPBR_LTC_STREAK_V1 - 1.0f) - 1e-2f;
    return lightSpread <= 1.57079633f && axes + viewSpread + lightSpread < limit; // NaN: false
}

// The NoV from which the streak estimate's weight (LTC_StreakWeight) is 0 whatever the light:
// with c above the horizon V.c >= -sqrt(1 - NoV^2), and the weight needs V.c < V1^2 / 2 - 1
// (LTC_StreakOutside), so NoV >= sqrt(1 - (1 - V1^2 / 2)^2) (0.695 for 0.75) gives none; 1e-2
// added as a margin for rounding. LTC_StreakSteep: NoV at least that (NaN: false).
RTPBR_FN float LTC_StreakSteepNoV() {
    float k = 1.0f - 0.5f * RTPBR_LTC_STREAK_V1 * RTPBR_LTC_STREAK_V1;
    return sqrt(max(1.0f - k * k, 0.0f)) + 1e-2f;
}

RTPBR_FN bool LTC_StreakSteep(float NoV) { return NoV >= LTC_StreakSteepNoV(); }

// The streak estimate over a stored local polygon (from LTC_PolygonToLocal: already clipped
// to the horizon); F its vector form factor (LTC_FormFactorVector). Tools and tests.
RTPBR_FN rtpbr_float2 LTC_StreakLocal(LtcLocalPolygon local, rtpbr_float3 F, rtpbr_float3 vLocal, float alpha) {
    LtcStreak s = LTC_StreakBegin();
    if (local.count < 3)
        return rtpbr_float2(-1.0f, 0.0f);
    for (int i = 0; i < RTPBR_LTC_CLIP_VERTICES; i++)
        if (i < local.count)
            LTC_StreakEdge(s, local.v[i], i + 1 < local.count ? local.v[i + 1] : local.v[0]);
    LTC_StreakNodes(s, F);
    for (int j = 0; j < RTPBR_LTC_CLIP_VERTICES; j++) // (j: Slang takes two loops' i as ambiguous)
        if (j < local.count)
            LTC_StreakChordEdge(s, local.v[j], j + 1 < local.count ? local.v[j + 1] : local.v[0]);
    return LTC_StreakEnd(s, vLocal, alpha);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_CORRECTIONS_H
