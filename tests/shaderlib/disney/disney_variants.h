// Entry points of the separately compiled flag variants of disney.h (see disney_variants.cpp).
#pragma once

#define DV_DECLARE(prefix)                                                                         \
    void prefix##_brdf(const float *params, const float *wo, const float *wi, float *out);         \
    void prefix##_model(const float *params, const float *wo, const float *wi, const float *t,     \
                        float *out);                                                               \
    void prefix##_ec(const float *params, const float *wo, const float *wi, const float *t,        \
                     float *out);                                                                  \
    float prefix##_pdf(const float *params, const float *wo, const float *wi);                     \
    float prefix##_pdf_ex(const float *params, const float *wo, const float *wi, int ec);

DV_DECLARE(dv_separable) // RTPBR_SMITH = RTPBR_SMITH_SEPARABLE (Burley's reference G)
DV_DECLARE(dv_ecflag)    // RTPBR_DISNEY_ENERGY_CONSERVING = 1
DV_DECLARE(dv_default)   // default flags
