// Writes the small images the rtpbr-diff command-line tests compare (into the directory given),
// so no test image is committed. All content is deterministic.
#include "rtpbr_common/image.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace {

bool write(const std::string& path, int w, int h, const std::vector<float>& rgb, rtpbr_tools::PixelType type) {
    rtpbr_tools::ImageWrite image;
    image.width = w, image.height = h, image.channels = 3, image.pixels = rgb.data(), image.file_type = type;
    std::string error;
    if (!rtpbr_tools::write_image(path, image, error)) {
        std::fprintf(stderr, "make_images: %s\n", error.c_str());
        return false;
    }
    return true;
}

// A smooth gradient with a bright square: something with edges for the feature pipeline.
std::vector<float> scene(int w, int h, float gain) {
    std::vector<float> rgb(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &rgb[(static_cast<std::size_t>(y) * w + x) * 3];
            const bool square = x >= w / 3 && x < 2 * w / 3 && y >= h / 3 && y < 2 * h / 3;
            p[0] = gain * (square ? 0.9f : 0.2f + 0.6f * x / w);
            p[1] = gain * (square ? 0.8f : 0.3f + 0.4f * y / h);
            p[2] = gain * (square ? 0.2f : 0.5f);
        }
    return rgb;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_images OUTDIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    const int w = 64, h = 48;
    const std::vector<float> ref = scene(w, h, 1.0f);
    std::vector<float> slight = ref, strong = ref;
    std::uint32_t state = 12345u;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        state = state * 1664525u + 1013904223u;  // Numerical Recipes LCG
        const float n = static_cast<float>(state >> 8) / 16777216.0f * 2.0f - 1.0f;
        slight[i] = std::fmin(1.0f, std::fmax(0.0f, ref[i] + 0.02f * n));
        strong[i] = std::fmin(1.0f, std::fmax(0.0f, ref[i] + 0.3f * n));
    }
    bool ok = write(dir + "/ref.png", w, h, ref, rtpbr_tools::PixelType::UInt8) &&
              write(dir + "/ref_copy.png", w, h, ref, rtpbr_tools::PixelType::UInt8) &&
              write(dir + "/slight.png", w, h, slight, rtpbr_tools::PixelType::UInt8) &&
              write(dir + "/strong.png", w, h, strong, rtpbr_tools::PixelType::UInt8) &&
              write(dir + "/small.png", w / 2, h / 2, scene(w / 2, h / 2, 1.0f), rtpbr_tools::PixelType::UInt8) &&
              write(dir + "/ref.exr", w, h, scene(w, h, 8.0f), rtpbr_tools::PixelType::Half) &&
              write(dir + "/test.exr", w, h, scene(w, h, 9.0f), rtpbr_tools::PixelType::Half);
    std::FILE* junk = std::fopen((dir + "/not_an_image.png").c_str(), "wb");
    if (!junk) return 2;
    std::fputs("this is not a PNG\n", junk);
    std::fclose(junk);
    return ok ? 0 : 2;
}
