// rtpbr shader library: disk, ellipse and sphere lights with Linearly Transformed Cosines.
//
// Heitz & Hill 2017, "Real-Time Line- and Disk-Light Shading with Linearly Transformed
// Cosines" (SIGGRAPH course): a linear map takes an ellipse to an ellipse, so the LTC's M^-1
// takes an elliptic light to an elliptic cone of directions, whose cosine integral and mean
// direction (its vector form factor F) come from the eigen decomposition of the cone's
// quadratic form. The horizon is then handled by a sphere proxy: the spherical cap with the
// same F (Hill & Heitz 2016), integrated exactly against the horizon (Snyder 1996, "Area Light
// Sources for Real-Time Graphics"; the form of Lagarde & de Rousiers 2014, "Moving Frostbite to
// PBR", Eq. 19). A sphere light is the disk that faces the shading point and fills the same
// cone of directions: exact for every lobe, since M^-1 maps that cone either way.
//
// Conventions: those of ltc.h (local frame, ltc1 from the tables, results are form factors in
// [0, 1]: the fraction of the LTC's mass above the horizon that falls on the light, so times
// ltc2's integrals they never exceed the albedo). An ellipse is its centre C and two conjugate
// semi-axes U, W (the points C + u U + w W with u^2 + w^2 <= 1; a disk of radius r has
// orthogonal U, W of length r); its front is the side cross(U, W) points to. Accuracy (measured
// against closed forms and quadrature: tests/shaderlib/ltc/test_ltc_shapes.cpp):
//   - above the horizon, exact for every lobe up to float rounding (the cone's integral and F
//     are closed forms); in a sharp lobe's far tail (a small light seen at grazing angles on a
//     polished surface) that rounding is within 1e-6 of the lobe's mass, not relative;
//   - across the horizon (or the LTC's), exact for a sphere under the Lambert lobe (a circular
//     cone: the cap's closed form), otherwise the error of the equal-area polygon that is
//     clipped instead; the test states it per case.
//
// Public functions
//   LTC_EllipseVector          an ellipse's vector form factor under M^-1 (relative, local)
//   LTC_DiskVector             a round disk's vector form factor (Lambert's: no cubic)
//   LTC_SphereCapFormFactor    the horizon-clipped form factor of the cap with vector form
//                              factor F, exact (no table; LTC_SphereFormFactor reads ltc2.w)
//   LTC_SphereAsDisk           the disk facing P that fills the same cone as a sphere
//   LTC_EllipsePolygon         the equal-area polygon of an ellipse (the horizon fallback)
//   LTC_EvaluateEllipse        one call: a world-space ellipse's form factor at P for ltc1
//   LTC_EvaluateSphere         one call: a sphere's form factor at P for ltc1
#ifndef RTPBR_LTC_SHAPES_H
#define RTPBR_LTC_SHAPES_H

#include "lang.h"
#include "config.h"
#include "ltc.h"

RTPBR_NAMESPACE_BEGIN

// The three real roots of x^3 + b x^2 + c x + d (a symmetric matrix's characteristic
// polynomial: the roots are real), largest first: Viete's trigonometric solution of the
// depressed cubic t^3 + p t + q (x = t - b/3). The smallest root is then refined by two Newton
// steps, since it is the one the cone needs and the one cancellation hurts when the others
// are much larger (a small light far away).
RTPBR_FN rtpbr_float3 LTC_ShapesCubicRoots(float b, float c, float d) {
    float p = c - b * b / 3.0f;
    float q = (2.0f * b * b * b - 9.0f * b * c) / 27.0f + d;
    float m = rtpbr_safe_sqrt(-p / 3.0f);
    float cosArg = m > 0.0f ? -q / (2.0f * m * m * m) : 0.0f;
    float phi = acos(clamp(cosArg, -1.0f, 1.0f)) / 3.0f;
    const float third = 2.0943951f; // 2 pi / 3
    rtpbr_float3 x = RTPBR_F3(2.0f * m) * rtpbr_float3(cos(phi), cos(phi - third), cos(phi + third)) - RTPBR_F3(b / 3.0f);
    // The smallest root from the product of the three (-d, Vieta's): the two large ones are
    // accurate to float rounding relative to themselves, where Viete's formula loses the small
    // one entirely when the others are 1e4 or more times larger (a thin ellipse far off the
    // lobe's axis); Newton then polishes it.
    float large = x.x * x.y;
    float z = large != 0.0f && abs(large) < 3.0e38f ? -d / large : x.z;
    for (int i = 0; i < 2; ++i) {
        float f = ((z + b) * z + c) * z + d;
        float df = (3.0f * z + 2.0f * b) * z + c;
        z = df != 0.0f ? z - f / df : z;
    }
    return rtpbr_float3(x.x, x.y, z);
}

