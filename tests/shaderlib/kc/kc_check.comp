#version 450
// Compile check of shaderlib/rtpbr/kulla_conty.h as GLSL (and, with RTPBR_HLSL, as HLSL
// through kc_check.hlsl): every public function is called once.
#extension GL_GOOGLE_include_directive : require
#include "rtpbr/kulla_conty.h"

layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec4 outv[]; };

void main() {
    vec2 uv = KC_TableCoord(0.5f, 0.3f);
    float u = KC_TableCoordAvg(0.3f);
    vec3 uvw = KC_TableCoord3D(0.5f, 0.3f, 1.5f);
    vec2 uv2 = KC_TableCoordAvg2D(0.3f, 1.5f);
    FresnelParams fp = Fresnel_FromConductor(vec3(0.2f, 0.9f, 1.1f), vec3(3.9f, 2.4f, 2.1f));
    vec3 favg = F_Avg_Microfacet(fp) + F_Avg_Schlick(vec3(0.04f), 1.0f) + F_Avg_Conductor(fp.eta, fp.k);
    float fd = F_Avg_Dielectric(1.5f);
    vec3 f = BRDF_SpecularMS(0.5f, 0.6f, 0.9f, 0.8f, 0.1f, fp, 0.9f, 0.8f, 0.85f, favg);
    vec3 layered = BRDF_DielectricOverDiffuse(0.5f, 0.6f, 0.9f, 0.8f, 0.1f, 1.5f, vec3(0.8f), 0.1f, 0.1f,
                                              0.1f, 0.9f, 0.8f, 0.85f);
    float poly = KC_PolygonLobe(0.9f, 0.8f, 0.85f, 0.3f) + Fd_KullaContyLayered(0.1f, 0.2f, 0.15f) +
                 KC_SpecularAlbedoDielectric(0.1f, 0.9f, 0.5f);
    outv[0] = vec4(uv, u, fd);
    outv[1] = vec4(uvw, poly);
    outv[2] = vec4(f + layered + KC_FmsColor(favg, 0.8f), uv2.x + uv2.y);
}
