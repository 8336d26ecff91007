#version 450
#extension GL_EXT_control_flow_attributes : require
// The yardstick of rtpbr-shader-stats' per-light table: a minimal LTC quad-light kernel doing
// what the demo of Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time Polygonal-Light Shading
// with Linearly Transformed Cosines" (SIGGRAPH), does per pixel and light, written here from
// the paper: a GGX lobe (the fitted M^-1, one table fetch) and a Lambert lobe (M = I), each
// integrated over the quad in its own LTC space (transform the 4 vertices, clip to the
// horizon, sum the edge integrals: the paper's polygon irradiance), specular
// scaled by the second table (norm and Fresnel, one fetch). No Kulla-Conty, no culling, no
// other material. Compiled for statistics only (never dispatched), with
// -DRTPBR_STATS_FIXED_LIGHTS=N: exactly N lights, a compile-time count.
// -DRTPBR_YARDSTICK_DEMO_CLIP=1 replaces the select-based clip by a port of the demo's own
// clip path (selfshadow/ltc_code, webgl/shaders/ltc/ltc_quad.fs: LTC_Evaluate without
// "clipless", ClipQuadToHorizon's 16 cases, a 5-vertex polygon) written here from its
// algorithm: issue 32's yardstick, per light.
// Both kernels start like the engine's lighting pass (lighting.comp): the same two per-pixel
// early exits (outside the frame; background depth) before the light loop, since ACO weights
// the code after an exit by its probability and a kernel without them looks cheaper per
// light than it is (issue 32: the select-based baseline read 0.87x of the engine without them).
layout(local_size_x = 8, local_size_y = 8) in;

struct QuadLight {
    vec4 vertices[4]; // world positions (xyz)
    vec4 emission;    // rgb radiance, w: two-sided
};
layout(set = 0, binding = 0, std430) readonly buffer Lights {
    QuadLight lights[];
};
layout(set = 0, binding = 1) uniform sampler2D gbuffer_position;         // xyz world position
layout(set = 0, binding = 2) uniform sampler2D gbuffer_normal_roughness; // xyz normal, w roughness
layout(set = 0, binding = 3) uniform sampler2D gbuffer_base_color;       // rgb base colour, a metallic
layout(set = 0, binding = 4) uniform sampler2D ltc_inverse;              // M^-1 of the GGX fit
layout(set = 0, binding = 5) uniform sampler2D ltc_terms;                // x: norm, y: Fresnel term
layout(set = 0, binding = 6, rgba32f) writeonly uniform image2D radiance;
layout(set = 0, binding = 7) uniform sampler2D gbuffer_depth;             // 1: background
layout(push_constant) uniform Params {
    vec4 camera_position;
    vec4 background;
    uvec2 size;
    uint light_count;
} params;

const float PI = 3.14159265f;
const float LUT_SIZE = 64.0f;

// The integral of the clamped cosine over the arc from a to b (unit vectors), times 2 pi:
// acos(a . b) times the z of the arc's unit normal (Lambert's polygon formula; the paper's
// Eq. 11 in LTC space), with theta / sin(theta) by the rational fit of Hill and Heitz 2016,
// "Real-Time Area Lighting: a Journey from Research to Production" (SIGGRAPH course), as the
// demo does, instead of acos.
float edge_integral(vec3 a, vec3 b)
{
    float x = dot(a, b);
    float y = abs(x);
    float v = (0.8543985f + (0.4965155f + 0.0145206f * y) * y) / (3.4175940f + (4.1616724f + y) * y);
    float thetaOverSinTheta = x > 0.0f ? v : 0.5f * inversesqrt(max(1.0f - x * x, 1e-7f)) - v;
    return cross(a, b).z * thetaOverSinTheta;
}

// The edge a -> b (unit vectors) clipped to the upper hemisphere z >= 0, by selects rather
// than branches (as a GPU compiles the paper's clipping anyway): its integral, and where the
// polygon leaves and re-enters the hemisphere, so that the clipped polygon is never stored.
float clipped_edge(vec3 a, vec3 b, inout vec3 leave, inout vec3 enter)
{
    bool aAbove = a.z >= 0.0f, bAbove = b.z >= 0.0f;
    vec3 h = normalize(mix(a, b, a.z / (a.z - b.z))); // used only when the signs differ
    leave = aAbove && !bAbove ? h : leave;
    enter = !aAbove && bAbove ? h : enter;
    return aAbove || bAbove ? edge_integral(aAbove ? a : h, bAbove ? b : h) : 0.0f;
}

