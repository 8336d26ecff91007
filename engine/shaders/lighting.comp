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
#include "material.glsl"
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
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EF) uniform sampler2D lut_kc_ef;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EFAVG) uniform sampler2D lut_kc_efavg;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_1) uniform sampler2D lut_ltc_disney_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_2) uniform sampler2D lut_ltc_disney_2;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

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

// Kulla-Conty tables (shaderlib/luts, kulla_conty.h coordinates).
float kc_E(float mu, float r) { return textureLod(lut_kc_e, KC_TableCoord(mu, r), 0.0f).KC_CHANNEL; }
float kc_Eavg(float r) { return textureLod(lut_kc_eavg, vec2(KC_TableCoordAvg(r), 0.5f), 0.0f).KC_CHANNEL; }
// E_F(mu, r, eta): the eta slices are stacked along v (engine/src/luts.c); two bilinear
// fetches at the neighbouring slices and a lerp along eta make the trilinear lookup.
float kc_EF(float mu, float r, float eta)
{
    vec2 uv = KC_TableCoord(mu, r);
    float s = KC_EtaAxis(eta) * (KC_LUT_SIZE_ETA - 1.0f);
    float s0 = min(floor(s), KC_LUT_SIZE_ETA - 2.0f);
    float v0 = (s0 + uv.y) / KC_LUT_SIZE_ETA; // uv.y * KC_LUT_SIZE texels into slice s0
    float e0 = textureLod(lut_kc_ef, vec2(uv.x, v0), 0.0f).KC_CHANNEL;
    float e1 = textureLod(lut_kc_ef, vec2(uv.x, v0 + 1.0f / KC_LUT_SIZE_ETA), 0.0f).KC_CHANNEL;
    return mix(e0, e1, s - s0);
}
float kc_EFavg(float r, float eta) { return textureLod(lut_kc_efavg, KC_TableCoordAvg2D(r, eta), 0.0f).KC_CHANNEL; }

