// IEC 61966-2-1 sRGB transfer functions (header-only): the image reader decodes integer
// formats with them, and the FLIP library (rtpbr_common/flip.hpp) offers them to its callers.
#pragma once

#include <cmath>

namespace rtpbr {

inline float srgb_to_linear(float e) {
    return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

inline float linear_to_srgb(float l) {
    return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

} // namespace rtpbr
