// Textures as glTF means them in the oracle (issue 28): sampler wrap modes, KHR_texture_transform
// with a texCoord override, and single-sided back faces, on the scenes the engine's
// test_engine_textures.c renders (tests/common/texture_scenes.h), loaded through the loader.
// Each checked pixel must be nearest (of the texture's colours) to the texel the closed form
// selects. The oracle samples level 0 (no mipmaps); its many samples per pixel filter it.
#include "texture_scene_render.h"

using namespace rtpbr_oracle;

namespace {

constexpr uint32_t kN = 48;

const uint8_t kPalette2x2[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 0, 255};

// Loads the scene through the loader (as a file) and renders it: a white furnace, direct light.
std::vector<float> renderScene(const texture_scene &s) {
    return renderWrittenScene([&](const char *path) { return texture_scene_write(&s, path); }, kN, 64, false);
}

// The texel whose linear colour is nearest to the pixel's.
int nearestTexel(const float *p, const uint8_t *texels, int count) {
    int best = -1;
    double bestD = 1e30;
    for (int i = 0; i < count; i++) {
        double d = 0.0;
        for (int c = 0; c < 3; c++) {
            double e = p[c] - texture_scene_srgb_to_linear(texels[4 * i + c]);
            d += e * e;
        }
        if (d < bestD)
            bestD = d, best = i;
    }
    return best;
}

void checkWrap(int wrapS, int wrapT, const char *what) {
    texture_scene s{};
    s.texture_width = s.texture_height = 2;
    s.rgba = kPalette2x2;
    s.wrap_s = wrapS;
    s.wrap_t = wrapT;
    s.mag_filter = s.min_filter = 9728;
    s.uv_min[0] = s.uv_min[1] = -1.0f;
    s.uv_max[0] = s.uv_max[1] = 2.0f;
    s.texcoord = -1;
    std::vector<float> rgb = renderScene(s);
    int checked = 0;
    for (uint32_t py = 0; py < kN; py++)
        for (uint32_t px = 0; px < kN; px++) {
            double x, y, uv[2], du, dv;
            texture_scene_pixel_point(px, py, kN, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            int tx = texture_scene_texel(uv[0], wrapS, 2, &du), ty = texture_scene_texel(uv[1], wrapT, 2, &dv);
            if (du < 0.15 || dv < 0.15)
                continue;
            int got = nearestTexel(&rgb[3 * (py * kN + px)], kPalette2x2, 4);
            if (got != ty * 2 + tx)
                fail_msg("%s: pixel (%u, %u) shows texel %d, expected %d", what, px, py, got, ty * 2 + tx);
            checked++;
        }
    assert_true(checked > int(kN * kN / 2));
}

void test_wrap_modes(void **) {
    checkWrap(10497, 10497, "repeat");
    checkWrap(33071, 33071, "clamp");
    checkWrap(33648, 33648, "mirror");
    checkWrap(33071, 33648, "clamp S, mirror T");
}

void test_texture_transform(void **) {
    uint8_t texels[64]; // 16 distinct colours
    texture_scene_distinct_texels(texels);
    texture_scene s = texture_scene_transformed_quad(texels);
    std::vector<float> rgb = renderScene(s);
    int checked = 0;
    for (uint32_t py = 0; py < kN; py++)
        for (uint32_t px = 0; px < kN; px++) {
            double x, y, uv[2], t[2], du, dv;
            texture_scene_pixel_point(px, py, kN, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            texture_scene_transform(&s, uv, t);
            int tx = texture_scene_texel(t[0], 10497, 4, &du), ty = texture_scene_texel(t[1], 10497, 4, &dv);
            if (du < 0.2 || dv < 0.2)
                continue;
            int got = nearestTexel(&rgb[3 * (py * kN + px)], texels, 16);
            if (got != ty * 4 + tx)
                fail_msg("transform: pixel (%u, %u) shows texel %d, expected %d", px, py, got, ty * 4 + tx);
            checked++;
        }
    assert_true(checked > int(kN * kN / 4));
}

// A single-sided quad seen from behind is not hit: the white box (radiance 1) shows through;
// double-sided, the red quad is seen.
void test_single_sided_back_face(void **) {
    texture_scene s = texture_scene_red_quad();
    s.facing_away = 1;
    std::vector<float> rgb = renderScene(s);
    for (uint32_t i = 0; i < kN * kN; i++) // radiance 1 plus what the black dielectric box reflects
        for (int c = 0; c < 3; c++)
            if (!(std::fabs(rgb[3 * i + c] - 1.0f) < 0.05f))
                fail_msg("pixel %u channel %d: %g, expected the box's 1", i, c, double(rgb[3 * i + c]));
    s.double_sided = 1;
    rgb = renderScene(s);
    const float *centre = &rgb[3 * (kN / 2 * kN + kN / 2)];
    if (!(centre[0] > 0.7f && centre[1] < 0.05f && centre[2] < 0.05f))
        fail_msg("double-sided quad from behind: centre (%g, %g, %g), expected red", double(centre[0]),
                 double(centre[1]), double(centre[2]));
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_wrap_modes),
                cmocka_unit_test(test_texture_transform),
                cmocka_unit_test(test_single_sided_back_face))
