// OpenImageIO image reading (rtpbr_common/image_read.hpp).
#include "rtpbr_common/image_read.hpp"

#include "rtpbr_common/srgb.hpp"

#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <memory>

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

// OpenEXR 3.1 and libpng 1.6 trust sizes in a file while reading it, before OpenImageIO sees
// the spec: an EXR attribute or a PNG text chunk claiming 2 GB makes a corrupt 400-byte file
// take gigabytes (found by fuzz/fuzz_image). So these containers are walked here first and
// every size must fit in the file: EXR (magic, version/flags, then per part attributes
// "name\0type\0size value" ending in an empty name; data windows must also fit max_pixels),
// PNG (signature, then chunks "length type data crc" up to IEND). Returns false with a
// message otherwise; what the scan cannot follow is left to the codec to reject.
bool png_chunks_fit(std::FILE* f, long long file_size, const std::string& path, std::string& error) {
    long long at = 8;
    unsigned char head[8];
    while (at + 12 <= file_size) {
        if (std::fseek(f, static_cast<long>(at), SEEK_SET) != 0 || std::fread(head, 1, 8, f) != 8) return true;
        const long long length = static_cast<long long>(head[0]) << 24 | head[1] << 16 | head[2] << 8 | head[3];
        if (length > file_size - at - 12) {
            error = "'" + path + "': PNG chunk '" + std::string(reinterpret_cast<const char*>(head + 4), 4) +
                    "' at byte " + std::to_string(at) + " claims " + std::to_string(length) +
                    " bytes, more than the file holds";
            return false;
        }
        if (std::memcmp(head + 4, "IEND", 4) == 0) break;
        at += 12 + length;
    }
    return true;
}

