// The HLSL twin of quad_light.frag: a pixel shader of your own that includes the rtpbr
// shader library directly and shades one quadrilateral area light the way rtpbr's engine does
// (shaderlib/rtpbr/area_light.h). RTPBR_HLSL must be defined before the includes (DXC defines
// __HLSL_VERSION, which the library also recognises; glslang does not).
// Compile with:  glslangValidator -V -D -e main -S frag -I<path>/shaderlib quad_light.hlsl
//           or:  dxc -T ps_6_0 -E main -I <path>/shaderlib quad_light.hlsl
#define RTPBR_HLSL 1
#include "rtpbr/lang.h"
#include "rtpbr/config.h"

cbuffer Shading : register(b0) {
    float4 quadCorners[4];    // world space, counter-clockwise seen from the emitting side
    float4 lightRadiance;     // rgb: radiance; w != 0: emits from both sides
    float4 cameraPosition;    // xyz
    float4 baseColorMetallic; // rgb: linear base colour, a: metallic
    float4 surface;           // x: perceptual roughness, y: KHR_materials_ior ior (1.5)
};

// Tables from shaderlib/luts/ (see quad_light.frag for the layouts); linear, clamp to edge.
SamplerState lutSampler : register(s1);
Texture2D<float4> ltcMatrix : register(t2);    // rtpbr_ltc_ggx_1
Texture2D<float4> ltcScale : register(t3);     // rtpbr_ltc_ggx_2
Texture2D<float> kcAlbedo : register(t4);      // rtpbr_kc_E[variant]
Texture2D<float> kcAvgAlbedo : register(t5);   // rtpbr_kc_Eavg[variant]
Texture3D<float> kcAlbedoF : register(t6);     // rtpbr_kc_EF[variant]
Texture2D<float> kcAvgAlbedoF : register(t7);  // rtpbr_kc_EFavg[variant]

#include "rtpbr/kulla_conty.h"
#include "rtpbr/sheen.h"

// The host bridge (area_light.h, surface.h): light 0 is the quad.
uint Host_LightVertexCount(uint light) { return 4u; }
float3 Host_LightVertex(uint light, uint k) { return quadCorners[k].xyz; }
float4 Host_LightPlane(uint light)
{
    float3 n = normalize(cross(quadCorners[1].xyz - quadCorners[0].xyz, quadCorners[2].xyz - quadCorners[0].xyz));
    return float4(n, -dot(n, quadCorners[0].xyz));
}
float4 Host_LightSphere(uint light)
{
    float3 c = 0.25f * (quadCorners[0].xyz + quadCorners[1].xyz + quadCorners[2].xyz + quadCorners[3].xyz);
    float r = 0.0f;
    for (int k = 0; k < 4; ++k) r = max(r, length(quadCorners[k].xyz - c));
    return float4(c, r);
}
bool Host_LightTwoSided(uint light) { return lightRadiance.w != 0.0f; }
float3 Host_LightRadiance(uint light) { return lightRadiance.rgb; }
float3 Host_LightVisibility(uint light) { return RTPBR_F3(1.0f); } // no shadows here
float4 Host_TableLtc1(int table, float2 uv) { return ltcMatrix.SampleLevel(lutSampler, uv, 0.0f); }
float4 Host_TableLtc2(int table, float2 uv) { return ltcScale.SampleLevel(lutSampler, uv, 0.0f); }
float2 Host_TableE_EF(float mu, float r, float eta)
{
    return float2(kcAlbedo.SampleLevel(lutSampler, KC_TableCoord(mu, r), 0.0f),
                  kcAlbedoF.SampleLevel(lutSampler, KC_TableCoord3D(mu, r, eta), 0.0f));
}
float Host_TableE(float mu, float r) { return kcAlbedo.SampleLevel(lutSampler, KC_TableCoord(mu, r), 0.0f); }
float Host_TableEavg(float r) { return kcAvgAlbedo.SampleLevel(lutSampler, float2(KC_TableCoordAvg(r), 0.5f), 0.0f); }
float Host_TableEFavg(float r, float eta) { return kcAvgAlbedoF.SampleLevel(lutSampler, KC_TableCoordAvg2D(r, eta), 0.0f); }
float Host_TableSheenE(float mu, float r) { return 0.0f; } // no sheen in this material

#define RTPBR_AREA_LIGHT_FULL 0 // metallic-roughness without coat, sheen or anisotropy
#define RTPBR_UNROLL [unroll]
#define RTPBR_DONT_UNROLL [loop]
#include "rtpbr/material.h"
#include "rtpbr/surface.h"
#include "rtpbr/area_light.h"

struct PixelInput {
    float4 position : SV_Position;
    float3 worldPosition : TEXCOORD0;
    float3 worldNormal : TEXCOORD1;
};

float4 main(PixelInput input) : SV_Target
{
    float3 P = input.worldPosition;
    float3 N = normalize(input.worldNormal);
    float3 V = normalize(cameraPosition.xyz - P);

    MaterialInputs m;
    m.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = baseColorMetallic.rgb;
    m.metallic = baseColorMetallic.a;
    m.roughness = surface.x;
    m.ior = surface.y;
    m.specularFactor = 1.0f;
    m.specularColor = RTPBR_F3(1.0f);
    m.clearcoatFactor = 0.0f;
    m.clearcoatRoughness = 0.0f;
    m.sheenColorFactor = RTPBR_F3(0.0f);
    m.sheenRoughness = 0.0f;
    m.anisotropyStrength = 0.0f;
    m.disney = Disney_DefaultMaterial();
    ShadingSurface s = Surface_Resolve(Material_Resolve(m), saturate(dot(N, V)), RTPBR_F3(0.0f));

    return float4(AreaLight_Evaluate(s, P, N, V, 0u), 1.0f);
}
