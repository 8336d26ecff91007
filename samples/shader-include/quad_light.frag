#version 450
#extension GL_GOOGLE_include_directive : require
// A GLSL fragment shader of your own that includes the rtpbr shader library directly
// (compile with: glslangValidator -V -I<path>/shaderlib quad_light.frag) and shades one
// quadrilateral area light: Lambertian diffuse and GGX (or Beckmann) specular integrated
// over the quad with Linearly Transformed Cosines, plus the Kulla-Conty multiple-scattering
// lobe. The library never samples textures: this shader fetches the tables it bound itself
// and hands the values over. Pick models with -D before the includes, e.g.
// -DRTPBR_NDF=RTPBR_NDF_BECKMANN, -DRTPBR_MULTISCATTER=0, -DRTPBR_LTC_CLIPLESS=1.
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ltc.h"
#include "rtpbr/kulla_conty.h"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 0) out vec4 outRadiance; // linear; tone-map in a later pass

layout(set = 0, binding = 0, std140) uniform Shading {
    vec4 quadCorners[4];   // world space, counter-clockwise seen from the emitting side
    vec4 lightRadiance;    // rgb: radiance; w != 0: emits from both sides
    vec4 cameraPosition;   // xyz
    vec4 baseColorMetallic;// rgb: linear base colour, a: metallic
    vec4 surface;          // x: perceptual roughness, y: dielectric reflectance at normal incidence (0.04)
} shading;

// Tables from shaderlib/luts/, uploaded as their headers describe; linear filtering,
// clamp to edge:
//   ltcMatrix   rtpbr_ltc_ggx_1 (or _beckmann_1), 64x64 RGBA32F
//   ltcScale    rtpbr_ltc_ggx_2 (or _beckmann_2), 64x64 RGBA32F
//   kcAlbedo    rtpbr_kc_E[variant], 32x32 R32F (rows: roughness, columns: sqrt(mu))
//   kcAvgAlbedo rtpbr_kc_Eavg[variant], 32x1 R32F
layout(set = 0, binding = 1) uniform sampler2D ltcMatrix;
layout(set = 0, binding = 2) uniform sampler2D ltcScale;
layout(set = 0, binding = 3) uniform sampler2D kcAlbedo;
layout(set = 0, binding = 4) uniform sampler2D kcAvgAlbedo;

void main()
{
    vec3 P = inWorldPosition;
    vec3 N = normalize(inWorldNormal);
    vec3 V = normalize(shading.cameraPosition.xyz - P);
    float NoV = rtpbr_saturate(dot(N, V));
    float roughness = shading.surface.x;
    float metallic = shading.baseColorMetallic.a;
    vec3 baseColor = shading.baseColorMetallic.rgb;
    vec3 f0 = mix(RTPBR_F3(shading.surface.y), baseColor, metallic);
    float f90 = 1.0f;
    vec3 diffuseColor = baseColor * (1.0f - metallic);

    vec2 ltcUv = LTC_LutCoord(NoV, roughness);
    vec4 ltc1 = textureLod(ltcMatrix, ltcUv, 0.0f);
    vec4 ltc2 = textureLod(ltcScale, ltcUv, 0.0f);

    LtcPolygon quad = LTC_Quad(shading.quadCorners[0].xyz, shading.quadCorners[1].xyz,
                               shading.quadCorners[2].xyz, shading.quadCorners[3].xyz);
    bool twoSided = shading.lightRadiance.w != 0.0f;
    mat3 frame = LTC_Frame(N, V);
#if RTPBR_LTC_CLIPLESS
    // Sphere proxy: no clipping, one vector form factor per lobe (Hill & Heitz 2016).
    LtcLocalPolygon unclipped = LTC_PolygonToLocalUnclipped(frame, P, quad, twoSided);
    vec3 diffuseF = LTC_FormFactorVector(unclipped, LTC_Identity());
    vec3 specularF = LTC_FormFactorVector(unclipped, ltc1);
    float diffuse = LTC_SphereFormFactor(diffuseF, textureLod(ltcScale, LTC_SphereLutCoord(diffuseF), 0.0f).w);
    float specular = LTC_SphereFormFactor(specularF, textureLod(ltcScale, LTC_SphereLutCoord(specularF), 0.0f).w);
#else
    // Exact: clip once to the horizon, integrate the clipped polygon for both lobes.
    LtcLocalPolygon local = LTC_PolygonToLocal(frame, P, quad, twoSided);
    float diffuse = LTC_IntegrateLocal(local, LTC_Identity());
    float specular = LTC_IntegrateLocal(local, ltc1);
    vec3 diffuseF = LTC_FormFactorVector(LTC_PolygonToLocalUnclipped(frame, P, quad, twoSided), LTC_Identity());
#endif
    vec3 lo = diffuseColor * diffuse + LTC_FresnelScale(ltc2, f0, f90) * specular;

#if RTPBR_MULTISCATTER
    // Kulla-Conty: the energy single scattering loses, over the quad, seen from the
    // direction of its vector form factor.
    float Eo = textureLod(kcAlbedo, KC_TableCoord(NoV, roughness), 0.0f).r;
    float Eavg = textureLod(kcAvgAlbedo, vec2(KC_TableCoordAvg(roughness), 0.5f), 0.0f).r;
    float lenF = length(diffuseF);
    float muRep = lenF > 0.0f ? rtpbr_saturate(diffuseF.z / lenF) : 0.0f;
    float Erep = textureLod(kcAlbedo, KC_TableCoord(muRep, roughness), 0.0f).r;
    lo += KC_FmsColor(F_Avg_Schlick(f0, f90), Eavg) * KC_PolygonLobe(Eo, Erep, Eavg, diffuse);
#endif

    outRadiance = vec4(shading.lightRadiance.rgb * lo, 1.0f);
}