// The vector form factor F of the cone of directions through the ellipse (C, U, W), relative to
// the shading point in the local frame, transformed by minv (the LTC's space, no horizon):
// |F| is the cone's form factor about its own axis, F points along that axis. Zero when the
// ellipse is degenerate or (one-sided) seen from behind; two-sided lights turn to face.
RTPBR_FN rtpbr_float3 LTC_EllipseVector(rtpbr_float3x3 minv, rtpbr_float3 C, rtpbr_float3 U, rtpbr_float3 W, bool twoSided) {
    // The shading point (the origin) sees the front when dot(cross(U, W), C) < 0.
    if (!twoSided && !(dot(cross(U, W), C) < 0.0f))
        return RTPBR_F3(0.0f);
    C = rtpbr_mul(minv, C);
    U = rtpbr_mul(minv, U);
    W = rtpbr_mul(minv, W);
    // Principal semi-axes of the ellipse: the eigenvectors of its 2x2 Gram matrix.
    float uu = dot(U, U), ww = dot(W, W), uw = dot(U, W);
    float mean = 0.5f * (uu + ww);
    float root = sqrt(0.25f * (uu - ww) * (uu - ww) + uw * uw);
    // squared semi-axis lengths; the smaller from the Gram determinant |U x W|^2 = e1 e2, not
    // mean - root, which cancels for a thin ellipse (a sharp lobe's image of a small light)
    float e1 = mean + root, e2 = max(mean - root, 0.0f);
    if (!(e2 > 0.0f))
        return RTPBR_F3(0.0f);
    rtpbr_float3 a1, a2;
    if (abs(uw) > 1e-6f * (uu + ww)) {
        a1 = uu > ww ? U * uw + W * (e1 - uu) : W * uw + U * (e1 - ww);
        a1 = normalize(a1);
        a2 = normalize(cross(cross(U, W), a1));
    } else {
        a1 = normalize(uu >= ww ? U : W);
        a2 = normalize(uu >= ww ? W : U);
    }
    rtpbr_float3 n = cross(a1, a2);
    n = dot(n, C) < 0.0f ? -n : n;
    float dist = dot(n, C); // the ellipse's plane is z' = dist in the basis (a1, a2, n)
    if (!(dist > 0.0f))
        return RTPBR_F3(0.0f);
    float x0 = dot(a1, C) / dist, y0 = dot(a2, C) / dist;
    float A = dist * dist / e1, B = dist * dist / e2;
    // The cone: A (x - x0 z)^2 + B (y - y0 z)^2 - z^2 <= 0. Its quadratic form's characteristic
    // polynomial is e^3 - (A (1 + x0^2) + B (1 + y0^2) - 1) e^2 + (A B (1 + x0^2 + y0^2) - A - B) e
    // + A B; one root is negative (the axis), two are positive.
    rtpbr_float3 e = LTC_ShapesCubicRoots(1.0f - A * (1.0f + x0 * x0) - B * (1.0f + y0 * y0),
                                          A * B * (1.0f + x0 * x0 + y0 * y0) - A - B, A * B);
    float eNeg = min(e.z, -1e-30f);
    rtpbr_float3 axis = rtpbr_float3(A * x0 / (A - eNeg), B * y0 / (B - eNeg), 1.0f);
    axis = normalize(a1 * axis.x + a2 * axis.y + n * axis.z);
    // Tangents of the cone's half-angles along its principal directions, and the form factor
    // of an elliptic cone about its axis: L1 L2 / sqrt((1 + L1^2)(1 + L2^2)).
    float t1 = -eNeg / max(e.x, 1e-30f), t2 = -eNeg / max(e.y, 1e-30f); // L1^2, L2^2
    float ff = sqrt(t1 * t2 / ((1.0f + t1) * (1.0f + t2)));
    return axis * ff;
}

