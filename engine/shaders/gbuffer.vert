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

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec3 out_world;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;

void main()
{
    vec4 world = draw.world_from_object * vec4(in_position, 1.0);
    mat3 n = mat3(draw.normal_matrix[0].xyz, draw.normal_matrix[1].xyz, draw.normal_matrix[2].xyz);
    out_normal = n * in_normal;
    out_world = world.xyz;
    out_uv = in_uv;
    out_tangent = vec4(mat3(draw.world_from_object) * in_tangent.xyz, in_tangent.w);
    gl_Position = frame.view_proj * world;
}
