// rtpbr shader library: polygonal area lights with Linearly Transformed Cosines (LTC).
//
// Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines": a BRDF lobe (times the cosine) for one view direction and roughness is
// D(w) = D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3, D_o = max(z, 0) / pi; its integral over
// a polygon is D_o's over the polygon transformed by M^-1, in closed form (Lambert 1760; Arvo
// 1995, "Applications of Irradiance Tensors"). This header is the stable core; beside it are
// ltc_anisotropy.h (stretched lobes), ltc_clipless.h (the sphere proxy) and ltc_corrections.h
// (EXPERIMENTAL). Usage, tables and measured accuracy: shaderlib/luts/ltc.md.
//
// Conventions
//   - Local LTC frame: z = N, x = normalize(V - N NoV), y = cross(N, x). Polygons: world-space
//     vertices, convex and planar, 3 to RTPBR_LTC_MAX_VERTICES (8); the front face is the side
//     they appear counter-clockwise from. One-sided lights emit from the front only.
//   - Every integral returned is a form factor in [0, 1], the fraction of the LTC's mass above
//     the horizon that falls on the polygon (so times ltc2's integrals it never exceeds the
//     interpolated albedo). For a light of radiance Le:
//       specular  Lo = Le * LTC_FresnelScale(ltc2, f0, f90) * LTC_EvaluatePolygon(.., ltc1, ..)
//       Lambert   Lo = Le * diffuseColor * LTC_EvaluatePolygon(.., LTC_Identity(), ..)
//   - The caller fetches (bilinear, clamp-to-edge) ltc1 = rtpbr_ltc_*_1 = (m00, m02, m20, m22)
//     of M^-1 (rows (m00 0 m02), (0 1 0), (m20 0 m22)) and ltc2 = rtpbr_ltc_*_2 = (albedo,
//     Fresnel moment, f82 moment, sphere form factor) at LTC_LutCoord (.w: ltc_clipless.h).
//   - The polygon is clipped to the upper hemisphere before the transform (as O3DE does: no
//     light from behind the surface where the lobe dips under the horizon), then to the LTC's
//     support (M^-1 w).z >= 0 (Heitz et al.'s clip).
//
// Public functions
//   polygons and tables
//     LTC_Triangle, LTC_Quad          an LtcPolygon of 3 or 4 world-space vertices
//     LTC_Identity                    ltc1 of the clamped cosine itself (Lambertian diffuse)
//     LTC_LutCoord                    the tables' coordinate for (NoV, perceptual roughness)
//     LTC_InverseMatrix               M^-1 from ltc1
//   frame and clipping (stored polygon)
//     LTC_Frame                       the world-to-local rotation for (N, V)
//     LTC_PolygonToLocal              a polygon relative to P, local, clipped to the horizon
//     LTC_PolygonRelative             the same unclipped: relative, local, oriented, or empty
//     LTC_ClipToHalfSpace             a stored polygon clipped to dot(p, n) >= 0
//   edge integral and horizon
//     LTC_EdgeFactor, LTC_EdgeFactorHalf  theta / (2 pi sin theta), fitted (Heitz et al. 2017)
//     LTC_EdgeIntegral, LTC_EdgeIntegralZ  one edge's vector form factor (Arvo 1995), its z
//     LTC_EdgeIntegralOf              the same for the directions of any two vectors
//     LTC_SafeNormalize               v / |v|, 0 for 0
//     LTC_HorizonMass, LTC_HorizonFraction  an LTC's mass above the horizon; a part of it
//     LTC_InverseHorizonMass, LTC_HorizonFractionInv  the same through 1 / the mass
//   streamed evaluation (edge by edge, nothing stored)
//     LTC_ClipperBegin, LTC_ClipEdge, LTC_ClipClose  the horizon clip of one light
//     LTC_ClipEdgeRecip               LTC_ClipEdge with its division given
//     LTC_LobeBegin, LTC_LobeEdge     one lobe: its M^-1, then each clipped segment
//     LTC_LobeEnd, LTC_LobeEndVector  the lobe's form factor; its vector form factor
//   stored and one-call evaluation
//     LTC_LobeOverLocal               the streamed lobe over a stored local polygon
//     LTC_IntegrateLocal, _Matrix, _Vector  its form factor for ltc1, for any M^-1; its vector
//     LTC_EvaluatePolygon             one call: a polygon's form factor at P for ltc1
//   Fresnel
//     LTC_FresnelScale                Schlick (f0, f90) times the lobe's integrals
//     LTC_FresnelScaleF82             the F82 model (Kutz et al. 2021)
//     LTC_FresnelScaleConductor       F82 fitted to the exact conductor Fresnel
//     LTC_FresnelScaleSelected        the model RTPBR_FRESNEL selects
#ifndef RTPBR_LTC_H
#define RTPBR_LTC_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"

