// A tube (capsule) light's surface for the passes that sample lights (shadow.comp,
// lighting_mc.comp): the capsule of radius r around the segment from a to b (RTPBR_LIGHT_FIELDS,
// TUBE: vertices[0], vertices[1], w = r). Convex: its point x with outward normal n is seen
// from p exactly where dot(n, p - x) > 0.
#ifndef RTPBR_CAPSULE_GLSL
#define RTPBR_CAPSULE_GLSL

// A point of the capsule uniform by area from u in [0, 1)^2: the cylinder (area 2 pi r L,
// a fraction q = L / (2 r + L) of 4 pi r^2 + 2 pi r L) where u.x < q, at height u.x / q of the
// segment, else the two caps, which make a whole sphere (z = 1 - 2 (u.x - q) / (1 - q) uniform
// on it, Archimedes; the cap of b where z > 0); azimuth 2 pi u.y. n: its outward normal.
vec3 capsule_point(vec3 a, vec3 b, float r, vec2 u, out vec3 n)
{
    vec3 ab = b - a;
    float L = length(ab);
    vec3 axis = L > 0.0f ? ab / L : vec3(0.0f, 0.0f, 1.0f);
    vec3 t1 = normalize(cross(abs(axis.z) < 0.9f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f), axis));
    vec3 t2 = cross(axis, t1);
    float phi = 6.28318531f * u.y;
    float q = L / (2.0f * r + L);
    bool side = u.x < q;
    float z = side ? 0.0f : clamp(1.0f - 2.0f * (u.x - q) / (1.0f - q), -1.0f, 1.0f);
    float s = sqrt(max(1.0f - z * z, 0.0f));
    n = (t1 * cos(phi) + t2 * sin(phi)) * s + axis * z;
    vec3 base = side ? a + ab * (u.x / q) : (z > 0.0f ? b : a);
    return base + r * n;
}

// capsule_point for a viewer at p: a point of the cylinder's far half (n.e < 0, e the unit
// direction from the axis toward p, across it) mirrored to its near half (n - 2 (n.e) e: the
// same height, p's side), where every point of the cylinder p sees lies (it sees x where
// n.e > r / its distance from the axis). density: the point's density over the uniform
// 1 / area, 2 on the cylinder (its near half sampled twice as densely), 1 on the caps (as
// capsule_point: a cap's point p sees may be on either side).
vec3 capsule_point_toward(vec3 a, vec3 b, float r, vec2 u, vec3 p, out vec3 n, out float density)
{
    vec3 x = capsule_point(a, b, r, u, n);
    vec3 ab = b - a;
    float L2 = dot(ab, ab);
    vec3 across = (p - a) - ab * (L2 > 0.0f ? dot(p - a, ab) / L2 : 0.0f);
    float e2 = dot(across, across);
    bool side = u.x < sqrt(L2) / (2.0f * r + sqrt(L2));
    density = side ? 2.0f : 1.0f;
    if (side && e2 > 0.0f) {
        vec3 e = across * inversesqrt(e2);
        float ne = dot(n, e);
        if (ne < 0.0f) {
            x -= (2.0f * r * ne) * e;
            n -= (2.0f * ne) * e;
        }
    }
    return x;
}

// Where the ray p + t w (t > 0, w unit) first meets the capsule from outside (Quilez's
// capsule intersection: the infinite cylinder's nearer root within the segment, else the
// nearer cap's sphere); n: the outward normal there.
bool capsule_ray(vec3 p, vec3 w, vec3 a, vec3 b, float r, out float t, out vec3 n)
{
    vec3 ba = b - a, oa = p - a;
    float baba = dot(ba, ba), bard = dot(ba, w), baoa = dot(ba, oa), rdoa = dot(w, oa), oaoa = dot(oa, oa);
    // |oa + t w - ba y(t)|^2 = r^2 with y the projection: A t^2 + 2 B t + C = 0
    float A = baba - bard * bard, B = baba * rdoa - baoa * bard, C = baba * oaoa - baoa * baoa - r * r * baba;
    float h = B * B - A * C;
    t = -1.0f;
    if (A > 0.0f && h >= 0.0f) {
        float tc = (-B - sqrt(h)) / A, y = baoa + tc * bard;
        if (y > 0.0f && y < baba) t = tc;
    }
    if (t < 0.0f) {
        // the cap on the side the cylinder's root fell (or, for a ray along the axis, the nearer end)
        float y = A > 0.0f && h >= 0.0f ? baoa + (-B - sqrt(h)) / A * bard : baoa;
        vec3 oc = y <= 0.0f ? oa : p - b;
        float bc = dot(w, oc), cc = dot(oc, oc) - r * r, hc = bc * bc - cc;
        if (hc >= 0.0f) t = -bc - sqrt(hc);
    }
    vec3 x = p + t * w;
    float k = baba > 0.0f ? clamp(dot(x - a, ba) / baba, 0.0f, 1.0f) : 0.0f;
    n = (x - a - ba * k) / r;
    return t > 0.0f;
}

#endif // RTPBR_CAPSULE_GLSL
