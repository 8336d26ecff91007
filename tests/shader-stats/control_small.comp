#version 450
// Positive control of test_shader_stats: a kernel far inside every bound (a few VGPRs, no
// spills, no scratch), which the checks must pass.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) buffer Values { float values[]; };

void main()
{
    values[gl_GlobalInvocationID.x] = sqrt(abs(values[gl_GlobalInvocationID.x]));
}
