// Texture decoding of the loader: a copy of stb_image of its own (PNG and JPEG only) whose
// every allocation is counted, so that a decode stops at a memory limit set from the image's
// header instead of following a compressed stream wherever it leads (issue 31: a 1x1 PNG
// whose zlib stream inflates to 1 GiB took 1 GiB through the shared libstb).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtpbr_gltf_detail {

struct ImageHeader {
    int width = 0;
    int height = 0;
    bool sixteen_bit = false;  // a PNG of 16-bit channels
};

// Reads the header of a PNG or JPEG. On failure returns false with a static reason in *why.
bool read_image_header(const unsigned char* bytes, size_t size, ImageHeader* header, const char** why);

// The most memory a decode of an image with this header may hold at once, by the decoder's
// own arithmetic (see the definition); past it the data is corrupt or hostile.
uint64_t image_decode_memory_limit(const ImageHeader& header, size_t encoded_size);

enum class ImageDecodeStatus { ok, corrupt, over_memory_limit };

struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;      // RGBA8; 16-bit channels rounded to 8 bits
    uint64_t decoder_peak = 0;      // the most the decoder held at once, in bytes
    const char* why = nullptr;      // for corrupt: the decoder's static reason
};

// Decodes into out->rgba. The decoder's allocations are counted on this thread: one that would
// take them past memory_limit fails, and the decode returns over_memory_limit.
ImageDecodeStatus decode_image_rgba8(const unsigned char* bytes, size_t size, uint64_t memory_limit,
                                     DecodedImage* out);

}  // namespace rtpbr_gltf_detail
