// rtpbr shader library: polygonal area lights with Linearly Transformed Cosines (LTC).
//
// Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines". A BRDF lobe (times the cosine) for one view direction and roughness is
// approximated by D(w) = D_o(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3 with D_o = max(z,0)/pi;
// the integral of D over a polygon is the integral of D_o over the polygon transformed by
// M^-1, which has a closed form (Lambert 1760; Arvo 1995, "Applications of Irradiance Tensors").
//
// Conventions
//   - The local LTC frame: z = N, x = normalize(V - N NoV) (so V lies in the xz plane with
//     x >= 0), y = cross(N, x). Polygons are given by world-space vertex positions and the
//     shading position P; nothing else is assumed about units.
//   - Polygons are convex and planar, 3 to RTPBR_LTC_MAX_VERTICES (8) vertices. Their front
//     face is the side from which the vertices appear counter-clockwise (the OpenGL
//     convention: normal = cross(p1 - p0, p2 - p0) points toward the front). One-sided lights
//     emit from the front only; two-sided from both faces.
//   - Every integral returned is a "form factor" in [0, 1]: the fraction of the LTC's mass
//     above the surface's horizon that falls on the polygon (LTC_LobeEnd divides the clipped
//     integral by LTC_HorizonMass of the matrix it was given, the bilinearly interpolated one).
//     Times ltc2's integrals it can therefore never exceed the interpolated albedo: the energy
//     bound holds whatever the fit of a cell is. Radiance from a light of radiance Le:
//       specular  Lo = Le * LTC_FresnelScale(ltc2, f0, f90) * LTC_EvaluatePolygon(.., ltc1, ..)
//       Lambert   Lo = Le * diffuseColor * LTC_EvaluatePolygon(.., LTC_Identity(), ..)
//   - The library never samples textures. The caller fetches, with bilinear filtering and
//     clamp-to-edge, ltc1 = rtpbr_ltc_*_1 and ltc2 = rtpbr_ltc_*_2 at LTC_LutCoord(NoV,
//     perceptualRoughness), and passes the rtpbr_float4 values in. Table layout: see
//     shaderlib/luts/ltc.md and rtpbr_ltc_tables.h.
//   - ltc1 = (m00, m02, m20, m22): the inverse matrix in the local frame, divided by its
//     middle element, is  M^-1 = | m00 0 m02 |
//                                |  0  1  0  |
//                                | m20 0 m22 |   (rows).
//   - ltc2 = (norm, fresnel, f82, sphere): the integrals over the hemisphere of f cos with
//     F = 1 (the directional albedo), of f cos (1 - VoH)^5 and of f cos VoH (1 - VoH)^6 (for
//     LTC_FresnelScaleF82); a light filling the hemisphere gives exactly them; in .w, at a
//     different coordinate (LTC_SphereLutCoord), the horizon-clipped sphere form factor for
//     the clipless path.
//
// Horizon clipping. The polygon is clipped to the surface's upper hemisphere *before* the
// transform (as O3DE does) and then to the LTC's own support, the half-space
// (M^-1 w).z >= 0, so the transformed polygon lies in z >= 0 where the closed form holds.
// The second clip is where Heitz et al. clip (after the transform; the same plane seen in the
// other space); the first one is what makes light from behind the surface never leak in:
// where the LTC lobe extends below the surface's horizon (grazing views, rough surfaces), the
// transformed horizon is not z = 0 and clipping only in LTC space would integrate light
// arriving from under the surface.
//
// Flags
//   RTPBR_LTC_CLIPLESS  0 (default): exact clipping as above.
//                       1: LTC_EvaluatePolygon uses the sphere proxy of Hill & Heitz 2016
//                       ("Real-Time Area Lighting: a Journey from Research to Production"):
//                       no clipping; the unclipped polygon's vector form factor F is
//                       replaced by the sphere with the same F, clipped to the horizon by
//                       the analytic approximation max((|F|^2 + F.z) / (|F| + 1), 0).
//                       The table form (LTC_SphereFormFactor with ltc2.w at
//                       LTC_SphereLutCoord) is more accurate; errors of both are in ltc.md.
#ifndef RTPBR_LTC_H
#define RTPBR_LTC_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "smith.h"

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

// ltc1 of the identity transform: the clamped cosine itself (Lambertian diffuse).
RTPBR_FN rtpbr_float4 LTC_Identity() { return rtpbr_float4(1.0f, 0.0f, 0.0f, 1.0f); }

// A convex planar polygon: world-space vertex positions v[0 .. count-1].
struct LtcPolygon {
    rtpbr_float3 v[RTPBR_LTC_MAX_VERTICES];
    int count;
};

// A polygon relative to the shading point, in the local LTC frame (the result of
// LTC_PolygonToLocal); count = 0 when the light cannot contribute.
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

