// rtpbr common: colour maps (see rtpbr_common/colormap.hpp).
#include "rtpbr_common/colormap.hpp"

#include <algorithm>
#include <cmath>

#include "rtpbr_common/magma_table.h"

namespace rtpbr_tools {

void magma(float t, uint8_t rgb[3]) {
    const int index = static_cast<int>(std::lround(std::min(1.0f, std::max(0.0f, t)) * 255.0f));
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<uint8_t>(std::lround(kMagma[index][c] * 255.0f));
}

void magma_coarse(double t, uint8_t rgb[3]) {
    static const double pts[][3] = {{0.001, 0.000, 0.014}, {0.231, 0.059, 0.439}, {0.550, 0.161, 0.506},
                                    {0.868, 0.288, 0.409}, {0.996, 0.624, 0.427}, {0.987, 0.991, 0.750}};
    t = std::clamp(t, 0.0, 1.0) * 5.0;
    const int i = std::min(int(t), 4);
    const double f = t - i;
    for (int k = 0; k < 3; k++)
        rgb[k] = static_cast<uint8_t>(std::lround(255.0 * (pts[i][k] + f * (pts[i + 1][k] - pts[i][k]))));
}

} // namespace rtpbr_tools