// RTPBR_LTC_CLIPLESS 1: LTC_EvaluatePolygon is ltc_clipless.h's (the sphere proxy; include it).
#ifndef RTPBR_LTC_CLIPLESS
#define RTPBR_LTC_CLIPLESS 0
#endif
// Texels per side of the LTC tables (shaderlib/luts/rtpbr_ltc_tables.h defines the same).
#ifndef RTPBR_LTC_SIZE
#define RTPBR_LTC_SIZE 64
#endif
// Must equal the engine's RTPBR_MAX_POLYGON_VERTICES (rtpbr/rtpbr.h, the source of truth);
// checked in engine/shaders/vertex_limit.glsl.
#define RTPBR_LTC_MAX_VERTICES 8
// Two half-space clips of a convex polygon add at most one vertex each.
#define RTPBR_LTC_CLIP_VERTICES 10

RTPBR_NAMESPACE_BEGIN

RTPBR_FN rtpbr_float4 LTC_Identity() { return rtpbr_float4(1.0f, 0.0f, 0.0f, 1.0f); }

// A convex planar polygon: world-space vertex positions v[0 .. count-1].
struct LtcPolygon {
    rtpbr_float3 v[RTPBR_LTC_MAX_VERTICES];
    int count;
};

// A polygon relative to the shading point in the LTC frame; count 0: the light cannot contribute.
struct LtcLocalPolygon {
    rtpbr_float3 v[RTPBR_LTC_CLIP_VERTICES];
    int count;
};

RTPBR_FN LtcPolygon LTC_Triangle(rtpbr_float3 p0, rtpbr_float3 p1, rtpbr_float3 p2) {
    LtcPolygon p;
    for (int i = 0; i < RTPBR_LTC_MAX_VERTICES; i++)
        p.v[i] = p0;
    p.v[1] = p1;
    p.v[2] = p2;
    p.count = 3;
    return p;
}

RTPBR_FN LtcPolygon LTC_Quad(rtpbr_float3 p0, rtpbr_float3 p1, rtpbr_float3 p2, rtpbr_float3 p3) {
    LtcPolygon p = LTC_Triangle(p0, p1, p2);
    p.v[3] = p3;
    p.count = 4;
    return p;
}

// ---- table coordinates ---------------------------------------------------------------------
// Texel (i, j) holds roughness i / (SIZE - 1) and sqrt(1 - NoV) = j / (SIZE - 1): mapped to
// texel centres, so bilinear filtering never extrapolates (Heitz et al. 2016, LUT_SCALE/BIAS).
RTPBR_FN rtpbr_float2 LTC_LutCoord(float NoV, float perceptualRoughness) {
    float u = rtpbr_saturate(perceptualRoughness);
    float v = rtpbr_safe_sqrt(1.0f - rtpbr_saturate(NoV));
    float scale = (float(RTPBR_LTC_SIZE) - 1.0f) / float(RTPBR_LTC_SIZE);
    float bias = 0.5f / float(RTPBR_LTC_SIZE);
    return rtpbr_float2(u * scale + bias, v * scale + bias);
}

// ---- geometry ------------------------------------------------------------------------------
// Rows x, y, z of the LTC frame. When V is along N any tangent will do (isotropic lobes).
RTPBR_FN rtpbr_float3x3 LTC_Frame(rtpbr_float3 N, rtpbr_float3 V) {
    rtpbr_float3 t = V - N * dot(N, V);
    float tl2 = dot(t, t);
    if (tl2 > 1e-10f) {
        t = t * rtpbr_rsqrt(tl2);
    } else {
        rtpbr_float3 up = rtpbr_float3(0.0f, 0.0f, 1.0f);
        if (abs(N.z) > 0.9f)
            up = rtpbr_float3(1.0f, 0.0f, 0.0f);
        t = normalize(cross(up, N));
    }
    return rtpbr_mat3_rows(t, cross(N, t), N);
}