// Texture coordinate of the LTC tables for (NoV, perceptual roughness). Texel (i, j) (column i,
// row j) holds roughness i / (SIZE - 1) and sqrt(1 - NoV) = j / (SIZE - 1): the coordinate maps
// those values to texel centres, (i + 0.5) / SIZE, so bilinear filtering interpolates between
// fitted values and never extrapolates (Heitz et al. 2016, the LUT_SCALE/LUT_BIAS of their code).
RTPBR_FN rtpbr_float2 LTC_LutCoord(float NoV, float perceptualRoughness) {
    float u = rtpbr_saturate(perceptualRoughness);
    float v = rtpbr_safe_sqrt(1.0f - rtpbr_saturate(NoV));
    float scale = (float(RTPBR_LTC_SIZE) - 1.0f) / float(RTPBR_LTC_SIZE);
    float bias = 0.5f / float(RTPBR_LTC_SIZE);
    return rtpbr_float2(u * scale + bias, v * scale + bias);
}

// Texture coordinate of the horizon-clipped sphere form factor (ltc2.w) for a vector form
// factor F: column = cos of F's elevation mapped to [0, 1] (z * 0.5 + 0.5), row = |F|
// (= sin^2 of the sphere's angular radius), texel centres as above.
RTPBR_FN rtpbr_float2 LTC_SphereLutCoord(rtpbr_float3 F) {
    float len = length(F);
    float z = len > 0.0f ? F.z / len : 0.0f;
    float scale = (float(RTPBR_LTC_SIZE) - 1.0f) / float(RTPBR_LTC_SIZE);
    float bias = 0.5f / float(RTPBR_LTC_SIZE);
    return rtpbr_float2(rtpbr_saturate(z * 0.5f + 0.5f) * scale + bias, rtpbr_saturate(len) * scale + bias);
}

// ---- geometry ------------------------------------------------------------------------------

// World-to-local rotation (rows x, y, z of the LTC frame). When V is along N any tangent
// will do: the fitted lobes are isotropic there.
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

// Sutherland-Hodgman clip of a convex polygon to the half-space dot(p, n) >= 0 (a plane
// through the shading point). Points on the plane are kept; the output has at most one
// vertex more than the input (capped at the buffer size for non-convex input).
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

// Shared part of LTC_PolygonToLocal and LTC_PolygonToLocalUnclipped: the polygon relative to
// P in the local frame, oriented so that it appears clockwise from P (its Newell normal
// points away from P), or count = 0 when it cannot contribute: fewer than 3 or more than 8
// vertices, zero area (collinear or coincident vertices), P on the polygon's plane (edge-on,
// or a vertex touching P: |plane distance| <= 1e-7 of the polygon's extent), or P behind a
// one-sided light. NaN input also gives count = 0.
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

// The polygon in the local frame relative to P, clipped to the surface's upper hemisphere
// (count = 0 when nothing is left or the light cannot contribute; see LTC_PolygonRelative).
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

// The polygon in the local frame relative to P, not clipped (for the clipless path).
RTPBR_FN LtcLocalPolygon LTC_PolygonToLocalUnclipped(rtpbr_float3x3 frame, rtpbr_float3 P, LtcPolygon poly, bool twoSided) {
    return LTC_PolygonRelative(frame, P, poly, twoSided);
}

// ---- integration ---------------------------------------------------------------------------

// M^-1 in the local frame from the table value ltc1 = (m00, m02, m20, m22).
RTPBR_FN rtpbr_float3x3 LTC_InverseMatrix(rtpbr_float4 ltc1) {
    return rtpbr_mat3_rows(rtpbr_float3(ltc1.x, 0.0f, ltc1.y), rtpbr_float3(0.0f, 1.0f, 0.0f),
                           rtpbr_float3(ltc1.z, 0.0f, ltc1.w));
}

// The mass of the LTC with inverse matrix minv above the surface's horizon z = 0, in [0, 1]:
// the directions w with w.z >= 0 are, in the cosine's space (w_o = M^-1 w), the half-space
// n . w_o >= 0 with n = M^-1 x x M^-1 y (the images of the horizon's axes, oriented toward
// M^-1 z), which holds (1 + n.z / |n|) / 2 of the clamped cosine (the sky view factor of a
// tilted plane). For n.z < 0 the same as (n.x^2 + n.y^2) / (2 |n| (|n| - n.z)): no
// cancellation for a lobe almost all below the horizon (fitted cells reach 1e-15). Any
// general M^-1 (anisotropic stretches included); 0 for a singular or NaN matrix.
RTPBR_FN float LTC_HorizonMass(rtpbr_float3x3 minv) {
    rtpbr_float3 cx = rtpbr_mul(minv, rtpbr_float3(1.0f, 0.0f, 0.0f));
    rtpbr_float3 cy = rtpbr_mul(minv, rtpbr_float3(0.0f, 1.0f, 0.0f));
    rtpbr_float3 cz = rtpbr_mul(minv, rtpbr_float3(0.0f, 0.0f, 1.0f));
    rtpbr_float3 n = cross(cx, cy);
    n = dot(n, cz) < 0.0f ? -n : n;
    float len = length(n);
    if (!(len > 0.0f))
        return 0.0f;
    float mass = n.z >= 0.0f ? 0.5f + 0.5f * (n.z / len) : 0.5f * (n.x * n.x + n.y * n.y) / (len * (len - n.z));
    return rtpbr_saturate(mass);
}

