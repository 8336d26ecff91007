// Compile check of shaderlib/rtpbr/ltc.h, ltc_anisotropy.h, ltc_clipless.h, ltc_corrections.h,
// ltc_shapes.h, ltc_lines.h and ltc_textured.h as HLSL (glslang's HLSL front end).
#define RTPBR_HLSL 1
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_anisotropy.h"
#include "rtpbr/ltc_clipless.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/ltc_shapes.h"
#include "rtpbr/ltc_lines.h"
#include "rtpbr/ltc_textured.h"
RWStructuredBuffer<float4> result : register(u0);
[numthreads(1, 1, 1)]
void main() {
    float3 N = float3(0.0f, 0.0f, 1.0f);
    float3 V = normalize(float3(0.3f, 0.0f, 1.0f));
    float3 P = RTPBR_F3(0.0f);
    LtcPolygon poly = LTC_Quad(float3(-1.0f, -1.0f, 2.0f), float3(1.0f, -1.0f, 2.0f),
                               float3(1.0f, 1.0f, 2.0f), float3(-1.0f, 1.0f, 2.0f));
    float4 ltc1 = float4(1.0f, 0.0f, 0.0f, 1.0f);
    float4 ltc2 = float4(1.0f, 0.1f, 0.01f, 1.0f);
    float2 uv = LTC_LutCoord(dot(N, V), 0.5f);
    float3x3 frame = LTC_Frame(N, V);
    LtcLocalPolygon local = LTC_PolygonToLocal(frame, P, poly, false);
    float spec = LTC_IntegrateLocal(local, ltc1);
    float diff = LTC_IntegrateLocal(local, LTC_Identity());
    float3 F = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(frame, P, poly, true), ltc1);
    float2 suv = LTC_SphereLutCoord(F);
    float s1 = LTC_SphereFormFactor(F, 1.0f);
    float s2 = LTC_SphereFormFactorApprox(F);
    float e = LTC_EvaluatePolygon(N, V, P, LTC_Triangle(poly.v[0], poly.v[1], poly.v[2]), ltc1, true);
    float3 fs = LTC_FresnelScale(ltc2, RTPBR_F3(0.04f), 1.0f);
    float3 fc = LTC_FresnelScaleConductor(ltc2, float3(0.2f, 0.9f, 1.1f), float3(3.9f, 2.4f, 2.2f));
    FresnelParams fp = Fresnel_FromF0(RTPBR_F3(0.04f));
    float3 fsel = LTC_FresnelScaleSelected(ltc2, fp);
    result[0] = float4(uv, suv);
    result[1] = float4(spec, diff, s1, s2);
    // The streamed path: one horizon clip, an anisotropically stretched lobe.
    LtcClipper horizon = LTC_ClipperBegin();
    LtcLobe lobe = LTC_LobeBegin(LTC_AnisotropicInverseMatrix(ltc1, float3(0.0f, 0.0f, 1.0f), float3(1.0f, 0.0f, 0.0f), 2.0f));
    float3 Fs = RTPBR_F3(0.0f);
    LtcSegment seg = LTC_ClipEdge(horizon, local.v[0], local.v[1]);
    if (seg.valid) {
        Fs += LTC_EdgeIntegral(LTC_SafeNormalize(seg.a), LTC_SafeNormalize(seg.b));
        LTC_LobeEdge(lobe, seg.a, seg.b);
    }
    seg = LTC_ClipClose(horizon);
    float streamed = LTC_LobeEnd(lobe) + LTC_EdgeIntegralZ(seg.a, seg.b) + LTC_EdgeFactor(0.5f, 0.8f) + Fs.x +
                     LTC_IntegrateLocalMatrix(local, LTC_InverseMatrix(ltc1));
    result[3] = RTPBR_F4(streamed);
    result[2] = float4(fs + fc + fsel, e);
    // ltc_shapes.h: disk, ellipse and sphere lights.
    float3 C, U, W;
    bool outside = LTC_SphereAsDisk(P, float3(0.5f, 0.0f, 2.0f), 0.3f, C, U, W);
    float3 Fe = LTC_EllipseVector(LTC_InverseMatrix(ltc1), C, U, W, true);
    LtcPolygon disk = LTC_EllipsePolygon(C, U, W);
    result[4] = float4(Fe, LTC_SphereCapFormFactor(Fe));
    result[5] = float4(LTC_EvaluateEllipse(N, V, P, float3(0.0f, 0.0f, 1.0f), float3(0.3f, 0.0f, 0.0f), float3(0.0f, -0.3f, 0.0f), ltc1, false),
                     LTC_EvaluateSphere(N, V, P, float3(0.5f, 0.0f, 2.0f), 0.3f, ltc1), outside ? 1.0f : 0.0f, disk.v[3].x);
    // ltc_textured.h: where to read a textured quad light.
    float3 uvf = LTC_TextureLookup(LTC_Frame(N, V), P, float3(-0.5f, 0.5f, 1.0f), float3(1.0f, 0.0f, 0.0f), float3(0.0f, -1.0f, 0.0f),
                                   LTC_InverseMatrix(ltc1), Fe);
    result[5].xyz += uvf + LTC_TextureLookupProjected(LTC_Frame(N, V), P, float3(-0.5f, 0.5f, 1.0f), float3(1.0f, 0.0f, 0.0f),
                                                      float3(0.0f, -1.0f, 0.0f), LTC_InverseMatrix(ltc1));
    // ltc_lines.h: line and tube (capsule) lights.
    float3 L1 = float3(-1.0f, -0.5f, 1.5f), L2 = float3(1.0f, 0.5f, 1.2f);
    float3x3 lineMinv = LTC_InverseMatrix(ltc1);
    float lineSum = LTC_EvaluateLine(N, V, P, L1, L2, 0.05f, ltc1) + LTC_LineCosineIntegral(L1, L2) +
                 LTC_LineWidthFactor(lineMinv, L1, L2) + LTC_IntegrateLineLocal(lineMinv, L1, L2, 0.05f);
    float3 tubeWeights = LTC_TubeWeights(P, L1, L2, 0.1f);
    LtcPolygon tubeQuad = LTC_TubeQuad(P, L1, L2, 0.1f);
    result[6] = float4(lineSum, LTC_EvaluateTube(N, V, P, L1, L2, 0.1f, ltc1) + LTC_TubeHalfWidth(P, L1, L2, 0.1f),
                     tubeWeights.x + tubeWeights.y, tubeQuad.v[2].x);
}
