// OpenImageIO reading for rtpbr-diff (image_read.h).
#include "image_read.h"

#include "flip.h"

#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdio>

namespace rtpbr {

namespace {

// Some codecs (libpng) print their own diagnostics to stderr; OpenImageIO also returns them
// through geterror(), which we report. Silences fd 2 while alive.
class SilenceStderr {
public:
    explicit SilenceStderr(bool enable) {
        if (!enable) return;
        std::fflush(stderr);
        saved_ = dup(STDERR_FILENO);
        const int null_fd = open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null_fd >= 0) dup2(null_fd, STDERR_FILENO);
        if (null_fd >= 0) close(null_fd);
    }
    ~SilenceStderr() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        dup2(saved_, STDERR_FILENO);
        close(saved_);
    }
    SilenceStderr(const SilenceStderr&) = delete;
    SilenceStderr& operator=(const SilenceStderr&) = delete;

private:
    int saved_ = -1;
};

}  // namespace

bool read_image(const std::string& path, Image& image, std::string& error, const ImageReadOptions& options) {
    SilenceStderr quiet(options.quiet);
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string why = OIIO::geterror();
        if (why.empty()) why = "cannot open";
        error = "cannot read '" + path + "': " + why;
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1 || spec.deep) {
        error = "'" + path + "' is not a flat 2D image with pixels";
        return false;
    }
    const int nch = spec.nchannels;
    std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * nch);
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, pixels.data())) {
        error = "cannot decode '" + path + "': " + in->geterror();
        return false;
    }
    in->close();
    const bool encoded = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                         spec.format.basetype != OIIO::TypeDesc::HALF &&
                         spec.format.basetype != OIIO::TypeDesc::DOUBLE;
    image.width = spec.width;
    image.height = spec.height;
    const std::size_t n = static_cast<std::size_t>(spec.width) * spec.height;
    image.rgb.resize(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            const int src = nch >= 3 ? c : 0;  // 1 or 2 channels: grey (+ alpha)
            float v = pixels[i * nch + src];
            if (!std::isfinite(v)) {
                error = "'" + path + "' holds NaN or infinite values";
                return false;
            }
            image.rgb[i * 3 + c] = encoded ? srgb_to_linear(v) : v;
        }
    }
    return true;
}

}  // namespace rtpbr