// A clipped LTC integral ff as the fraction of the lobe's mass above the horizon (mass,
// LTC_HorizonMass): ff <= mass mathematically, so the fraction lies in [0, 1]; it is kept
// there against rounding (a lobe of mass 1e-15 sums edge terms of order 1). 0 where nothing
// is above the horizon.
RTPBR_FN float LTC_HorizonFraction(float ff, float mass) {
    return mass > 0.0f && ff > 0.0f ? min(ff / mass, 1.0f) : 0.0f;
}

// ---- streamed integration (the real-time path) ----------------------------------------------
// A light is integrated edge by edge, without ever storing the clipped polygon (GPU compilers
// turn run-time-indexed private arrays into select chains or scratch memory). The caller walks
// the light's edges a -> b as vectors from the shading point in the LTC frame (LTC_Frame),
// clips each to the surface's upper hemisphere with LTC_ClipEdge (one clip per light), and
// hands every surviving segment to each lobe: LTC_LobeEdge for an LTC lobe (which clips it
// again to the lobe's own support, in the lobe's space) and LTC_EdgeIntegral for the
// Lambertian form factor vector. After the last edge, LTC_ClipClose gives the segment that
// closes the clipped polygon along the horizon, and LTC_LobeEnd the lobe's form factor.
// Valid for convex planar polygons (a half-space clip then leaves one exit and one entry).

// Heitz, Dupuy, Hill & Neubelt 2017, the fitted edge integral of their LTC code (ltc_code,
// "IntegrateEdgeVec"): theta / sin(theta) / (2 pi) for two unit vectors with x = cos(theta),
// as a rational fit in |x| (relative error below 2e-6 on [-1, 1], measured in tests/shaderlib/ltc);
// for x < 0 the identity theta / sin = pi / sin - (pi - theta) / sin folds it onto |x|. sinT =
// |a x b|, passed in so that opposite vectors (sin -> 0) stay consistent with the cross product.
RTPBR_FN float LTC_EdgeFactor(float x, float sinT) {
    float y = abs(x);
    float a = 0.8543985f + (0.4965155f + 0.0145206f * y) * y;
    float b = 3.4175940f + (4.1616724f + y) * y;
    float v = a / b;
    return x >= 0.0f ? v : 0.5f / max(sinT, 1e-7f) - v;
}

// The edge term of Lambert's formula divided by 2 pi for unit vectors a, b:
// theta / (2 pi sin theta) * cross(a, b) (theta the angle between them); summed over a
// polygon's edges it is the polygon's vector form factor (Arvo 1995), up to orientation.
RTPBR_FN rtpbr_float3 LTC_EdgeIntegral(rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 c = cross(a, b);
    return c * LTC_EdgeFactor(dot(a, b), length(c));
}

// The z component of LTC_EdgeIntegral alone (the form factor against the cosine lobe).
RTPBR_FN float LTC_EdgeIntegralZ(rtpbr_float3 a, rtpbr_float3 b) {
    rtpbr_float3 c = cross(a, b);
    return c.z * LTC_EdgeFactor(dot(a, b), length(c));
}

// v / |v|, and 0 for the zero vector (a vertex at the shading point contributes nothing).
RTPBR_FN rtpbr_float3 LTC_SafeNormalize(rtpbr_float3 v) {
    return v * rtpbr_rsqrt(max(dot(v, v), 1e-30f));
}

// The state of a streamed clip of a convex polygon to the half-space z >= 0 (a plane through
// the shading point): where its boundary leaves the half-space and where it comes back.
struct LtcClipper {
    rtpbr_float3 exitPoint;
    rtpbr_float3 entryPoint;
    bool crossed;
};

// A clipped edge: the segment a -> b, or nothing (valid = false).
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

