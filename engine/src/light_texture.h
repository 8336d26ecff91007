// The prefiltered mip chain of a textured quad light's emission (issue 30), built on the host,
// for the lookup of shaderlib/rtpbr/ltc_textured.h (Heitz, Dupuy, Hill & Neubelt 2016,
// "Real-Time Polygonal-Light Shading with Linearly Transformed Cosines", section 6): the lookup
// reads at lod = log2(footprint * RTPBR_LIGHT_TEXTURE_SIZE), and expects mip k to be the emission
// blurred with a half-mass radius of 2^k level-0 texels.
//
// The light is the parallelogram corner + s edgeS + t edgeT, s, t in [0, 1]; the chain is indexed
// by (s, t), so the lookup's (u, v) read it directly. Level 0 is the light's emission resampled
// onto an S x S grid of (s, t) cells; level k is level 0 blurred by a Gaussian normalised over the
// light, then averaged over 2^k x 2^k blocks (details at rtpbr_light_texture_prefilter).
// Plain C on the caller's memory: no allocation, no Vulkan.
#ifndef RTPBR_LIGHT_TEXTURE_H
#define RTPBR_LIGHT_TEXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "rtpbr/rtpbr.h"

#define RTPBR_LIGHT_TEXTURE_SIZE 128 // level 0 is S x S
#define RTPBR_LIGHT_TEXTURE_LEVELS 8 // S, S/2, ..., 1

// Floats (RGBA) of a whole chain: the sum over k of (S >> k)^2 * 4.
size_t rtpbr_light_texture_floats(void);
// Offset in floats of level k in a chain; k = RTPBR_LIGHT_TEXTURE_LEVELS (or more) gives the
// chain's size, rtpbr_light_texture_floats().
size_t rtpbr_light_texture_level_offset(uint32_t k);

// Builds the chain of src's texture over the parallelogram of texture coordinates
// uv0 + s du + t dv, s, t in [0, 1] (glTF texture coordinates: u right, v down the image; texel
// (i, j) covers u in [i/W, (i+1)/W], v in [j/H, (j+1)/H]), into out:
//   level 0: texel (x, y) is the mean of the texture over its cell s in [x/S, (x+1)/S],
//     t in [y/S, (y+1)/S]: n_s x n_t bilinear reads honouring src's wrap_s and wrap_t, n per axis
//     max(2, ceil(2 * texels the cell spans along that axis)), at most 16 (a texture much larger
//     than the light's grid is averaged, not aliased). Colours are sRGB-decoded first when
//     src->srgb (the exact EOTF per channel), so the chain is linear RGB; alpha is 1.
//     src's filters and mipmap mode are not used.
//   level k >= 1: level 0 convolved with a Gaussian of sigma = 2^k / sqrt(2 ln 2) level-0 texels
//     (half of its mass within radius 2^k), truncated at 3.5 sigma and normalised over the
//     light: (level 0 * G) / (indicator of the light * G), the mean emission over the part of
//     the light the lobe sees, so a constant emission stays constant and the edges are not
//     darkened; then averaged over 2^k x 2^k blocks into (S >> k)^2 texels.
// out holds rtpbr_light_texture_floats() floats: level k at rtpbr_light_texture_level_offset(k),
// row y (t) major, x (s) minor, RGBA.
// Returns 0, or -1 (out untouched) for bad input: NULL src, src->rgba, uv0, du, dv or out, a
// width or height of 0 or over RTPBR_MAX_RENDER_SIZE, an unknown wrap mode, a non-finite
// uv0, du or dv.
int rtpbr_light_texture_prefilter(const rtpbr_texture_desc *src, const float uv0[2], const float du[2],
                                  const float dv[2], float *out);

#endif
