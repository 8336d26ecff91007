#version 450
#extension GL_GOOGLE_include_directive : require
// Lighting pass: one workgroup per RTPBR_TILE_SIZE^2 screen tile; reads the G-buffer and the
// scene's materials and writes linear radiance. Model flags (RTPBR_NDF, RTPBR_MULTISCATTER) come from the build,
// one SPIR-V variant per combination. All BRDF and polygon-integration math comes from the
// shader library (shaderlib/rtpbr); this file only fetches, loops and sums.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ltc.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "material.glsl"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_TILE_SIZE, local_size_y = RTPBR_TILE_SIZE) in;

#include "lighting_common.glsl"
#include "shadow_ratio.glsl"

layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_1) uniform sampler2D lut_ltc_ggx_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_2) uniform sampler2D lut_ltc_ggx_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_1) uniform sampler2D lut_ltc_beckmann_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_2) uniform sampler2D lut_ltc_beckmann_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_1) uniform sampler2D lut_ltc_disney_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_2) uniform sampler2D lut_ltc_disney_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_1) uniform sampler2D lut_ltc_sheen_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_2) uniform sampler2D lut_ltc_sheen_2;

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

// The LTC tables of the NDF this variant is built for.
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define LUT_LTC_1 lut_ltc_beckmann_1
#define LUT_LTC_2 lut_ltc_beckmann_2
#else
#define LUT_LTC_1 lut_ltc_ggx_1
#define LUT_LTC_2 lut_ltc_ggx_2
#endif

