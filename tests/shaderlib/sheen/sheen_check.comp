#version 450
#extension GL_GOOGLE_include_directive : require
// Compile check of shaderlib/rtpbr/sheen.h as GLSL (every public function).
#include "rtpbr/sheen.h"

layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec4 result[]; };

void main() {
    vec3 wo = normalize(vec3(0.3f, 0.1f, 0.9f));
    vec3 wi = normalize(vec3(-0.2f, 0.4f, 0.8f));
    vec3 c = vec3(0.9f, 0.5f, 0.2f);
    float a = Sheen_Alpha(0.4f);
    vec3 f = BRDF_Sheen(c, 0.4f, wo.z, wi.z, 0.95f) + BRDF_SheenLocal(c, 0.4f, wo, wi) +
             Sheen_LtcScale(vec4(0.5f, 0.0f, 0.0f, 1.0f), c);
    vec2 uv = Sheen_TableCoord(wo.z, 0.4f);
    vec3 h = Sample_Charlie(vec2(0.3f, 0.7f), a) + Sample_SheenLobe(wo, vec2(0.3f, 0.7f), a);
    float p = D_Charlie(0.5f, a) + V_Charlie(wo.z, wi.z, a) + V_Neubelt(wo.z, wi.z) + V_Sheen(wo.z, wi.z, a) +
              Lambda_Charlie(0.3f, a) + Lambda_CharlieSoftened(0.3f, a) + Sheen_AlbedoScaling(c, 0.2f, 0.3f) +
              Sheen_AlbedoScalingView(c, 0.2f) + PDF_SheenLobe(wo, wi, a) + uv.x + uv.y;
    result[0] = vec4(f + h, p);
}