// The part of the edge a -> b in z >= 0 (points on the plane are inside); records the exit
// and entry points for LTC_ClipClose.
RTPBR_FN LtcSegment LTC_ClipEdge(RTPBR_INOUT(LtcClipper) clip, rtpbr_float3 a, rtpbr_float3 b) {
    bool inA = a.z >= 0.0f;
    bool inB = b.z >= 0.0f;
    // a.z and b.z have opposite signs when the edge crosses: a.z - b.z != 0, t in [0, 1].
    float t = inA != inB ? a.z / (a.z - b.z) : 0.0f;
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

// The segment along the plane that closes the clipped polygon (valid when it was crossed).
RTPBR_FN LtcSegment LTC_ClipClose(LtcClipper clip) {
    LtcSegment s;
    s.a = clip.exitPoint;
    s.b = clip.entryPoint;
    s.valid = clip.crossed;
    return s;
}

// One LTC lobe being integrated over a streamed polygon: its M^-1 (LTC_InverseMatrix, or a
// general matrix such as LTC_AnisotropicInverseMatrix's), the clip to its support
// (M^-1 w).z >= 0 done in its own space (a linear map keeps segments straight), and the sum
// of the edge integrals.
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

// Adds the segment a -> b (vectors from the shading point in the LTC frame, already clipped to
// the surface's upper hemisphere) to the lobe.
RTPBR_FN void LTC_LobeEdge(RTPBR_INOUT(LtcLobe) lobe, rtpbr_float3 a, rtpbr_float3 b) {
    LtcSegment s = LTC_ClipEdge(lobe.clip, rtpbr_mul(lobe.minv, a), rtpbr_mul(lobe.minv, b));
    if (s.valid) // the whole edge vector; callers that never read x, y let the compiler drop them
        lobe.vec += LTC_EdgeIntegral(LTC_SafeNormalize(s.a), LTC_SafeNormalize(s.b));
}

// The lobe's form factor in [0, 1] after the last edge (closes its own clip): the fraction of
// the lobe's mass above the horizon that the (horizon-clipped) polygon holds
// (LTC_HorizonFraction). A convex polygon in z >= 0 gives a sum of one sign (its
// orientation's).
RTPBR_FN float LTC_LobeEnd(LtcLobe lobe) {
    float sum = lobe.vec.z;
    if (lobe.clip.crossed)
        sum += LTC_EdgeIntegralZ(LTC_SafeNormalize(lobe.clip.exitPoint), LTC_SafeNormalize(lobe.clip.entryPoint));
    return LTC_HorizonFraction(abs(sum), LTC_HorizonMass(lobe.minv));
}

// The lobe's vector form factor in its own space (Arvo 1995) after the last edge, turned to
// z >= 0: its direction is that of the solid-angle centroid of the part of the polygon the
// lobe sees (the polygon clipped to the horizon and to the lobe's support, in the LTC's space).
RTPBR_FN rtpbr_float3 LTC_LobeEndVector(LtcLobe lobe) {
    rtpbr_float3 v = lobe.vec;
    if (lobe.clip.crossed)
        v += LTC_EdgeIntegral(LTC_SafeNormalize(lobe.clip.exitPoint), LTC_SafeNormalize(lobe.clip.entryPoint));
    return v.z < 0.0f ? -v : v;
}

// Anisotropic lobes (ours, from the LTC construction of Heitz et al. 2016): an anisotropic
// GGX lobe of alphas (at, ab) is approximated by the isotropic lobe of alpha = sqrt(at ab)
// stretched about its centre c (the mirror direction) by k = sqrt(at / ab) along the
// anisotropy direction and by 1 / k across it: the slope distribution of D_aniso is D_iso's
// stretched so (GGX and Beckmann are stretch invariant), and near c directions follow slopes
// linearly. As an LTC, M_aniso = A M_iso with A = k e1 e1^T + (1 / k) e2 e2^T + c c^T (e1 the
// anisotropy direction made orthogonal to c, e2 = c x e1; det A = 1), so the polygon integral
// is the isotropic LTC's over A^-1 P: the lobe's inverse matrix is M^-1 A^-1
// (LTC_AnisotropicInverseMatrix), applied to polygons already clipped to the horizon, so only
// directions above it count. c and e1 unit and orthogonal; k >= 1 when at >= ab (NaN or
// <= 0: no stretch).
//
// A^-1 v for the anisotropic stretch A (A^-1 is symmetric).
RTPBR_FN rtpbr_float3 LTC_AnisotropicUnstretch(rtpbr_float3 v, rtpbr_float3 c, rtpbr_float3 e1, float k) {
    float kk = k > 0.0f ? k : 1.0f;
    rtpbr_float3 e2 = cross(c, e1);
    return e1 * (dot(e1, v) / kk) + e2 * (dot(e2, v) * kk) + c * dot(c, v);
}

// M^-1 A^-1: the inverse matrix of the isotropic LTC ltc1 stretched by A (rows of M^-1 times
// the symmetric A^-1), for LTC_LobeBegin. c, e1 unit and orthogonal, k >= 1.
RTPBR_FN rtpbr_float3x3 LTC_AnisotropicInverseMatrix(rtpbr_float4 ltc1, rtpbr_float3 c, rtpbr_float3 e1, float k) {
    return rtpbr_mat3_rows(LTC_AnisotropicUnstretch(rtpbr_float3(ltc1.x, 0.0f, ltc1.y), c, e1, k),
                           LTC_AnisotropicUnstretch(rtpbr_float3(0.0f, 1.0f, 0.0f), c, e1, k),
                           LTC_AnisotropicUnstretch(rtpbr_float3(ltc1.z, 0.0f, ltc1.w), c, e1, k));
}

// The albedo of the stretched lobe against the isotropic one's (the table's norm): the part
// of the stretched LTC's mass that stays above the horizon against the isotropic LTC's,
// capped at 1. LTC_LobeEnd normalises each lobe to its own mass above the horizon, so a
// light filling the hemisphere gives the table's albedo for either lobe; but a stretch that
// leans the lobe under the horizon loses that part of the BRDF's albedo too (masking): scaled
// by this ratio, 108 square lights over anisotropic GGX come within 10.7 % of Monte Carlo
// (mean relative error; 12.5 % without it, tests/shaderlib/ltc/test_ltc_mc.cpp). Capped, the
// energy bound stays: never more than the table's albedo.
RTPBR_FN float LTC_AnisotropicAlbedoScale(rtpbr_float4 ltc1, rtpbr_float3x3 stretchedMinv) {
    float iso = LTC_HorizonMass(LTC_InverseMatrix(ltc1));
    float stretched = LTC_HorizonMass(stretchedMinv);
    return iso > 0.0f ? min(stretched / iso, 1.0f) : 0.0f;
}

// The streamed lobe integration (LTC_LobeBegin, LTC_LobeEdge) over a stored local polygon
// (from LTC_PolygonToLocal), with fixed trip count: the compiler can unroll it and index the
// array statically. Read with LTC_LobeEnd or LTC_LobeEndVector.
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

// The form factor (in [0, 1]) of a local polygon (from LTC_PolygonToLocal) under the LTC
// given by ltc1: the integral of the LTC distribution over the part of the polygon above the
// surface's horizon. With ltc1 = LTC_Identity() it is the polygon's Lambertian form factor.
// LTC_IntegrateLocalMatrix takes any M^-1 (e.g. LTC_AnisotropicInverseMatrix's).
RTPBR_FN float LTC_IntegrateLocalMatrix(LtcLocalPolygon local, rtpbr_float3x3 minv) {
    return LTC_LobeEnd(LTC_LobeOverLocal(local, minv));
}

RTPBR_FN float LTC_IntegrateLocal(LtcLocalPolygon local, rtpbr_float4 ltc1) {
    return LTC_IntegrateLocalMatrix(local, LTC_InverseMatrix(ltc1));
}

// ---- the point correction (issue 19) --------------------------------------------------------
// A single LTC cannot follow the true lobe everywhere: near the horizon and on the side of the
// viewer (a light between the eye and a far floor) it puts light where the BRDF has almost
// none, and for rough lobes near the horizon too little. For a light that holds a small part
// of the lobe, the integral is about the lobe's value at the light times the light's size, so
// the LTC's error there is the ratio k of the two lobes' values at the light: rtpbr multiplies
// the LTC result by k, taken at the centre of the part of the light the LTC sees, faded out as
// the light holds more of the LTC's mass (the LTC integral itself is then right by
// construction). A k above 1 is trusted only where the true lobe is not much narrower than the
// light or is no streak: a view and a light both near the horizon on the mirror side make the
// lobe a streak across the plane of incidence about alpha |V + L| wide (the half vector turns
// by dL / |V + L|), and one point at the streak's centre overstates a light wider than that
// (LTC_PointWidthRatio; the |V + L| test since the fifth round). Measured in
// shaderlib/luts/ltc.md ("Fourth round"): the random lights of rtpbr-ltc-validate and the
// grazing floors of rtpbr-ltc-floor.

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

RTPBR_FN LtcPoint LTC_LobePoint(rtpbr_float3 F, rtpbr_float4 ltc1) {
    // M^-1 = [[a, 0, b], [0, 1, 0], [c, 0, d]] (rows): det M F = (d Fx - b Fz, det Fy, a Fz - c Fx)
    float det = ltc1.x * ltc1.w - ltc1.y * ltc1.z;
    rtpbr_float3 u = rtpbr_float3(ltc1.w * F.x - ltc1.y * F.z, det * F.y, ltc1.x * F.z - ltc1.z * F.x);
    float uu = dot(u, u), f2 = dot(F, F);
    LtcPoint p;
    p.dir = u * ((det < 0.0f ? -1.0f : 1.0f) * rtpbr_rsqrt(max(uu, 1e-30f)));
    float den = RTPBR_PI * f2 * f2 * det * det * LTC_HorizonMass(LTC_InverseMatrix(ltc1));
    p.density = f2 > 1e-16f && den > 0.0f ? max(F.z, 0.0f) * uu * sqrt(uu) / den : 0.0f;
    return p;
}

// The lobe's width across the plane of incidence over the light's angular radius: alpha |V + w|
// (vPlusW = the length of V + LtcPoint.dir, both unit) over sqrt(|F|), F the light's
// (horizon-clipped) vector form factor, whose length is about the solid angle / pi of a small
// light (so sqrt(|F|) about its angular radius). For LTC_PointFactor. The streak it guards
// against needs |V + w| small (both directions near the horizon on opposite sides: |V + w| =
// 2 V.h): from |V + w| = 0.6 to 1 the ratio is raised to at least 1.5 (LTC_PointFactor's gate
// wide open), so that a light beside or behind a lobe, however much wider than it, gets its
// ratio (fifth round: `quad_light`'s sides, the random lights).
RTPBR_FN float LTC_PointWidthRatio(float alpha, float vPlusW, float formFactorLength) {
    float noStreak = vPlusW > 0.6f ? min((vPlusW - 0.6f) * 2.5f, 1.0f) * 1.5f : 0.0f; // NaN -> 0
    return max(alpha * vPlusW * rtpbr_rsqrt(max(formFactorLength, 1e-12f)), noStreak);
}

// The factor on the LTC result: fCos = the true f NoL at LtcPoint.dir (F = 1, the lobe the
// table was fitted to), ltcValue = norm x LtcPoint.density (the table's scale, ltc2.x, times
// the density), ff = the LTC's form factor of the light (LTC_LobeEnd), widthRatio =
// LTC_PointWidthRatio. With k = fCos / ltcValue: k below 1 as it is; above 1 (at most 16),
// 1 + (k - 1) smoothstep(1, 1.5, widthRatio); then faded, k t + (1 - t) with t = (1 - ff)^16.
// 1 for NaN or zero values. The constants were chosen among 1-64 (fade), 0.5-2 / 1-4 (the
// width's smoothstep) on the two measurements above.
RTPBR_FN float LTC_PointFactor(float fCos, float ltcValue, float ff, float widthRatio) {
    float k = ltcValue > 0.0f && fCos >= 0.0f ? min(fCos / ltcValue, 16.0f) : 1.0f; // NaN: 1
    if (k > 1.0f) {
        float x = widthRatio > 1.0f ? min((widthRatio - 1.0f) * 2.0f, 1.0f) : 0.0f; // NaN: 0
        k = 1.0f + (k - 1.0f) * (x * x * (3.0f - 2.0f * x));
    }
    // k t + (1 - t), t = u^16, u = 1 - ff; 1 - t = ff (1 + u)(1 + u^2)(1 + u^4)(1 + u^8) without
    // the cancellation of 1 - t (a factor near 0 keeps its relative precision)
    float f = rtpbr_saturate(ff);
    float u = 1.0f - f;
    float u2 = u * u;
    float u4 = u2 * u2;
    float u8 = u4 * u4;
    return k * (u8 * u8) + f * (1.0f + u) * (1.0f + u2) * (1.0f + u4) * (1.0f + u8);
}

// ---- the tail estimate (issue 19, fifth round) -----------------------------------------------
// An LTC is a transformed clamped cosine: it is exactly 0 beyond its own horizon, while the
// GGX / Beckmann lobe has a long tail. A light far from the lobe's peak (beside it, or beyond
// it on a grazing floor) gets little or nothing from the LTC, and the point correction cannot
// scale nothing up. There the true lobe varies slowly across the light, so the midpoint rule
// holds: the integral is about f (F = 1, without the cosine) at the direction c = F / |F| of
// the light's (horizon-clipped) vector form factor F, times pi F.z (the light's cosine-weighted
// solid angle). rtpbr takes the larger of that and the point-corrected LTC, where the light
// lies in the LTC's own tail (the cosine of the lobe's vector form factor Fl, LTC_LobeEndVector,
// in the LTC's original space: its mass's mean direction, below 0.2, fading out by 0.4) and
// the LTC is thin over it (LTC_PointTailWeight). Measured in shaderlib/luts/ltc.md ("Fifth
// round").

// The tail estimate in units of the LTC result before the table's scale: f pi formFactor /
// norm (norm = ltc2.x, as LTC_PointFactor's ltcValue), f = D V at c (the BRDF with F = 1),
// formFactor = F.z. 0 for NaN, negative or zero inputs.
RTPBR_FN float LTC_PointTail(float f, float formFactor, float norm) {
    float t = norm > 0.0f && f > 0.0f && formFactor > 0.0f ? f * RTPBR_PI * formFactor / norm : 0.0f;
    return t < 3.0e38f ? t : 0.0f; // +Inf (f overflowing) -> 0
}

// How much of the tail estimate to trust: where the light lies in the LTC's tail, and the LTC
// is thin over it. From the lobe's vector form factor Fl: 1 where its cosine Fl.z / |Fl| is at
// most 0.2 (and where the LTC sees nothing), 0 from 0.4 up, smoothstep between; times 1 where
// the LTC's form factor ltcFF is at most half the light's cosine form factor formFactor (the
// LTC's mean density over the light is below half the cosine's), 0 from twice, smoothstep
// between (ratio ltcFF / formFactor): a light close below a narrow lobe's peak has a small
// cosine there but a dense LTC, and the midpoint rule overstates it. (0.1-0.3, 0.3-0.5 and
// ratios 0.1-0.5 to 1-4 measured too: the fifth round's table.)
RTPBR_FN float LTC_PointTailWeight(rtpbr_float3 lobeVector, float ltcFF, float formFactor) {
    float l2 = dot(lobeVector, lobeVector);
    float c = l2 > 1e-30f ? lobeVector.z * rtpbr_rsqrt(l2) : 0.0f;
    float x = c > 0.2f ? min((c - 0.2f) * 5.0f, 1.0f) : 0.0f; // NaN -> 0
    float rho = formFactor > 0.0f ? ltcFF / formFactor : 0.0f; // NaN ltcFF -> 0 below
    float y = rho > 0.5f ? min((rho - 0.5f) * (1.0f / 1.5f), 1.0f) : 0.0f;
    return (1.0f - x * x * (3.0f - 2.0f * x)) * (1.0f - y * y * (3.0f - 2.0f * y));
}

// The corrected LTC result (before the table's scale): the larger of the point-corrected LTC
// (LTC result x LTC_PointFactor) and the weighted tail estimate. NaN in either: the other.
RTPBR_FN float LTC_PointCombine(float corrected, float tail, float weight) {
    float a = corrected >= 0.0f ? corrected : 0.0f;
    float b = tail * weight;
    return b > a ? b : a;
}

// ---- the streak estimate (issue 19, sixth round) -----------------------------------------
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
// lateral extent there). Ours; measured on rtpbr-ltc-floor's floors against the quadrature in
// shaderlib/luts/ltc.md ("Sixth round"). Streamed like LtcLobe over the (horizon-clipped)
// edges: one pass for the elevations (LTC_StreakEdge; it can share the pass that sums the
// light's vector form factor F), LTC_StreakNodes(F), one pass for the chords
// (LTC_StreakChordEdge), then LTC_StreakEnd.
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
// far corners (a light turned about the normal: a range widened by its corners put the nodes'
// chords over elevations the streak does not reach, +18% a tenth of the light off its axis).
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

// The estimate: the integral of D V NoL (F = 1: the lobe the tables were fitted to, with
// the configured Smith term) over the light, from both passes (.x), and how far to trust it
// (.y, in [0, 1]), the product of three factors, each 0 below its first constant, 1 above its
// second, smoothstep between (constants chosen among others on rtpbr-ltc-floor's floors and
// rtpbr-ltc-validate's random lights: the sixth round's table in ltc.md):
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
#ifndef RTPBR_LTC_STREAK_Q0
#define RTPBR_LTC_STREAK_Q0 0.5f
#endif
#ifndef RTPBR_LTC_STREAK_Q1
#define RTPBR_LTC_STREAK_Q1 1.0f
#endif
#ifndef RTPBR_LTC_STREAK_R0
#define RTPBR_LTC_STREAK_R0 0.4f
#endif
#ifndef RTPBR_LTC_STREAK_R1
#define RTPBR_LTC_STREAK_R1 0.7f
#endif
#ifndef RTPBR_LTC_STREAK_W0
#define RTPBR_LTC_STREAK_W0 1.0f
#endif
#ifndef RTPBR_LTC_STREAK_W1
#define RTPBR_LTC_STREAK_W1 2.0f
#endif
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
    float sx0 = LTC_StreakSlope(s.ends.x, s.ends.y, vLocal), sx1 = LTC_StreakSlope(s.ends.z, s.ends.w, vLocal);
    float near2 = sx0 * sx1 <= 0.0f ? 0.0f : min(sx0 * sx0, sx1 * sx1);
    float q = abs(sx1 - sx0) * rtpbr_rsqrt(al2 + near2);
    float rho = max(term[0], term[1]) > 0.0f ? min(term[0], term[1]) / max(term[0], term[1]) : 0.0f;
    float trust = (1.0f - LTC_StreakRamp(q, RTPBR_LTC_STREAK_Q0, RTPBR_LTC_STREAK_Q1)) *
                  LTC_StreakRamp(rho, RTPBR_LTC_STREAK_R0, RTPBR_LTC_STREAK_R1) *
                  LTC_StreakRamp(widest, RTPBR_LTC_STREAK_W0, RTPBR_LTC_STREAK_W1);
    bool finite = sum >= 0.0f && sum < 3.0e38f;
    return finite ? rtpbr_float2(sum, trust) : RTPBR_F2(0.0f);
}

