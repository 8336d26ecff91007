// The C shim's model-independent functions: the C++ build of the shader library, default flags.
#include "shim_common.hpp"

using namespace rtpbr_shim;

extern "C" {

float rtpbr_F_Schlick1(float f0, float f90, float VoH) { return rtpbr::F_Schlick1(f0, f90, VoH); }
rtpbr_v3 rtpbr_F_Schlick(rtpbr_v3 f0, float f90, float VoH) { return out(rtpbr::F_Schlick(in(f0), f90, VoH)); }
float rtpbr_F0_FromIor(float eta) { return rtpbr::F0_FromIor(eta); }
float rtpbr_F_Dielectric(float c, float eta) { return rtpbr::F_Dielectric(c, eta); }
rtpbr_v3 rtpbr_F_Conductor(float c, rtpbr_v3 eta, rtpbr_v3 k) { return out(rtpbr::F_Conductor(c, in(eta), in(k))); }
rtpbr_fresnel_params rtpbr_Fresnel_FromF0(rtpbr_v3 f0) { return out(rtpbr::Fresnel_FromF0(in(f0))); }
rtpbr_fresnel_params rtpbr_Fresnel_FromDielectric(float eta) { return out(rtpbr::Fresnel_FromDielectric(eta)); }
rtpbr_fresnel_params rtpbr_Fresnel_FromConductor(rtpbr_v3 eta, rtpbr_v3 k) {
    return out(rtpbr::Fresnel_FromConductor(in(eta), in(k)));
}

float rtpbr_Alpha_FromPerceptual(float r) { return rtpbr::Alpha_FromPerceptual(r); }
float rtpbr_D_GGX(float NoH, float a) { return rtpbr::D_GGX(NoH, a); }
float rtpbr_D_GGX_Aniso(float NoH, float ToH, float BoH, float ax, float ay) { return rtpbr::D_GGX_Aniso(NoH, ToH, BoH, ax, ay); }
float rtpbr_D_Beckmann(float NoH, float a) { return rtpbr::D_Beckmann(NoH, a); }
float rtpbr_D_Beckmann_Aniso(float NoH, float ToH, float BoH, float ax, float ay) {
    return rtpbr::D_Beckmann_Aniso(NoH, ToH, BoH, ax, ay);
}
float rtpbr_D_GTR(float NoH, float a, float gamma) { return rtpbr::D_GTR(NoH, a, gamma); }

float rtpbr_erf(float x) { return rtpbr::rtpbr_erf(x); }
float rtpbr_erfc(float x) { return rtpbr::rtpbr_erfc(x); }
float rtpbr_Lambda_GGX(float c, float a) { return rtpbr::Lambda_GGX(c, a); }
float rtpbr_Lambda_GGX_Aniso(rtpbr_v3 w, float ax, float ay) { return rtpbr::Lambda_GGX_Aniso(in(w), ax, ay); }
float rtpbr_G1_GGX(float c, float a) { return rtpbr::G1_GGX(c, a); }
float rtpbr_G1_GGX_Aniso(rtpbr_v3 w, float ax, float ay) { return rtpbr::G1_GGX_Aniso(in(w), ax, ay); }
float rtpbr_Lambda_Beckmann(float c, float a) { return rtpbr::Lambda_Beckmann(c, a); }
float rtpbr_Lambda_Beckmann_Aniso(rtpbr_v3 w, float ax, float ay) { return rtpbr::Lambda_Beckmann_Aniso(in(w), ax, ay); }
float rtpbr_G1_Beckmann(float c, float a) { return rtpbr::G1_Beckmann(c, a); }
float rtpbr_G1_Beckmann_Fast(float c, float a) { return rtpbr::G1_Beckmann_Fast(c, a); }
float rtpbr_V_SmithGGXCorrelated(float v, float l, float a) { return rtpbr::V_SmithGGXCorrelated(v, l, a); }
float rtpbr_V_SmithGGXCorrelated_Fast(float v, float l, float a) { return rtpbr::V_SmithGGXCorrelated_Fast(v, l, a); }
float rtpbr_V_SmithGGXSeparable(float v, float l, float a) { return rtpbr::V_SmithGGXSeparable(v, l, a); }

float rtpbr_erfinv(float x) { return rtpbr::rtpbr_erfinv(x); }
rtpbr_v3 rtpbr_Sample_GGX_VNDF(rtpbr_v3 wo, float ax, float ay, float u0, float u1) {
    return out(rtpbr::Sample_GGX_VNDF(in(wo), ax, ay, rtpbr::float2(u0, u1)));
}
float rtpbr_PDF_GGX_VNDF(rtpbr_v3 wo, rtpbr_v3 wm, float ax, float ay) { return rtpbr::PDF_GGX_VNDF(in(wo), in(wm), ax, ay); }
float rtpbr_PDF_GGX_Reflection(rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay) {
    return rtpbr::PDF_GGX_Reflection(in(wo), in(wi), ax, ay);
}
rtpbr_v3 rtpbr_Sample_Beckmann_VNDF(rtpbr_v3 wo, float ax, float ay, float u0, float u1) {
    return out(rtpbr::Sample_Beckmann_VNDF(in(wo), ax, ay, rtpbr::float2(u0, u1)));
}
float rtpbr_PDF_Beckmann_VNDF(rtpbr_v3 wo, rtpbr_v3 wm, float ax, float ay) {
    return rtpbr::PDF_Beckmann_VNDF(in(wo), in(wm), ax, ay);
}
float rtpbr_PDF_Beckmann_Reflection(rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay) {
    return rtpbr::PDF_Beckmann_Reflection(in(wo), in(wi), ax, ay);
}
rtpbr_v3 rtpbr_Sample_CosineHemisphere(float u0, float u1) {
    return out(rtpbr::Sample_CosineHemisphere(rtpbr::float2(u0, u1)));
}
float rtpbr_PDF_CosineHemisphere(rtpbr_v3 w) { return rtpbr::PDF_CosineHemisphere(in(w)); }

} // extern "C"
