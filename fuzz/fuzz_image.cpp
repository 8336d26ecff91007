// libFuzzer target: the image reading of rtpbr-diff and the viewer
// (common/rtpbr_common/image_read.hpp, OpenImageIO).
// The reader takes a path, so each input is written to a file in a private temporary folder.
// Checks beyond "no crash": a success yields width × height × 3 finite values.
#include "rtpbr_common/image_read.hpp"

#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

char g_dir[64];
std::string g_path;

// Files given to rtpbr-diff are named after their format: the input gets the extension its
// magic number suggests (OpenImageIO tries that reader first, then every other reader when
// it fails, as for a misnamed file); unknown content gets none (every reader is tried).
const char* extension_for(const uint8_t* d, size_t n) {
    auto starts = [&](const char* magic, size_t len) { return n >= len && std::memcmp(d, magic, len) == 0; };
    if (starts("\x89PNG", 4)) return ".png";
    if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
    if (starts("#?", 2)) return ".hdr";
    if (starts("\xff\xd8", 2)) return ".jpg";
    if (starts("II*", 3) || starts("MM\0*", 4)) return ".tif";
    if (starts("BM", 2)) return ".bmp";
    if (n >= 2 && d[0] == 'P' && d[1] >= '1' && d[1] <= '7') return ".ppm";
    return "";
}

void cleanup() {
    for (const char* ext : {"", ".png", ".exr", ".hdr", ".jpg", ".tif", ".bmp", ".ppm"})
        std::remove((g_path + ext).c_str());
    if (g_dir[0]) rmdir(g_dir);
}

void check(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_image: broken promise: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::snprintf(g_dir, sizeof g_dir, "/tmp/rtpbr-fuzz-image-XXXXXX");
    if (!mkdtemp(g_dir)) {
        std::perror("fuzz_image: mkdtemp");
        std::abort();
    }
    g_path = std::string(g_dir) + "/input";
    std::atexit(cleanup);
    // One thread: executions stay deterministic and do not compete for the shared cores.
    OIIO::attribute("threads", 1);
    OIIO::attribute("exr_threads", 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = g_path + extension_for(data, size);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    check(f != nullptr, "temporary file writable");
    if (size > 0) check(std::fwrite(data, 1, size, f) == size, "temporary file written");
    std::fclose(f);

    rtpbr::ImageReadOptions options;
    options.quiet = false;  // keep sanitizer reports visible; run with -close_fd_mask=2
    options.max_pixels = 1 << 20;  // same code path as the default, faster executions
    rtpbr::Image image;
    std::string error;
    if (rtpbr::read_image(path, image, error, options)) {
        check(image.width > 0 && image.height > 0, "positive size");
        check(image.rgb.size() == static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3,
              "width x height x 3 values");
        for (float v : image.rgb) check(std::isfinite(v), "finite values");
        if (std::getenv("RTPBR_FUZZ_VERBOSE")) std::fprintf(stderr, "fuzz_image: %dx%d\n", image.width, image.height);
    } else {
        check(!error.empty(), "a message on failure");
        if (std::getenv("RTPBR_FUZZ_VERBOSE")) std::fprintf(stderr, "fuzz_image: %s\n", error.c_str());
    }
    return 0;
}
