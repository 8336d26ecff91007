/* Memory of texture decoding on hostile input (issue 31): a PNG whose zlib stream inflates far
 * past what its header declares is refused while inflating, with a message, and the process
 * stays small; real images, with the slack encoders leave, still load. The PNGs are made here
 * with zlib (RFC 1950 streams, PNG chunks per ISO/IEC 15948). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_main.h"
#include <sys/resource.h>
#include <zlib.h>

#include "test_scene_util.h"

static const float kQuad[] = {-0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 0, -0.5f, -0.5f, 0, -0.5f};
static const uint32_t kQuadIdx[] = {0, 1, 2, 0, 2, 3};
static const float kQuadUv[] = {0, 0, 1, 0, 1, 1, 0, 1};

typedef struct bytes {
    unsigned char* p;
    size_t size, capacity;
} bytes;

static void append(bytes* b, const void* data, size_t n) {
    if (b->size + n > b->capacity) {
        b->capacity = (b->size + n) * 2;
        b->p = realloc(b->p, b->capacity);
        assert_non_null(b->p);
    }
    memcpy(b->p + b->size, data, n);
    b->size += n;
}

static void append_be32(bytes* b, uint32_t v) {
    const unsigned char p[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8),
                                (unsigned char)v};
    append(b, p, 4);
}

static void append_chunk(bytes* b, const char* type, const unsigned char* data, size_t n) {
    append_be32(b, (uint32_t)n);
    const size_t at = b->size;
    append(b, type, 4);
    if (n) append(b, data, n);
    append_be32(b, (uint32_t)crc32(0, b->p + at, (uInt)(4 + n)));
}

/* The zlib stream of `raw` followed by `zeros` zero bytes, fed in 1 MiB pieces so that a
 * 256 MiB stream costs this process no more than its compressed size. */
static bytes zlib_stream(const unsigned char* raw, size_t raw_size, size_t zeros) {
    bytes z = {0};
    z_stream s;
    memset(&s, 0, sizeof s);
    assert_int_equal(deflateInit(&s, 9), Z_OK);
    static unsigned char zero[1 << 20];
    unsigned char out[1 << 16];
    for (int part = 0; part < 2; ++part) {
        size_t left = part ? zeros : raw_size;
        const unsigned char* from = part ? zero : raw;
        do {
            const size_t n = left < sizeof zero ? left : sizeof zero;
            s.next_in = (Bytef*)from;
            s.avail_in = (uInt)n;
            const int flush = part && n == left ? Z_FINISH : Z_NO_FLUSH;
            do {
                s.next_out = out;
                s.avail_out = sizeof out;
                assert_int_not_equal(deflate(&s, flush), Z_STREAM_ERROR);
                append(&z, out, sizeof out - s.avail_out);
            } while (s.avail_out == 0);
            left -= n;
            if (!part) from += n;
        } while (left > 0);
    }
    deflateEnd(&s);
    return z;
}

/* A PNG of the given header whose single IDAT holds `z` followed by `trailing` bytes. */
static bytes png_file(uint32_t w, uint32_t h, int depth, int interlace, const bytes* z, const char* trailing) {
    bytes png = {0};
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    append(&png, signature, 8);
    const unsigned char ihdr[13] = {(unsigned char)(w >> 24), (unsigned char)(w >> 16), (unsigned char)(w >> 8),
                                    (unsigned char)w, (unsigned char)(h >> 24), (unsigned char)(h >> 16),
                                    (unsigned char)(h >> 8), (unsigned char)h, (unsigned char)depth,
                                    6 /* RGBA */, 0, 0, (unsigned char)interlace};
    append_chunk(&png, "IHDR", ihdr, sizeof ihdr);
    bytes idat = {0};
    append(&idat, z->p, z->size);
    if (trailing) append(&idat, trailing, strlen(trailing));
    append_chunk(&png, "IDAT", idat.p, idat.size);
    append_chunk(&png, "IEND", NULL, 0);
    free(idat.p);
    return png;
}

/* Loads a quad whose base colour is `png` (written as tex.png in dir). */
static rtpbr_gltf_result load_textured(const char* dir, const bytes* png, rtpbr_gltf_scene** scene, char* err,
                                       size_t err_size) {
    ts_write(dir, "tex.png", png->p, png->size);
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6,
                  .texcoords = kQuadUv, .material = 0,
                  .extra = ",\"images\":[{\"uri\":\"tex.png\"}],\"textures\":[{\"source\":0}]",
                  .materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}"};
    char* json = ts_scene_json(&s);
    rtpbr_gltf_result r = ts_load_text(dir, "t.gltf", json, NULL, scene, err, err_size);
    free(json);
    return r;
}

static double peak_rss_mib(void) {
    struct rusage u;
    assert_int_equal(getrusage(RUSAGE_SELF, &u), 0);
    return (double)u.ru_maxrss / 1024.0; /* kilobytes on Linux */
}