// Sutherland-Hodgman, n through the shading point; points on the plane are kept; at most one
// vertex more than the input (capped at the buffer for non-convex input).
RTPBR_FN LtcLocalPolygon LTC_ClipToHalfSpace(LtcLocalPolygon p, rtpbr_float3 n) {
    LtcLocalPolygon r;
    r.count = 0;
    for (int k = 0; k < RTPBR_LTC_CLIP_VERTICES; k++)
        r.v[k] = RTPBR_F3(0.0f);
    for (int i = 0; i < p.count; i++) {
        int j = i + 1 < p.count ? i + 1 : 0;
        rtpbr_float3 a = p.v[i];
        rtpbr_float3 b = p.v[j];
        float da = dot(a, n);
        float db = dot(b, n);
        if (da >= 0.0f && r.count < RTPBR_LTC_CLIP_VERTICES) {
            r.v[r.count] = a;
            r.count += 1;
        }
        if ((da >= 0.0f) != (db >= 0.0f) && r.count < RTPBR_LTC_CLIP_VERTICES) {
            // da and db have opposite signs: da - db != 0 and t is in [0, 1].
            r.v[r.count] = a + (b - a) * (da / (da - db));
            r.count += 1;
        }
    }
    return r;
}

// Oriented to appear clockwise from P (its Newell normal points away from P); count = 0 for
// fewer than 3 or more than 8 vertices, zero area, P on the polygon's plane (|plane distance|
// <= 1e-7 of its extent), P behind a one-sided light, or NaN input.
RTPBR_FN LtcLocalPolygon LTC_PolygonRelative(rtpbr_float3x3 frame, rtpbr_float3 P, LtcPolygon poly, bool twoSided) {
    LtcLocalPolygon r;
    r.count = 0;
    for (int k = 0; k < RTPBR_LTC_CLIP_VERTICES; k++)
        r.v[k] = RTPBR_F3(0.0f);
    if (!(poly.count >= 3 && poly.count <= RTPBR_LTC_MAX_VERTICES))
        return r;
    rtpbr_float3 p0 = poly.v[0];
    rtpbr_float3 normal = RTPBR_F3(0.0f); // Newell's normal, from edges relative to p0 (precision)
    float extent2 = 0.0f;
    for (int e = 1; e + 1 < poly.count; e++) {
        rtpbr_float3 e1 = poly.v[e] - p0;
        rtpbr_float3 e2 = poly.v[e + 1] - p0;
        normal += cross(e1, e2);
        extent2 = max(extent2, max(dot(e1, e1), dot(e2, e2)));
    }
    float nl = length(normal);
    rtpbr_float3 d0 = p0 - P;
    extent2 = max(extent2, dot(d0, d0));
    if (!(nl > 0.0f))
        return r;
    float planeDist = dot(normal, d0) / nl; // > 0: P sees the back face
    if (!(abs(planeDist) > 1e-7f * sqrt(extent2)))
        return r;
    if (!twoSided && planeDist > 0.0f)
        return r;
    // Reverse front-facing polygons: every polygon then appears clockwise from P.
    bool reverse = planeDist < 0.0f;
    for (int i = 0; i < poly.count; i++) {
        int src = reverse ? poly.count - 1 - i : i;
        r.v[i] = rtpbr_mul(frame, poly.v[src] - P);
    }
    r.count = poly.count;
    return r;
}

// frame = LTC_Frame(N, V). Compute once per light, then integrate it for each lobe.
RTPBR_FN LtcLocalPolygon LTC_PolygonToLocal(rtpbr_float3x3 frame, rtpbr_float3 P, LtcPolygon poly, bool twoSided) {
    LtcLocalPolygon r = LTC_PolygonRelative(frame, P, poly, twoSided);
    if (r.count == 0)
        return r;
    r = LTC_ClipToHalfSpace(r, rtpbr_float3(0.0f, 0.0f, 1.0f));
    for (int i = 0; i < r.count; i++) // exactly on the horizon, for horizon edges along z
        r.v[i].z = max(r.v[i].z, 0.0f);
    if (r.count < 3)
        r.count = 0;
    return r;
}

