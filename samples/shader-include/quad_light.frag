#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// A GLSL fragment shader of your own that includes the rtpbr shader library directly
// (compile with: glslangValidator -V -I<path>/shaderlib quad_light.frag) and shades one
// quadrilateral area light the way rtpbr's engine does (shaderlib/rtpbr/area_light.h): a
// glTF metallic-roughness material (Material_Resolve), its GGX (or Beckmann) specular lobe and
// Lambertian base integrated over the quad with Linearly Transformed Cosines, the LTC
// corrections, and the Kulla-Conty multiple-scattering and layering terms. The library never
// samples textures: this shader says how it reads the light and its tables (the Host_*
// functions, defined before the includes that call them). Pick models with -D before the
// includes, e.g. -DRTPBR_NDF=RTPBR_NDF_BECKMANN, -DRTPBR_MULTISCATTER=0.
#include "rtpbr/lang.h"
#include "rtpbr/config.h"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outRadiance; // linear; tone-map in a later pass

layout(set = 0, binding = 0, std140) uniform Shading {
    vec4 quadCorners[4];   // world space, counter-clockwise seen from the emitting side
    vec4 lightRadiance;    // rgb: radiance; w != 0: emits from both sides
    vec4 cameraPosition;   // xyz
    vec4 baseColorMetallic;// rgb: linear base colour, a: metallic
    vec4 surface;          // x: perceptual roughness, y: KHR_materials_ior ior (1.5)
} shading;

// Tables from shaderlib/luts/, uploaded as their headers describe; linear filtering,
// clamp to edge (variant = the NDF's: rtpbr_kc_tables.h):
//   ltcMatrix    rtpbr_ltc_ggx_1 (or _beckmann_1), 64x64 RGBA32F
//   ltcScale     rtpbr_ltc_ggx_2 (or _beckmann_2), 64x64 RGBA32F
//   kcAlbedo     rtpbr_kc_E[variant], 32x32 R32F (rows: roughness, columns: KC_MuAxis(mu))
//   kcAvgAlbedo  rtpbr_kc_Eavg[variant], 32x1 R32F
//   kcAlbedoF    rtpbr_kc_EF[variant], 32x32x16 R32F (the dielectric's, depth: KC_EtaAxis(eta))
//   kcAvgAlbedoF rtpbr_kc_EFavg[variant], 32x16 R32F
layout(set = 0, binding = 1) uniform sampler2D ltcMatrix;
layout(set = 0, binding = 2) uniform sampler2D ltcScale;
layout(set = 0, binding = 3) uniform sampler2D kcAlbedo;
layout(set = 0, binding = 4) uniform sampler2D kcAvgAlbedo;
layout(set = 0, binding = 5) uniform sampler3D kcAlbedoF;
layout(set = 0, binding = 6) uniform sampler2D kcAvgAlbedoF;

#include "rtpbr/kulla_conty.h"
#include "rtpbr/sheen.h"

// The host bridge (area_light.h, surface.h): light 0 is the quad.
uint Host_LightVertexCount(uint light) { return 4u; }
vec3 Host_LightVertex(uint light, uint k) { return shading.quadCorners[k].xyz; }
vec4 Host_LightPlane(uint light)
{
    vec3 n = normalize(cross(shading.quadCorners[1].xyz - shading.quadCorners[0].xyz,
                             shading.quadCorners[2].xyz - shading.quadCorners[0].xyz));
    return vec4(n, -dot(n, shading.quadCorners[0].xyz));
}
vec4 Host_LightSphere(uint light)
{
    vec3 c = 0.25f * (shading.quadCorners[0].xyz + shading.quadCorners[1].xyz + shading.quadCorners[2].xyz +
                      shading.quadCorners[3].xyz);
    float r = 0.0f;
    for (int k = 0; k < 4; ++k) r = max(r, length(shading.quadCorners[k].xyz - c));
    return vec4(c, r);
}
bool Host_LightTwoSided(uint light) { return shading.lightRadiance.w != 0.0f; }
vec3 Host_LightRadiance(uint light) { return shading.lightRadiance.rgb; }
vec3 Host_LightVisibility(uint light) { return vec3(1.0f); } // no shadows here
vec4 Host_TableLtc1(int table, vec2 uv) { return textureLod(ltcMatrix, uv, 0.0f); }
vec4 Host_TableLtc2(int table, vec2 uv) { return textureLod(ltcScale, uv, 0.0f); }
vec2 Host_TableE_EF(float mu, float r, float eta)
{
    return vec2(textureLod(kcAlbedo, KC_TableCoord(mu, r), 0.0f).r,
                textureLod(kcAlbedoF, KC_TableCoord3D(mu, r, eta), 0.0f).r);
}
float Host_TableE(float mu, float r) { return textureLod(kcAlbedo, KC_TableCoord(mu, r), 0.0f).r; }
float Host_TableEavg(float r) { return textureLod(kcAvgAlbedo, vec2(KC_TableCoordAvg(r), 0.5f), 0.0f).r; }
float Host_TableEFavg(float r, float eta) { return textureLod(kcAvgAlbedoF, KC_TableCoordAvg2D(r, eta), 0.0f).r; }
float Host_TableSheenE(float mu, float r) { return 0.0f; } // no sheen in this material

#define RTPBR_AREA_LIGHT_FULL 0 // metallic-roughness without coat, sheen or anisotropy
#define RTPBR_UNROLL [[unroll]]
#define RTPBR_DONT_UNROLL [[dont_unroll]]
#include "rtpbr/material.h"
#include "rtpbr/surface.h"
#include "rtpbr/area_light.h"

void main()
{
    vec3 P = inWorldPosition;
    vec3 N = normalize(inWorldNormal);
    vec3 V = normalize(shading.cameraPosition.xyz - P);

    MaterialInputs m;
    m.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = shading.baseColorMetallic.rgb;
    m.metallic = shading.baseColorMetallic.a;
    m.roughness = shading.surface.x;
    m.ior = shading.surface.y;
    m.specularFactor = 1.0f;
    m.specularColor = vec3(1.0f);
    m.clearcoatFactor = 0.0f;
    m.clearcoatRoughness = 0.0f;
    m.sheenColorFactor = vec3(0.0f);
    m.sheenRoughness = 0.0f;
    m.anisotropyStrength = 0.0f;
    m.disney = Disney_DefaultMaterial();
    ShadingSurface s = Surface_Resolve(Material_Resolve(m), rtpbr_saturate(dot(N, V)), vec3(0.0f));

    outRadiance = vec4(AreaLight_Evaluate(s, P, N, V, 0u), 1.0f);
}
