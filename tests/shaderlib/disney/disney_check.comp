#version 450
#extension GL_GOOGLE_include_directive : require
// Compile check of shaderlib/rtpbr/disney.h as GLSL (both model variants are compiled; the
// energy-conserving one through its named functions).
#include "rtpbr/disney.h"

layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec4 result[]; };

void main() {
    DisneyMaterial m = Disney_DefaultMaterial();
    m.anisotropic = 0.5f;
    m.clearcoat = 1.0f;
    vec3 wo = normalize(vec3(0.3f, 0.1f, 0.9f));
    vec3 wi = normalize(vec3(-0.2f, 0.4f, 0.8f));
    DisneyEnergyTerms t;
    t.dfgO = vec2(0.8f, 0.05f);
    t.dfgI = vec2(0.7f, 0.06f);
    t.Eavg = 0.8f;
    DisneyEnergyTerms k = Disney_EnergyTermsFromKullaConty(0.9f, 0.8f, 0.85f, wo.z, wi.z);
    vec2 kcUv = Disney_KullaContyCoord(m, wo.z) + vec2(Disney_KullaContyCoordAvg(m), Disney_SpecularTableRoughness(m));
    vec3 f = BRDF_Disney(m, wo, wi) + BRDF_DisneyModel(m, wo, wi, k) +
             BRDF_DisneyEnergyConserving(m, wo, wi, t) + BRDF_DisneyDiffuse(m, wo, wi) +
             BRDF_DisneySheen(m, wo, wi) + BRDF_DisneySpecular(m, wo, wi) +
             BRDF_DisneyEnergyConservingDiffuse(m, wo, wi, t) + BRDF_DisneyEnergyConservingSpecular(m, wo, wi);
    DisneySample s = Disney_Sample(m, wo, vec3(0.1f, 0.2f, 0.3f));
    DisneySample s2 = Disney_SampleEx(m, wo, vec3(0.9f, 0.2f, 0.3f), true);
    float p = Disney_PDF(m, wo, wi) + Disney_PDFEx(m, wo, wi, true) + s.pdf + s2.pdf +
              BRDF_DisneyClearcoat(m, wo, wi) + Disney_SpecularTableAlpha(m) + float(s.lobe) + kcUv.x + kcUv.y;
    result[0] = vec4(f, p) + vec4(s.wi + s2.wi, 0.0f);
}