// ---- integration ---------------------------------------------------------------------------
RTPBR_FN rtpbr_float3x3 LTC_InverseMatrix(rtpbr_float4 ltc1) {
    return rtpbr_mat3_rows(rtpbr_float3(ltc1.x, 0.0f, ltc1.y), rtpbr_float3(0.0f, 1.0f, 0.0f),
                           rtpbr_float3(ltc1.z, 0.0f, ltc1.w));
}

// w.z >= 0 is, in the cosine's space (w_o = M^-1 w), n . w_o >= 0 for n = M^-1 x x M^-1 y
// (toward M^-1 z), holding (1 + n.z / |n|) / 2 of the clamped cosine (a tilted plane's sky view
// factor); for n.z < 0 (n.x^2 + n.y^2) / (2 |n| (|n| - n.z)), without cancellation for a lobe
// almost all below the horizon (fitted cells reach 1e-15). Any M^-1; 0 if singular or NaN.
// Both forms computed and selected, no branch: the per-light evaluation calls it twice with the
// same M^-1 (AreaLight_LobeClose, LTC_LobePoint), and only straight-line code lets the compiler
// keep one copy (docs/performance.md, 17).
RTPBR_FN float LTC_HorizonMass(rtpbr_float3x3 minv) {
    rtpbr_float3 cx = rtpbr_mul(minv, rtpbr_float3(1.0f, 0.0f, 0.0f));
    rtpbr_float3 cy = rtpbr_mul(minv, rtpbr_float3(0.0f, 1.0f, 0.0f));
    rtpbr_float3 cz = rtpbr_mul(minv, rtpbr_float3(0.0f, 0.0f, 1.0f));
    rtpbr_float3 n = cross(cx, cy);
    // (latency: docs/performance.md, 30) |n| and the side of cz from n at once; one root
    float side = dot(n, cz);
    float nxy2 = n.x * n.x + n.y * n.y;
    float len2 = n.z * n.z + nxy2;
    float rl = rtpbr_rsqrt(len2);
    float nz = side < 0.0f ? -n.z : n.z;
    float len = len2 * rl;
    float above = 0.5f + 0.5f * (nz * rl);
    float below = 0.5f * nxy2 / (len * (len - nz));
    float mass = nz >= 0.0f ? above : below;
    return len2 > 0.0f ? rtpbr_saturate(mass) : 0.0f;
}

// ff <= mass mathematically; kept in [0, 1] against rounding (a lobe of mass 1e-15 sums edge
// terms of order 1). 0 where nothing is above the horizon.
RTPBR_FN float LTC_HorizonFraction(float ff, float mass) {
    return mass > 0.0f && ff > 0.0f ? min(ff / mass, 1.0f) : 0.0f;
}

// 1 / LTC_HorizonMass(minv), 0 where that is 0: for a caller evaluating many lights with one
// lobe, taken once per point (LTC_HorizonFractionInv's: a product per light, not a division).
RTPBR_FN float LTC_InverseHorizonMass(rtpbr_float3x3 minv) {
    float mass = LTC_HorizonMass(minv);
    return mass > 0.0f ? 1.0f / mass : 0.0f;
}

// LTC_HorizonFraction from invMass = LTC_InverseHorizonMass (never negative or NaN).
RTPBR_FN float LTC_HorizonFractionInv(float ff, float invMass) {
    return rtpbr_saturate(ff * invMass);
}

// ---- streamed integration (the real-time path) ----------------------------------------------
// Edge by edge, never storing the clipped polygon (GPU compilers turn run-time-indexed private
// arrays into select chains or scratch memory): the caller walks a convex light's edges a -> b
// (from the shading point, LTC frame), clips each to the horizon once (LTC_ClipEdge), hands each
// surviving segment to every lobe (LTC_LobeEdge clips it to the lobe's support in its own space;
// or LTC_EdgeIntegral), then LTC_ClipClose's segment; LTC_LobeEnd gives the form factor.

