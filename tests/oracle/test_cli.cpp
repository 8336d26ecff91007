// The rtpbr-oracle command line and bad scenes. Bad scenes get a clear error, never a crash:
// through the loader + the oracle's validation (API) and through the command line (exit
// status 1, one message on stderr). Sample-range and region renders written as accumulator
// files and merged by --merge give exactly the full render.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>

using namespace rtpbr_oracle;

namespace {

const char *gOracleExe = nullptr;

std::string base64(const std::string &in) {
    static const char *t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8) | uint8_t(in[i + 2]);
        out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
    }
    if (i + 1 == in.size()) {
        uint32_t v = uint8_t(in[i]) << 16;
        out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == in.size()) {
        uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8);
        out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
    }
    return out;
}

struct GltfOptions {
    bool camera = true;
    bool emissive = true;
    bool nanVertex = false;
    std::string bufferUri; // empty: embedded data URI
    int bufferLengthDelta = 0;
    std::string cameraTranslation = "[0,0.5,3]";
    std::string floorNode = R"({"mesh":0})"; // e.g. scaled by 0 to hide it
};

// One quad (floor, material 0) and one emissive quad (light, material 1) above it.
std::string makeGltf(const GltfOptions &o) {
    float pos[8][3] = {{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                       {-0.3f, 1, -0.3f}, {0.3f, 1, -0.3f}, {0.3f, 1, 0.3f}, {-0.3f, 1, 0.3f}};
    if (o.nanVertex)
        pos[2][1] = std::numeric_limits<float>::quiet_NaN();
    uint32_t idx[12] = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3}; // the light quad emits downwards
    std::string data(reinterpret_cast<const char *>(pos), sizeof pos);
    data += std::string(reinterpret_cast<const char *>(idx), sizeof idx);
    std::ostringstream j;
    j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1)" << (o.camera ? ",2" : "") << R"(]}],)"
      << R"("nodes":[)" << o.floorNode << R"(,{"mesh":1})"
      << (o.camera ? R"(,{"camera":0,"translation":)" + o.cameraTranslation + "}" : "") << "],"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":2,"material":0}]},)"
      << R"({"primitives":[{"attributes":{"POSITION":1},"indices":3,"material":1}]}],)"
      << R"("materials":[{"pbrMetallicRoughness":{"metallicFactor":0}},{"emissiveFactor":)"
      << (o.emissive ? "[1,1,1]" : "[0,0,0]") << "}],"
      << (o.camera ? R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.01}}],)" : "")
      << R"("accessors":[)"
      << R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,0,-1],"max":[1,0,1]},)"
      << R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC3","min":[-0.3,1,-0.3],"max":[0.3,1,0.3]},)"
      << R"({"bufferView":2,"componentType":5125,"count":6,"type":"SCALAR"},)"
      << R"({"bufferView":2,"byteOffset":24,"componentType":5125,"count":6,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":48},)"
      << R"({"buffer":0,"byteOffset":96,"byteLength":48}],)"
      << R"("buffers":[{"byteLength":)" << int(data.size()) + o.bufferLengthDelta << R"(,"uri":")"
      << (o.bufferUri.empty() ? "data:application/octet-stream;base64," + base64(data) : o.bufferUri) << "\"}]}";
    return j.str();
}

std::string writeFile(const std::string &name, const std::string &text) {
    std::ofstream f(name, std::ios::binary);
    f << text;
    return name;
}

// Loads with the shared loader, then validates for the oracle. Returns a short tag of what
// failed: "load:<result>" or "oracle:<result>" or "ok".
std::string loadAndValidate(const std::string &path, std::string *message) {
    char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_load_desc desc = {};
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene *scene = nullptr;
    rtpbr_gltf_result lr = rtpbr_gltf_load(path.c_str(), &desc, &scene);
    if (lr != RTPBR_GLTF_SUCCESS) {
        *message = err;
        return std::string("load:") + rtpbr_gltf_result_string(lr);
    }
    RenderSettings s;
    Result r = validateScene(*scene, s, message);
    rtpbr_gltf_destroy(scene);
    return r == Result::Success ? "ok" : std::string("oracle:") + resultString(r);
}

