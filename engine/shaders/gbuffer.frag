#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass: writes the material parameters the lighting pass needs.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/material.h"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_GBUFFER_FRAME
#include "frame.glsl"

#include "draw.glsl"

#include "material.glsl"
layout(set = 0, binding = RTPBR_BINDING_GBUFFER_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

#include "fragment_material.glsl"

layout(location = 0) out vec4 out_gbuffer0; // base colour rgb, metallic
layout(location = 1) out vec4 out_gbuffer1; // world normal xyz, perceptual roughness
layout(location = 2) out vec4 out_gbuffer2; // emitted radiance rgb, material index
layout(location = 3) out vec4 out_gbuffer3; // anisotropy direction (world, unit; zero: none)
// The extension textures' values (multipliers of the record's factors), written only in frames
// whose scene has such textures (rtpbr_shared.h, RTPBR_EXTENSION_TEXTURES_*; otherwise these
// attachments have no image view).
layout(location = 4) out vec4 out_gbuffer4; // specular colour rgb, specular a
layout(location = 5) out vec4 out_gbuffer5; // sheen colour rgb, sheen roughness a
layout(location = 6) out vec2 out_gbuffer6; // clearcoat, clearcoat roughness

void main()
{
    Material m = materials[draw.material];
    FragmentMaterial f = fragment_material(m); // samples every texture first
    // The extension textures' values (multiplying the material's factors in the lighting
    // passes), sampled here too before any discard, in uniform control flow (a branch on the
    // frame's uniform flags keeps it uniform); only for scenes that have such textures.
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_SPECULAR) != 0u)
        out_gbuffer4 = vec4(texture(specular_color_texture, in_uv_specular.zw).rgb,
                            texture(specular_texture, in_uv_specular.xy).a);
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_COAT_SHEEN) != 0u) {
        out_gbuffer5 = vec4(texture(sheen_color_texture, in_uv_sheen.xy).rgb,
                            texture(sheen_roughness_texture, in_uv_sheen.zw).a);
        out_gbuffer6 = vec2(texture(clearcoat_texture, in_uv_clearcoat.xy).r,
                            texture(clearcoat_roughness_texture, in_uv_clearcoat.zw).g);
    }
    // glTF alphaMode MASK: cut out where the coverage is below the cutoff. (BLEND materials are
    // not drawn here: the forward pass shades them.)
    if ((m.flags & RTPBR_MATERIAL_FLAG_ALPHA_MASK) != 0u && f.alpha < m.alpha_cutoff) discard;
    out_gbuffer0 = vec4(f.baseColor, f.metallic);
    out_gbuffer1 = vec4(f.normal, f.roughness);
    out_gbuffer2 = vec4(f.emission, float(draw.material)); // exact: RTPBR_MAX_MATERIALS < 2^24
    out_gbuffer3 = vec4(f.anisotropyDirection, 0.0);
}