// V.h at the middle of the light's elevation range in the plane of incidence (after
// LTC_StreakNodes): where the streak's Fresnel is taken (the tables' Fresnel scale averages it
// over the whole lobe, ~10% low for a copper streak at grazing: tests/engine, ltc_streak_floor).
RTPBR_FN float LTC_StreakVoH(LtcStreak s, rtpbr_float3 vLocal) {
    rtpbr_float3 q = rtpbr_float3(s.ends.x + s.ends.z, 0.0f, s.ends.y + s.ends.w);
    rtpbr_float3 h = vLocal + q * rtpbr_rsqrt(max(dot(q, q), 1e-30f));
    return rtpbr_saturate(dot(vLocal, h) * rtpbr_rsqrt(max(dot(h, h), 1e-30f)));
}

// How much of the streak estimate to take: 1 - smoothstep(0.35, 0.75, |V + c|), c = +-F / |F|
// the direction of the light's vector form factor (turned to z >= 0; |V + c| = 2 V.h is small
// only on the mirror side near the horizon). (0.6-1.0, 0.3-0.7, 0.4-0.8 and others measured
// too: the sixth round's table.) 0 for NaN or zero F.
#ifndef RTPBR_LTC_STREAK_V0
#define RTPBR_LTC_STREAK_V0 0.35f
#endif
#ifndef RTPBR_LTC_STREAK_V1
#define RTPBR_LTC_STREAK_V1 0.75f
#endif
RTPBR_FN float LTC_StreakWeight(rtpbr_float3 vLocal, rtpbr_float3 F) {
    float l2 = dot(F, F);
    float v = l2 > 1e-30f ? length(vLocal + F * ((F.z < 0.0f ? -1.0f : 1.0f) * rtpbr_rsqrt(l2))) : 1.0f;
    return 1.0f - LTC_StreakRamp(v, RTPBR_LTC_STREAK_V0, RTPBR_LTC_STREAK_V1); // NaN -> 1 -> weight 0
}

