#version 450
// Compile check of shaderlib/rtpbr/area_light.h's disk lights as GLSL (RTPBR_AREA_LIGHT_DISKS
// 1; its HLSL twin: area_light_compile.hlsl): a host bridge over a buffer of lights (each a
// quad's corners or a disk's centre and half-axes), the disk path called by AreaLight_AddDisk
// and by AreaLight_AddShape's run-time flag, beside polygons (and spheres, with
// -DRTPBR_AREA_LIGHT_SPHERES=1). The meson test runs it with the flags' other values too
// (RTPBR_AREA_LIGHT_FULL, _SPHERE_CLIP), and with textured quads (-DRTPBR_AREA_LIGHT_TEXTURED=1)
// and tubes (-DRTPBR_AREA_LIGHT_TUBES=1; with a range: -DRTPBR_AREA_LIGHT_TUBE_RANGE=1).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "rtpbr/lang.h"
#include "rtpbr/config.h"

layout(local_size_x = 1) in;
struct Light {
    vec4 v[4];      // a quad's corners; a disk's centre (v[0].xyz, w its longer half-axis) and half-axes v[1], v[2]
    vec4 radiance;  // rgb; w: 1 = a disk, 2 = a sphere (v[0]: centre, radius), 3 = a textured quad, 4 = a tube (v[0], v[1]: its ends, w its radius), else a quad
};
layout(std430, binding = 0) readonly buffer Lights { Light lights[]; };
layout(std430, binding = 1) buffer Out { vec4 result[]; };
layout(binding = 2) uniform sampler2D tables[4];

#include "rtpbr/kulla_conty.h"
#include "rtpbr/sheen.h"

uint Host_LightVertexCount(uint light) { return 4u; }
vec3 Host_LightVertex(uint light, uint k) { return lights[light].v[k].xyz; }
vec4 Host_LightPlane(uint light) {
    vec3 n = normalize(cross(lights[light].v[1].xyz - lights[light].v[0].xyz, lights[light].v[2].xyz - lights[light].v[0].xyz));
    return vec4(n, -dot(n, lights[light].v[0].xyz));
}
vec4 Host_LightSphere(uint light) { return lights[light].v[0]; }
vec3 Host_LightDiskAxis(uint light, uint k) { return lights[light].v[1u + k].xyz; }
vec4 Host_LightPosition(uint light) { return vec4(lights[light].v[0].xyz, 0.0f); }
bool Host_LightTwoSided(uint light) { return false; }
vec3 Host_LightRadiance(uint light) { return lights[light].radiance.rgb; }
vec3 Host_LightVisibility(uint light) { return vec3(1.0f); }
vec4 Host_LightTube(uint light, uint k) { return lights[light].v[k]; }
float Host_LightTubeInvRange2(uint light) { return lights[light].v[3].w; } // (RTPBR_AREA_LIGHT_TUBE_RANGE)
// (RTPBR_AREA_LIGHT_TEXTURED: a textured quad's emission, here one of the tables)
vec3 Host_LightTexture(uint light, vec3 lookup) { return textureLod(tables[3], lookup.xy, log2(max(lookup.z * 128.0f, 1e-6f))).rgb; }
vec4 Host_TableLtc1(int table, vec2 uv) { return textureLod(tables[0], uv, 0.0f); }
vec4 Host_TableLtc2(int table, vec2 uv) { return textureLod(tables[1], uv, 0.0f); }
vec2 Host_TableE_EF(float mu, float r, float eta) { return textureLod(tables[2], KC_TableCoord(mu, r), 0.0f).rg; }
float Host_TableE(float mu, float r) { return textureLod(tables[2], KC_TableCoord(mu, r), 0.0f).r; }
float Host_TableEavg(float r) { return textureLod(tables[3], vec2(KC_TableCoordAvg(r), 0.5f), 0.0f).r; }
float Host_TableEFavg(float r, float eta) { return textureLod(tables[3], KC_TableCoordAvg2D(r, eta), 0.0f).r; }
float Host_TableSheenE(float mu, float r) { return 0.0f; }

#define RTPBR_AREA_LIGHT_DISKS 1
#define RTPBR_UNROLL [[unroll]]
#define RTPBR_DONT_UNROLL [[dont_unroll]]
#include "rtpbr/material.h"
#include "rtpbr/surface.h"
#include "rtpbr/area_light.h"

void main() {
    vec3 P = vec3(0.0f), N = vec3(0.0f, 0.0f, 1.0f), V = normalize(vec3(0.3f, 0.0f, 1.0f));
    MaterialInputs m;
    m.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = vec3(0.8f);
    m.metallic = 0.0f;
    m.roughness = 0.4f;
    m.ior = 1.5f;
    m.specularFactor = 1.0f;
    m.specularColor = vec3(1.0f);
    m.clearcoatFactor = 0.0f;
    m.clearcoatRoughness = 0.0f;
    m.sheenColorFactor = vec3(0.0f);
    m.sheenRoughness = 0.0f;
    m.anisotropyStrength = 0.0f;
    m.disney = Disney_DefaultMaterial();
    ShadingSurface s = Surface_Resolve(Material_Resolve(m), rtpbr_saturate(dot(N, V)), vec3(0.0f));
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    AreaLightSum acc = AreaLight_SumBegin();
    for (uint i = 0u; i < uint(lights.length()); ++i) {
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
    result[0] = vec4(AreaLight_End(px, acc, s, P), 1.0f);
}
