#version 450
#extension GL_GOOGLE_include_directive : require
// rtpbr-sample-host's G-buffer shader (samples/host; tests/engine/test_engine_lightpass uses
// it too): the host's material table (its own layout), written through the shader library's
// G-buffer contract (gbuffer.h) as a host would: GBuffer_DefaultSurface, the fields it knows,
// GBuffer_Encode (with its clean-up: not trusted).
#include "rtpbr/lang.h"
#include "rtpbr/gbuffer.h"
#if RTPBR_GBUFFER_VERSION != 1
#error "this shader writes G-buffer layout 1"
#endif

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(push_constant) uniform Draw {
    mat4 view_proj;
    vec4 camera;
    uint material;
} draw;
struct HostMaterial {
    vec4 base_metallic;      // linear base colour, metallic
    vec4 emission_roughness; // emitted radiance, perceptual roughness
};
layout(set = 0, binding = 0, std430) readonly buffer HostMaterials {
    HostMaterial materials[];
};
layout(location = 0) out vec4 out_g0;
layout(location = 1) out vec4 out_g1;
layout(location = 2) out vec4 out_g2;
layout(location = 3) out vec4 out_g3;

void main()
{
    HostMaterial m = materials[draw.material];
    vec3 n = normalize(in_normal);
    bool back = dot(n, draw.camera.xyz - in_world) < 0.0; // shade the side the camera sees
    GBufferSurface g = GBuffer_DefaultSurface();
    g.baseColor = m.base_metallic.rgb;
    g.metallic = m.base_metallic.a;
    g.normal = back ? -n : n;
    g.roughness = m.emission_roughness.a;
    g.emission = m.emission_roughness.rgb; // double-sided emitters
    g.materialIndex = draw.material;       // the record rtpbr reads (the targets' materials)
    GBufferTargets t = GBuffer_Encode(g);
    out_g0 = t.g0;
    out_g1 = t.g1;
    out_g2 = t.g2;
    out_g3 = t.g3;
}