// Heitz et al. 2017, ltc_code's "IntegrateEdgeVec": theta / (2 pi sin theta) for unit vectors,
// x = cos theta, fitted in |x| (relative error < 2e-6); x < 0 folds onto |x| by theta / sin =
// pi / sin - (pi - theta) / sin, sinT = |a x b| (consistent with the cross product near pi).
// LTC_EdgeFactorHalf: the same with 0.5 / sin theta given (halfInvSinT, read only for x < 0).
RTPBR_FN float LTC_EdgeFactorHalf(float x, float halfInvSinT) {
    float y = abs(x);
    float b = 3.4175940f + (4.1616724f + y) * y; // (the divisor first: its reciprocal's latency)
    float a = 0.8543985f + (0.4965155f + 0.0145206f * y) * y;
    float v = a / b;
    return x >= 0.0f ? v : halfInvSinT - v;
}

RTPBR_FN float LTC_EdgeFactor(float x, float sinT) {
    return LTC_EdgeFactorHalf(x, 0.5f / max(sinT, 1e-7f));
}

// theta / (2 pi sin theta) * cross(a, b) for unit a, b: summed over a polygon's edges, its
// vector form factor (Arvo 1995), up to orientation.
RTPBR_FN rtpbr_float3 LTC_EdgeIntegral(rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 c = cross(a, b);
    return c * LTC_EdgeFactor(dot(a, b), length(c));
}

RTPBR_FN float LTC_EdgeIntegralZ(rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 c = cross(a, b);
    return c.z * LTC_EdgeFactor(dot(a, b), length(c));
}

// (A vertex at the shading point contributes nothing.)
RTPBR_FN rtpbr_float3 LTC_SafeNormalize(rtpbr_float3 v) {
    return v * rtpbr_rsqrt(max(dot(v, v), 1e-30f));
}

// LTC_EdgeIntegral(LTC_SafeNormalize(a), LTC_SafeNormalize(b)) (up to the rounding of
// 0.5 / sin theta for obtuse edges), written for latency (docs/performance.md, 30): the two
// lengths' sums side by side (their floor LTC_SafeNormalize's, as the first term rather than a
// step of its own), and 0.5 / sin theta as one root (LTC_EdgeFactorHalf) where LTC_EdgeFactor
// takes a root and a division.
// (Scaling dot(a, b) and cross(a, b) by 1 / (|a| |b|) instead was faster still but lost
// precision where two long edges nearly cancel: a thin quad's, 4.8e-6 against ltc_lines.h.)
RTPBR_FN rtpbr_float3 LTC_EdgeIntegralOf(rtpbr_float3 a, rtpbr_float3 b) {
    float aa = a.x * a.x + 1e-30f;
    float bb = b.x * b.x + 1e-30f;
    aa = a.y * a.y + aa;
    bb = b.y * b.y + bb;
    aa = a.z * a.z + aa;
    bb = b.z * b.z + bb;
    float ra = rtpbr_rsqrt(aa);
    float rb = rtpbr_rsqrt(bb);
    a = a * ra;
    b = b * rb;
    rtpbr_float3 c = cross(a, b);
    return c * LTC_EdgeFactorHalf(dot(a, b), 0.5f * rtpbr_rsqrt(max(dot(c, c), 1e-14f)));
}

// A streamed clip to z >= 0: where the boundary leaves the half-space and where it comes back.
struct LtcClipper {
    rtpbr_float3 exitPoint;
    rtpbr_float3 entryPoint;
    bool crossed;
};

// A clipped edge: the segment a -> b, or nothing (valid = false; a and b are then not values to read).
struct LtcSegment {
    rtpbr_float3 a;
    rtpbr_float3 b;
    bool valid;
};

RTPBR_FN LtcClipper LTC_ClipperBegin() {
    LtcClipper c;
    c.exitPoint = RTPBR_F3(0.0f);
    c.entryPoint = RTPBR_F3(0.0f);
    c.crossed = false;
    return c;
}

