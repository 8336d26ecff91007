// sheen.h compiled with RTPBR_SHEEN_VISIBILITY = RTPBR_SHEEN_VISIBILITY_NEUBELT (its own
// RTPBR_CPP_VARIANT, see lang.h): the flag's entry points, called by test_sheen.cpp.
#include <rtpbr/sheen.h>

float sheen_neubelt_V_Sheen(float NoV, float NoL, float alpha) { return rtpbr::V_Sheen(NoV, NoL, alpha); }

float sheen_neubelt_BRDF(float NoV, float NoL, float NoH, float roughness) {
    return rtpbr::BRDF_Sheen(rtpbr::float3(1.0f), roughness, NoV, NoL, NoH).x;
}
