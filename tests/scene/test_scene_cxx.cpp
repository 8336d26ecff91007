// The public header from C++ (the oracle's language): compiles warning-free
// with -Wall -Wextra, links, loads a scene from memory.
#include <rtpbr/rtpbr_gltf.h>

#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <csetjmp>
extern "C" {  // this cmocka.h has no C++ guards
#include "test_main.h"
}

#include <cstring>
#include <string>

static void test_load_from_cxx(void**) {
    // One triangle at z = 0, counter-clockwise about +Z, positions as a
    // base64 data: URI (9 floats: 0,0,0  1,0,0  0,1,0).
    const std::string json =
        R"({"asset":{"version":"2.0"},)"
        R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
        R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
        R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    rtpbr_gltf_load_desc desc{};
    char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene* scene = nullptr;
    rtpbr_gltf_result r = rtpbr_gltf_load_memory(json.data(), json.size(), &desc, &scene);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->primitive_count, 1);
    assert_int_equal(scene->primitives[0].vertex_count, 3);
    assert_int_equal(scene->primitives[0].index_count, 3);
    assert_true(scene->primitives[0].positions[3] == 1.0f);
    assert_true(scene->primitives[0].normals[2] == 1.0f);  // generated flat normal
    rtpbr_gltf_destroy(scene);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_load_from_cxx))
