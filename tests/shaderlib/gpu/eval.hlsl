// rtpbr GPU test, HLSL build (glslangValidator -D): the same kernel and layout as eval.comp.
#define RTPBR_HLSL 1
#include "kernel.h"

struct Params {
    uint count;
};
[[vk::push_constant]] ConstantBuffer<Params> params;
[[vk::binding(0, 0)]] StructuredBuffer<float4> inputs; // a_i, b_i
[[vk::binding(1, 0)]] RWStructuredBuffer<float> outputs;

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
    uint i = id.x;
    uint j = id.y;
    if (i >= params.count)
        return;
    outputs[j * params.count + i] = rtpbr_test_eval(inputs[2u * i], inputs[2u * i + 1u], j);
}