// The part of a -> b in z >= 0 (points on the plane inside); records exit and entry points.
// LTC_ClipEdge with 1 / (a.z - b.z) given (rden: a caller can issue its division early).
RTPBR_FN LtcSegment LTC_ClipEdgeRecip(RTPBR_INOUT(LtcClipper) clip, rtpbr_float3 a, rtpbr_float3 b, float rden) {
    bool inA = a.z >= 0.0f;
    bool inB = b.z >= 0.0f;
    // a.z and b.z have opposite signs when the edge crosses: a.z - b.z != 0, t in [0, 1]. Not
    // selected to 0 elsewhere: x is read only where the edge crosses (docs/performance.md, 10).
    float t = a.z * rden;
    rtpbr_float3 x = a + (b - a) * t;
    x.z = 0.0f;
    if (inA && !inB) {
        clip.exitPoint = x;
        clip.crossed = true;
    }
    if (!inA && inB)
        clip.entryPoint = x;
    LtcSegment s;
    s.a = inA ? a : x;
    s.b = inB ? b : x;
    s.valid = inA || inB;
    return s;
}

RTPBR_FN LtcSegment LTC_ClipEdge(RTPBR_INOUT(LtcClipper) clip, rtpbr_float3 a, rtpbr_float3 b) {
    return LTC_ClipEdgeRecip(clip, a, b, 1.0f / (a.z - b.z));
}

// The segment along the plane that closes the clipped polygon (valid when it was crossed).
RTPBR_FN LtcSegment LTC_ClipClose(LtcClipper clip) {
    LtcSegment s;
    s.a = clip.exitPoint;
    s.b = clip.entryPoint;
    s.valid = clip.crossed;
    return s;
}

// One LTC lobe over a streamed polygon: its M^-1 (LTC_InverseMatrix or any, such as
// ltc_anisotropy.h's), the clip to its support (M^-1 w).z >= 0 done in its own
// space (a linear map keeps segments straight), and the sum of the edge integrals.
struct LtcLobe {
    rtpbr_float3x3 minv;
    LtcClipper clip;
    rtpbr_float3 vec; // the vector form factor of the part seen so far; .z: the form factor
};

RTPBR_FN LtcLobe LTC_LobeBegin(rtpbr_float3x3 minv) {
    LtcLobe lobe;
    lobe.minv = minv;
    lobe.clip = LTC_ClipperBegin();
    lobe.vec = RTPBR_F3(0.0f);
    return lobe;
}

// a -> b: vectors from the shading point in the LTC frame, already clipped to the horizon.
RTPBR_FN void LTC_LobeEdge(RTPBR_INOUT(LtcLobe) lobe, rtpbr_float3 a, rtpbr_float3 b) {
    LtcSegment s = LTC_ClipEdge(lobe.clip, rtpbr_mul(lobe.minv, a), rtpbr_mul(lobe.minv, b));
    if (s.valid) // the whole edge vector; callers that never read x, y let the compiler drop them
        lobe.vec += LTC_EdgeIntegralOf(s.a, s.b);
}

// In [0, 1] (LTC_HorizonFraction); closes the lobe's clip. Convex: the sum has one sign.
RTPBR_FN float LTC_LobeEnd(LtcLobe lobe) {
    float sum = lobe.vec.z;
    if (lobe.clip.crossed)
        sum += LTC_EdgeIntegralOf(lobe.clip.exitPoint, lobe.clip.entryPoint).z;
    return LTC_HorizonFraction(abs(sum), LTC_HorizonMass(lobe.minv));
}

// In the lobe's space (Arvo 1995), turned to z >= 0: toward the seen part's solid-angle centroid.
RTPBR_FN rtpbr_float3 LTC_LobeEndVector(LtcLobe lobe) {
    rtpbr_float3 v = lobe.vec;
    if (lobe.clip.crossed)
        v += LTC_EdgeIntegralOf(lobe.clip.exitPoint, lobe.clip.entryPoint);
    return v.z < 0.0f ? -v : v;
}

// ---- stored polygons and the one-call form -------------------------------------------------
// From LTC_PolygonToLocal; fixed trip count, so the compiler can unroll it and index the array
// statically. Read with LTC_LobeEnd or LTC_LobeEndVector.
RTPBR_FN LtcLobe LTC_LobeOverLocal(LtcLocalPolygon local, rtpbr_float3x3 minv) {
    LtcLobe lobe = LTC_LobeBegin(minv);
    if (local.count >= 3) { // fewer: nothing seen (form factor and vector 0)
        for (int i = 0; i < RTPBR_LTC_CLIP_VERTICES; i++) {
            if (i < local.count) {
                rtpbr_float3 b = i + 1 < local.count ? local.v[i + 1] : local.v[0];
                LTC_LobeEdge(lobe, local.v[i], b);
            }
        }
    }
    return lobe;
}

