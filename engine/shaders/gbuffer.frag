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

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec3 in_world;
layout(location = 2) in vec4 in_uv_base_color_metallic_roughness; // each slot's (gbuffer.vert)
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_uv_emission_normal;
layout(location = 5) in vec4 in_uv_clearcoat; // clearcoat, clearcoat roughness
layout(location = 6) in vec4 in_uv_sheen;     // sheen colour, sheen roughness
layout(location = 7) in vec4 in_uv_specular;  // specular, specular colour

// The material's textures, name##_texture at its slot's binding (rtpbr_shared.h); a slot
// without a texture holds a 1x1 white one.
#define DECLARE_TEXTURE(unused_a, unused_b, name, slot) layout(set = 1, binding = slot) uniform sampler2D name##_texture;
RTPBR_MATERIAL_TEXTURE_SLOTS(DECLARE_TEXTURE, 0, 0)

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
    // Every texture is sampled here, in uniform control flow, where the implicit derivatives
    // that pick the mip level are defined.
    vec4 base_color_texel = texture(base_color_texture, in_uv_base_color_metallic_roughness.xy);
    vec4 metallic_roughness_texel = texture(metallic_roughness_texture, in_uv_base_color_metallic_roughness.zw);
    vec4 emission_texel = texture(emission_texture, in_uv_emission_normal.xy);
    vec4 normal_texel = texture(normal_texture, in_uv_emission_normal.zw);
    // (a branch on the frame's uniform flags: control flow stays uniform)
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_SPECULAR) != 0u)
        out_gbuffer4 = vec4(texture(specular_color_texture, in_uv_specular.zw).rgb,
                            texture(specular_texture, in_uv_specular.xy).a);
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_COAT_SHEEN) != 0u) {
        out_gbuffer5 = vec4(texture(sheen_color_texture, in_uv_sheen.xy).rgb,
                            texture(sheen_roughness_texture, in_uv_sheen.zw).a);
        out_gbuffer6 = vec2(texture(clearcoat_texture, in_uv_clearcoat.xy).r,
                            texture(clearcoat_roughness_texture, in_uv_clearcoat.zw).g);
    }
    vec3 n = normalize(in_normal);
    // Every surface reflects on the side the camera sees; it emits there only if that is its
    // front side or the material is double-sided.
    bool back = dot(n, frame.camera_position.xyz - in_world) < 0.0;
    // glTF normal textures: tangent-space normal (x, y scaled by normalTexture.scale) in the
    // frame (T, B = w N x T, N) of the interpolated vertex tangent.
    if ((m.flags & RTPBR_MATERIAL_FLAG_NORMAL_MAPPED) != 0u && dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
        vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
        vec3 b = (in_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
        vec3 ts = normal_texel.xyz * 2.0 - 1.0;
        ts.xy *= m.normal_scale;
        n = normalize(t * ts.x + b * ts.y + n * ts.z);
    }
    // The anisotropy direction (KHR_materials_anisotropy; Disney: the tangent): the tangent
    // made orthogonal to the shading normal, rotated toward the bitangent. Zero without tangents.
    vec3 anisotropyDirection = vec3(0.0);
    if (dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
        vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
        if (dot(t, t) > 1e-12) {
            t = normalize(t);
            vec3 b = (in_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
            float rotation = m.anisotropy_rotation;
            anisotropyDirection = t * cos(rotation) + b * sin(rotation);
        }
    }
    if (back) n = -n;
    vec3 emission = back && (m.flags & RTPBR_MATERIAL_FLAG_DOUBLE_SIDED) == 0u ? vec3(0.0) : m.emission * emission_texel.rgb;
    // glTF: textures multiply the factors; metallic-roughness holds roughness in g, metallic in b.
    vec4 mr = metallic_roughness_texel;
    // The roughness floor of the shader library's material resolve (material.h), applied here
    // so that the lighting passes read the G-buffer's roughness as the resolve would.
    float roughness = Material_PerceptualRoughness(m.roughness * mr.g);
    out_gbuffer0 = vec4(m.base_color * base_color_texel.rgb, rtpbr_saturate(m.metallic * mr.b));
    out_gbuffer1 = vec4(n, roughness);
    out_gbuffer2 = vec4(emission, float(draw.material)); // exact: RTPBR_MAX_MATERIALS < 2^24
    out_gbuffer3 = vec4(anisotropyDirection, 0.0);
}