/* Runs first, so the process has not yet grown: a 1x1 RGBA8 PNG (5 bytes of rows) whose stream
 * inflates to 256 MiB of zeros. The shared libstb inflated all of it and loaded the image. */
static void test_inflation_bomb_refused(void** state) {
    (void)state;
    const unsigned char row[5] = {0, 10, 20, 30, 255};
    bytes z = zlib_stream(row, sizeof row, (size_t)256 << 20);
    bytes png = png_file(1, 1, 8, 0, &z, NULL);
    free(z.p);
    assert_true(png.size < (size_t)1 << 20);
    const double before = peak_rss_mib();
    char err[512] = "";
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = load_textured(ts_dir("memory-bomb"), &png, &scene, err, sizeof err);
    const double grown = peak_rss_mib() - before;
    free(png.p);
    print_message("peak RSS grew by %.1f MiB while loading; %s: %s\n", grown, rtpbr_gltf_result_string(r), err);
    if (scene) rtpbr_gltf_destroy(scene);
    assert_int_equal(r, RTPBR_GLTF_ERROR_IMAGE_DECODE);
    assert_null(scene);
    assert_non_null(strstr(err, "image 0 (1x1)"));
    assert_non_null(strstr(err, "expands past what its header declares"));
    /* The decoder stops near 1.5 MiB; the bound leaves room for sanitizer runtimes. */
    assert_true(grown < 64.0);
}

/* Slack real encoders leave: extra zero rows inflated after the image (stb_image accepts them,
 * libpng issue seen in the wild) and bytes after the end of the zlib stream. */
static void test_slack_still_loads(void** state) {
    (void)state;
    const unsigned char rows[2 * (1 + 8)] = {0, 255, 0, 0, 255, 0, 255, 0, 255,
                                             0, 0, 0, 255, 255, 9, 8, 7, 128};
    bytes z = zlib_stream(rows, sizeof rows, 64);
    bytes png = png_file(2, 2, 8, 0, &z, "trailing garbage");
    free(z.p);
    char err[512] = "";
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = load_textured(ts_dir("memory-slack"), &png, &scene, err, sizeof err);
    free(png.p);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->texture_count, 1);
    const unsigned char expected[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 8, 7, 128};
    assert_int_equal(scene->textures[0].width, 2);
    assert_memory_equal(scene->textures[0].pixels, expected, sizeof expected);
    rtpbr_gltf_destroy(scene);
}

/* The case the decoder needs most for: 16-bit RGBA, Adam7-interlaced, whose passes take more
 * rows than stb_image's first guess (its buffer doubles), large enough that the per-texel part
 * of the limit, not its constant, decides. Every texel is checked. */
static void test_interlaced_16bit_loads(void** state) {
    (void)state;
    enum { W = 509, H = 515 };
    /* Adam7 passes (ISO/IEC 15948 §8.2): start x, start y, step x, step y. */
    static const int pass[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                   {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
    bytes raw = {0};
    for (int p = 0; p < 7; ++p) {
        const int pw = (W - pass[p][0] + pass[p][2] - 1) / pass[p][2];
        const int ph = (H - pass[p][1] + pass[p][3] - 1) / pass[p][3];
        if (pw <= 0 || ph <= 0) continue;
        for (int j = 0; j < ph; ++j) {
            const unsigned char filter = 0;
            append(&raw, &filter, 1);
            for (int i = 0; i < pw; ++i) {
                const uint32_t x = (uint32_t)(pass[p][0] + i * pass[p][2]), y = (uint32_t)(pass[p][1] + j * pass[p][3]);
                for (uint32_t c = 0; c < 4; ++c) {
                    const uint32_t v = (x * 131u + y * 71u + c * 9000u) & 0xffffu;
                    const unsigned char be16[2] = {(unsigned char)(v >> 8), (unsigned char)v};
                    append(&raw, be16, 2);
                }
            }
        }
    }
    bytes z = zlib_stream(raw.p, raw.size, 0);
    free(raw.p);
    bytes png = png_file(W, H, 16, 1, &z, NULL);
    free(z.p);
    char err[512] = "";
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = load_textured(ts_dir("memory-interlaced"), &png, &scene, err, sizeof err);
    free(png.p);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    const rtpbr_gltf_texture* t = &scene->textures[0];
    assert_int_equal(t->width, W);
    assert_int_equal(t->height, H);
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                const uint32_t v = (x * 131u + y * 71u + c * 9000u) & 0xffffu;
                const unsigned got = t->pixels[((size_t)y * W + x) * 4 + c];
                if (got != (v * 255u + 32767u) / 65535u) fail_msg("texel %u,%u channel %u: %u", x, y, c, got);
            }
    rtpbr_gltf_destroy(scene);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_inflation_bomb_refused),
                cmocka_unit_test(test_slack_still_loads),
                cmocka_unit_test(test_interlaced_16bit_loads))
