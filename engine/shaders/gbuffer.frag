#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass: writes the material parameters the lighting pass needs, through the shader
// library's G-buffer contract (shaderlib/rtpbr/gbuffer.h: the layout, GBuffer_Encode).
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/material.h"
#define RTPBR_GBUFFER_TRUSTED 1 // values from validated materials (gbuffer.h)
#include "rtpbr/gbuffer.h"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_GBUFFER_FRAME
#include "frame.glsl"

#include "draw.glsl"

#include "material.glsl"
layout(set = 0, binding = RTPBR_BINDING_GBUFFER_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

#include "fragment_material.glsl"

// gbuffer.h's targets g0 to g6 (their formats: engine/src/passes/gbuffer.c). The extension
// texels (g4 to g6) are written only in frames whose scene has such textures (rtpbr_shared.h,
// RTPBR_EXTENSION_TEXTURES_*; otherwise these attachments have no image view).
layout(location = 0) out vec4 out_gbuffer0;
layout(location = 1) out vec4 out_gbuffer1;
layout(location = 2) out vec4 out_gbuffer2;
layout(location = 3) out vec4 out_gbuffer3;
layout(location = 4) out vec4 out_gbuffer4;
layout(location = 5) out vec4 out_gbuffer5;
layout(location = 6) out vec2 out_gbuffer6;

void main()
{
    Material m = materials[draw.material];
    FragmentMaterial f = fragment_material(m); // samples every texture first
    GBufferSurface g = GBuffer_DefaultSurface();
    // The extension textures' values (multipliers of the material's factors in the lighting
    // passes), sampled here too before any discard, in uniform control flow (a branch on the
    // frame's uniform flags keeps it uniform); only for scenes that have such textures.
    bool specular = (frame.extension_textures & RTPBR_EXTENSION_TEXTURES_SPECULAR) != 0u;
    bool coat_sheen = (frame.extension_textures & RTPBR_EXTENSION_TEXTURES_COAT_SHEEN) != 0u;
    if (specular)
        g.specular = vec4(texture(specular_color_texture, in_uv_specular.zw).rgb,
                          texture(specular_texture, in_uv_specular.xy).a);
    if (coat_sheen) {
        g.sheen = vec4(texture(sheen_color_texture, in_uv_sheen.xy).rgb,
                       texture(sheen_roughness_texture, in_uv_sheen.zw).a);
        g.coat = vec2(texture(clearcoat_texture, in_uv_clearcoat.xy).r,
                      texture(clearcoat_roughness_texture, in_uv_clearcoat.zw).g);
    }
    // glTF alphaMode MASK: cut out where the coverage is below the cutoff. (BLEND materials are
    // not drawn here: the forward pass shades them.)
    if ((m.flags & RTPBR_MATERIAL_FLAG_ALPHA_MASK) != 0u && f.alpha < m.alpha_cutoff) discard;
    g.baseColor = f.baseColor;
    g.metallic = f.metallic;
    g.normal = f.normal;
    g.roughness = f.roughness;
    g.emission = f.emission;
    g.materialIndex = draw.material; // < RTPBR_MAX_MATERIALS < RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT
    g.anisotropyDirection = f.anisotropyDirection;
    GBufferTargets t = GBuffer_Encode(g);
    out_gbuffer0 = t.g0;
    out_gbuffer1 = t.g1;
    out_gbuffer2 = t.g2;
    out_gbuffer3 = t.g3;
    if (specular) out_gbuffer4 = t.g4;
    if (coat_sheen) {
        out_gbuffer5 = t.g5;
        out_gbuffer6 = t.g6;
    }
}