#if RTPBR_YARDSTICK_DEMO_CLIP
// The point where the edge from `above` (z > 0) to `below` (z <= 0) meets the horizon z = 0,
// up to a positive scale (the integral normalises every vertex).
vec3 horizon_point(vec3 above, vec3 below)
{
    return above.z * below - below.z * above;
}

// The demo's clip: the quad L[0..3] (LTC space, not normalised) clipped to z > 0 into L[0..n-1]
// (n = 0, 3, 4 or 5) in the same winding, L[n] = L[0] closing it; a case per set of vertices
// above the horizon (5 and 10, two opposite vertices only, cannot happen for a planar quad).
void clip_quad_to_horizon(inout vec3 L[5], out int n)
{
    int config = (L[0].z > 0.0f ? 1 : 0) + (L[1].z > 0.0f ? 2 : 0) + (L[2].z > 0.0f ? 4 : 0) + (L[3].z > 0.0f ? 8 : 0);
    vec3 a = L[0], b = L[1], c = L[2], d = L[3];
    n = 0;
    if (config == 1) { L[1] = horizon_point(a, b); L[2] = horizon_point(a, d); n = 3; }
    else if (config == 2) { L[0] = horizon_point(b, a); L[2] = horizon_point(b, c); n = 3; }
    else if (config == 3) { L[2] = horizon_point(b, c); L[3] = horizon_point(a, d); n = 4; }
    else if (config == 4) { L[0] = horizon_point(c, d); L[1] = horizon_point(c, b); n = 3; }
    else if (config == 6) { L[0] = horizon_point(b, a); L[3] = horizon_point(c, d); n = 4; }
    else if (config == 7) { L[4] = horizon_point(a, d); L[3] = horizon_point(c, d); n = 5; }
    else if (config == 8) { L[0] = horizon_point(d, a); L[1] = horizon_point(d, c); L[2] = d; n = 3; }
    else if (config == 9) { L[1] = horizon_point(a, b); L[2] = horizon_point(d, c); n = 4; }
    else if (config == 11) { L[4] = d; L[3] = horizon_point(d, c); L[2] = horizon_point(b, c); n = 5; }
    else if (config == 12) { L[1] = horizon_point(c, b); L[0] = horizon_point(d, a); n = 4; }
    else if (config == 13) { L[4] = d; L[3] = c; L[2] = horizon_point(c, b); L[1] = horizon_point(a, b); n = 5; }
    else if (config == 14) { L[4] = horizon_point(d, a); L[0] = horizon_point(b, a); n = 5; }
    else if (config == 15) { n = 4; }
    if (n == 3) L[3] = L[0];
    if (n == 4) L[4] = L[0];
}

// The demo's LTC_Evaluate (clip path): the frame built from N and V and folded into Minv per
// call, as the demo does; the polygon clipped, projected to the sphere and integrated.
float ltc_quad_demo(vec3 N, vec3 V, vec3 P, mat3 Minv, vec3 q0, vec3 q1, vec3 q2, vec3 q3, bool twoSided)
{
    vec3 T1 = normalize(V - N * dot(V, N));
    vec3 T2 = cross(N, T1);
    Minv = Minv * transpose(mat3(T1, T2, N));
    vec3 L[5];
    L[0] = Minv * (q0 - P);
    L[1] = Minv * (q1 - P);
    L[2] = Minv * (q2 - P);
    L[3] = Minv * (q3 - P);
    L[4] = L[3];
    int n;
    clip_quad_to_horizon(L, n);
    if (n == 0) return 0.0f;
    for (int i = 0; i < 5; ++i) L[i] = normalize(L[i]);
    float sum = edge_integral(L[0], L[1]) + edge_integral(L[1], L[2]) + edge_integral(L[2], L[3]);
    if (n >= 4) sum += edge_integral(L[3], L[4]);
    if (n == 5) sum += edge_integral(L[4], L[0]);
    sum = twoSided ? abs(sum) : max(0.0f, sum);
    return sum / (2.0f * PI);
}

