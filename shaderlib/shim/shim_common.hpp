// Conversions between the C shim's plain structs and the C++ shader library types.
#pragma once
#include "rtpbr_shim.h"
#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

namespace rtpbr_shim {
inline rtpbr::float3 in(rtpbr_v3 v) { return rtpbr::float3(v.x, v.y, v.z); }
inline rtpbr_v3 out(rtpbr::float3 v) { return rtpbr_v3{v.x, v.y, v.z}; }
inline rtpbr::FresnelParams in(const rtpbr_fresnel_params &p) {
    rtpbr::FresnelParams r;
    r.f0 = in(p.f0);
    r.f90 = p.f90;
    r.eta = in(p.eta);
    r.k = in(p.k);
    return r;
}
inline rtpbr_fresnel_params out(const rtpbr::FresnelParams &p) {
    return rtpbr_fresnel_params{out(p.f0), p.f90, out(p.eta), out(p.k)};
}
} // namespace rtpbr_shim
