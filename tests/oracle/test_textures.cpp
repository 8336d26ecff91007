// Textured materials: a Lambertian plate with an sRGB base-colour texture (nearest, two
// texels) inside an enclosure of radiance 1 reflects radiance = its albedo, i.e.
// baseColorFactor x sRGB-decoded texel, on each half.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

using namespace rtpbr_oracle;

namespace {

void test_base_color_texture(void **) {
    SceneBuilder b;
    uint32_t plate = b.material(glm::vec3(0.8f), 0.0f, 1.0f);
    b.materials[plate].specular.specular_factor = 0.0f;
    b.materials[plate].base_color_texture = 0;
    b.polygon({{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}}, plate);
    // u = 0 at x = -1, u = 1 at x = +1.
    float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    std::copy(uv, uv + 8, b.floatArrays[b.floatArrays.size() - 2].begin());
    b.primitives[0].has_texcoords = true;
    const float s = 10.0f;
    glm::vec3 c[8] = {{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}, {-s, -s, s}, {s, -s, s}, {s, s, s}, {-s, s, s}};
    int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
    for (auto &f : faces)
        b.light({c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, glm::vec3(1.0f), true);
    b.camera(glm::vec3(0.0f, 3.0f, 0.01f), glm::vec3(0.0f), 0.5f);
    uint8_t texels[8] = {188, 188, 188, 255, 255, 255, 255, 255}; // sRGB 188 = linear 0.50289
    rtpbr_gltf_texture tex{};
    tex.width = 2;
    tex.height = 1;
    tex.pixels = texels;
    tex.srgb = true;
    tex.wrap_s = tex.wrap_t = RTPBR_GLTF_WRAP_CLAMP_TO_EDGE;
    tex.nearest = true;
    tex.gltf_texture = -1;
    b.build();
    b.scene.textures = &tex;
    b.scene.texture_count = 1;

    RenderSettings st;
    st.width = 8;
    st.height = 8;
    st.spp = 256;
    Accumulator acc;
    std::string err;
    if (render(b.scene, st, &acc, &err, nullptr) != Result::Success)
        fail_msg("render: %s", err.c_str());
    std::vector<float> rgb, se;
    resolve(acc, &rgb, &se);
    // The camera looks straight down with +x to the right: columns 0-3 see u < 0.5.
    const double dark = 0.8 * 0.50289, bright = 0.8 * 1.0;
    for (uint32_t y = 1; y < 7; y++)
        for (uint32_t x = 1; x < 7; x++) {
            if (x == 3 || x == 4)
                continue; // pixels straddling the texel edge
            size_t i = 3 * (y * 8 + x);
            double expected = x < 4 ? dark : bright;
            EXPECT_AGREE(rgb[i], se[i], expected, 0.0, 4.5, 2e-3);
        }
    // The alpha channel and the texture's G/B channels pass through untouched: still grey.
    assert_true(std::fabs(rgb[3 * (2 * 8 + 1)] - rgb[3 * (2 * 8 + 1) + 2]) < 1e-6f);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_base_color_texture))
