// Compile check of shaderlib/rtpbr/sheen.h as HLSL (glslang's HLSL front end).
#define RTPBR_HLSL 1
#include "rtpbr/sheen.h"

RWStructuredBuffer<float4> result : register(u0);

[numthreads(1, 1, 1)]
void main() {
    float3 wo = normalize(float3(0.3f, 0.1f, 0.9f));
    float3 wi = normalize(float3(-0.2f, 0.4f, 0.8f));
    float3 c = float3(0.9f, 0.5f, 0.2f);
    float a = Sheen_Alpha(0.4f);
    float3 f = BRDF_Sheen(c, 0.4f, wo.z, wi.z, 0.95f) + BRDF_SheenLocal(c, 0.4f, wo, wi) +
               Sheen_LtcScale(float4(0.5f, 0.0f, 0.0f, 1.0f), c);
    float2 uv = Sheen_TableCoord(wo.z, 0.4f);
    float3 h = Sample_Charlie(float2(0.3f, 0.7f), a) + Sample_SheenLobe(wo, float2(0.3f, 0.7f), a);
    float p = D_Charlie(0.5f, a) + V_Charlie(wo.z, wi.z, a) + V_Neubelt(wo.z, wi.z) + V_Sheen(wo.z, wi.z, a) +
              Lambda_Charlie(0.3f, a) + Lambda_CharlieSoftened(0.3f, a) + Sheen_AlbedoScaling(c, 0.2f, 0.3f) +
              Sheen_AlbedoScalingView(c, 0.2f) + PDF_SheenLobe(wo, wi, a) + uv.x + uv.y;
    result[0] = float4(f + h, p);
}