bool container_sizes_fit(const std::string& path, long long max_pixels, std::string& error) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return true;  // OpenImageIO reports why
    std::vector<unsigned char> head(1 << 16);
    head.resize(std::fread(head.data(), 1, head.size(), f));
    long long file_size = -1;
    if (std::fseek(f, 0, SEEK_END) == 0) file_size = std::ftell(f);
    static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    const bool png = head.size() >= 8 && std::memcmp(head.data(), kPngSignature, 8) == 0;
    const bool png_fits = !png || file_size < 0 || png_chunks_fit(f, file_size, path, error);
    std::fclose(f);
    if (png) return png_fits;
    auto u32 = [&](std::size_t at) {
        return static_cast<uint32_t>(head[at]) | static_cast<uint32_t>(head[at + 1]) << 8 |
               static_cast<uint32_t>(head[at + 2]) << 16 | static_cast<uint32_t>(head[at + 3]) << 24;
    };
    // BMP: OpenImageIO's reader decodes an RLE image while opening it, before its spec can be
    // checked: a 5 x 687865859 RLE header made it resize a vector past the limit (found by
    // fuzz_image). The info header's size is checked here first.
    if (head.size() >= 26 && head[0] == 'B' && head[1] == 'M') {
        const uint32_t info = u32(14);
        long long w = 0, h = 0;
        if (info == 12) {  // BITMAPCOREHEADER: uint16 width and height
            w = head[18] | head[19] << 8;
            h = head[20] | head[21] << 8;
        } else if (info >= 40) {  // BITMAPINFOHEADER and later: int32 width, height (< 0: top-down)
            w = std::llabs(static_cast<long long>(static_cast<int32_t>(u32(18))));
            h = std::llabs(static_cast<long long>(static_cast<int32_t>(u32(22))));
        }
        if (w > 0 && h > 0 && w > max_pixels / h) {
            error = "'" + path + "': BMP of " + std::to_string(w) + "x" + std::to_string(h) + " pixels exceeds the limit of " +
                    std::to_string(max_pixels) + " pixels";
            return false;
        }
        return true;
    }
    if (head.size() < 8 || u32(0) != 20000630u || file_size < 0) return true;  // not EXR
    const bool multipart = (u32(4) & 0x1000u) != 0;
    // Tiles larger than both the data window and 256 x 256 pixels: OpenEXR allocates a tile's
    // buffers when it opens the file (a 64 x 64 image declaring 1069 x 262179 tiles: 1.7 GB),
    // before OpenImageIO's spec can be checked (open_checked checks it again, for TIFF too).
    // Unsigned 64 bits: two uint32 tile sizes multiply without overflow.
    unsigned long long window_pixels = 0, tile_pixels = 0;
    const auto tiles_fit = [&]() {
        if (tile_pixels <= std::max(window_pixels, 65536ULL)) return true;
        error = "'" + path + "': EXR tiles of " + std::to_string(tile_pixels) + " pixels for a data window of " +
                std::to_string(window_pixels);
        return false;
    };
    std::size_t at = 8;
    while (at < head.size()) {
        if (head[at] == 0) {  // end of a header; a multi-part file ends with an empty one
            ++at;
            if (!tiles_fit()) return false;
            window_pixels = tile_pixels = 0;
            if (!multipart || (at < head.size() && head[at] == 0)) break;
            continue;
        }
        const auto zero_after = [&](std::size_t from) {
            return static_cast<std::size_t>(std::find(head.begin() + static_cast<std::ptrdiff_t>(from), head.end(), 0) -
                                            head.begin());
        };
        const std::size_t name_end = zero_after(at);
        if (name_end >= head.size()) break;
        const std::size_t type_end = zero_after(name_end + 1);
        if (type_end + 4 >= head.size()) break;
        const std::string name(reinterpret_cast<const char*>(&head[at]), name_end - at);
        const long long size = u32(type_end + 1);
        const std::size_t value = type_end + 5;
        if (size > file_size - static_cast<long long>(value)) {
            error = "'" + path + "': EXR attribute '" + name.substr(0, 64) + "' claims " + std::to_string(size) +
                    " bytes, more than the file holds";
            return false;
        }
        if (static_cast<std::size_t>(size) > head.size() - value) break;  // beyond what was read
        // OpenEXR reads an attribute of a fixed-size type at that size whatever the size field
        // says, and this walk would then follow other attributes than OpenEXR does: a 12-byte
        // dataWindow made it read a huge window from the next bytes and allocate 1.8 GB of line
        // offsets, a 0-byte box2i hid 1069 x 262179 tiles from this walk (found by fuzz_image).
        // Refused unless the sizes agree (OpenEXR 3.1's fixed-size attribute types).
        static const struct { const char* type; long long size; } kFixed[] = {
            {"box2i", 16}, {"box2f", 16}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12},
            {"v3d", 24}, {"int", 4}, {"float", 4}, {"double", 8}, {"compression", 1}, {"lineOrder", 1},
            {"envmap", 1}, {"deepImageState", 1}, {"tiledesc", 9}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64},
            {"m44d", 128}, {"chromaticities", 32}, {"rational", 8}, {"timecode", 8}, {"keycode", 28}};
        const std::string type(reinterpret_cast<const char*>(&head[name_end + 1]), type_end - name_end - 1);
        for (const auto& fixed : kFixed) {
            if (type == fixed.type && size != fixed.size) {
                error = "'" + path + "': EXR attribute '" + name.substr(0, 64) + "' of type " + type + " is " +
                        std::to_string(size) + " bytes, not " + std::to_string(fixed.size);
                return false;
            }
        }
        if (name == "dataWindow" && type == "box2i") {
            const auto s32 = [&](std::size_t i) { return static_cast<long long>(static_cast<int32_t>(u32(value + 4 * i))); };
            const long long w = s32(2) - s32(0) + 1, h = s32(3) - s32(1) + 1;
            if (w <= 0 || h <= 0 || w > max_pixels / h) {
                error = "'" + path + "': EXR data window " + std::to_string(w) + "x" + std::to_string(h) +
                        (w <= 0 || h <= 0 ? " is empty" : " exceeds the limit of " + std::to_string(max_pixels) + " pixels");
                return false;
            }
            window_pixels = static_cast<unsigned long long>(w * h);  // <= max_pixels (checked above)
        }
        if (name == "tiles" && type == "tiledesc")  // x size, y size (uint32), mode
            tile_pixels = static_cast<unsigned long long>(u32(value)) * u32(value + 4);
        at = value + static_cast<std::size_t>(size);
    }
    return tiles_fit();
}

