#version 450
// rtpbr GPU test, GLSL build: output j of input tuple i is rtpbr_test_eval(a_i, b_i, j)
// (kernel.h). One invocation per (i, j); j is the workgroup's y, so a subgroup takes one
// branch of the kernel. Outputs are stored j-major: out[j * count + i].
#extension GL_GOOGLE_include_directive : require

#include "kernel.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer Inputs { vec4 inputs[]; }; // a_i, b_i
layout(std430, set = 0, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Params { uint count; } params;

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint j = gl_GlobalInvocationID.y;
    if (i >= params.count)
        return;
    outputs[j * params.count + i] = rtpbr_test_eval(inputs[2u * i], inputs[2u * i + 1u], j);
}
