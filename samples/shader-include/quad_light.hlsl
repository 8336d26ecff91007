// The HLSL twin of quad_light.frag: a pixel shader of your own that includes the rtpbr
// shader library directly and shades one quadrilateral area light with LTC (diffuse and
// specular) and Kulla-Conty compensation. RTPBR_HLSL must be defined before the includes
// (DXC defines __HLSL_VERSION, which the library also recognises; glslang does not).
// Compile with:  glslangValidator -V -D -e main -S frag -I<path>/shaderlib quad_light.hlsl
//           or:  dxc -T ps_6_0 -E main -I <path>/shaderlib quad_light.hlsl
#define RTPBR_HLSL 1
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ltc.h"
#include "rtpbr/kulla_conty.h"

cbuffer Shading : register(b0) {
    float4 quadCorners[4];    // world space, counter-clockwise seen from the emitting side
    float4 lightRadiance;     // rgb: radiance; w != 0: emits from both sides
    float4 cameraPosition;    // xyz
    float4 baseColorMetallic; // rgb: linear base colour, a: metallic
    float4 surface;           // x: perceptual roughness, y: dielectric reflectance at normal incidence (0.04)
};

// Tables from shaderlib/luts/ (see quad_light.frag for the layouts); linear, clamp to edge.
SamplerState lutSampler : register(s1);
Texture2D<float4> ltcMatrix : register(t2);   // rtpbr_ltc_ggx_1
Texture2D<float4> ltcScale : register(t3);    // rtpbr_ltc_ggx_2
Texture2D<float> kcAlbedo : register(t4);     // rtpbr_kc_E[variant]
Texture2D<float> kcAvgAlbedo : register(t5);  // rtpbr_kc_Eavg[variant]

struct PixelInput {
    float4 position : SV_Position;
    float3 worldPosition : TEXCOORD0;
    float3 worldNormal : TEXCOORD1;
};

float4 main(PixelInput input) : SV_Target
{
    float3 P = input.worldPosition;
    float3 N = normalize(input.worldNormal);
    float3 V = normalize(cameraPosition.xyz - P);
    float NoV = saturate(dot(N, V));
    float roughness = surface.x;
    float metallic = baseColorMetallic.a;
    float3 baseColor = baseColorMetallic.rgb;
    float3 f0 = lerp(RTPBR_F3(surface.y), baseColor, metallic);
    float f90 = 1.0f;
    float3 diffuseColor = baseColor * (1.0f - metallic);

    float2 ltcUv = LTC_LutCoord(NoV, roughness);
    float4 ltc1 = ltcMatrix.SampleLevel(lutSampler, ltcUv, 0.0f);
    float4 ltc2 = ltcScale.SampleLevel(lutSampler, ltcUv, 0.0f);

    LtcPolygon quad = LTC_Quad(quadCorners[0].xyz, quadCorners[1].xyz,
                               quadCorners[2].xyz, quadCorners[3].xyz);
    bool twoSided = lightRadiance.w != 0.0f;
    float3x3 frame = LTC_Frame(N, V);
#if RTPBR_LTC_CLIPLESS
    // Sphere proxy: no clipping, one vector form factor per lobe (Hill & Heitz 2016).
    LtcLocalPolygon unclipped = LTC_PolygonToLocalUnclipped(frame, P, quad, twoSided);
    float3 diffuseF = LTC_FormFactorVector(unclipped, LTC_Identity());
    float3 specularF = LTC_FormFactorVector(unclipped, ltc1);
    float diffuse = LTC_SphereFormFactor(diffuseF, ltcScale.SampleLevel(lutSampler, LTC_SphereLutCoord(diffuseF), 0.0f).w);
    float specular = LTC_SphereFormFactor(specularF, ltcScale.SampleLevel(lutSampler, LTC_SphereLutCoord(specularF), 0.0f).w);
#else
    // Exact: clip once to the horizon, integrate the clipped polygon for both lobes.
    LtcLocalPolygon local = LTC_PolygonToLocal(frame, P, quad, twoSided);
    float diffuse = LTC_IntegrateLocal(local, LTC_Identity());
    float specular = LTC_IntegrateLocal(local, ltc1);
    float3 diffuseF = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(frame, P, quad, twoSided), LTC_Identity());
#endif
    float3 lo = diffuseColor * diffuse + LTC_FresnelScale(ltc2, f0, f90) * specular;

#if RTPBR_MULTISCATTER
    // Kulla-Conty: the energy single scattering loses, over the quad, seen from the
    // direction of its vector form factor.
    float Eo = kcAlbedo.SampleLevel(lutSampler, KC_TableCoord(NoV, roughness), 0.0f);
    float Eavg = kcAvgAlbedo.SampleLevel(lutSampler, float2(KC_TableCoordAvg(roughness), 0.5f), 0.0f);
    float lenF = length(diffuseF);
    float muRep = lenF > 0.0f ? saturate(diffuseF.z / lenF) : 0.0f;
    float Erep = kcAlbedo.SampleLevel(lutSampler, KC_TableCoord(muRep, roughness), 0.0f);
    lo += KC_FmsColor(F_Avg_Schlick(f0, f90), Eavg) * KC_PolygonLobe(Eo, Erep, Eavg, diffuse);
#endif

    return float4(lightRadiance.rgb * lo, 1.0f);
}
