#version 450
#extension GL_GOOGLE_include_directive : require
// Lighting pass: one workgroup per RTPBR_TILE_SIZE^2 screen tile; reads the G-buffer and
// writes linear radiance. Model flags (RTPBR_NDF, RTPBR_MULTISCATTER) come from the build,
// one SPIR-V variant per combination. All BRDF and polygon-integration math comes from the
// shader library (shaderlib/rtpbr); this file only fetches, loops and sums.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#if RTPBR_HAVE_LTC
#include "rtpbr/ltc.h"
#endif
#if RTPBR_HAVE_KC
#include "rtpbr/kulla_conty.h"
#endif
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_TILE_SIZE, local_size_y = RTPBR_TILE_SIZE) in;

// C mirror: rtpbr_shader_light.
struct Light {
    vec4 vertices[RTPBR_SHADER_MAX_POLYGON_VERTICES];
    vec4 emission; // rgb radiance, w: two-sided
    vec4 plane;    // unit normal, -dot(normal, vertex 0)
    vec4 sphere;   // bounding sphere: centre, radius
    uint vertex_count;
    float area;
    uint pad0, pad1;
};
layout(set = 0, binding = RTPBR_BINDING_LIGHT_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER0) uniform sampler2D gbuffer0;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER1) uniform sampler2D gbuffer1;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER2) uniform sampler2D gbuffer2;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER3) uniform sampler2D gbuffer3;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_DEPTH) uniform sampler2D gbuffer_depth;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_RADIANCE, rgba32f) writeonly uniform image2D radiance;

layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_1) uniform sampler2D lut_ltc_ggx_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_2) uniform sampler2D lut_ltc_ggx_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_1) uniform sampler2D lut_ltc_beckmann_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_2) uniform sampler2D lut_ltc_beckmann_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_E) uniform sampler2D lut_kc_e;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EAVG) uniform sampler2D lut_kc_eavg;

// ---- per-tile light culling ------------------------------------------------------------------
// The workgroup's pixels form one screen tile. Their world positions are bounded by a box;
// light i is kept for the tile (bit i of tile_lights) unless
//   (1) the light is one-sided and every corner of the box is behind its plane: it cannot
//       light any point of the tile (exact), or
//   (2) the box is at distance d > 0 from the light's bounding sphere and A / (pi d^2) <
//       frame.cull_form_factor: A / (pi d^2) bounds the light's form factor (1/pi) int cos dw
//       at every point of the tile (the solid angle of a polygon of area A at distance >= d is
//       at most A / d^2), so the light's diffuse contribution is below Le * albedo *
//       cull_form_factor. Glossy reflections of such a light are dropped with it (a bias
//       bounded only for the diffuse term). cull_form_factor < 0 disables this test.
shared uint tile_min[3];
shared uint tile_max[3];
shared uint tile_lights[RTPBR_SHADER_MAX_LIGHTS / 32];

