// Reference images through OpenImageIO (see reference.h).
#include "reference.h"

#include <OpenImageIO/imageio.h>
#include <cstdio>
#include <cstdlib>
#include <vector>

float *viewer_reference_load(const char *path, int *width, int *height)
{
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::fprintf(stderr, "rtpbr-viewer: cannot open reference %s: %s\n", path, OIIO::geterror().c_str());
        return nullptr;
    }
    const OIIO::ImageSpec &spec = in->spec();
    int channels = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || spec.width > 16384 || spec.height > 16384) {
        std::fprintf(stderr, "rtpbr-viewer: reference %s: unsupported size\n", path);
        return nullptr;
    }
    std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        std::fprintf(stderr, "rtpbr-viewer: cannot read reference %s: %s\n", path, in->geterror().c_str());
        return nullptr;
    }
    size_t n = static_cast<size_t>(spec.width) * spec.height;
    float *rgba = static_cast<float *>(std::malloc(n * 4 * sizeof(float)));
    if (!rgba) return nullptr;
    for (size_t i = 0; i < n; ++i) {
        const float *p = &pixels[i * channels];
        rgba[4 * i + 0] = p[0];
        rgba[4 * i + 1] = channels > 1 ? p[1] : p[0];
        rgba[4 * i + 2] = channels > 2 ? p[2] : p[0];
        rgba[4 * i + 3] = channels > 3 ? p[3] : 1.0f;
    }
    *width = spec.width;
    *height = spec.height;
    return rgba;
}