// The vector form factor (1/pi) int w dw of the round disk of centre C (relative to the shading
// point), unit normal n and radius r, without the horizon: the Lambert lobe's exact vector, with
// no cubic. Its component toward the disk's plane is the configuration factor of a differential
// element parallel to a disk, (1/2) (1 - (h^2 + a^2 - r^2) / q), and its component toward the
// disk's axis in that plane the perpendicular element's, (h / 2a) ((h^2 + a^2 + r^2) / q - 1),
// q = sqrt((h^2 + a^2 + r^2)^2 - 4 a^2 r^2), h the distance to the plane and a the offset from
// the axis (Howell's catalog of configuration factors, element to a coaxial-plane disk; valid
// inside the disk's cylinder too: the unclamped vector). Two-sided: a one-sided disk seen from
// behind is the caller's to drop. Agrees with LTC_EllipseVector under the identity.
RTPBR_FN rtpbr_float3 LTC_DiskVector(rtpbr_float3 C, rtpbr_float3 n, float r) {
    float s = dot(C, n);
    rtpbr_float3 toPlane = s > 0.0f ? n : -n; // toward the disk's plane
    float h = abs(s);
    rtpbr_float3 toAxis = C - n * s; // from the shading point's foot on the plane to the centre
    float a2 = dot(toAxis, toAxis), r2 = r * r;
    float Z = h * h + a2 + r2;
    float q = sqrt(max(Z * Z - 4.0f * a2 * r2, 0.0f));
    if (!(q > 0.0f))
        return RTPBR_F3(0.0f);
    // (1/2) (1 - Y / q), Y = h^2 + a^2 - r^2: for Y >= 0 as 2 r^2 h^2 / (q (q + Y)) (q^2 - Y^2 =
    // 4 r^2 h^2), which keeps a small far disk's r^2 / d^2 that 1 - Y / q loses in float
    float Y = h * h + a2 - r2;
    float along = Y >= 0.0f ? 2.0f * r2 * h * h / (q * (q + Y)) : 0.5f - 0.5f * Y / q;
    // (h / 2a) (Z / q - 1) along toAxis / a: h (Z - q) / (2 a^2 q) along toAxis; with Z - q =
    // 4 a^2 r^2 / (Z + q) (no cancellation): 2 h r^2 / (q (Z + q)) along toAxis
    float across = 2.0f * h * r2 / (q * (Z + q));
    return toPlane * along + toAxis * across;
}

// The horizon-clipped form factor of the spherical cap whose (unclipped) vector form factor is
// F: |F| = sin^2 of its angular radius, F / |F| its centre. Exact (Snyder 1996; Lagarde & de
// Rousiers 2014, Eq. 19, divided by pi).
RTPBR_FN float LTC_SphereCapFormFactor(rtpbr_float3 F) {
    float s2 = min(length(F), 1.0f); // sin^2 sigma
    if (!(s2 > 0.0f))
        return 0.0f;
    float cosT = clamp(F.z / length(F), -1.0f, 1.0f);
    if (cosT * cosT > s2)
        return cosT > 0.0f ? s2 * cosT : 0.0f;
    float sinT = rtpbr_safe_sqrt(1.0f - cosT * cosT);
    float x = rtpbr_safe_sqrt(1.0f / s2 - 1.0f); // cot sigma
    float y = sinT > 0.0f ? clamp(-x * cosT / sinT, -1.0f, 1.0f) : 0.0f;
    float sinTy = sinT * rtpbr_safe_sqrt(1.0f - y * y);
    float e = (cosT * acos(y) - x * sinTy) * s2 + atan(sinTy / max(x, 1e-30f));
    return rtpbr_saturate(e / RTPBR_PI);
}

// The disk (C, U, W), relative to P, that faces P and fills the cone of the sphere (centre,
// radius): a disk through the centre, perpendicular to the view of it, of radius
// r d / sqrt(d^2 - r^2). False (nothing written) when P is inside the sphere.
RTPBR_FN bool LTC_SphereAsDisk(rtpbr_float3 P, rtpbr_float3 centre, float radius, RTPBR_OUT(rtpbr_float3) C,
                               RTPBR_OUT(rtpbr_float3) U, RTPBR_OUT(rtpbr_float3) W) {
    C = centre - P;
    float d2 = dot(C, C);
    if (!(d2 > radius * radius))
        return false;
    float rho = radius * sqrt(d2 / (d2 - radius * radius));
    rtpbr_float3 axis = C * rtpbr_rsqrt(d2);
    rtpbr_float3 t = abs(axis.z) < 0.9f ? rtpbr_float3(0.0f, 0.0f, 1.0f) : rtpbr_float3(1.0f, 0.0f, 0.0f);
    rtpbr_float3 b1 = normalize(cross(t, axis));
    // cross(U, W) = -axis * rho^2: the front faces P.
    U = b1 * rho;
    W = cross(b1, axis) * rho;
    return true;
}