// Floats as uints that sort in the same order (for atomicMin / atomicMax).
uint ordered_bits(float f)
{
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float from_ordered_bits(uint u)
{
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}

bool light_may_contribute(Light light, vec3 boxMin, vec3 boxMax)
{
    if (light.emission.w == 0.0f) {
        bool anyInFront = false;
        for (int c = 0; c < 8; ++c) {
            vec3 corner = vec3((c & 1) != 0 ? boxMax.x : boxMin.x, (c & 2) != 0 ? boxMax.y : boxMin.y,
                               (c & 4) != 0 ? boxMax.z : boxMin.z);
            anyInFront = anyInFront || dot(light.plane.xyz, corner) + light.plane.w > 0.0f;
        }
        if (!anyInFront) return false;
    }
    if (frame.cull_form_factor >= 0.0f) {
        vec3 nearest = clamp(light.sphere.xyz, boxMin, boxMax);
        float d = length(light.sphere.xyz - nearest) - light.sphere.w;
        if (d > 0.0f && light.area < frame.cull_form_factor * 3.14159265f * d * d) return false;
    }
    return true;
}

#if RTPBR_HAVE_LTC
// The lighting tables of the NDF this variant is built for.
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define LUT_LTC_1 lut_ltc_beckmann_1
#define LUT_LTC_2 lut_ltc_beckmann_2
#define KC_CHANNEL g
#else
#define LUT_LTC_1 lut_ltc_ggx_1
#define LUT_LTC_2 lut_ltc_ggx_2
#define KC_CHANNEL r
#endif

// Reflected radiance from every polygonal light: Lambertian diffuse and LTC specular with
// Fresnel from the tables (Heitz et al. 2016, shaderlib ltc.h) plus, with RTPBR_MULTISCATTER,
// the Kulla-Conty multiple-scattering lobe over each polygon (shaderlib kulla_conty.h).
// Material mapping (glTF metallic-roughness + KHR_materials_specular / _ior):
//   dielectric f0 = min(F0(ior) * specularColor, 1) * specular, f90 = specular;
//   metal f0 = baseColor, f90 = 1; mixed by metallic; diffuse colour = baseColor (1 - metallic).
vec3 shade_lights(vec3 P, vec3 N, vec3 V, vec4 g0, float roughness, vec4 g2, vec4 g3)
{
    vec3 baseColor = g0.rgb;
    float metallic = g0.a;
    vec3 f0Dielectric = min(RTPBR_F3(F0_FromIor(g2.a)) * g3.rgb, RTPBR_F3(1.0f)) * g3.a;
    vec3 f0 = mix(f0Dielectric, baseColor, metallic);
    float f90 = mix(g3.a, 1.0f, metallic);
    vec3 diffuseColor = baseColor * (1.0f - metallic);
    float NoV = saturate(dot(N, V));

    vec2 uv = LTC_LutCoord(NoV, roughness);
    vec4 ltc1 = textureLod(LUT_LTC_1, uv, 0.0f);
    vec4 ltc2 = textureLod(LUT_LTC_2, uv, 0.0f);
    vec3 specularScale = LTC_FresnelScale(ltc2, f0, f90);
#if RTPBR_MULTISCATTER && RTPBR_HAVE_KC
    float Eo = textureLod(lut_kc_e, KC_TableCoord(NoV, roughness), 0.0f).KC_CHANNEL;
    float Eavg = textureLod(lut_kc_eavg, vec2(KC_TableCoordAvg(roughness), 0.5f), 0.0f).KC_CHANNEL;
    vec3 Fms = KC_FmsColor(F_Avg_Schlick(f0, f90), Eavg);
#endif

    mat3 ltcFrame = LTC_Frame(N, V);
    vec3 sum = vec3(0.0f);
    for (uint word = 0u; word < (frame.light_count + 31u) / 32u; ++word)
    for (uint bits = tile_lights[word]; bits != 0u; bits &= bits - 1u) {
        Light light = lights[word * 32u + uint(findLSB(bits))];
        LtcPolygon poly;
        for (int k = 0; k < RTPBR_SHADER_MAX_POLYGON_VERTICES; ++k) poly.v[k] = light.vertices[k].xyz;
        poly.count = int(light.vertex_count);
        bool twoSided = light.emission.w != 0.0f;
        LtcLocalPolygon local = LTC_PolygonToLocal(ltcFrame, P, poly, twoSided);
        if (local.count == 0) continue;
        float diffuseFF = LTC_IntegrateLocal(local, LTC_Identity());
        vec3 lo = diffuseColor * diffuseFF + specularScale * LTC_IntegrateLocal(local, ltc1);
#if RTPBR_MULTISCATTER && RTPBR_HAVE_KC
        // The representative direction of the polygon: its vector form factor's.
        vec3 F = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(ltcFrame, P, poly, twoSided), LTC_Identity());
        float muRep = length(F) > 0.0f ? saturate(F.z / length(F)) : 0.0f;
        float Erep = textureLod(lut_kc_e, KC_TableCoord(muRep, roughness), 0.0f).KC_CHANNEL;
        lo += Fms * KC_PolygonLobe(Eo, Erep, Eavg, diffuseFF);
#endif
        sum += light.emission.rgb * lo;
    }
    return sum;
}
#endif

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(uvec2(pixel), frame.size));
    float depth = inside ? texelFetch(gbuffer_depth, pixel, 0).r : 1.0f;
    bool surface = depth < 1.0f;
    vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
    vec3 P = world.xyz / world.w;

    // The tile's bounding box, then its light set (every invocation reaches every barrier).
    uint local = gl_LocalInvocationIndex;
    if (local < 3u) {
        tile_min[local] = 0xffffffffu;
        tile_max[local] = 0u;
    }
    for (uint w = local; w < uint(RTPBR_SHADER_MAX_LIGHTS / 32); w += uint(RTPBR_TILE_SIZE * RTPBR_TILE_SIZE))
        tile_lights[w] = 0u;
    barrier();
    if (surface) {
        for (int k = 0; k < 3; ++k) {
            atomicMin(tile_min[k], ordered_bits(P[k]));
            atomicMax(tile_max[k], ordered_bits(P[k]));
        }
    }
    barrier();
    if (tile_max[0] != 0u) { // at least one surface pixel in the tile
        vec3 boxMin = vec3(from_ordered_bits(tile_min[0]), from_ordered_bits(tile_min[1]), from_ordered_bits(tile_min[2]));
        vec3 boxMax = vec3(from_ordered_bits(tile_max[0]), from_ordered_bits(tile_max[1]), from_ordered_bits(tile_max[2]));
        for (uint i = local; i < frame.light_count; i += uint(RTPBR_TILE_SIZE * RTPBR_TILE_SIZE))
            if (light_may_contribute(lights[i], boxMin, boxMax)) atomicOr(tile_lights[i / 32u], 1u << (i % 32u));
    }
    barrier();

    if (!inside) return;
    if (!surface) {
        imageStore(radiance, pixel, vec4(frame.background.rgb, 0.0));
        return;
    }
    vec4 g2 = texelFetch(gbuffer2, pixel, 0);
    vec3 result = g2.rgb; // emitted radiance
#if RTPBR_HAVE_LTC
    vec4 g0 = texelFetch(gbuffer0, pixel, 0);
    vec4 g1 = texelFetch(gbuffer1, pixel, 0);
    vec4 g3 = texelFetch(gbuffer3, pixel, 0);
    vec3 V = normalize(frame.camera_position.xyz - P);
    vec3 N = normalize(g1.xyz);
    // The position from the depth buffer is off by up to about one depth quantum along the
    // view ray; an emitter's own surface could then land on its emitting side and light
    // itself. Shade a point lifted along N by a few quanta (measured at this depth) instead.
    vec4 further = frame.inv_view_proj * vec4(ndc, min(depth * (1.0f + 4.0f / 16777216.0f), 1.0f), 1.0f);
    float lift = length(further.xyz / further.w - P) + 1e-6f * length(frame.camera_position.xyz - P);
    result += shade_lights(P + N * lift, N, V, g0, g1.w, g2, g3);
#endif
    // Without ltc.h (RTPBR_HAVE_LTC 0) lights contribute nothing but their emissive geometry.

    imageStore(radiance, pixel, vec4(result, 1.0));
}
