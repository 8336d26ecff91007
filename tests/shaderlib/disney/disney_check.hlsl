// Compile check of shaderlib/rtpbr/disney.h as HLSL (glslang's HLSL front end).
#define RTPBR_HLSL 1
#include "rtpbr/disney.h"

RWStructuredBuffer<float4> result : register(u0);

[numthreads(1, 1, 1)]
void main() {
    DisneyMaterial m = Disney_DefaultMaterial();
    m.anisotropic = 0.5f;
    m.clearcoat = 1.0f;
    float3 wo = normalize(float3(0.3f, 0.1f, 0.9f));
    float3 wi = normalize(float3(-0.2f, 0.4f, 0.8f));
    DisneyEnergyTerms t;
    t.dfgO = float2(0.8f, 0.05f);
    t.dfgI = float2(0.7f, 0.06f);
    t.Eavg = 0.8f;
    DisneyEnergyTerms k = Disney_EnergyTermsFromKullaConty(0.9f, 0.8f, 0.85f, wo.z, wi.z);
    float2 kcUv = Disney_KullaContyCoord(m, wo.z) + float2(Disney_KullaContyCoordAvg(m), Disney_SpecularTableRoughness(m));
    float3 f = BRDF_Disney(m, wo, wi) + BRDF_DisneyModel(m, wo, wi, k) +
               BRDF_DisneyEnergyConserving(m, wo, wi, t) + BRDF_DisneyDiffuse(m, wo, wi) +
               BRDF_DisneySheen(m, wo, wi) + BRDF_DisneySpecular(m, wo, wi) +
               BRDF_DisneyEnergyConservingDiffuse(m, wo, wi, t) + BRDF_DisneyEnergyConservingSpecular(m, wo, wi);
    DisneySample s = Disney_Sample(m, wo, float3(0.1f, 0.2f, 0.3f));
    DisneySample s2 = Disney_SampleEx(m, wo, float3(0.9f, 0.2f, 0.3f), true);
    float p = Disney_PDF(m, wo, wi) + Disney_PDFEx(m, wo, wi, true) + s.pdf + s2.pdf +
              BRDF_DisneyClearcoat(m, wo, wi) + Disney_SpecularTableAlpha(m) + float(s.lobe) + kcUv.x + kcUv.y;
    result[0] = float4(f, p) + float4(s.wi + s2.wi, 0.0f);
}
