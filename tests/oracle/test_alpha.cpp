// glTF alphaMode in the oracle (issue 28), on the scenes the engine's test_engine_alpha.c renders
// (tests/common/texture_scenes.h), loaded through the loader: MASK cuts out where
// baseColorFactor alpha x texture alpha < alphaCutoff (the white furnace box shows through),
// BLEND is stochastic opacity (a hit of alpha 0.5 is kept half the time: the mean is
// 0.5 quad + 0.5 background), and a MASK occluder with holes lets the shadow rays through.
#include "texture_scene_render.h"

using namespace rtpbr_oracle;

namespace {

constexpr uint32_t kN = 48;

// A scene written by `write`, rendered by the oracle at kN x kN (texture_scene_render.h).
std::vector<float> renderFile(const std::function<int(const char *)> &write, uint32_t spp, bool noShadows) {
    return renderWrittenScene(write, kN, spp, noShadows);
}

// MASK: a 4x4 red texture whose alpha is 255 and 128 in a checkerboard, baseColorFactor alpha
// 0.8, cutoff 0.5: coverage 0.8 (kept: red) or 0.40 (cut: the box's emission 1 behind it).
void test_mask_cutout(void **) {
    uint8_t t[4 * 4 * 4];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) {
            uint8_t *p = t + 4 * (4 * y + x);
            p[0] = 255, p[1] = 0, p[2] = 0, p[3] = (x + y) % 2 ? 128 : 255;
        }
    texture_scene s = texture_scene_quad(4, 4, t, 33071, 9728);
    s.alpha_mode = 1;
    s.base_alpha = 0.8f;
    s.alpha_cutoff = 0.5f;
    std::vector<float> rgb = renderFile([&](const char *path) { return texture_scene_write(&s, path); }, 64, false);
    int cut = 0, kept = 0;
    double cutError[3] = {0.0, 0.0, 0.0}, keptError[3] = {0.0, 0.0, 0.0};
    for (uint32_t py = 0; py < kN; py++)
        for (uint32_t px = 0; px < kN; px++) {
            double x, y, uv[2], du, dv;
            texture_scene_pixel_point(px, py, kN, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            int tx = texture_scene_texel(uv[0], s.wrap_s, 4, &du), ty = texture_scene_texel(uv[1], s.wrap_t, 4, &dv);
            if (du < 0.15 || dv < 0.15)
                continue;
            bool isCut = (tx + ty) % 2 != 0;
            const float *p = &rgb[3 * (py * kN + px)];
            const double expected[3] = {1.0, isCut ? 1.0 : 0.0, isCut ? 1.0 : 0.0};
            // each pixel within its noise (64 samples), each class's mean within 0.02
            for (int c = 0; c < 3; c++) {
                if (!(std::fabs(p[c] - expected[c]) < 0.15))
                    fail_msg("MASK: pixel (%u, %u) (texel %d, %d, %s) is (%g, %g, %g)", px, py, tx, ty,
                             isCut ? "cut" : "kept", double(p[0]), double(p[1]), double(p[2]));
                (isCut ? cutError : keptError)[c] += p[c] - expected[c];
            }
            isCut ? cut++ : kept++;
        }
    assert_true(cut > int(kN * kN / 4) && kept > int(kN * kN / 4));
    for (int c = 0; c < 3; c++)
        if (!(std::fabs(cutError[c] / cut) < 0.02 && std::fabs(keptError[c] / kept) < 0.02))
            fail_msg("MASK: channel %d off by %g (cut cells), %g (kept cells) on average", c, cutError[c] / cut,
                     keptError[c] / kept);
}

// BLEND: the red quad at alpha 0.5 over the box (emission 1): the image's mean is
// 0.5 (1, 0, 0) + 0.5 (1, 1, 1); each pixel within its noise.
void test_blend_half(void **) {
    texture_scene s = texture_scene_red_quad();
    s.alpha_mode = 2;
    s.base_alpha = 0.5f;
    std::vector<float> rgb = renderFile([&](const char *path) { return texture_scene_write(&s, path); }, 256, false);
    double mean[3] = {0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < kN * kN; i++)
        for (int c = 0; c < 3; c++) {
            mean[c] += rgb[3 * i + c] / double(kN * kN);
            const double expected = c == 0 ? 1.0 : 0.5;
            // a Bernoulli(0.5) choice between 0 and 1 per sample: standard error 0.5 / 16
            if (!(std::fabs(rgb[3 * i + c] - expected) < 0.15))
                fail_msg("BLEND: pixel %u channel %d is %g, expected %g", i, c, double(rgb[3 * i + c]), expected);
        }
    for (int c = 0; c < 3; c++)
        if (!(std::fabs(mean[c] - (c == 0 ? 1.0 : 0.5)) < 0.01))
            fail_msg("BLEND: mean channel %d is %g", c, mean[c]);
}

// Shadows: the occluder's texture is cut (alpha 0) in its left column and solid in its right
// one: the floor is lit below the left half and shadowed below the right; with alphaMode OPAQUE
// (the control) both halves are shadowed.
double floorMean(const std::vector<float> &rgb, double x0, double x1) {
    double sum = 0.0;
    int n = 0;
    for (uint32_t py = 0; py < kN; py++)
        for (uint32_t px = 0; px < kN; px++) {
            double x, y;
            texture_scene_pixel_point(px, py, kN, &x, &y);
            if (x < x0 || x > x1 || std::fabs(y) > 0.8)
                continue;
            sum += rgb[3 * (py * kN + px)];
            n++;
        }
    assert_true(n > 0);
    return sum / n;
}

void test_mask_shadow(void **) {
    static const uint8_t t[16] = {255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255};
    auto scene = [&](int opaque) {
        return [opaque](const char *path) { return alpha_shadow_scene_write(2, 2, t, opaque, path); };
    };
    double unshadowed = floorMean(renderFile(scene(0), 16, true), -0.9, -0.25);
    std::vector<float> masked = renderFile(scene(0), 16, false);
    double holes = floorMean(masked, -0.9, -0.25), solid = floorMean(masked, 0.25, 0.9);
    double opaque = floorMean(renderFile(scene(1), 16, false), -0.9, -0.25);
    std::fprintf(stderr, "floor: unshadowed %g, below the holes %g, below the solid half %g, below an opaque occluder %g\n",
                 unshadowed, holes, solid, opaque);
    assert_true(unshadowed > 0.01);
    assert_true(holes > 0.9 * unshadowed);
    assert_true(solid < 0.05 * unshadowed);
    assert_true(opaque < 0.05 * unshadowed);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_mask_cutout),
                cmocka_unit_test(test_blend_half),
                cmocka_unit_test(test_mask_shadow))
