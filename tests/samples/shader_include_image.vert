#version 450
// The vertex shader of test_shader_include_image: world-space geometry (the glTF loader's)
// through the engine's view-projection (engine/src/math.c, a push constant), with the world
// position and normal as the varyings samples/shader-include/quad_light.frag reads.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(push_constant) uniform Camera {
    mat4 viewProj;
} camera;

void main()
{
    outWorldPosition = inPosition;
    outWorldNormal = inNormal;
    gl_Position = camera.viewProj * vec4(inPosition, 1.0);
}