// Reflected radiance from every polygonal light of the tile, for the model of
// lighting_common.glsl (surface_terms). Every lobe's polygon integral comes from the shader
// library: LTC (Heitz et al. 2016, ltc.h) for the specular lobes and Burley's diffuse,
// Lambert's polygon formula for the form factor, Kulla-Conty (kulla_conty.h) for the
// multiple-scattering lobes and the dielectric-over-diffuse layering. Separable lobes (f_ms,
// the layered base) integrate as (1 - E(mu_o)) / (1 - E_avg) times the form factor times
// 1 - (the cosine-weighted mean of E over the polygon), from E at the representative
// direction (that of the polygon's vector form factor) widened towards E_avg with the
// polygon's size (KC_PolygonLobe, KC_PolygonMeanE). Disney's subsurface shape and sheen are
// evaluated at the representative direction times pi x the form factor; its GTR1 coat is
// integrated as GGX at the same alpha. Per-pixel table fetches are skipped for lobes the
// material does not have (coat, Disney diffuse).
vec3 shade_lights(vec3 P, vec3 N, vec3 V, Surface s)
{
    vec2 uv = LTC_LutCoord(s.NoV, s.specR);
    vec4 ltc1 = textureLod(LUT_LTC_1, uv, 0.0f);
    vec3 specularScale = LTC_FresnelScale(textureLod(LUT_LTC_2, uv, 0.0f), s.f0, s.f90);
    bool coated = s.coat > 0.0f;
    vec4 ltc1c = LTC_Identity();
    vec3 coatScale = RTPBR_F3(0.0f);
    if (coated) {
        vec2 uvc = LTC_LutCoord(s.NoV, s.coatR);
        ltc1c = textureLod(LUT_LTC_1, uvc, 0.0f);
        coatScale = s.coat * LTC_FresnelScale(textureLod(LUT_LTC_2, uvc, 0.0f), RTPBR_F3(0.04f), 1.0f);
    }
    // Burley's diffuse (Disney): its LTC fit, column = the material's roughness.
    vec4 ltc1d = LTC_Identity();
    vec3 burleyScale = RTPBR_F3(0.0f);
    DisneyMaterial dss = s.dm; // the subsurface shape alone
    dss.subsurface = 1.0f;
    if (s.disney) {
        vec2 uvd = LTC_LutCoord(s.NoV, s.roughness);
        ltc1d = textureLod(lut_ltc_disney_1, uvd, 0.0f);
        burleyScale = ((1.0f - s.dm.subsurface) * textureLod(lut_ltc_disney_2, uvd, 0.0f).x) * s.diffuseColor;
    }
    // KHR sheen: its LTC fit (sheen.h); the layer below is scaled by the KHR albedo scaling
    // with E_sheen at NoV and at the polygon's representative direction.
    vec4 ltc1s = LTC_Identity();
    vec3 sheenScale = RTPBR_F3(0.0f);
    if (s.sheen) {
        vec2 uvs = LTC_LutCoord(s.NoV, s.sheenR);
        ltc1s = textureLod(lut_ltc_sheen_1, uvs, 0.0f);
        sheenScale = Sheen_LtcScale(textureLod(lut_ltc_sheen_2, uvs, 0.0f), s.sheenColor);
    }
    // The view direction in the LTC frame (LTC_Frame: x along V's tangential part).
    vec3 vLocal = vec3(sqrt(max(1.0f - s.NoV * s.NoV, 0.0f)), 0.0f, s.NoV);

    mat3 ltcFrame = LTC_Frame(N, V);
    // The anisotropic stretch about the mirror direction (LTC_AnisotropicStretchInverse): the
    // anisotropy direction made orthogonal to it; no stretch without one.
    vec3 mirror = vec3(-vLocal.x, 0.0f, vLocal.z);
    vec3 anisoLocal = rtpbr_mul(ltcFrame, s.anisoDir);
    vec3 e1 = anisoLocal - mirror * dot(anisoLocal, mirror);
    float e1Length = length(e1);
    bool stretched = s.anisoK > 1.0001f && e1Length > 1e-4f;
    e1 = stretched ? e1 / e1Length : vec3(1.0f, 0.0f, 0.0f);
    vec3 sum = vec3(0.0f);
    for (uint word = 0u; word < (frame.light_count + 31u) / 32u; ++word)
    for (uint bits = tile_lights[word]; bits != 0u; bits &= bits - 1u) {
        uint lightIndex = word * 32u + uint(findLSB(bits));
        Light light = lights[lightIndex];
        LtcPolygon poly;
        for (int k = 0; k < RTPBR_SHADER_MAX_POLYGON_VERTICES; ++k) poly.v[k] = light.vertices[k].xyz;
        poly.count = int(light.vertex_count);
        bool twoSided = light.emission.w != 0.0f;
        LtcLocalPolygon local = LTC_PolygonToLocal(ltcFrame, P, poly, twoSided);
        if (local.count == 0) continue;
        float ff = LTC_IntegrateLocal(local, LTC_Identity());
        // The representative direction of the polygon: its vector form factor's.
        vec3 F = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(ltcFrame, P, poly, twoSided), LTC_Identity());
        float lenF = length(F);
        vec3 lRep = lenF > 0.0f ? F / lenF : vec3(0.0f, 0.0f, 1.0f);
        float muRep = saturate(lRep.z);
        // The cosine-weighted mean of each albedo over the polygon (KC_PolygonMeanE).
        float Erep = KC_PolygonMeanE(kc_E(muRep, s.specR), s.Eavg, lenF);

        LtcLocalPolygon specularLocal = local;
        if (stretched) specularLocal = LTC_AnisotropicStretchInverse(local, mirror, e1, s.anisoK);
        vec3 lo = specularScale * LTC_IntegrateLocal(specularLocal, ltc1) + s.msColor * KC_PolygonLobe(s.Eo, Erep, s.Eavg, ff);
        vec3 base;
        if (s.disney) {
            float LoH = saturate(dot(lRep, normalize(lRep + vLocal)));
            base = burleyScale * LTC_IntegrateLocal(local, ltc1d) +
                   (s.dm.subsurface * Disney_DiffuseLobe(dss, s.NoV, muRep, LoH) + Disney_SheenLobe(s.dm, LoH)) *
                       (RTPBR_PI * ff);
        } else {
            float EFrep = s.w > 0.0f ? KC_PolygonMeanE(kc_EF(muRep, s.specR, s.eta), s.EFavg, lenF) : 0.0f;
            float Esrep = s.w * KC_SpecularAlbedoDielectric(EFrep, Erep, s.FmsDielectric);
            base = s.diffuseColor * KC_PolygonLobe(s.Eso, Esrep, s.EsAvg, ff);
        }
        lo += base;
        if (s.sheen)
            lo = lo * Sheen_AlbedoScaling(s.sheenColor, s.EsheenO, sheen_E(muRep, s.sheenR)) +
                 sheenScale * LTC_IntegrateLocal(local, ltc1s);
        lo *= s.baseAttenuation;
        if (coated)
            lo += coatScale * LTC_IntegrateLocal(local, ltc1c) +
                  s.msCoat * KC_PolygonLobe(s.Eoc, KC_PolygonMeanE(kc_E(muRep, s.coatR), s.Eavgc, lenF), s.Eavgc, ff);
        sum += light.emission.rgb * lo * shadow_factor(lightIndex);
    }
    return sum;
}

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
    vec4 g0 = texelFetch(gbuffer0, pixel, 0);
    vec4 g1 = texelFetch(gbuffer1, pixel, 0);
    vec3 V = normalize(frame.camera_position.xyz - P);
    vec3 N = normalize(g1.xyz);
    Surface s = surface_terms(g0, g1.w, materials[uint(g2.a)], saturate(dot(N, V)), texelFetch(gbuffer3, pixel, 0).xyz);
    result += shade_lights(lifted_point(ndc, depth, P, N), N, V, s);

    imageStore(radiance, pixel, vec4(result, 1.0));
}
