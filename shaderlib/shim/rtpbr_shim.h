/* rtpbr shader library: C shim over the C++ build.
 *
 * C programs (the cmocka tests, C engines that want CPU reference values) call the very
 * code the GPU runs through these functions. Names follow the shader functions with an
 * rtpbr_ prefix; see the shader headers for their definitions and conventions.
 * The model-dependent entry points exist once per variant (suffix): each is a separate
 * compilation of the library with the flags named in rtpbr_shim_variant_names.
 */
#ifndef RTPBR_SHIM_H
#define RTPBR_SHIM_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rtpbr_v3 { float x, y, z; } rtpbr_v3;

/* FresnelParams of fresnel.h */
typedef struct rtpbr_fresnel_params {
    rtpbr_v3 f0;
    float f90;
    rtpbr_v3 eta;
    rtpbr_v3 k;
} rtpbr_fresnel_params;

/* fresnel.h */
float rtpbr_F_Schlick1(float f0, float f90, float VoH);
rtpbr_v3 rtpbr_F_Schlick(rtpbr_v3 f0, float f90, float VoH);
float rtpbr_F0_FromIor(float eta);
float rtpbr_F_Dielectric(float cosThetaI, float eta);
rtpbr_v3 rtpbr_F_Conductor(float cosThetaI, rtpbr_v3 eta, rtpbr_v3 k);
rtpbr_fresnel_params rtpbr_Fresnel_FromF0(rtpbr_v3 f0);
rtpbr_fresnel_params rtpbr_Fresnel_FromDielectric(float eta);
rtpbr_fresnel_params rtpbr_Fresnel_FromConductor(rtpbr_v3 eta, rtpbr_v3 k);

/* ndf.h */
float rtpbr_Alpha_FromPerceptual(float perceptualRoughness);
float rtpbr_D_GGX(float NoH, float alpha);
float rtpbr_D_GGX_Aniso(float NoH, float ToH, float BoH, float alphaX, float alphaY);
float rtpbr_D_Beckmann(float NoH, float alpha);
float rtpbr_D_Beckmann_Aniso(float NoH, float ToH, float BoH, float alphaX, float alphaY);
float rtpbr_D_GTR(float NoH, float alpha, float gamma);

/* smith.h */
float rtpbr_erf(float x);
float rtpbr_erfc(float x);
float rtpbr_Lambda_GGX(float cosTheta, float alpha);
float rtpbr_Lambda_GGX_Aniso(rtpbr_v3 w, float alphaX, float alphaY);
float rtpbr_G1_GGX(float cosTheta, float alpha);
float rtpbr_G1_GGX_Aniso(rtpbr_v3 w, float alphaX, float alphaY);
float rtpbr_Lambda_Beckmann(float cosTheta, float alpha);
float rtpbr_Lambda_Beckmann_Aniso(rtpbr_v3 w, float alphaX, float alphaY);
float rtpbr_G1_Beckmann(float cosTheta, float alpha);
float rtpbr_G1_Beckmann_Fast(float cosTheta, float alpha);
float rtpbr_V_SmithGGXCorrelated(float NoV, float NoL, float alpha);
float rtpbr_V_SmithGGXCorrelated_Fast(float NoV, float NoL, float alpha);
float rtpbr_V_SmithGGXSeparable(float NoV, float NoL, float alpha);

/* sampling.h */
float rtpbr_erfinv(float x);
rtpbr_v3 rtpbr_Sample_GGX_VNDF(rtpbr_v3 wo, float alphaX, float alphaY, float u0, float u1);
float rtpbr_PDF_GGX_VNDF(rtpbr_v3 wo, rtpbr_v3 wm, float alphaX, float alphaY);
float rtpbr_PDF_GGX_Reflection(rtpbr_v3 wo, rtpbr_v3 wi, float alphaX, float alphaY);
rtpbr_v3 rtpbr_Sample_Beckmann_VNDF(rtpbr_v3 wo, float alphaX, float alphaY, float u0, float u1);
float rtpbr_PDF_Beckmann_VNDF(rtpbr_v3 wo, rtpbr_v3 wm, float alphaX, float alphaY);
float rtpbr_PDF_Beckmann_Reflection(rtpbr_v3 wo, rtpbr_v3 wi, float alphaX, float alphaY);
rtpbr_v3 rtpbr_Sample_CosineHemisphere(float u0, float u1);
float rtpbr_PDF_CosineHemisphere(rtpbr_v3 w);

/* Model variants of microfacet.h / smith.h generic entry points. */
typedef enum rtpbr_shim_variant {
    RTPBR_SHIM_GGX_HEIGHT_CORRELATED,   /* RTPBR_NDF_GGX, RTPBR_SMITH_HEIGHT_CORRELATED */
    RTPBR_SHIM_GGX_SEPARABLE,           /* RTPBR_NDF_GGX, RTPBR_SMITH_SEPARABLE */
    RTPBR_SHIM_GGX_FAST,                /* RTPBR_NDF_GGX, RTPBR_SMITH_FAST */
    RTPBR_SHIM_BECKMANN_HEIGHT_CORRELATED,
    RTPBR_SHIM_BECKMANN_SEPARABLE,
    RTPBR_SHIM_BECKMANN_FAST,
    RTPBR_SHIM_GTR1_5,                  /* RTPBR_NDF_GTR, RTPBR_GTR_GAMMA 1.5 */
    RTPBR_SHIM_CONDUCTOR,               /* GGX, height-correlated, RTPBR_FRESNEL_CONDUCTOR */
    RTPBR_SHIM_DIELECTRIC,              /* GGX, height-correlated, RTPBR_FRESNEL_DIELECTRIC */
    RTPBR_SHIM_VARIANT_COUNT
} rtpbr_shim_variant;

const char *rtpbr_shim_variant_name(rtpbr_shim_variant v);
rtpbr_v3 rtpbr_BRDF_Specular(rtpbr_shim_variant v, float NoV, float NoL, float NoH, float VoH,
                             float alpha, rtpbr_fresnel_params fresnel);
rtpbr_v3 rtpbr_BRDF_SpecularLocal(rtpbr_shim_variant v, rtpbr_v3 wo, rtpbr_v3 wi,
                                  float alphaX, float alphaY, rtpbr_fresnel_params fresnel);
float rtpbr_D_Microfacet(rtpbr_shim_variant v, float NoH, float alpha);
float rtpbr_V_Microfacet(rtpbr_shim_variant v, float NoV, float NoL, float alpha);
float rtpbr_G2_Microfacet(rtpbr_shim_variant v, rtpbr_v3 wo, rtpbr_v3 wi, float alphaX, float alphaY);

#ifdef __cplusplus
}
#endif

#endif /* RTPBR_SHIM_H */
