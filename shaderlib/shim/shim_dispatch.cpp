// Runtime dispatch of the C shim's model variants to their separately compiled builds.
#include "rtpbr_shim.h"

#define RTPBR_SHIM_VARIANTS(X) \
    X(ggx_hc) X(ggx_sep) X(ggx_fast) X(beckmann_hc) X(beckmann_sep) X(beckmann_fast) X(gtr1_5) \
    X(conductor) X(dielectric)

#define RTPBR_SHIM_DECLARE(s)                                                                      \
    extern "C" rtpbr_v3 rtpbr_shimv_BRDF_Specular_##s(float, float, float, float, float,          \
                                                     rtpbr_fresnel_params);                       \
    extern "C" rtpbr_v3 rtpbr_shimv_BRDF_SpecularLocal_##s(rtpbr_v3, rtpbr_v3, float, float,      \
                                                          rtpbr_fresnel_params);                  \
    extern "C" float rtpbr_shimv_D_Microfacet_##s(float, float);                                  \
    extern "C" float rtpbr_shimv_V_Microfacet_##s(float, float, float);                           \
    extern "C" float rtpbr_shimv_G2_Microfacet_##s(rtpbr_v3, rtpbr_v3, float, float);
RTPBR_SHIM_VARIANTS(RTPBR_SHIM_DECLARE)

namespace {
struct VariantTable {
    const char *name;
    rtpbr_v3 (*brdf)(float, float, float, float, float, rtpbr_fresnel_params);
    rtpbr_v3 (*brdfLocal)(rtpbr_v3, rtpbr_v3, float, float, rtpbr_fresnel_params);
    float (*d)(float, float);
    float (*v)(float, float, float);
    float (*g2)(rtpbr_v3, rtpbr_v3, float, float);
};
#define RTPBR_SHIM_ENTRY(s)                                                                        \
    {#s, rtpbr_shimv_BRDF_Specular_##s, rtpbr_shimv_BRDF_SpecularLocal_##s,                       \
     rtpbr_shimv_D_Microfacet_##s, rtpbr_shimv_V_Microfacet_##s, rtpbr_shimv_G2_Microfacet_##s},
const VariantTable kVariants[RTPBR_SHIM_VARIANT_COUNT] = {RTPBR_SHIM_VARIANTS(RTPBR_SHIM_ENTRY)};

const VariantTable &get(rtpbr_shim_variant v) {
    unsigned i = static_cast<unsigned>(v);
    return kVariants[i < RTPBR_SHIM_VARIANT_COUNT ? i : 0];
}
} // namespace

extern "C" {
const char *rtpbr_shim_variant_name(rtpbr_shim_variant v) { return get(v).name; }
rtpbr_v3 rtpbr_BRDF_Specular(rtpbr_shim_variant v, float NoV, float NoL, float NoH, float VoH, float alpha,
                             rtpbr_fresnel_params f) {
    return get(v).brdf(NoV, NoL, NoH, VoH, alpha, f);
}
rtpbr_v3 rtpbr_BRDF_SpecularLocal(rtpbr_shim_variant v, rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay,
                                  rtpbr_fresnel_params f) {
    return get(v).brdfLocal(wo, wi, ax, ay, f);
}
float rtpbr_D_Microfacet(rtpbr_shim_variant v, float NoH, float alpha) { return get(v).d(NoH, alpha); }
float rtpbr_V_Microfacet(rtpbr_shim_variant v, float NoV, float NoL, float alpha) { return get(v).v(NoV, NoL, alpha); }
float rtpbr_G2_Microfacet(rtpbr_shim_variant v, rtpbr_v3 wo, rtpbr_v3 wi, float ax, float ay) {
    return get(v).g2(wo, wi, ax, ay);
}
}
