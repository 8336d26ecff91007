// The image is a function of (scene, settings, seed, spp) only: the same for 1 and 2 threads,
// and renders split into sample ranges and image regions merge into exactly the full render
// (also through accumulator files); incompatible accumulators are refused.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

#include <cstring>

using namespace rtpbr_oracle;

namespace {

constexpr uint32_t kW = 20, kH = 14;

// A small closed box: diffuse walls, a rough metal floor, a rough plastic block, a ceiling light.
struct Box {
    SceneBuilder b;
    Box() {
        uint32_t wall = b.material(glm::vec3(0.7f, 0.6f, 0.5f), 0.0f, 0.8f);
        uint32_t metal = b.material(glm::vec3(0.9f, 0.7f, 0.4f), 1.0f, 0.4f);
        uint32_t plastic = b.material(glm::vec3(0.1f, 0.3f, 0.7f), 0.0f, 0.3f);
        b.polygon({{-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1}}, metal);  // floor, up
        b.polygon({{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}}, wall);      // ceiling, down
        b.polygon({{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}}, wall);  // back
        b.polygon({{-1, -1, 1}, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}}, wall);  // left
        b.polygon({{1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}}, wall);      // right
        b.polygon({{-0.3f, -0.4f, -0.2f}, {0.4f, -0.4f, -0.4f}, {0.5f, 0.3f, -0.4f}, {-0.2f, 0.3f, -0.2f}}, plastic);
        b.light({{-0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, 0.3f}, {-0.3f, 0.99f, 0.3f}},
                 glm::vec3(8.0f, 7.0f, 6.0f), false, int32_t(wall));
        b.camera(glm::vec3(0.0f, 0.0f, 3.0f), glm::vec3(0.0f, 0.0f, 0.0f), 0.8f);
        b.build();
    }
};

RenderSettings baseSettings() {
    RenderSettings s;
    s.width = kW;
    s.height = kH;
    s.spp = 8;
    s.seed = 42;
    s.maxDepth = 6;
    return s;
}

Accumulator renderOrFail(const rtpbr_gltf_scene &scene, const RenderSettings &s) {
    Accumulator acc;
    std::string err;
    Result r = render(scene, s, &acc, &err, nullptr);
    if (r != Result::Success)
        fail_msg("render: %s: %s", resultString(r), err.c_str());
    return acc;
}

void assertSameImage(const Accumulator &a, const Accumulator &b) {
    assert_int_equal(a.width, b.width);
    assert_int_equal(a.height, b.height);
    assert_true(a.samples == b.samples);
    assert_true(a.sum == b.sum);
    std::vector<float> ra, rb;
    resolve(a, &ra, nullptr);
    resolve(b, &rb, nullptr);
    assert_int_equal(ra.size(), b.samples.size() * 3);
    assert_memory_equal(ra.data(), rb.data(), ra.size() * sizeof(float));
}

void test_threads_do_not_change_the_image(void **) {
    Box box;
    RenderSettings s = baseSettings();
    s.threads = 1;
    Accumulator one = renderOrFail(box.b.scene, s);
    s.threads = 2;
    Accumulator two = renderOrFail(box.b.scene, s);
    assertSameImage(one, two);
    // The image is not trivially constant.
    std::vector<float> rgb;
    resolve(one, &rgb, nullptr);
    float lo = 1e30f, hi = 0.0f;
    for (float v : rgb) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    assert_true(hi > 0.05f && hi > 2.0f * lo);
    // A different seed does change it.
    s.seed = 43;
    Accumulator other = renderOrFail(box.b.scene, s);
    assert_false(other.sum == one.sum);
}

