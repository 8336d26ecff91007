// Texture decoding with counted allocations (scene_image_decode.hpp).
//
// Debian's libstb is a compiled library, so its allocator cannot be replaced; this file compiles
// the implementation from the same header (/usr/include/stb/stb_image.h) a second time, static
// to this file and limited to PNG and JPEG, with STBI_MALLOC/STBI_REALLOC/STBI_FREE (the
// header's documented hooks) pointing at counters. It is built with warnings off, as
// third-party code (scene/meson.build); what is ours here is the counting.
#include "scene_image_decode.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace {

struct DecodeMemory {
    uint64_t limit = 0;
    uint64_t live = 0;
    uint64_t peak = 0;
    bool refused = false;
};

thread_local DecodeMemory* t_memory = nullptr;  // the decode running on this thread, if any

// Each block carries its size in front; 16 bytes keep malloc's alignment.
constexpr size_t kPrefix = 16;

size_t block_size(void* p) {
    size_t n;
    std::memcpy(&n, static_cast<unsigned char*>(p) - kPrefix, sizeof n);
    return n;
}

void* counted_realloc(void* p, size_t n) {
    const size_t old = p ? block_size(p) : 0;
    DecodeMemory* m = t_memory;
    if (n > SIZE_MAX - kPrefix) return nullptr;
    if (m && (n > m->limit || m->live - std::min<uint64_t>(m->live, old) > m->limit - n)) {
        m->refused = true;
        return nullptr;
    }
    void* base = p ? static_cast<unsigned char*>(p) - kPrefix : nullptr;
    unsigned char* q = static_cast<unsigned char*>(std::realloc(base, n + kPrefix));
    if (!q) return nullptr;
    std::memcpy(q, &n, sizeof n);
    if (m) {
        m->live = m->live - std::min<uint64_t>(m->live, old) + n;
        m->peak = std::max(m->peak, m->live);
    }
    return q + kPrefix;
}

void* counted_malloc(size_t n) { return counted_realloc(nullptr, n); }

void counted_free(void* p) {
    if (!p) return;
    if (DecodeMemory* m = t_memory) m->live -= std::min<uint64_t>(m->live, block_size(p));
    std::free(static_cast<unsigned char*>(p) - kPrefix);
}

}  // namespace

#define STBI_MALLOC(n) counted_malloc(n)
#define STBI_REALLOC(p, n) counted_realloc(p, n)
#define STBI_FREE(p) counted_free(p)
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#include <stb_image.h>

namespace rtpbr_gltf_detail {

namespace {

// Sets the counters of this thread for one scope.
class CountedScope {
public:
    explicit CountedScope(DecodeMemory* m) : saved_(t_memory) { t_memory = m; }
    ~CountedScope() { t_memory = saved_; }
    CountedScope(const CountedScope&) = delete;
    CountedScope& operator=(const CountedScope&) = delete;

private:
    DecodeMemory* saved_;
};

}  // namespace

bool read_image_header(const unsigned char* bytes, size_t size, ImageHeader* header, const char** why) {
    int comp = 0;
    if (!stbi_info_from_memory(bytes, int(size), &header->width, &header->height, &comp)) {
        *why = stbi_failure_reason() ? stbi_failure_reason() : "unknown";
        return false;
    }
    header->sixteen_bit = stbi_is_16_bit_from_memory(bytes, int(size)) != 0;
    return true;
}

// What stb_image 2022-09-08 holds at once, per texel of a (w + 32) x (h + 32) image (JPEG pads
// each side to its MCU, up to 32 texels): a PNG's inflated rows (8 bytes at 16-bit RGBA, twice
// that when an overlong stream makes the buffer double once) with the unfiltered image (8) and
// an interlaced pass (8); a JPEG's planes with, progressive, their coefficients (3 bytes a
// texel for each of up to 4 components) and the output (4). So 32 bytes a padded texel, plus the
// compressed data gathered from the chunks (up to twice the file, the buffer doubling) and
// 1 MiB for the decoder's tables and line buffers.
uint64_t image_decode_memory_limit(const ImageHeader& header, size_t encoded_size) {
    const uint64_t padded = (uint64_t(header.width) + 32) * (uint64_t(header.height) + 32);
    return 32 * padded + 2 * uint64_t(encoded_size) + (uint64_t(1) << 20);
}

ImageDecodeStatus decode_image_rgba8(const unsigned char* bytes, size_t size, uint64_t memory_limit,
                                     DecodedImage* out) {
    DecodeMemory memory;
    memory.limit = memory_limit;
    CountedScope scope(&memory);
    int w = 0, h = 0, comp = 0;
    const bool sixteen = stbi_is_16_bit_from_memory(bytes, int(size)) != 0;
    std::unique_ptr<void, void (*)(void*)> pixels(
        sixteen ? static_cast<void*>(stbi_load_16_from_memory(bytes, int(size), &w, &h, &comp, 4))
                : static_cast<void*>(stbi_load_from_memory(bytes, int(size), &w, &h, &comp, 4)),
        stbi_image_free);
    out->decoder_peak = memory.peak;
    if (!pixels) {
        out->why = stbi_failure_reason() ? stbi_failure_reason() : "unknown";
        return memory.refused ? ImageDecodeStatus::over_memory_limit : ImageDecodeStatus::corrupt;
    }
    const size_t count = size_t(w) * size_t(h) * 4;
    out->width = w;
    out->height = h;
    out->rgba.resize(count);
    if (sixteen) {
        const stbi_us* p = static_cast<const stbi_us*>(pixels.get());
        for (size_t i = 0; i < count; ++i) out->rgba[i] = uint8_t((uint32_t(p[i]) * 255u + 32767u) / 65535u);
    } else {
        std::memcpy(out->rgba.data(), pixels.get(), count);
    }
    return ImageDecodeStatus::ok;
}

}  // namespace rtpbr_gltf_detail