// The integral of the LTC over the part of the polygon above the horizon, in [0, 1]; with
// LTC_Identity() the polygon's Lambertian form factor.
RTPBR_FN float LTC_IntegrateLocalMatrix(LtcLocalPolygon local, rtpbr_float3x3 minv) {
    return LTC_LobeEnd(LTC_LobeOverLocal(local, minv));
}

RTPBR_FN float LTC_IntegrateLocal(LtcLocalPolygon local, rtpbr_float4 ltc1) {
    return LTC_IntegrateLocalMatrix(local, LTC_InverseMatrix(ltc1));
}

RTPBR_FN rtpbr_float3 LTC_IntegrateLocalVector(LtcLocalPolygon local, rtpbr_float4 ltc1) {
    return LTC_LobeEndVector(LTC_LobeOverLocal(local, LTC_InverseMatrix(ltc1)));
}

// LTC_Identity() for Lambertian diffuse. With RTPBR_LTC_CLIPLESS 1 ltc_clipless.h defines it.
#if !RTPBR_LTC_CLIPLESS
RTPBR_FN float LTC_EvaluatePolygon(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, LtcPolygon poly, rtpbr_float4 ltc1, bool twoSided) {
    return LTC_IntegrateLocal(LTC_PolygonToLocal(LTC_Frame(N, V), P, poly, twoSided), ltc1);
}
#endif

// ---- Fresnel -------------------------------------------------------------------------------
// Hill & Heitz 2016: with Schlick's F = f0 + (f90 - f0)(1 - VoH)^5, the integral of f F cos is
// f0 * norm + (f90 - f0) * fresnel exactly (norm, fresnel = ltc2.xy).
RTPBR_FN rtpbr_float3 LTC_FresnelScale(rtpbr_float4 ltc2, rtpbr_float3 f0, float f90) {
    return f0 * ltc2.x + (RTPBR_F3(f90) - f0) * ltc2.y;
}

// Kutz et al. 2021, "Novel aspects of the Adobe Standard Material" (Hoffman 2023): F =
// Schlick(f0) - a VoH (1 - VoH)^6, a chosen so that F is f82 at VoH = 1/7 (about 82 degrees).
RTPBR_FN rtpbr_float3 LTC_FresnelScaleF82(rtpbr_float4 ltc2, rtpbr_float3 f0, rtpbr_float3 f82) {
    const float muBar = 1.0f / 7.0f;
    float m = 1.0f - muBar;
    float m5 = m * m * m * m * m;
    rtpbr_float3 schlickBar = f0 + (RTPBR_F3(1.0f) - f0) * m5;
    rtpbr_float3 a = (schlickBar - f82) / (muBar * m5 * m);
    return f0 * ltc2.x + (RTPBR_F3(1.0f) - f0) * ltc2.y - a * ltc2.z;
}

// F_Conductor (complex IOR eta + i k) at VoH = 1 and 1/7.
RTPBR_FN rtpbr_float3 LTC_FresnelScaleConductor(rtpbr_float4 ltc2, rtpbr_float3 eta, rtpbr_float3 k) {
    return LTC_FresnelScaleF82(ltc2, F_Conductor(1.0f, eta, k), F_Conductor(1.0f / 7.0f, eta, k));
}

// Schlick directly; the exact dielectric and conductor through the F82 model.
RTPBR_FN rtpbr_float3 LTC_FresnelScaleSelected(rtpbr_float4 ltc2, FresnelParams p) {
#if RTPBR_FRESNEL == RTPBR_FRESNEL_CONDUCTOR
    return LTC_FresnelScaleConductor(ltc2, p.eta, p.k);
#elif RTPBR_FRESNEL == RTPBR_FRESNEL_DIELECTRIC
    return LTC_FresnelScaleF82(ltc2, RTPBR_F3(F_Dielectric(1.0f, p.eta.x)),
                               RTPBR_F3(F_Dielectric(1.0f / 7.0f, p.eta.x)));
#else
    return LTC_FresnelScale(ltc2, p.f0, p.f90);
#endif
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_H