#else
// The form factor of the quad q0..q3 (positions relative to the shading point in the
// shading frame) under the cosine lobe transformed by Minv.
float ltc_quad(mat3 Minv, vec3 q0, vec3 q1, vec3 q2, vec3 q3, bool twoSided)
{
    vec3 p0 = normalize(Minv * q0), p1 = normalize(Minv * q1), p2 = normalize(Minv * q2), p3 = normalize(Minv * q3);
    if (max(max(p0.z, p1.z), max(p2.z, p3.z)) < 0.0f) return 0.0f; // below the horizon (so does the demo)
    // Both stay 0 unless the quad crosses the horizon; then the clipped polygon closes along it.
    vec3 leave = vec3(0.0f), enter = vec3(0.0f);
    float sum = clipped_edge(p0, p1, leave, enter) + clipped_edge(p1, p2, leave, enter) +
                clipped_edge(p2, p3, leave, enter) + clipped_edge(p3, p0, leave, enter);
    bool crossed = leave != vec3(0.0f);
    sum += crossed ? edge_integral(leave, enter) : 0.0f;
    sum = twoSided ? abs(sum) : max(sum, 0.0f);
    return sum / (2.0f * PI);
}

#endif

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size))) return;
    if (texelFetch(gbuffer_depth, pixel, 0).r == 1.0f) {
        imageStore(radiance, pixel, params.background);
        return;
    }
    vec3 P = texelFetch(gbuffer_position, pixel, 0).xyz;
    vec4 nr = texelFetch(gbuffer_normal_roughness, pixel, 0);
    vec4 baseMetal = texelFetch(gbuffer_base_color, pixel, 0);
    vec3 N = normalize(nr.xyz);
    vec3 V = normalize(params.camera_position.xyz - P);
    float NoV = clamp(dot(N, V), 1e-4f, 1.0f);
    vec3 f0 = mix(vec3(0.04f), baseMetal.rgb, baseMetal.a);
    vec3 diffuseColor = (1.0f - baseMetal.a) * baseMetal.rgb;

    // The tables are indexed by (roughness, sqrt(1 - NoV)), half-texel inset.
    vec2 uv = vec2(nr.w, sqrt(1.0f - NoV)) * ((LUT_SIZE - 1.0f) / LUT_SIZE) + 0.5f / LUT_SIZE;
    vec4 m = textureLod(ltc_inverse, uv, 0.0f);
    vec2 terms = textureLod(ltc_terms, uv, 0.0f).xy;
    mat3 Minv = mat3(vec3(m.x, 0.0f, m.y), vec3(0.0f, 1.0f, 0.0f), vec3(m.z, 0.0f, m.w));
    vec3 specularScale = f0 * terms.x + (1.0f - f0) * terms.y;

    // The shading frame: x along V's tangential part, z = N (LTC fits are isotropic about N).
    vec3 T1 = normalize(V - N * dot(V, N));
    mat3 toLocal = transpose(mat3(T1, cross(N, T1), N));
    mat3 toSpecular = Minv * toLocal;

    vec3 sum = vec3(0.0f);
#ifdef RTPBR_STATS_FIXED_LIGHTS
    // Unrolled: the N-light build holds N copies of the loop body (a loop kept as a loop would
    // compile the same for every N and differences would be 0).
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i) {
#else
    for (uint i = 0u; i < params.light_count; ++i) {
#endif
        QuadLight light = lights[i];
        bool twoSided = light.emission.w != 0.0f;
#if RTPBR_YARDSTICK_DEMO_CLIP
        vec3 q0 = light.vertices[0].xyz, q1 = light.vertices[1].xyz, q2 = light.vertices[2].xyz, q3 = light.vertices[3].xyz;
        float specular = ltc_quad_demo(N, V, P, Minv, q0, q1, q2, q3, twoSided);
        float diffuse = ltc_quad_demo(N, V, P, mat3(1.0f), q0, q1, q2, q3, twoSided);
#else
        vec3 q0 = light.vertices[0].xyz - P, q1 = light.vertices[1].xyz - P;
        vec3 q2 = light.vertices[2].xyz - P, q3 = light.vertices[3].xyz - P;
        float specular = ltc_quad(toSpecular, q0, q1, q2, q3, twoSided);
        float diffuse = ltc_quad(toLocal, q0, q1, q2, q3, twoSided);
#endif
        sum += light.emission.rgb * (specularScale * specular + diffuseColor * diffuse);
    }
    imageStore(radiance, pixel, vec4(sum, 1.0f));
}
