// rtpbr tools: writing images (EXR, PNG, anything OpenImageIO knows by the file's extension).
// The one OpenImageIO writer of the tools, the oracle, the benches and the tests.
#ifndef RTPBR_TOOLS_IMAGE_HPP
#define RTPBR_TOOLS_IMAGE_HPP

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rtpbr_tools {

enum class PixelType { UInt8, Half, Float };

struct ImageWrite {
    int width = 0, height = 0, channels = 3; // channels 1..4
    const void *pixels = nullptr;            // width x height x channels, rows top to bottom
    PixelType pixel_type = PixelType::Float; // what `pixels` holds: UInt8 or Float
    PixelType file_type = PixelType::Float;  // what the file stores; values are converted
    std::vector<std::string> channel_names;  // empty: R, G, B, A
    // Metadata set in this order, e.g. {"compression", "zip"}, or {"DateTime", ""} so that
    // writing the same pixels again gives the same bytes.
    std::vector<std::pair<std::string, std::string>> attributes;
};

// Writes `image` to `path`; the format follows the extension. On failure returns false and
// sets `error` to "cannot write PATH: reason"; nothing is left open.
bool write_image(const std::string &path, const ImageWrite &image, std::string &error);

// The two common cases: 8-bit pixels stored as 8 bits, float pixels stored as float.
bool write_image_u8(const std::string &path, int width, int height, int channels, const uint8_t *pixels,
                    std::string &error);
bool write_image_float(const std::string &path, int width, int height, int channels, const float *pixels,
                       std::string &error);

} // namespace rtpbr_tools

#endif
