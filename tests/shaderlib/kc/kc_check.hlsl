// Compile check of shaderlib/rtpbr/kulla_conty.h as HLSL (glslang's HLSL front end).
#define RTPBR_HLSL 1
#include "rtpbr/kulla_conty.h"

RWStructuredBuffer<float4> outv : register(u0);

[numthreads(1, 1, 1)]
void main() {
    float2 uv = KC_TableCoord(0.5f, 0.3f);
    float u = KC_TableCoordAvg(0.3f);
    float3 uvw = KC_TableCoord3D(0.5f, 0.3f, 1.5f);
    float2 uv2 = KC_TableCoordAvg2D(0.3f, 1.5f);
    FresnelParams fp = Fresnel_FromConductor(float3(0.2f, 0.9f, 1.1f), float3(3.9f, 2.4f, 2.1f));
    float3 favg = F_Avg_Microfacet(fp) + F_Avg_Schlick(RTPBR_F3(0.04f), 1.0f) + F_Avg_Conductor(fp.eta, fp.k);
    float fd = F_Avg_Dielectric(1.5f);
    float3 f = BRDF_SpecularMS(0.5f, 0.6f, 0.9f, 0.8f, 0.1f, fp, 0.9f, 0.8f, 0.85f, favg);
    float3 layered = BRDF_DielectricOverDiffuse(0.5f, 0.6f, 0.9f, 0.8f, 0.1f, 1.5f, RTPBR_F3(0.8f), 0.1f,
                                                0.1f, 0.1f, 0.9f, 0.8f, 0.85f);
    float poly = KC_PolygonLobe(0.9f, 0.8f, 0.85f, 0.3f) + Fd_KullaContyLayered(0.1f, 0.2f, 0.15f) +
                 KC_SpecularAlbedoDielectric(0.1f, 0.9f, 0.5f);
    outv[0] = float4(uv, u, fd);
    outv[1] = float4(uvw, poly);
    outv[2] = float4(f + layered + KC_FmsColor(favg, 0.8f), uv2.x + uv2.y);
}
