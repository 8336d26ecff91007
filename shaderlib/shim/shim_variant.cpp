// One model variant of the shader library's generic entry points, compiled once per variant
// by meson with RTPBR_* flags, RTPBR_CPP_VARIANT (its own C++ namespace) and
// RTPBR_SHIM_SUFFIX (the exported symbol suffix).
#include "shim_common.hpp"

using namespace rtpbr_shim;

#define RTPBR_SHIM_CAT2(a, b) a##_##b
#define RTPBR_SHIM_CAT(a, b) RTPBR_SHIM_CAT2(a, b)
#define RTPBR_SHIM_NAME(fn) RTPBR_SHIM_CAT(fn, RTPBR_SHIM_SUFFIX)

extern "C" {
rtpbr_v3 RTPBR_SHIM_NAME(rtpbr_shimv_BRDF_Specular)(float NoV, float NoL, float NoH, float VoH, float alpha,
                                                    rtpbr_fresnel_params f) {
    return out(rtpbr::BRDF_Specular(NoV, NoL, NoH, VoH, alpha, in(f)));
}
rtpbr_v3 RTPBR_SHIM_NAME(rtpbr_shimv_BRDF_SpecularLocal)(rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay,
                                                         rtpbr_fresnel_params f) {
    return out(rtpbr::BRDF_SpecularLocal(in(wo), in(wi), ax, ay, in(f)));
}
float RTPBR_SHIM_NAME(rtpbr_shimv_D_Microfacet)(float NoH, float alpha) { return rtpbr::D_Microfacet(NoH, alpha); }
float RTPBR_SHIM_NAME(rtpbr_shimv_V_Microfacet)(float NoV, float NoL, float alpha) {
    return rtpbr::V_Microfacet(NoV, NoL, alpha);
}
float RTPBR_SHIM_NAME(rtpbr_shimv_G2_Microfacet)(rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay) {
    return rtpbr::G2_Microfacet(in(wo), in(wi), ax, ay);
}
}
