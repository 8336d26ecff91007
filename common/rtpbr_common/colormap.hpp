// rtpbr tools: the colour maps of the error pictures (rtpbr-diff's heat map, the viewer's
// live FLIP overlay, the LTC fit and validation plots).
#ifndef RTPBR_TOOLS_COLORMAP_HPP
#define RTPBR_TOOLS_COLORMAP_HPP

#include <cstdint>

namespace rtpbr_tools {

// Matplotlib's 256-entry "magma" (van der Walt & Smith 2015) as 8-bit sRGB: t in [0, 1]
// (clamped) picks entry lround(255 t), black at 0, pale yellow at 1.
void magma(float t, uint8_t rgb[3]);

// A coarse magma: straight lines in sRGB through six control points of the map, rounded to
// three decimals. The committed LTC error plots (shaderlib/luts/ltc_*_error*.png) are drawn
// with it, so it stays as it is: regenerating them gives the same bytes.
void magma_coarse(double t, uint8_t rgb[3]);

} // namespace rtpbr_tools

#endif