// Reflected radiance from every polygonal light of the tile. Every lobe's polygon integral
// comes from the shader library: LTC (Heitz et al. 2016, ltc.h) for the specular lobes and
// Burley's diffuse, Lambert's polygon formula for the form factor, Kulla-Conty (kulla_conty.h)
// for the multiple-scattering lobes and the dielectric-over-diffuse layering. The model is
// the oracle's (oracle/bsdf.h, docs/materials.md):
//   metallic-roughness: f = (1 - c Fc(NoV)) [metallic f_metal + (1 - metallic) f_dielectric]
//                           + c f_coat,
//     f_metal = GGX, Schlick(F0 = baseColor, 1) + its Kulla-Conty lobe,
//     f_dielectric = w GGX Schlick(F0(ior) specularColor, 1) + w F_ms f_ms
//                    + baseColor (1 - Es(mu_o)) (1 - Es(mu_i)) / (pi (1 - Es_avg)),
//     Es = w (E_F + F_ms (1 - E)) (KC_SpecularAlbedoDielectric; E_F with exact Fresnel),
//     f_coat = GGX(clearcoat roughness), Schlick(0.04, 1) + its Kulla-Conty lobe;
//   Disney (Burley 2012, disney.h): specular GGX Schlick(Disney_SpecularF0, 1) + Kulla-Conty
//     lobe, Burley diffuse by its own LTC fit, the subsurface shape and sheen at the polygon's
//     representative direction, clearcoat 0.25 c GGX(sqrt(GTR1 alpha)) Schlick(0.04, 1).
// Separable lobes (f_ms, the layered base) integrate as (1 - E(mu_o)) / (1 - E_avg) times the
// form factor times 1 - (the cosine-weighted mean of E over the polygon), from E at the
// representative direction (that of the polygon's vector form factor) widened towards E_avg
// with the polygon's size (KC_PolygonLobe, KC_PolygonMeanE). Anisotropic lobes are shaded isotropically at sqrt(alpha_t alpha_b).
vec3 shade_lights(vec3 P, vec3 N, vec3 V, vec4 g0, float roughness, Material m)
{
    vec3 baseColor = g0.rgb;
    float metallic = g0.a;
    float NoV = saturate(dot(N, V));
    bool disney = m.coat.z > 0.5f;

    DisneyMaterial dm;
    dm.baseColor = baseColor;
    dm.metallic = metallic;
    dm.subsurface = m.disney0.x;
    dm.specular = m.disney0.y;
    dm.specularTint = m.disney0.z;
    dm.roughness = roughness;
    dm.anisotropic = m.disney1.w;
    dm.sheen = m.disney0.w;
    dm.sheenTint = m.disney1.x;
    dm.clearcoat = m.disney1.y;
    dm.clearcoatGloss = m.disney1.z;
    dm = Disney_SanitizeMaterial(dm);
    DisneyMaterial dss = dm; // the subsurface shape alone
    dss.subsurface = 1.0f;

    // The specular lobe, isotropic at sqrt(alpha_t alpha_b) (KHR: alpha_t = mix(alpha, 1, s^2)).
    float alpha = roughness * roughness;
    float aniso = m.coat.w;
    float specR = disney ? Disney_SpecularTableRoughness(dm) : sqrt(sqrt(mix(alpha, 1.0f, aniso * aniso) * alpha));
    specR = clamp(specR, RTPBR_SHADER_MIN_ROUGHNESS, 1.0f);
    float w = m.specular.x;
    float eta = m.specular_color_ior.w;
    vec3 f0Dielectric = min(RTPBR_F3(F0_FromIor(eta)) * m.specular_color_ior.rgb, RTPBR_F3(1.0f));
    vec3 f0 = disney ? Disney_SpecularF0(dm) : mix(w * f0Dielectric, baseColor, metallic);
    float f90 = disney ? 1.0f : mix(w, 1.0f, metallic);
    vec2 uv = LTC_LutCoord(NoV, specR);
    vec4 ltc1 = textureLod(LUT_LTC_1, uv, 0.0f);
    vec3 specularScale = LTC_FresnelScale(textureLod(LUT_LTC_2, uv, 0.0f), f0, f90);
    float Eo = kc_E(NoV, specR);
    float Eavg = kc_Eavg(specR);
#if RTPBR_MULTISCATTER
    float FmsDielectric = KC_FmsColor(RTPBR_F3(F_Avg_Dielectric(eta)), Eavg).x;
    vec3 msColor = disney ? KC_FmsColor(F_Avg_Schlick(f0, 1.0f), Eavg)
                          : metallic * KC_FmsColor(F_Avg_Schlick(baseColor, 1.0f), Eavg) +
                                RTPBR_F3((1.0f - metallic) * w * FmsDielectric);
#else
    float FmsDielectric = 0.0f;
    vec3 msColor = RTPBR_F3(0.0f);
#endif
    // The layered base (metallic-roughness): the specular layer's albedo at mu_o and on average.
    vec3 diffuseColor = (1.0f - metallic) * baseColor;
    float Eso = w * KC_SpecularAlbedoDielectric(kc_EF(NoV, specR, eta), Eo, FmsDielectric);
    float EFavg = kc_EFavg(specR, eta);
    float EsAvg = w * KC_SpecularAlbedoDielectric(EFavg, Eavg, FmsDielectric);
    // Burley's diffuse (Disney): its LTC fit, column = the material's roughness.
    vec2 uvd = LTC_LutCoord(NoV, roughness);
    vec4 ltc1d = textureLod(lut_ltc_disney_1, uvd, 0.0f);
    vec3 burleyScale = ((1.0f - dm.subsurface) * textureLod(lut_ltc_disney_2, uvd, 0.0f).x) * diffuseColor;
    // The view direction in the LTC frame (LTC_Frame: x along V's tangential part).
    vec3 vLocal = vec3(sqrt(max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);

    // The coat: KHR clearcoat (attenuates the rest by 1 - c Fc(NoV)) or Disney's (does not).
    float coat = disney ? RTPBR_DISNEY_CLEARCOAT_SCALE * dm.clearcoat : m.coat.x;
    float coatR = clamp(disney ? sqrt(Disney_ClearcoatAlpha(dm)) : m.coat.y, RTPBR_SHADER_MIN_ROUGHNESS, 1.0f);
    float baseAttenuation = disney ? 1.0f : 1.0f - coat * F_Schlick1(0.04f, 1.0f, NoV);
    vec2 uvc = LTC_LutCoord(NoV, coatR);
    vec4 ltc1c = textureLod(LUT_LTC_1, uvc, 0.0f);
    vec3 coatScale = coat * LTC_FresnelScale(textureLod(LUT_LTC_2, uvc, 0.0f), RTPBR_F3(0.04f), 1.0f);
    float Eoc = kc_E(NoV, coatR);
    float Eavgc = kc_Eavg(coatR);
#if RTPBR_MULTISCATTER
    vec3 msCoat = coat * KC_FmsColor(F_Avg_Schlick(RTPBR_F3(0.04f), 1.0f), Eavgc);
#else
    vec3 msCoat = RTPBR_F3(0.0f);
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
        float ff = LTC_IntegrateLocal(local, LTC_Identity());
        // The representative direction of the polygon: its vector form factor's.
        vec3 F = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(ltcFrame, P, poly, twoSided), LTC_Identity());
        float lenF = length(F);
        vec3 lRep = lenF > 0.0f ? F / lenF : vec3(0.0f, 0.0f, 1.0f);
        float muRep = saturate(lRep.z);
        // The cosine-weighted mean of each albedo over the polygon (KC_PolygonMeanE).
        float Erep = KC_PolygonMeanE(kc_E(muRep, specR), Eavg, lenF);
        float EFrep = KC_PolygonMeanE(kc_EF(muRep, specR, eta), EFavg, lenF);

        vec3 lo = specularScale * LTC_IntegrateLocal(local, ltc1) + msColor * KC_PolygonLobe(Eo, Erep, Eavg, ff);
        float Esrep = w * KC_SpecularAlbedoDielectric(EFrep, Erep, FmsDielectric);
        vec3 base = diffuseColor * KC_PolygonLobe(Eso, Esrep, EsAvg, ff);
        if (disney) {
            float LoH = saturate(dot(lRep, normalize(lRep + vLocal)));
            base = burleyScale * LTC_IntegrateLocal(local, ltc1d) +
                   (dm.subsurface * Disney_DiffuseLobe(dss, NoV, muRep, LoH) + Disney_SheenLobe(dm, LoH)) * (RTPBR_PI * ff);
        }
        lo = (lo + base) * baseAttenuation;
        if (coat > 0.0f)
            lo += coatScale * LTC_IntegrateLocal(local, ltc1c) + msCoat * KC_PolygonLobe(Eoc, KC_PolygonMeanE(kc_E(muRep, coatR), Eavgc, lenF), Eavgc, ff);
        sum += light.emission.rgb * lo;
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
    // The position from the depth buffer is off by up to about one depth quantum along the
    // view ray; an emitter's own surface could then land on its emitting side and light
    // itself. Shade a point lifted along N by a few quanta (measured at this depth) instead.
    vec4 further = frame.inv_view_proj * vec4(ndc, min(depth * (1.0f + 4.0f / 16777216.0f), 1.0f), 1.0f);
    float lift = length(further.xyz / further.w - P) + 1e-6f * length(frame.camera_position.xyz - P);
    result += shade_lights(P + N * lift, N, V, g0, g1.w, materials[uint(g2.a)]);

    imageStore(radiance, pixel, vec4(result, 1.0));
}