void test_sample_ranges_and_regions_merge_exactly(void **) {
    Box box;
    RenderSettings s = baseSettings();
    s.threads = 2;
    Accumulator whole = renderOrFail(box.b.scene, s);

    RenderSettings a = s, b = s;
    a.sampleBegin = 0;
    a.sampleEnd = 3;
    b.sampleBegin = 3;
    b.sampleEnd = 8;
    Accumulator merged = renderOrFail(box.b.scene, a);
    std::string err;
    assert_true(merge(&merged, renderOrFail(box.b.scene, b), &err) == Result::Success);
    assertSameImage(whole, merged);

    // Four regions, one of them split into sample ranges as well.
    Region regions[4] = {{0, 0, 7, 14}, {7, 0, 20, 5}, {7, 5, 13, 14}, {13, 5, 20, 14}};
    Accumulator tiled;
    for (int i = 0; i < 4; i++) {
        RenderSettings r = s;
        r.region = regions[i];
        r.threads = 1 + i % 2;
        if (i == 2) {
            r.sampleEnd = 5;
            Accumulator part = renderOrFail(box.b.scene, r);
            r.sampleBegin = 5;
            r.sampleEnd = 8;
            assert_true(merge(&part, renderOrFail(box.b.scene, r), &err) == Result::Success);
            assert_true(merge(&tiled, part, &err) == Result::Success);
            continue;
        }
        Accumulator part = renderOrFail(box.b.scene, r);
        if (i == 0)
            tiled = part;
        else
            assert_true(merge(&tiled, part, &err) == Result::Success);
    }
    assertSameImage(whole, tiled);

    // Through files.
    const char *pa = "oracle_test_part_a.acc", *pb = "oracle_test_part_b.acc";
    assert_true(writeAccumulator(pa, renderOrFail(box.b.scene, a), &err) == Result::Success);
    assert_true(writeAccumulator(pb, renderOrFail(box.b.scene, b), &err) == Result::Success);
    Accumulator fa, fb;
    assert_true(readAccumulator(pa, &fa, &err) == Result::Success);
    assert_true(readAccumulator(pb, &fb, &err) == Result::Success);
    assert_true(merge(&fa, fb, &err) == Result::Success);
    assertSameImage(whole, fa);
    assert_true(std::fabs(fa.sumSquares[7] - whole.sumSquares[7]) <= 1e-9 * std::fabs(whole.sumSquares[7]));
    std::remove(pa);
    std::remove(pb);
}

void test_incompatible_accumulators_are_refused(void **) {
    Box box;
    RenderSettings s = baseSettings();
    s.spp = 2;
    Accumulator a = renderOrFail(box.b.scene, s);
    std::string err;
    RenderSettings t = s;
    t.seed = 7;
    Accumulator b = renderOrFail(box.b.scene, t);
    assert_true(merge(&a, b, &err) == Result::Incompatible);
    assert_true(!err.empty());
    t = s;
    t.singleScatter = true;
    Accumulator c = renderOrFail(box.b.scene, t);
    assert_true(merge(&a, c, &err) == Result::Incompatible);
    t = s;
    t.width = kW + 1;
    Accumulator d = renderOrFail(box.b.scene, t);
    assert_true(merge(&a, d, &err) == Result::Incompatible);
    // Garbage files are refused with a message.
    FILE *f = fopen("oracle_test_garbage.acc", "wb");
    assert_non_null(f);
    fputs("not an accumulator", f);
    fclose(f);
    Accumulator g;
    assert_true(readAccumulator("oracle_test_garbage.acc", &g, &err) == Result::Io);
    assert_true(err.find("not an rtpbr-oracle accumulator") != std::string::npos);
    std::remove("oracle_test_garbage.acc");
    assert_true(readAccumulator("does/not/exist.acc", &g, &err) == Result::Io);
}

void test_bad_settings_are_refused(void **) {
    Box box;
    std::string err;
    Accumulator acc;
    RenderSettings s = baseSettings();
    s.sampleBegin = 5;
    s.sampleEnd = 5;
    assert_true(render(box.b.scene, s, &acc, &err, nullptr) == Result::InvalidArgument);
    s = baseSettings();
    s.sampleEnd = 9;
    assert_true(render(box.b.scene, s, &acc, &err, nullptr) == Result::InvalidArgument);
    s = baseSettings();
    s.region = {0, 0, kW + 1, kH};
    assert_true(render(box.b.scene, s, &acc, &err, nullptr) == Result::InvalidArgument);
    s = baseSettings();
    s.spp = 0;
    assert_true(render(box.b.scene, s, &acc, &err, nullptr) == Result::InvalidArgument);
    s = baseSettings();
    s.camera = 1;
    assert_true(render(box.b.scene, s, &acc, &err, nullptr) == Result::NoCamera);
    assert_true(!err.empty());
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_threads_do_not_change_the_image),
                cmocka_unit_test(test_sample_ranges_and_regions_merge_exactly),
                cmocka_unit_test(test_incompatible_accumulators_are_refused),
                cmocka_unit_test(test_bad_settings_are_refused))