// The formats rtpbr reads, each recognised by its signature, or (TGA, which has none) by its
// extension: a misnamed file still reads. Only these readers run. OpenImageIO's own fallback
// tries every reader it has on an unrecognised file: camera raw, HEIF, video, DICOM, ... (a
// large attack surface for files nobody compares; libheif once spun forever on a directory).
// Trying them also took half of each fuzz_image execution: replaying its corpus went from
// 7.7 to 3.8 ms per input.
// OpenImageIO's reader for the file's first bytes (or its extension, for TGA); null if none.
const char* format_of(const std::string& path, const unsigned char* head, std::size_t n) {
    auto starts = [&](const char* magic, std::size_t len) { return n >= len && std::memcmp(head, magic, len) == 0; };
    if (starts("\x89PNG\r\n\x1a\n", 8)) return "png";
    if (starts("\x76\x2f\x31\x01", 4)) return "openexr";      // OpenEXR magic 20000630
    if (starts("#?", 2)) return "hdr";                        // "#?RADIANCE" / "#?RGBE"
    if (starts("\xff\xd8\xff", 3)) return "jpeg";
    if (starts("II*\0", 4) || starts("MM\0*", 4)) return "tiff";
    if (starts("BM", 2)) return "bmp";
    if (n >= 2 && head[0] == 'P' && ((head[1] >= '1' && head[1] <= '6') || head[1] == 'F' || head[1] == 'f'))
        return "pnm";                                         // PBM/PGM/PPM and PFM
    const std::size_t dot = path.find_last_of("./");
    if (dot != std::string::npos && path[dot] == '.') {
        std::string ext = path.substr(dot + 1);
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext == "tga" || ext == "tpic") return "targa";
    }
    return nullptr;
}

// Opens `path` after the checks above and those of its spec (flat 2D image, pixel limit),
// reading no pixel. Null with a message on failure.
std::unique_ptr<OIIO::ImageInput> open_checked(const std::string& path, std::string& error,
                                               const ImageReadOptions& options) {
    // Only regular files go to OpenImageIO: given a directory it tries every format plugin,
    // and libheif's reader spins forever on one (seen under ASan in the bad-input suite).
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) {
        error = "cannot read '" + path + "': " + std::strerror(errno);
        return nullptr;
    }
    if (!S_ISREG(st.st_mode)) {
        error = "cannot read '" + path + "': not a regular file";
        return nullptr;
    }
    const long long max_pixels = options.max_pixels > 0 ? options.max_pixels : kMaxImagePixels;
    if (!container_sizes_fit(path, max_pixels, error)) return nullptr;
    unsigned char head[8] = {};
    std::size_t n = 0;
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
        n = std::fread(head, 1, sizeof head, f);
        std::fclose(f);
    }
    const char* format = format_of(path, head, n);
    if (!format) {
        error = "cannot read '" + path + "': not a PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM/PFM or TGA file";
        return nullptr;
    }
    auto in = OIIO::ImageInput::create(format);
    OIIO::ImageSpec opened;
    if (!in || !in->open(path, opened)) {
        std::string why = in ? in->geterror() : OIIO::geterror();
        if (why.empty()) why = "cannot open";
        error = "cannot read '" + path + "': " + why;
        return nullptr;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1 || spec.deep) {
        error = "'" + path + "' is not a flat 2D image with pixels";
        return nullptr;
    }
    if (spec.width > max_pixels / spec.height) {
        error = "'" + path + "' is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                ", more than the limit of " + std::to_string(max_pixels) + " pixels";
        return nullptr;
    }
    // Tiles are decoded whole: a 5 x 3 OpenEXR file declaring 4 x 33554436 tiles made OpenEXR
    // allocate 1.7 GB (found by fuzz_image; container_sizes_fit refuses such EXR files before
    // OpenEXR opens them, this covers TIFF). A tile may exceed a small image (64 x 64 tiles
    // over a 5 x 3 image are legitimate), but not both the image and 256 x 256 pixels.
    if (spec.tile_width > 0) {
        const long long tile_pixels = static_cast<long long>(spec.tile_width) * std::max(spec.tile_height, 1) *
                                      std::max(spec.tile_depth, 1);
        const long long image_pixels = static_cast<long long>(spec.width) * spec.height;
        if (tile_pixels > std::max(image_pixels, 65536LL)) {
            error = "'" + path + "' declares " + std::to_string(spec.tile_width) + "x" +
                    std::to_string(spec.tile_height) + " tiles for a " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + " image";
            return nullptr;
        }
    }
    return in;
}


// The codecs throw on some hostile files (OpenImageIO's BMP reader: std::length_error from a
// vector resize, found by fuzz_image); both public functions turn that into a message.
template <typename Read>
bool without_exceptions(const std::string& path, std::string& error, Read read) {
    try {
        return read();
    } catch (const std::bad_alloc&) {
        error = "cannot read '" + path + "': out of memory while decoding";
    } catch (const std::exception& e) {
        error = "cannot read '" + path + "': the decoder failed (" + e.what() + ")";
    }
    return false;
}