// The regular polygon of RTPBR_LTC_MAX_VERTICES vertices inscribed in the ellipse (centre,
// U, W) scaled to the ellipse's area (radius factor sqrt(2 pi / (n sin(2 pi / n)))), in the
// ellipse's winding (its front is the side cross(U, W) points to).
RTPBR_FN LtcPolygon LTC_EllipsePolygon(rtpbr_float3 centre, rtpbr_float3 U, rtpbr_float3 W) {
    const float n = float(RTPBR_LTC_MAX_VERTICES);
    float scale = sqrt(2.0f * RTPBR_PI / (n * sin(2.0f * RTPBR_PI / n)));
    LtcPolygon p;
    for (int k = 0; k < RTPBR_LTC_MAX_VERTICES; k++) {
        float phi = 2.0f * RTPBR_PI * float(k) / n;
        p.v[k] = centre + (U * cos(phi) + W * sin(phi)) * scale;
    }
    p.count = RTPBR_LTC_MAX_VERTICES;
    return p;
}

// The form factor at P (normal N, view V) of the ellipse with world-space centre and conjugate
// semi-axes (U, W), for the lobe ltc1 (LTC_Identity() for Lambert). While the ellipse is above
// the horizon and its image above the LTC's (the usual case), the cone's closed form: exact.
// Across either horizon, the horizon must cut the ellipse exactly (the sphere proxy leaks
// light from below the surface into sheared lobes: 20 % in the test), so its equal-area
// polygon is clipped and integrated instead (ltc.h's path): the measured error is the
// polygon's.
RTPBR_FN float LTC_EvaluateEllipse(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, rtpbr_float3 centre, rtpbr_float3 U,
                                   rtpbr_float3 W, rtpbr_float4 ltc1, bool twoSided) {
    rtpbr_float3x3 frame = LTC_Frame(N, V);
    rtpbr_float3x3 minv = LTC_InverseMatrix(ltc1);
    rtpbr_float3 c = rtpbr_mul(frame, centre - P), u = rtpbr_mul(frame, U), w = rtpbr_mul(frame, W);
    float extent = sqrt(u.z * u.z + w.z * w.z); // the ellipse spans c.z +- extent in z
    if (!(c.z + extent > 0.0f))
        return 0.0f;
    rtpbr_float3 cl = rtpbr_mul(minv, c), ul = rtpbr_mul(minv, u), wl = rtpbr_mul(minv, w);
    if (c.z - extent >= 0.0f && cl.z - sqrt(ul.z * ul.z + wl.z * wl.z) >= 0.0f)
        return LTC_HorizonFraction(rtpbr_pos(LTC_EllipseVector(minv, c, u, w, twoSided).z), LTC_HorizonMass(minv));
    return LTC_IntegrateLocalMatrix(LTC_PolygonToLocal(frame, P, LTC_EllipsePolygon(centre, U, W), twoSided), minv);
}

// The same for a sphere (always two-sided: it faces every point); inside it, 1. Under the
// Lambert lobe (ltc1 = LTC_Identity()) the cone is circular in the local frame and the cap's
// horizon clip is exact, so that case takes it whatever the horizon.
RTPBR_FN float LTC_EvaluateSphere(rtpbr_float3 N, rtpbr_float3 V, rtpbr_float3 P, rtpbr_float3 centre, float radius,
                                  rtpbr_float4 ltc1) {
    rtpbr_float3 C, U, W;
    if (!LTC_SphereAsDisk(P, centre, radius, C, U, W))
        return 1.0f;
    if (ltc1.x == 1.0f && ltc1.y == 0.0f && ltc1.z == 0.0f && ltc1.w == 1.0f) {
        float d2 = dot(C, C);
        rtpbr_float3 F = rtpbr_mul(LTC_Frame(N, V), C) * (radius * radius / (d2 * sqrt(d2))); // sin^2 times the axis
        return LTC_SphereCapFormFactor(F);
    }
    return LTC_EvaluateEllipse(N, V, P, P + C, U, W, ltc1, true);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_LTC_SHAPES_H
