// Helpers of the brute-force Monte Carlo lighting pass (lighting_mc.comp): a per-pixel
// random number stream, uniform area sampling of a convex polygon and ray-polygon
// intersection. GLSL only (engine shader code, not shader library). Include after
// lighting_common.glsl: polygons are read from the light buffer, never copied into a private
// array (GPU compilers lower run-time-indexed private arrays into selects or scratch).
#ifndef RTPBR_MC_SAMPLING_GLSL
#define RTPBR_MC_SAMPLING_GLSL

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering" (JCGT 9(3)): the PCG hash, an
// LCG step followed by PCG's RXS-M-XS output permutation (O'Neill 2014).
uint mc_pcg_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The random stream: an LCG state (O'Neill 2014's PCG-RXS-M-XS-32 constants) whose outputs
// go through the same permutation.
uint mc_next(inout uint state)
{
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A float uniform in [0, 1): the top 24 bits of the next output.
float mc_uniform(inout uint state)
{
    return float(mc_next(state) >> 8u) * (1.0f / 16777216.0f);
}

// Seed of the stream of one pixel and one light for frame seed `seed`.
uint mc_seed(uvec2 pixel, uint light, uint seed)
{
    return mc_pcg_hash(pixel.x + mc_pcg_hash(pixel.y + mc_pcg_hash(light + mc_pcg_hash(seed))));
}

// Uniform point on triangle (a, b, c) from two uniform numbers (Osada et al. 2002, "Shape
// Distributions", sec. 4.2): (1 - sqrt u1) a + sqrt u1 (1 - u2) b + sqrt u1 u2 c.
vec3 mc_triangle_point(vec3 a, vec3 b, vec3 c, vec2 u)
{
    float s = sqrt(u.x);
    return (1.0f - s) * a + (s * (1.0f - u.y)) * b + (s * u.y) * c;
}

// Whether the ray P + t w (t > 0) crosses the convex polygon of light `light` (count
// vertices, counter-clockwise about its plane's normal); t receives the distance.
bool mc_ray_polygon(vec3 P, vec3 w, uint light, uint count, out float t)
{
    vec4 plane = lights[light].plane;
    float denom = dot(plane.xyz, w);
    t = denom != 0.0f ? -(dot(plane.xyz, P) + plane.w) / denom : -1.0f;
    vec3 X = P + t * w;
    bool inside = t > 0.0f;
    vec3 a = lights[light].vertices[count - 1u].xyz;
    for (uint k = 0u; k < count; ++k) {
        vec3 b = lights[light].vertices[k].xyz;
        inside = inside && dot(cross(b - a, X - a), plane.xyz) >= 0.0f;
        a = b;
    }
    return inside;
}

// Does the ray P + t w (t > 0) meet disk light `light` (RTPBR_LIGHT_FIELDS, DISK: centre
// vertices[0], orthogonal half-axes vertices[1], vertices[2])? t: where it meets its plane.
bool mc_ray_disk(vec3 P, vec3 w, uint light, out float t)
{
    vec4 plane = lights[light].plane;
    float denom = dot(plane.xyz, w);
    t = denom != 0.0f ? -(dot(plane.xyz, P) + plane.w) / denom : -1.0f;
    vec3 X = P + t * w - lights[light].vertices[0].xyz;
    vec3 u = lights[light].vertices[1].xyz, v = lights[light].vertices[2].xyz;
    float a = dot(X, u) / dot(u, u), b = dot(X, v) / dot(v, v);
    return t > 0.0f && a * a + b * b <= 1.0f;
}

// A point of disk light `light` uniform by area from u in [0, 1)^2 (polar: radius sqrt(u.x)).
vec3 mc_disk_point(uint light, vec2 u)
{
    float rho = sqrt(u.x), phi = 6.28318531f * u.y;
    return lights[light].vertices[0].xyz + lights[light].vertices[1].xyz * (rho * cos(phi)) +
           lights[light].vertices[2].xyz * (rho * sin(phi));
}

#endif // RTPBR_MC_SAMPLING_GLSL
