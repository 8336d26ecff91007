// Compile check of shaderlib/rtpbr/area_light.h's disk lights as HLSL (glslang's HLSL front
// end): the twin of area_light_compile.comp, the same bridge and calls.
#define RTPBR_HLSL 1
#include "rtpbr/lang.h"
#include "rtpbr/config.h"

struct Light {
    float4 v[4];     // a quad's corners; a disk's centre (v[0].xyz, w its longer half-axis) and half-axes v[1], v[2]
    float4 radiance; // rgb; w: 1 = a disk, 2 = a sphere (v[0]: centre, radius), 3 = a textured quad, 4 = a tube (v[0], v[1]: its ends, w its radius), else a quad
};
StructuredBuffer<Light> lights : register(t0);
RWStructuredBuffer<float4> result : register(u1);
SamplerState lutSampler : register(s2);
Texture2D<float4> tables[4] : register(t3);

#include "rtpbr/kulla_conty.h"
#include "rtpbr/sheen.h"

uint Host_LightVertexCount(uint light) { return 4u; }
float3 Host_LightVertex(uint light, uint k) { return lights[light].v[k].xyz; }
float4 Host_LightPlane(uint light) {
    float3 n = normalize(cross(lights[light].v[1].xyz - lights[light].v[0].xyz, lights[light].v[2].xyz - lights[light].v[0].xyz));
    return float4(n, -dot(n, lights[light].v[0].xyz));
}
float4 Host_LightSphere(uint light) { return lights[light].v[0]; }
float3 Host_LightDiskAxis(uint light, uint k) { return lights[light].v[1u + k].xyz; }
float4 Host_LightPosition(uint light) { return float4(lights[light].v[0].xyz, 0.0f); }
bool Host_LightTwoSided(uint light) { return false; }
float3 Host_LightRadiance(uint light) { return lights[light].radiance.rgb; }
float3 Host_LightVisibility(uint light) { return RTPBR_F3(1.0f); }
float4 Host_LightTube(uint light, uint k) { return lights[light].v[k]; }
float Host_LightTubeInvRange2(uint light) { return lights[light].v[3].w; } // (RTPBR_AREA_LIGHT_TUBE_RANGE)
// (RTPBR_AREA_LIGHT_TEXTURED: a textured quad's emission, here one of the tables)
float3 Host_LightTexture(uint light, float3 lookup) { return tables[3].SampleLevel(lutSampler, lookup.xy, log2(max(lookup.z * 128.0f, 1e-6f))).rgb; }
float4 Host_TableLtc1(int table, float2 uv) { return tables[0].SampleLevel(lutSampler, uv, 0.0f); }
float4 Host_TableLtc2(int table, float2 uv) { return tables[1].SampleLevel(lutSampler, uv, 0.0f); }
float2 Host_TableE_EF(float mu, float r, float eta) { return tables[2].SampleLevel(lutSampler, KC_TableCoord(mu, r), 0.0f).rg; }
float Host_TableE(float mu, float r) { return tables[2].SampleLevel(lutSampler, KC_TableCoord(mu, r), 0.0f).r; }
float Host_TableEavg(float r) { return tables[3].SampleLevel(lutSampler, float2(KC_TableCoordAvg(r), 0.5f), 0.0f).r; }
float Host_TableEFavg(float r, float eta) { return tables[3].SampleLevel(lutSampler, KC_TableCoordAvg2D(r, eta), 0.0f).r; }
float Host_TableSheenE(float mu, float r) { return 0.0f; }

#define RTPBR_AREA_LIGHT_DISKS 1
#define RTPBR_UNROLL [unroll]
#define RTPBR_DONT_UNROLL [loop]
#include "rtpbr/material.h"
#include "rtpbr/surface.h"
#include "rtpbr/area_light.h"

[numthreads(1, 1, 1)]
void main() {
    float3 P = RTPBR_F3(0.0f), N = float3(0.0f, 0.0f, 1.0f), V = normalize(float3(0.3f, 0.0f, 1.0f));
    MaterialInputs m;
    m.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = RTPBR_F3(0.8f);
    m.metallic = 0.0f;
    m.roughness = 0.4f;
    m.ior = 1.5f;
    m.specularFactor = 1.0f;
    m.specularColor = RTPBR_F3(1.0f);
    m.clearcoatFactor = 0.0f;
    m.clearcoatRoughness = 0.0f;
    m.sheenColorFactor = RTPBR_F3(0.0f);
    m.sheenRoughness = 0.0f;
    m.anisotropyStrength = 0.0f;
    m.disney = Disney_DefaultMaterial();
    ShadingSurface s = Surface_Resolve(Material_Resolve(m), rtpbr_saturate(dot(N, V)), RTPBR_F3(0.0f));
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    AreaLightSum acc = AreaLight_SumBegin();
    uint count, stride;
    lights.GetDimensions(count, stride);
    for (uint i = 0u; i < count; ++i) {
        float kind = lights[i].radiance.w;
        if (kind == 1.0f)
            AreaLight_AddDisk(px, acc, s, P, N, i);
#if RTPBR_AREA_LIGHT_SPHERES
        else if (kind == 2.0f)
            AreaLight_AddSphere(px, acc, s, P, N, i);
#endif
        else
            AreaLight_Add(px, acc, s, P, N, i);
        // the run-time flag: one call for every kind
        AreaLight_AddShape(px, acc, s, P, N, i, kind == 2.0f, kind == 1.0f RTPBR_AREA_LIGHT_TEXTURE_ARG(kind == 3.0f)
                               RTPBR_AREA_LIGHT_TUBE_ARG(kind == 4.0f));
#if RTPBR_AREA_LIGHT_TUBES
        if (kind == 4.0f)
            AreaLight_AddTube(px, acc, s, P, N, i);
#endif
#if RTPBR_AREA_LIGHT_TEXTURED
        if (kind == 3.0f)
            AreaLight_AddTexturedQuad(px, acc, s, P, N, i);
#endif
    }
    result[0] = float4(AreaLight_End(px, acc, s, P), 1.0f);
}
