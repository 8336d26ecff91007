// Shadow pass, step 1 of 2 (issue 17): the two Monte Carlo estimates of the ratio estimator
// (Heitz, Hill & McGuire 2018, "Combining Analytic Direct Illumination and Stochastic
// Shadows"), per pixel and shadowed light k < frame.shadow_light_count, from the same samples:
//   unshadowed U = (1/n) sum_j w_j,  shadowed S = (1/n) sum_j w_j V(x, y_j),
//   w_j = A max(cos_x, 0) cos_y / |y_j - x|^2,
// y_j uniform on the light polygon by area (pdf 1/A; a fan triangle picked by area, then a
// uniform point on it), so both estimate the cosine-weighted solid-angle integrals
// int_light cos_x dw (with and without visibility): the Lambertian weight. cos_y is the
// light's cosine toward x (its absolute value for a two-sided light; 0 behind a one-sided one).
// The n points are a rank-1 lattice (the R2 sequence, Roberts 2018) shifted per pixel and
// light by a hash (Cranley-Patterson rotation): stratified, and independent between pixels.
// V traces a ray from x (lifted off the surface by a few depth ulps) to y_j, shortened by
// 1e-3 of its length so that the light's own emitting triangles do not occlude it; in a tile
// whose slot shadow_select.comp proved clear (no triangle can block any of its rays toward
// the light, shadow_cull.glsl), V = 1 without a ray.
// One workgroup: an entry of the work list (shadow_list.comp: an 8 x 8 pixel group and shadow
// slot k of its tile, light shadow_tiles[slot k], chosen by shadow_select.comp; an empty
// slot's sums stay 0); one invocation: one pixel of it (none for a background pixel), samples
// first_sample .. first_sample + samples - 1 of the n, added to the sums n S and n U (layers
// 2k and 2k + 1; the first dispatch writes them): passes/shadow.c splits n over several dispatches, because lavapipe
// stops every loop of a shader once its invocations together have taken 65535 loop
// iterations (llvmpipe's LP_MAX_TGSI_LOOP_ITERATIONS, one budget for all the loops of a
// shader run) and silently skips what follows them.
// A punctual light (point, spot, directional) takes one ray, w = max(cos_x, 0), V to its
// position or along its reverse direction. A sphere light: n directions uniform in the cone it
// subtends (R2 as above), w = max(cos_x, 0), V to where each meets the sphere. A disk: as a
// polygon, its points uniform by area (polar, R2 as above). A tube: its capsule's points
// uniform by area, the cylinder's far half mirrored to its near half (capsule_point_toward:
// the cylinder's density doubled, w halved there), cos_y by each point's own normal (0 facing
// away).
// shadow_denoise.comp filters n S and n U and writes their ratio, S / U.
#include "rtpbr_shared.h"
#include "shadow_common.glsl"
#include "material.glsl"
#include "bvh.glsl"
#if RTPBR_SHADOW_RAY_QUERY
#include "ray_query.glsl"
#endif

// How far a directional light's shadow ray goes (world units).
#define RTPBR_SHADOW_FAR 1.0e7f