// Whether a light can get any trust (LTC_StreakEnd's third factor): its extent across the
// plane of incidence, at most its angular diameter (bounding sphere of radius r at distance d:
// 2 r / sqrt(d^2 - r^2) = 2 tan(asin(r / d)), above the angle), must reach RTPBR_LTC_STREAK_W0
// lobe widths h.z alpha, and h.z >= NoV. A cheap test before the passes (the engine's); false
// only where the estimate's trust would be 0.
RTPBR_FN bool LTC_StreakCandidate(float radius, float distance, float alpha, float NoV) {
    float d2 = distance * distance - radius * radius;
    return !(d2 > 0.0f) || 2.0f * radius >= RTPBR_LTC_STREAK_W0 * max(alpha, 1e-3f) * NoV * sqrt(d2);
}

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

// The vector of LTC_LobeEndVector for a stored local polygon (tools and tests).
RTPBR_FN rtpbr_float3 LTC_IntegrateLocalVector(LtcLocalPolygon local, rtpbr_float4 ltc1) {
    return LTC_LobeEndVector(LTC_LobeOverLocal(local, LTC_InverseMatrix(ltc1)));
}

// The vector form factor (Arvo 1995) of an unclipped local polygon (from
// LTC_PolygonToLocalUnclipped) transformed by M^-1: F = (1 / 2pi) sum of the edge vectors,
// pointing toward the polygon; |F| is the form factor of the polygon seen head-on and F.z its
// (signed, unclipped) form factor against the LTC's cosine.
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
// is F, from the table value sphereLut = ltc2.w fetched at LTC_SphereLutCoord(F).
RTPBR_FN float LTC_SphereFormFactor(rtpbr_float3 F, float sphereLut) {
    return min(rtpbr_pos(length(F) * sphereLut), 1.0f);
}