// Runs rtpbr-oracle with the given arguments; returns its exit status and stderr.
int runOracleArgs(const std::string &args, std::string *err) {
    std::string cmd = std::string("'") + gOracleExe + "' " + args + " 2> oracle_test_bad.err";
    int status = std::system(cmd.c_str());
    std::ifstream f("oracle_test_bad.err");
    std::stringstream ss;
    ss << f.rdbuf();
    *err = ss.str();
    std::remove("oracle_test_bad.err");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int runOracle(const std::string &scene, std::string *err) {
    return runOracleArgs("'" + scene + "' -o oracle_test_bad.exr --width 8 --height 8 --spp 1 --quiet", err);
}

std::string readAll(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void expectFailure(const std::string &file, const char *expectedTag, const char *expectedWords) {
    std::string message;
    std::string tag = loadAndValidate(file, &message);
    if (tag != expectedTag)
        fail_msg("%s: got %s (%s), expected %s", file.c_str(), tag.c_str(), message.c_str(), expectedTag);
    assert_true(!message.empty());
    std::string err;
    int status = runOracle(file, &err);
    if (status != 1 || err.find(expectedWords) == std::string::npos)
        fail_msg("%s: rtpbr-oracle exit %d, stderr \"%s\" (expected status 1 and \"%s\")", file.c_str(), status,
                 err.c_str(), expectedWords);
}

void test_good_scene_renders(void **) {
    std::string f = writeFile("oracle_test_good.gltf", makeGltf({}));
    std::string message;
    assert_string_equal(loadAndValidate(f, &message).c_str(), "ok");
    std::string err;
    int status = runOracle(f, &err);
    if (status != 0)
        fail_msg("good scene: exit %d: %s", status, err.c_str());
    std::remove("oracle_test_bad.exr");
}

void test_cli_split_and_merge(void **) {
    std::string f = writeFile("oracle_test_split.gltf", makeGltf({}));
    std::string err;
    const std::string common = "'" + f + "' --width 12 --height 10 --spp 6 --seed 3 --quiet --max-depth 3";
    assert_int_equal(runOracleArgs(common + " -o oracle_test_whole.acc", &err), 0);
    assert_int_equal(runOracleArgs(common + " --threads 1 --sample-range 0:4 -o oracle_test_s0.acc", &err), 0);
    assert_int_equal(runOracleArgs(common + " --sample-range 4:6 --region 0:0:5:10 -o oracle_test_s1.acc", &err), 0);
    assert_int_equal(runOracleArgs(common + " --sample-range 4:6 --region 5:0:12:10 -o oracle_test_s2.acc", &err), 0);
    assert_int_equal(runOracleArgs("--merge oracle_test_s0.acc oracle_test_s1.acc oracle_test_s2.acc -o "
                                   "oracle_test_merged.acc --stderr-image oracle_test_se.exr",
                                   &err),
                     0);
    std::string whole = readAll("oracle_test_whole.acc"), merged = readAll("oracle_test_merged.acc");
    assert_true(whole.size() > 1000);
    // The sums of squares are doubles added in another order: compare everything before them.
    size_t exact = whole.size() - 3 * 12 * 10 * sizeof(double);
    assert_true(merged.size() == whole.size());
    assert_memory_equal(whole.data(), merged.data(), exact);
    assert_true(readAll("oracle_test_se.exr").size() > 0);
    // EXR + preview from the merged accumulator; a merge with a different seed is refused.
    assert_int_equal(runOracleArgs("--merge oracle_test_merged.acc -o oracle_test_merged.exr --preview "
                                   "oracle_test_merged.png",
                                   &err),
                     0);
    assert_true(readAll("oracle_test_merged.png").size() > 0);
    assert_int_equal(runOracleArgs(common + " --seed 4 -o oracle_test_other.acc", &err), 0);
    assert_int_equal(runOracleArgs("--merge oracle_test_whole.acc oracle_test_other.acc -o oracle_test_x.exr", &err),
                     1);
    assert_true(err.find("differ") != std::string::npos);
    // Usage errors.
    assert_int_equal(runOracleArgs("'" + f + "' -o x.exr --spp abc", &err), 2);
    assert_int_equal(runOracleArgs("'" + f + "' -o x.exr --region 3:3:2:2", &err), 1);
    assert_int_equal(runOracleArgs("'" + f + "' -o x.exr --sample-range 0:99 --spp 4", &err), 1);
    assert_true(err.find("sample range") != std::string::npos);
    for (const char *p : {"oracle_test_whole.acc", "oracle_test_s0.acc", "oracle_test_s1.acc", "oracle_test_s2.acc",
                          "oracle_test_merged.acc", "oracle_test_se.exr", "oracle_test_merged.exr",
                          "oracle_test_merged.png", "oracle_test_other.acc"})
        std::remove(p);
}

void test_missing_buffer(void **) {
    GltfOptions o;
    o.bufferUri = "oracle_test_missing.bin";
    expectFailure(writeFile("oracle_test_missing_buffer.gltf", makeGltf(o)), "load:RTPBR_GLTF_ERROR_FILE_NOT_FOUND",
                  "oracle_test_missing.bin");
}

void test_short_buffer(void **) {
    GltfOptions o;
    o.bufferLengthDelta = -100;
    std::string message;
    std::string tag = loadAndValidate(writeFile("oracle_test_short_buffer.gltf", makeGltf(o)), &message);
    assert_true(tag.rfind("load:", 0) == 0);
    assert_true(!message.empty());
}

void test_nan_vertex(void **) {
    GltfOptions o;
    o.nanVertex = true;
    expectFailure(writeFile("oracle_test_nan.gltf", makeGltf(o)), "load:RTPBR_GLTF_ERROR_NONFINITE", "NONFINITE");
}

void test_no_camera(void **) {
    GltfOptions o;
    o.camera = false;
    expectFailure(writeFile("oracle_test_no_camera.gltf", makeGltf(o)), "oracle:no camera", "no camera");
}

void test_no_lights(void **) {
    GltfOptions o;
    o.emissive = false;
    expectFailure(writeFile("oracle_test_no_lights.gltf", makeGltf(o)), "oracle:no lights", "no lights");
}

void test_not_gltf(void **) {
    std::string f = writeFile("oracle_test_garbage.gltf", "{ this is not json");
    std::string message;
    assert_true(loadAndValidate(f, &message).rfind("load:", 0) == 0);
    std::string err;
    assert_int_equal(runOracle(f, &err), 1);
    assert_true(err.find("rtpbr-oracle:") != std::string::npos);
    assert_int_equal(runOracle("oracle_test_does_not_exist.gltf", &err), 1);
    assert_true(err.find("FILE_NOT_FOUND") != std::string::npos);
}

// Issue 18, class 1: finite but absurd values reach Embree only within its range (a camera
// translated by 1e19 tripped Embree's ray.valid() assertion and aborted).
void test_absurd_extent(void **) {
    GltfOptions o;
    o.cameraTranslation = "[0,0.5,1e19]";
    expectFailure(writeFile("oracle_test_far_camera.gltf", makeGltf(o)), "oracle:invalid scene", "scene extent");
    o = GltfOptions();
    o.floorNode = R"({"mesh":0,"scale":[1e17,1,1e17]})";
    expectFailure(writeFile("oracle_test_huge_floor.gltf", makeGltf(o)), "oracle:invalid scene", "scene extent");
}

// Issue 18, class 4: a node scaled by 0 (hidden) leaves a primitive without triangles; the
// loader skips it with a warning and the scene still renders.
void test_hidden_node(void **) {
    GltfOptions o;
    o.floorNode = R"({"mesh":0,"scale":[0,0,0]})";
    std::string f = writeFile("oracle_test_hidden.gltf", makeGltf(o));
    std::string message;
    assert_string_equal(loadAndValidate(f, &message).c_str(), "ok");
    std::string err;
    int status = runOracle(f, &err);
    if (status != 0)
        fail_msg("hidden node: exit %d: %s", status, err.c_str());
    std::remove("oracle_test_bad.exr");
}

// Issue 18, class 1: --merge opens regular files only (a FIFO blocked it forever; the test
// would time out), and the memory need is stated and checked before allocating.
void test_merge_and_memory(void **) {
    std::remove("oracle_test.fifo");
    assert_int_equal(mkfifo("oracle_test.fifo", 0600), 0);
    std::string err;
    assert_int_equal(runOracleArgs("--merge oracle_test.fifo -o oracle_test_x.exr", &err), 1);
    std::remove("oracle_test.fifo");
    if (err.find("not a regular file") == std::string::npos)
        fail_msg("FIFO: stderr \"%s\"", err.c_str());
    std::string f = writeFile("oracle_test_memory.gltf", makeGltf({}));
    // 16384 x 16384 at 100 bytes per pixel: 25 GiB, over a 1 GiB limit, refused with a message.
    assert_int_equal(runOracleArgs("'" + f + "' -o oracle_test_x.exr --width 16384 --height 16384 --quiet "
                                   "--memory-limit 1024",
                                   &err),
                     1);
    if (err.find("needs 25.00 GiB") == std::string::npos)
        fail_msg("memory: stderr \"%s\"", err.c_str());
    // An accumulator file whose header claims more pixels than its size holds is refused.
    assert_int_equal(runOracleArgs("'" + f + "' --width 4 --height 4 --spp 1 --quiet -o oracle_test_ok.acc", &err), 0);
    std::string bytes = readAll("oracle_test_ok.acc");
    assert_true(bytes.size() > 16);
    uint32_t dims[2] = {65536, 4096};
    bytes.replace(8, sizeof dims, reinterpret_cast<const char *>(dims), sizeof dims);
    writeFile("oracle_test_lying.acc", bytes);
    assert_int_equal(runOracleArgs("--merge oracle_test_lying.acc -o oracle_test_x.exr", &err), 1);
    if (err.find("accumulator has") == std::string::npos)
        fail_msg("lying accumulator: stderr \"%s\"", err.c_str());
    for (const char *p : {"oracle_test_ok.acc", "oracle_test_lying.acc", "oracle_test_x.exr"})
        std::remove(p);
}

// Hand-built scenes (plain data, no loader) are validated by the oracle itself.
void test_hand_built_bad_scenes(void **) {
    std::string err;
    Accumulator acc;
    RenderSettings s;
    s.width = s.height = 4;
    {
        SceneBuilder b;
        uint32_t m = b.material(glm::vec3(0.5f), 0.0f, 0.5f);
        b.polygon({{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, m);
        b.light({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}}, glm::vec3(1.0f), true);
        b.camera(glm::vec3(0, 1, 3), glm::vec3(0.0f), 0.8f);
        b.floatArrays[0][4] = std::numeric_limits<float>::infinity();
        b.build();
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::InvalidScene);
        assert_true(err.find("non-finite") != std::string::npos);
        b.floatArrays[0][4] = 0.0f;
        b.indexArrays[0][1] = 7;
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::InvalidScene);
        assert_true(err.find("out of range") != std::string::npos);
        b.indexArrays[0][1] = 1;
        b.primitives[0].material = 3;
        b.build();
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::InvalidScene);
        b.primitives[0].material = 0;
        b.lights[0].radiance[1] = std::numeric_limits<float>::quiet_NaN();
        b.build();
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::InvalidScene);
        b.lights[0].radiance[1] = 1.0f;
        b.cameras[0].yfov = 0.0f;
        b.build();
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::InvalidScene);
        b.cameras[0].yfov = 0.8f;
        b.build();
        assert_true(render(b.scene, s, &acc, &err, nullptr) == Result::Success);
    }
    rtpbr_gltf_scene empty{};
    assert_true(render(empty, s, &acc, &err, nullptr) == Result::NoCamera);
}

} // namespace

int main(int argc, char **argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s PATH/TO/rtpbr-oracle\n", argv[0]);
        return 2;
    }
    gOracleExe = argv[1];
    RTPBR_RUN_TESTS(NULL, NULL,
                    cmocka_unit_test(test_good_scene_renders),
                    cmocka_unit_test(test_cli_split_and_merge),
                    cmocka_unit_test(test_missing_buffer),
                    cmocka_unit_test(test_short_buffer),
                    cmocka_unit_test(test_nan_vertex),
                    cmocka_unit_test(test_no_camera),
                    cmocka_unit_test(test_no_lights),
                    cmocka_unit_test(test_not_gltf),
                    cmocka_unit_test(test_hand_built_bad_scenes),
                    cmocka_unit_test(test_absurd_extent),
                    cmocka_unit_test(test_hidden_node),
                    cmocka_unit_test(test_merge_and_memory));
}
