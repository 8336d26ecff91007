// The Disney BRDF compiled with non-default flags, each in its own C++ inline namespace
// (RTPBR_CPP_VARIANT) so that the test program can link several variants. Parameters cross the
// boundary as plain floats: material = {r, g, b, metallic, subsurface, specular, specularTint,
// roughness, anisotropic, sheen, sheenTint, clearcoat, clearcoatGloss}.
#include <rtpbr/disney.h>
#include "disney_flat.h"
#include "disney_variants.h"

#ifndef DISNEY_VARIANT_PREFIX
#error "DISNEY_VARIANT_PREFIX must name the exported functions' prefix"
#endif
#define DV_CAT2(a, b) a##_##b
#define DV_CAT(a, b) DV_CAT2(a, b)
#define DV_NAME(fn) DV_CAT(DISNEY_VARIANT_PREFIX, fn)

namespace {
rtpbr::float3 v(const float *w) { return rtpbr::float3(w[0], w[1], w[2]); }
void put(rtpbr::float3 f, float *out) {
    out[0] = f.x;
    out[1] = f.y;
    out[2] = f.z;
}
rtpbr::DisneyEnergyTerms terms(const float *t) {
    rtpbr::DisneyEnergyTerms e;
    e.dfgO = rtpbr::float2(t[0], t[1]);
    e.dfgI = rtpbr::float2(t[2], t[3]);
    e.Eavg = t[4];
    return e;
}
} // namespace

void DV_NAME(brdf)(const float *params, const float *wo, const float *wi, float *out) {
    put(rtpbr::BRDF_Disney(unflatten(params), v(wo), v(wi)), out);
}
void DV_NAME(model)(const float *params, const float *wo, const float *wi, const float *t, float *out) {
    put(rtpbr::BRDF_DisneyModel(unflatten(params), v(wo), v(wi), terms(t)), out);
}
void DV_NAME(ec)(const float *params, const float *wo, const float *wi, const float *t, float *out) {
    put(rtpbr::BRDF_DisneyEnergyConserving(unflatten(params), v(wo), v(wi), terms(t)), out);
}
float DV_NAME(pdf)(const float *params, const float *wo, const float *wi) {
    return rtpbr::Disney_PDF(unflatten(params), v(wo), v(wi));
}
float DV_NAME(pdf_ex)(const float *params, const float *wo, const float *wi, int ec) {
    return rtpbr::Disney_PDFEx(unflatten(params), v(wo), v(wi), ec != 0);
}