bool read_image_size_unguarded(const std::string& path, int& width, int& height, std::string& error,
                               const ImageReadOptions& options) {
    SilenceStderr quiet(options.quiet);
    const auto in = open_checked(path, error, options);
    if (!in) return false;
    width = in->spec().width;
    height = in->spec().height;
    return true;
}

bool read_image_unguarded(const std::string& path, Image& image, std::string& error, const ImageReadOptions& options) {
    SilenceStderr quiet(options.quiet);
    const auto in = open_checked(path, error, options);
    if (!in) return false;
    const OIIO::ImageSpec spec = in->spec();
    const bool encoded = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                         spec.format.basetype != OIIO::TypeDesc::HALF &&
                         spec.format.basetype != OIIO::TypeDesc::DOUBLE;
    const std::size_t width = static_cast<std::size_t>(spec.width);
    const std::size_t n = width * static_cast<std::size_t>(spec.height);
    image.width = spec.width;
    image.height = spec.height;
    image.rgb.assign(n * 3, 0.0f);
    // Stores count pixels of `channels` floats each from pixel `first` on: RGB, or grey
    // (channel 0) when there are fewer than 3 channels; alpha and the rest are ignored.
    auto store = [&](const float* values, int channels, std::size_t first, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            for (int c = 0; c < 3; ++c) {
                const float v = values[i * channels + (channels >= 3 ? c : 0)];
                if (!std::isfinite(v)) {
                    error = "'" + path + "' holds NaN or infinite values";
                    return false;
                }
                image.rgb[(first + i) * 3 + c] = encoded ? srgb_to_linear(v) : v;
            }
        }
        return true;
    };
    auto fail = [&]() {
        error = "cannot decode '" + path + "': " + in->geterror();
        image = Image();
        return false;
    };
    if (spec.tile_width == 0 && spec.channelformats.empty()) {
        // Scanline images: rows in their own format, 4 MiB at a time (and at most 16 MiB of their
        // floats), converted here.
        // (Asked for floats, OpenImageIO's read_image converts through a 64 MiB buffer it
        // allocates on every call, whatever the image's size: imageinput.cpp, read_scanlines.)
        const std::size_t row_bytes = std::max<std::size_t>(1, spec.scanline_bytes(true));
        const std::size_t rows =
            std::min<std::size_t>(static_cast<std::size_t>(spec.height), std::max<std::size_t>(1, (4u << 20) / row_bytes));
        const std::size_t row_values = width * static_cast<std::size_t>(spec.nchannels);
        std::vector<unsigned char> native(rows * row_bytes);
        std::vector<float> values(rows * row_values);
        for (std::size_t y = 0; y < static_cast<std::size_t>(spec.height); y += rows) {
            const std::size_t count = std::min(rows, static_cast<std::size_t>(spec.height) - y);
            const int y0 = spec.y + static_cast<int>(y);
            if (!in->read_scanlines(0, 0, y0, y0 + static_cast<int>(count), 0, 0, spec.nchannels,
                                    OIIO::TypeDesc::UNKNOWN, native.data()))
                return fail();
            if (!OIIO::convert_pixel_values(spec.format, native.data(), OIIO::TypeDesc::FLOAT, values.data(),
                                            static_cast<int>(count * row_values)))
                return fail();
            if (!store(values.data(), spec.nchannels, y * width, count * width)) {
                image = Image();
                return false;
            }
        }
    } else {
        // Tiled images and per-channel formats (OpenEXR): OpenImageIO converts tile by tile.
        const int nch = spec.nchannels >= 3 ? 3 : 1;
        std::vector<float> pixels(n * static_cast<std::size_t>(nch));
        if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, pixels.data())) return fail();
        if (!store(pixels.data(), nch, 0, n)) {
            image = Image();
            return false;
        }
    }
    in->close();
    return true;
}

}  // namespace

bool read_image_size(const std::string& path, int& width, int& height, std::string& error,
                     const ImageReadOptions& options) {
    return without_exceptions(path, error, [&] { return read_image_size_unguarded(path, width, height, error, options); });
}

bool read_image(const std::string& path, Image& image, std::string& error, const ImageReadOptions& options) {
    const bool ok = without_exceptions(path, error, [&] { return read_image_unguarded(path, image, error, options); });
    if (!ok) image = Image();
    return ok;
}

}  // namespace rtpbr