// Hill & Heitz 2016 (the cheap form of their course code): the same without a table,
// max((|F|^2 + F.z) / (|F| + 1), 0). Exact for a sphere entirely above the horizon.
RTPBR_FN float LTC_SphereFormFactorApprox(rtpbr_float3 F) {
    float l = length(F);
    return min(rtpbr_pos((l * l + F.z) / (l + 1.0f)), 1.0f);
}

// One-call form: the form factor of a polygon light at P for the lobe ltc1 (LTC_Identity() for
// Lambertian diffuse). Exact clipping unless RTPBR_LTC_CLIPLESS (analytic sphere proxy).
RTPBR_FN float LTC_EvaluatePolygon(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, LtcPolygon poly, rtpbr_float4 ltc1, bool twoSided) {
    rtpbr_float3x3 frame = LTC_Frame(N, V);
#if RTPBR_LTC_CLIPLESS
    return LTC_HorizonFraction(LTC_SphereFormFactorApprox(LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(frame, P, poly, twoSided), ltc1)),
                               LTC_HorizonMass(LTC_InverseMatrix(ltc1)));
#else
    return LTC_IntegrateLocal(LTC_PolygonToLocal(frame, P, poly, twoSided), ltc1);
#endif
}

// ---- Fresnel -------------------------------------------------------------------------------