#include "light.glsl"
#include "capsule.glsl"
layout(set = 0, binding = RTPBR_BINDING_SHADOW_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

// The estimates of one pixel (of an 8 x 8 group) and shadow slot.
void trace(ivec2 pixel, uvec2 group, uint k)
{
    ivec3 shadowedTexel = ivec3(pixel, int(2u * k)), unshadowedTexel = ivec3(pixel, int(2u * k + 1u));
    float shadowed = 0.0f, unshadowed = 0.0f;
    if (params.first_sample > 0u) {
        shadowed = imageLoad(shadow_estimates, shadowedTexel).r;
        unshadowed = imageLoad(shadow_estimates, unshadowedTexel).r;
    }
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    vec3 P = shadow_world_point(pixel, depth);
    vec3 N = normalize(texelFetch(gbuffer_normal, pixel, 0).xyz);
    vec3 origin = shadow_ray_origin(pixel, depth, P, N); // lifted off the surface

    uint slotBase = shadow_group_slot_base(group);
    uint li = shadow_tiles[slotBase + k]; // the slot's light (uniform)
    // No triangle can block a ray of this tile toward it (shadow_select.comp, shadow_cull.glsl):
    // every ray would be unoccluded, so none is traced and the shadowed sum is the unshadowed.
    bool clear = ((shadow_tiles[slotBase - uint(RTPBR_TILE_SHADOW_SLOTS) + uint(RTPBR_TILE_SHADOW_CLEAR)] >> k) & 1u) != 0u;
    bool slotUsed = li < frame.light_count;
    li = slotUsed ? li : 0u;
    Light light = lights[li];
    bool tubeLight = light.shape == uint(RTPBR_LIGHT_SHAPE_TUBE);
    bool twoSided = light.two_sided != 0.0f && !tubeLight; // a tube: each sample's own normal, one-sided
    // Background or an empty slot (both stay 0); behind a one-sided light, or the light below
    // the horizon everywhere: both stay 0.
    bool facing = slotUsed && depth < 1.0f && (twoSided || dot(light.plane.xyz, origin) + light.plane.w > 0.0f);
    uint h = bvh_hash( // PCG (Jarzynski & Olano 2020; bvh.glsl); by light, not slot
        uint(pixel.x) + bvh_hash(uint(pixel.y) + bvh_hash(li + bvh_hash(params.seed))));
    vec2 shift = vec2(float(h & 0xffffu), float(h >> 16u)) / 65536.0f;
    vec3 v0 = light.vertices[0].xyz;
    // A punctual light: one ray (every sample would be the same), to its position or, for a
    // directional light, RTPBR_SHADOW_FAR along its reverse direction; weight N.L.
    bool sphereLight = light.shape == uint(RTPBR_LIGHT_SHAPE_SPHERE);
    bool punctual = light.shape != uint(RTPBR_LIGHT_SHAPE_POLYGON) && !sphereLight && light.shape != uint(RTPBR_LIGHT_SHAPE_DISK) && !tubeLight;
    // A sphere: directions uniform in the cone it subtends from x (from inside it, every
    // direction), each to where it meets the sphere, weight max(cos_x, 0) (the cone's constant
    // density cancels in the ratio).
    vec3 toCentre = light.sphere.xyz - origin;
    float centre2 = dot(toCentre, toCentre), radius2 = light.sphere.w * light.sphere.w;
    bool insideSphere = centre2 <= radius2;
    float oneMinusCos = insideSphere ? 2.0f : radius2 / centre2 / (1.0f + sqrt(max(1.0f - radius2 / centre2, 0.0f)));
    vec3 sphereAxis = toCentre * inversesqrt(max(centre2, 1e-30f));
    vec3 sphereA1 = normalize(cross(abs(sphereAxis.z) < 0.9f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f), sphereAxis));
    vec3 sphereA2 = cross(sphereAxis, sphereA1);
    uint sampleEnd = punctual ? min(params.samples, 1u) * uint(params.first_sample == 0u) : params.samples;
    uint last = params.first_sample + sampleEnd;
    // The samples in packets of RTPBR_BVH_PACKET rays, traced by one walk (bvh_occluded_packet);
    // each sample's weight added to both sums in the samples' order, as one by one.
    for (uint j0 = params.first_sample; facing && j0 < last; j0 += uint(RTPBR_BVH_PACKET)) {
      vec3 rays[RTPBR_BVH_PACKET];
      float rayWeights[RTPBR_BVH_PACKET];
      uint traced = 0u; // the packet's rays to trace
      // (unrolled: lavapipe counts every loop trip against its budget, shadow.c)
      [[unroll]] for (uint ray = 0u; ray < uint(RTPBR_BVH_PACKET); ++ray) {
        uint j = j0 + ray;
        // R2: the lattice of the plastic number (Roberts 2018).
        vec2 u = fract(shift + float(j) * vec2(0.7548776662f, 0.5698402910f));
        // The fan triangle (v0, v_i, v_i+1) holding u.x of the area, and u.x rescaled in it;
        // vertices[i].w is the area of the fan below v_i (rtpbr_shared.h, RTPBR_LIGHT_FIELDS).
        float target = u.x * light.area;
        uint i = 1u;
        while (i + 2u < light.vertex_count && light.vertices[i + 1u].w < target) ++i;
        // The picked vertices from the buffer, not the private copy: indexed by a per-pixel i,
        // the copy's whole fan stays in scalar registers (4 SGPRs spilled on navi21 and gfx1100).
        vec4 a4 = lights[li].vertices[i], b4 = lights[li].vertices[i + 1u];
        vec3 a = a4.xyz, b = b4.xyz;
        float below = a4.w, triArea = b4.w - a4.w;
        float ux = clamp((target - below) / max(triArea, 1e-30f), 0.0f, 1.0f);
        // Uniform on the triangle (Turk 1990): sqrt warps the first coordinate.
        float su = sqrt(ux);
        // A disk: uniform by area (polar, radius sqrt(u.x)); a and b are then its half-axes,
        // vertices[1] and [2] (vertex_count 0 leaves i at 1), w as a polygon's. One expression
        // for both kinds, by their weights, chosen by the vertex count (a disk's own loads, sum
        // and flag spilled 2-4 SGPRs on navi21 and gfx1100).
        float phi = 6.28318531f * u.y, rho = sqrt(u.x);
        // (vertex_count 0 is also a sphere's and a punctual light's, whose y is set below)
        vec3 weights = light.vertex_count == 0u ? vec3(1.0f, rho * cos(phi), rho * sin(phi)) : vec3(1.0f - su, su * (1.0f - u.y), su * u.y);
        vec3 y = v0 * weights.x + a * weights.y + b * weights.z;
        if (punctual)
            y = light.shape == uint(RTPBR_LIGHT_SHAPE_DIRECTIONAL) ? origin - light.vertices[1].xyz * RTPBR_SHADOW_FAR : v0;
        if (sphereLight) {
            float cosT = 1.0f - u.x * oneMinusCos;
            float sinT = sqrt(max(1.0f - cosT * cosT, 0.0f));
            float phi = 6.28318531f * u.y;
            vec3 dir = sphereAxis * cosT + (sphereA1 * cos(phi) + sphereA2 * sin(phi)) * sinT;
            // the ray's first meeting with the sphere (from inside: its exit)
            float b = dot(dir, toCentre);
            float root = sqrt(max(b * b - centre2 + radius2, 0.0f));
            y = origin + dir * (insideSphere ? b + root : b - root);
        }
        // A tube: a point of its surface uniform by area (capsule.glsl), weighted as a
        // polygon's by its own normal (the capsule hides its points facing away).
        vec3 lightNormal = light.plane.xyz;
        float density = 1.0f; // a tube's: capsule_point_toward's (its cylinder's near half, twice as dense)
        if (tubeLight) y = capsule_point_toward(v0, light.vertices[1].xyz, light.vertices[0].w, u, origin, lightNormal, density);
        vec3 d = y - origin;
        float dist2 = dot(d, d);
        float dist = sqrt(dist2);
        vec3 l = d / dist;
        float cosX = dot(N, l);
        float cosY = -dot(lightNormal, l);
        cosY = twoSided ? abs(cosY) : cosY;
        float w = cosX > 0.0f && cosY > 0.0f ? light.area / density * cosX * cosY / dist2 : 0.0f;
        if (punctual || sphereLight) w = max(cosX, 0.0f);
        w = j < last ? w : 0.0f;
        unshadowed += w;
        rays[ray] = d;
        rayWeights[ray] = w;
        if (w > 0.0f && !clear) traced |= 1u << ray;
      }
      uint blocked = 0u;
#if RTPBR_SHADOW_RAY_QUERY
      // By the device's ray queries (ray_query.glsl), ray by ray.
      [[unroll]] for (uint i = 0u; i < uint(RTPBR_BVH_PACKET); ++i)
          if ((traced & (1u << i)) != 0u && rq_occluded(origin, rays[i], 1.0f - 1e-3f, bvh_hash(h + j0 + i)))
              blocked |= 1u << i;
#else
      if (bvh_alpha_tested && !bvh_packet_alpha) { // a scene with MASK or BLEND materials on a GPU: ray by ray
          [[unroll]] for (uint i = 0u; i < uint(RTPBR_BVH_PACKET); ++i)
              if ((traced & (1u << i)) != 0u && bvh_occluded(origin, rays[i], 1.0f - 1e-3f, bvh_hash(h + j0 + i)))
                  blocked |= 1u << i;
      } else if (traced != 0u) {
          // One walk for the packet (with bvh_alpha_tested, on a CPU device: ray i's stochastic
          // opacity keyed by bvh_hash(h + j0 + i), as ray by ray).
          blocked = bvh_occluded_packet(origin, rays, 1.0f - 1e-3f, traced, h + j0);
      }
#endif
      [[unroll]] for (uint i = 0u; i < uint(RTPBR_BVH_PACKET); ++i)
          if (rayWeights[i] > 0.0f && (blocked & (1u << i)) == 0u) shadowed += rayWeights[i];
    }
    imageStore(shadow_estimates, shadowedTexel, vec4(shadowed));
    imageStore(shadow_estimates, unshadowedTexel, vec4(unshadowed));
}

void main()
{
    // The workgroup's entry of the work list (shadow_list.comp): its 8 x 8 pixels and slot.
    uint g = gl_WorkGroupID.y * RTPBR_SHADOW_WORK_ROW + gl_WorkGroupID.x;
    if (g >= shadow_work[3]) return; // the last row's rest (uniform)
    uint entry = shadow_work[RTPBR_SHADOW_WORK_HEADER + g];
    uint k = entry & 7u;
    uvec2 group = uvec2((entry >> 3u) & 0x3fffu, entry >> 17u);
    ivec2 pixel = ivec2(group * uint(RTPBR_SHADOW_GROUP_SIZE) + gl_LocalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size))) return;
    // Nothing reads a background pixel's estimates (the denoiser passes over them).
    if (texelFetch(gbuffer_depth, pixel, 0).r >= 1.0f) return;
    trace(pixel, group, k);
}
