// The oracle tests on the engine's texture and alphaMode scenes (tests/common/texture_scenes.h):
// a scene written to a temporary glTF file, loaded through the loader and rendered by the
// oracle, direct light only, as the engine's tests render it.
#ifndef RTPBR_TESTS_ORACLE_TEXTURE_SCENE_RENDER_H
#define RTPBR_TESTS_ORACLE_TEXTURE_SCENE_RENDER_H

#include "test_common.h"

#include "oracle.h"

#include <rtpbr/rtpbr_gltf.h>

#include "texture_scenes.h"

#include <unistd.h>

#include <functional>

// Writes a scene with `write` to a temporary file, loads it through the loader and renders it
// at n x n pixels and spp samples per pixel (direct light; shadows unless noShadows). Fails the
// test if the scene does not load or render.
inline std::vector<float> renderWrittenScene(const std::function<int(const char *)> &write, uint32_t n, uint32_t spp,
                                             bool noShadows) {
    char path[] = "/tmp/rtpbr-oracle-scene-XXXXXX.gltf";
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(write(path), 0);
    rtpbr_gltf_load_desc desc{};
    char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE] = "";
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene *scene = nullptr;
    rtpbr_gltf_result r = rtpbr_gltf_load(path, &desc, &scene);
    unlink(path);
    if (r != RTPBR_GLTF_SUCCESS)
        fail_msg("load: %s", err);
    rtpbr_oracle::RenderSettings st;
    st.width = st.height = n;
    st.spp = spp;
    st.directOnly = true;
    st.noShadows = noShadows;
    rtpbr_oracle::Accumulator acc;
    std::string error;
    if (rtpbr_oracle::render(*scene, st, &acc, &error, nullptr) != rtpbr_oracle::Result::Success)
        fail_msg("render: %s", error.c_str());
    std::vector<float> rgb;
    rtpbr_oracle::resolve(acc, &rgb, nullptr);
    rtpbr_gltf_destroy(scene);
    return rgb;
}

#endif