// Hill & Heitz 2016: with Schlick's F = f0 + (f90 - f0)(1 - VoH)^5, the integral of f F cos is
// f0 * norm + (f90 - f0) * fresnel exactly (norm, fresnel = ltc2.xy).
RTPBR_FN rtpbr_float3 LTC_FresnelScale(rtpbr_float4 ltc2, rtpbr_float3 f0, float f90) {
    return f0 * ltc2.x + (RTPBR_F3(f90) - f0) * ltc2.y;
}

// Kutz et al. 2021, "Novel aspects of the Adobe Standard Material" (the F82 model; Hoffman
// 2023): F = Schlick(f0) - a VoH (1 - VoH)^6 with a chosen so that F matches f82, the true
// reflectance at VoH = 1/7 (about 82 degrees). Its integral uses ltc2.z.
RTPBR_FN rtpbr_float3 LTC_FresnelScaleF82(rtpbr_float4 ltc2, rtpbr_float3 f0, rtpbr_float3 f82) {
    const float muBar = 1.0f / 7.0f;
    float m = 1.0f - muBar;
    float m5 = m * m * m * m * m;
    rtpbr_float3 schlickBar = f0 + (RTPBR_F3(1.0f) - f0) * m5;
    rtpbr_float3 a = (schlickBar - f82) / (muBar * m5 * m);
    return f0 * ltc2.x + (RTPBR_F3(1.0f) - f0) * ltc2.y - a * ltc2.z;
}

// The exact conductor option: the F82 model fitted to F_Conductor (complex IOR eta + i k)
// at normal incidence and at VoH = 1/7.
RTPBR_FN rtpbr_float3 LTC_FresnelScaleConductor(rtpbr_float4 ltc2, rtpbr_float3 eta, rtpbr_float3 k) {
    return LTC_FresnelScaleF82(ltc2, F_Conductor(1.0f, eta, k), F_Conductor(1.0f / 7.0f, eta, k));
}

// The Fresnel model selected by RTPBR_FRESNEL: Schlick directly; the exact dielectric and
// conductor through the F82 model.
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
