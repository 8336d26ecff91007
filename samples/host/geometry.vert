#version 450
// rtpbr-sample-host's geometry pass (samples/host; tests/engine/test_engine_lightpass uses it
// too): world-space triangles through the host's view-projection (a push constant), the world
// position and normal as varyings.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(push_constant) uniform Draw {
    mat4 view_proj;
    vec4 camera; // xyz: position
    uint material;
} draw;

void main()
{
    out_world = in_position;
    out_normal = in_normal;
    gl_Position = draw.view_proj * vec4(in_position, 1.0);
}
