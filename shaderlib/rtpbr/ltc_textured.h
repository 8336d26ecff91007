// rtpbr shader library: where to read a textured area light's prefiltered emission.
//
// Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines", section 6 (textured lights): the integral of the LTC D times the
// light's emission T over the light is approximated by the form factor times T prefiltered
// (blurred) around one point of the light: Lo = Le * E * T_filtered(uv, footprint). The
// library never samples a texture; it returns where to read (uv) and how blurred (footprint),
// and the host reads its prefiltered mip chain there.
//
// The point read: the ray along the LTC's vector form factor F over the light (the mean
// direction of the light as the lobe sees it, horizon-clipped; LTC_LobeEndVector) meets the
// light's plane there (in the LTC's space, where the lobe is a clamped cosine). Heitz et al.'s
// demo (selfshadow/ltc_code) reads at the orthogonal projection of the shading point onto the
// plane instead. tests/shaderlib/ltc/test_ltc_shapes.cpp measures both against the exact
// lobe-weighted mean of (u, v) over the light (what a linear emission integrates to) in twelve
// cases: F's point is never farther; it is within 0.031 of the mean for lights above the
// horizon, within 0.087 for walls the horizon cuts, and exact for a light parallel to the
// horizon in the LTC's space (at height h, F = (h / pi) int p / r^4 dA, so F h / F.z is the
// mean of p under the cosine's own weights h^2 / r^4 dA). The projection is off by 0.26 to
// 0.84 in six of the twelve (it ignores both the clip and where the lobe looks), and by 5.5
// light widths for a small far light (its foot point is far off the light; the demo's coarse
// mip then hides it).
//
// The footprint: d / sqrt(A), with d the plane's distance and A the light's area in the LTC's
// space: a clamped cosine facing a plane at distance d puts half of its mass on the plane
// within radius d of the foot point (1 - d^2 / (d^2 + R^2) = 1/2 at R = d), so this is that
// radius in units of the light's size. A host whose mip k blurs with a radius of 2^k texels
// reads lod = log2(footprint * texture size), clamped to its chain. Measured end to end (the
// same test, an emission 1/2 + 1/2 cos(2 pi k u) cos(2 pi k v) blurred by a Gaussian of that
// half-mass radius, sigma = footprint / 1.1774): a sharp lobe's reflection of a screen reads
// within 0.4-5.9 % of the exact integral (4-50 % unblurred), the lobes wider than their light
// within 2.5 %; the worst, 16-21 % at k = 1, 2, is a glossy lobe over a near large wall,
// where one blurred read cannot stand for a wide lobe over an uneven emission.
//
// Conventions: ltc.h's. The light is the parallelogram corner + s edgeS + t edgeT, s, t in
// [0, 1], with texture coordinate (s, t) (flip t on upload if the texture's rows run the other
// way); a quad light's vertices v0..v3 are corner = v0, edgeS = v1 - v0, edgeT = v3 - v0.
//
// Public functions
//   LTC_TextureLookup          (u, v, footprint) for one lobe, from its M^-1 and F
//   LTC_TextureLookupProjected the same at the demo's point (the orthogonal projection)
#ifndef RTPBR_LTC_TEXTURED_H
#define RTPBR_LTC_TEXTURED_H

#include "lang.h"
#include "config.h"
#include "ltc.h"

RTPBR_NAMESPACE_BEGIN

// (s, t) of the point q of the plane through c with edges e1, e2 (all in the LTC's space), and
// the footprint; q is the plane's point along dir from the shading point (the origin).
RTPBR_FN rtpbr_float3 LTC_TexturePlanePoint(rtpbr_float3 c, rtpbr_float3 e1, rtpbr_float3 e2, rtpbr_float3 dir) {
    rtpbr_float3 n = cross(e1, e2);
    float nn = dot(n, n);
    float nc = dot(n, c); // the plane's distance times |n|
    float nd = dot(n, dir);
    if (!(nn > 0.0f) || !(abs(nd) > 1e-7f * sqrt(nn * dot(dir, dir))))
        return rtpbr_float3(0.5f, 0.5f, 0.0f); // degenerate light, or dir along its plane
    rtpbr_float3 r = dir * (nc / nd) - c;
    float a = dot(e1, e1), b = dot(e1, e2), g = dot(e2, e2);
    float r1 = dot(r, e1), r2 = dot(r, e2);
    float det = a * g - b * b; // = nn (Lagrange's identity)
    float s = (g * r1 - b * r2) / det;
    float t = (a * r2 - b * r1) / det;
    float footprint = abs(nc) / (nn * rtpbr_rsqrt(sqrt(nn))); // (|nc| / |n|) / sqrt(|n|)
    return rtpbr_float3(s, t, footprint);
}

// frame = LTC_Frame(N, V), minv the lobe's M^-1, F its vector form factor over the light
// (LTC_LobeEndVector, or LTC_IntegrateLocalVector; zero when the light is not seen).
// Returns (u, v, footprint): u, v may fall outside [0, 1] when the lobe looks past the light's
// edge (clamp-to-edge reads of a chain blurred with its border do the right thing).
RTPBR_FN rtpbr_float3 LTC_TextureLookup(rtpbr_float3x3 frame, rtpbr_float3 P, rtpbr_float3 corner, rtpbr_float3 edgeS,
                                         rtpbr_float3 edgeT, rtpbr_float3x3 minv, rtpbr_float3 F) {
    rtpbr_float3 c = rtpbr_mul(minv, rtpbr_mul(frame, corner - P));
    rtpbr_float3 e1 = rtpbr_mul(minv, rtpbr_mul(frame, edgeS));
    rtpbr_float3 e2 = rtpbr_mul(minv, rtpbr_mul(frame, edgeT));
    rtpbr_float3 dir = dot(F, F) > 0.0f ? F : cross(e1, e2); // not seen: any point will do
    return LTC_TexturePlanePoint(c, e1, e2, dir);
}

// The demo's point: the orthogonal projection of the shading point onto the light's plane in
// the LTC's space (measured against LTC_TextureLookup in the test; kept for comparison).
RTPBR_FN rtpbr_float3 LTC_TextureLookupProjected(rtpbr_float3x3 frame, rtpbr_float3 P, rtpbr_float3 corner,
                                                  rtpbr_float3 edgeS, rtpbr_float3 edgeT, rtpbr_float3x3 minv) {
    rtpbr_float3 c = rtpbr_mul(minv, rtpbr_mul(frame, corner - P));
    rtpbr_float3 e1 = rtpbr_mul(minv, rtpbr_mul(frame, edgeS));
    rtpbr_float3 e2 = rtpbr_mul(minv, rtpbr_mul(frame, edgeT));
    return LTC_TexturePlanePoint(c, e1, e2, cross(e1, e2));
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_TEXTURED_H
