#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass: transforms one mesh (per-draw constants: rtpbr_shader_draw).
#include "rtpbr_shared.h"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_GBUFFER_FRAME
#include "frame.glsl"

#include "draw.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec2 in_uv1;

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec4 out_uv_base_color_metallic_roughness; // each slot's texture coordinates
layout(location = 3) out vec4 out_tangent;
layout(location = 4) out vec4 out_uv_emission_normal;
// The extension textures' slots (two per location). Written in every frame, unconditionally:
// with the writes under a branch on rtpbr_shader_frame.extension_textures, lavapipe (Mesa
// 22.3.6) leaked the JIT code of 9 shader variants per test process (a cycle of six llvmpipe
// allocations each, LeakSanitizer and valgrind in CI; found by removing one change at a time).
// Six 2x3 transforms per vertex cost nothing measurable.
layout(location = 5) out vec4 out_uv_clearcoat;       // clearcoat, clearcoat roughness
layout(location = 6) out vec4 out_uv_sheen;           // sheen colour, sheen roughness
layout(location = 7) out vec4 out_uv_specular;        // specular, specular colour

struct TextureTransforms {
    RTPBR_TEXTURE_TRANSFORMS_FIELDS(RTPBR_SHARED_FIELD, TextureTransforms)
};
layout(set = 0, binding = RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS, std430) readonly buffer TextureTransformsBuffer {
    TextureTransforms texture_transforms[];
};

// A slot's texture coordinates: its set (TEXCOORD_0 or _1) through its KHR_texture_transform
// (rows of the 2x3 matrix; rtpbr_shared.h). Affine, so transforming per vertex is exact; and
// the fragment shader's implicit derivatives (mip level) then see only interpolated inputs.
vec2 slot_uv(vec4 rows[2])
{
    vec3 uv = vec3(rows[0].w != 0.0 ? in_uv1 : in_uv, 1.0);
    return vec2(dot(rows[0].xyz, uv), dot(rows[1].xyz, uv));
}

void main()
{
    vec4 world = draw.world_from_object * vec4(in_position, 1.0);
    mat3 n = mat3(draw.normal_matrix[0].xyz, draw.normal_matrix[1].xyz, draw.normal_matrix[2].xyz);
    out_normal = n * in_normal;
    out_world = world.xyz;
    TextureTransforms t = texture_transforms[draw.material];
    out_uv_base_color_metallic_roughness = vec4(slot_uv(t.base_color), slot_uv(t.metallic_roughness));
    out_uv_emission_normal = vec4(slot_uv(t.emission), slot_uv(t.normal));
    out_uv_clearcoat = vec4(slot_uv(t.clearcoat), slot_uv(t.clearcoat_roughness));
    out_uv_sheen = vec4(slot_uv(t.sheen_color), slot_uv(t.sheen_roughness));
    out_uv_specular = vec4(slot_uv(t.specular), slot_uv(t.specular_color));
    out_tangent = vec4(mat3(draw.world_from_object) * in_tangent.xyz, in_tangent.w);
    gl_Position = frame.view_proj * world;
}
