/* Scene loader: bad input gets a specific result code and a message naming
 * the offending object, never a crash or a leak (run under ASan too). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include "test_main.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_scene_util.h"

static const float kTri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const uint32_t kTriIdx[] = {0, 1, 2};

/* Loads the JSON, expects `want` and a message containing `needle`. */
static void expect(const char* dir, const char* name, const char* json, const rtpbr_gltf_load_desc* desc,
                   rtpbr_gltf_result want, const char* needle) {
    char err[512];
    rtpbr_gltf_scene* scene = (rtpbr_gltf_scene*)(uintptr_t)1;
    rtpbr_gltf_result r = ts_load_text(dir, name, json, desc, &scene, err, sizeof err);
    if (r != want)
        fail_msg("%s: got %s (%s), expected %s", name, rtpbr_gltf_result_string(r), err,
                 rtpbr_gltf_result_string(want));
    assert_null(scene);
    if (needle && !strstr(err, needle)) fail_msg("%s: message '%s' lacks '%s'", name, err, needle);
}

static void expect_scene(const char* dir, const char* name, const ts_scene* s, rtpbr_gltf_result want,
                         const char* needle) {
    char* json = ts_scene_json(s);
    expect(dir, name, json, NULL, want, needle);
    free(json);
}

static void test_files(void** state) {
    (void)state;
    const char* dir = ts_dir("files");
    char err[256];
    rtpbr_gltf_load_desc desc = {0};
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene* scene = NULL;
    char* missing = ts_path(dir, "missing.gltf");
    assert_int_equal(rtpbr_gltf_load(missing, &desc, &scene), RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    assert_null(scene);
    assert_non_null(strstr(err, "missing.gltf"));
    assert_int_equal(rtpbr_gltf_load(dir, &desc, &scene), RTPBR_GLTF_ERROR_IO);
    assert_non_null(strstr(err, "directory"));
    assert_int_equal(rtpbr_gltf_load(NULL, &desc, &scene), RTPBR_GLTF_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gltf_load(missing, &desc, NULL), RTPBR_GLTF_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gltf_load_memory(NULL, 0, &desc, &scene), RTPBR_GLTF_ERROR_INVALID_ARGUMENT);
    rtpbr_gltf_load_desc half = desc;
    half.allocator.alloc = (void* (*)(size_t, void*))(uintptr_t)malloc;
    assert_int_equal(rtpbr_gltf_load(missing, &half, &scene), RTPBR_GLTF_ERROR_INVALID_ARGUMENT);
    free(missing);

    /* Empty and truncated JSON, wrong GLB magic, truncated GLB. */
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = -1};
    char* json = ts_scene_json(&s);
    json[strlen(json) / 2] = '\0';
    expect(dir, "truncated.gltf", json, NULL, RTPBR_GLTF_ERROR_INVALID_JSON, NULL);
    expect(dir, "empty.gltf", "", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, NULL);
    expect(dir, "notjson.gltf", "hello world", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, NULL);
    expect(dir, "array.gltf", "[1,2,3]", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, NULL);
    free(json);
    char deep[4096];
    memset(deep, '[', sizeof deep - 1);
    deep[sizeof deep - 1] = '\0';
    expect(dir, "deep.gltf", deep, NULL, RTPBR_GLTF_ERROR_INVALID_JSON, "nested");
    const unsigned char bad_magic[32] = {'g', 'l', 'T', 'X', 2, 0, 0, 0, 32, 0, 0, 0, 12, 0, 0, 0, 'J', 'S', 'O', 'N'};
    ts_write(dir, "magic.glb", bad_magic, sizeof bad_magic);
    char* magic = ts_path(dir, "magic.glb");
    assert_int_equal(rtpbr_gltf_load(magic, &desc, &scene), RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(err, "magic"));
    free(magic);
    const unsigned char short_glb[] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 200, 0, 0, 0, 8, 0, 0, 0, 'J', 'S', 'O', 'N'};
    ts_write(dir, "short.glb", short_glb, sizeof short_glb);
    char* p = ts_path(dir, "short.glb");
    assert_int_equal(rtpbr_gltf_load(p, &desc, &scene), RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_int_equal(rtpbr_gltf_load_memory(short_glb, sizeof short_glb, &desc, &scene),
                     RTPBR_GLTF_ERROR_INVALID_GLB);
    const unsigned char v1[] = {'g', 'l', 'T', 'F', 1, 0, 0, 0, 20, 0, 0, 0, 0, 0, 0, 0, 'J', 'S', 'O', 'N'};
    assert_int_equal(rtpbr_gltf_load_memory(v1, sizeof v1, &desc, &scene), RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(err, "version 1"));
    free(p);
}

static void test_accessors(void** state) {
    (void)state;
    const char* dir = ts_dir("accessors");
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = -1};
    /* count 4 × 12 bytes > bufferView 0 (36 bytes) */
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "count.gltf", &s, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor 0");
    /* byteOffset pushes the last element out of the view */
    s.accessors = "{\"bufferView\":0,\"byteOffset\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "offset.gltf", &s, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "exceeds bufferView 0");
    /* huge count must not overflow the bound check */
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":1537228672809129301,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    char* json = ts_scene_json(&s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "huge.gltf", json, NULL, &scene, err, sizeof err);
    assert_true(r == RTPBR_GLTF_ERROR_INVALID_ACCESSOR || r == RTPBR_GLTF_ERROR_TOO_MANY_VERTICES);
    assert_null(scene);
    free(json);
    /* wrong type and component type */
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC4\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "type.gltf", &s, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor 0");
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "ctype.gltf", &s, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor 1");
    /* dangling references */
    s.accessors = "{\"bufferView\":7,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "view.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "bufferView 7");
    s.accessors = NULL;
    s.meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":9},\"indices\":1}]}";
    expect_scene(dir, "acc.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "accessor 9");
    s.meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":3}]}";
    expect_scene(dir, "mat.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "material 3");
    s.meshes = NULL;
    s.nodes = "{\"mesh\":5}";
    expect_scene(dir, "mesh.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "mesh 5");
    s.nodes = "{\"mesh\":0,\"children\":[1]},{\"children\":[0]}";
    expect_scene(dir, "cycle.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "cycle");
    s.nodes = NULL;
    /* a bufferView past its buffer */
    s.accessors = NULL;
    s.extra = NULL;
    json = ts_scene_json(&s);
    char* at = strstr(json, "\"byteLength\":36}");
    assert_non_null(at);
    memcpy(at, "\"byteLength\":99}", 16);
    expect(dir, "bv.gltf", json, NULL, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "bufferView 0");
    free(json);
}

static void test_indices_and_values(void** state) {
    (void)state;
    const char* dir = ts_dir("values");
    const uint32_t bad_idx[] = {0, 1, 3};
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = bad_idx, .index_count = 3, .material = -1};
    expect_scene(dir, "index.gltf", &s, RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE, "index 3");
    const float nan_pos[] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    s.indices = kTriIdx;
    s.positions = nan_pos;
    expect_scene(dir, "nan.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "POSITION");
    const float inf_pos[] = {0, 0, 0, 1, INFINITY, 0, 0, 1, 0};
    s.positions = inf_pos;
    expect_scene(dir, "inf.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "not finite");
    s.positions = kTri;
    s.nodes = "{\"mesh\":0,\"scale\":[1e300,1,1]}";
    expect_scene(dir, "overflow.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "node 0");
    s.nodes = "{\"mesh\":0,\"rotation\":[0,0,0,0]}";
    expect_scene(dir, "quat.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "node 0");
    s.nodes = NULL;
    s.material = 0;
    s.materials = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1]}}";
    expect_scene(dir, "color.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "baseColorFactor");
    s.materials = "{\"extensions\":{\"KHR_materials_ior\":{\"ior\":0.5}}}";
    expect_scene(dir, "ior.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "material 0");
    s.materials = "{\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
                  "{\"emissiveStrength\":1e300}}}"; /* finite double, not a float */
    expect_scene(dir, "strength.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "emissiveStrength");
    s.materials = "{\"extras\":{\"rtpbr_disney\":{\"sheen\":\"much\"}}}";
    expect_scene(dir, "disney.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "sheen");
    s.materials = NULL;
    s.material = -1;
    s.extra = ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
              "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]";
    expect_scene(dir, "required.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "KHR_draco_mesh_compression");
    s.extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0,\"znear\":0.1}}]";
    s.nodes = "{\"mesh\":0,\"camera\":0}";
    expect_scene(dir, "camera.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "/cameras/0");
    s.extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0.1}}]";
    s.nodes = "{\"mesh\":0,\"camera\":4}";
    expect_scene(dir, "camref.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "camera 4");
    s.nodes = "{\"extensions\":{\"EXT_lights_area\":{\"light\":2}}}";
    s.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\"}]}}";
    expect_scene(dir, "arealight.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "light 2");
    s.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"sphere\"}]}}";
    s.nodes = "{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}";
    expect_scene(dir, "sphere.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "sphere");
    s.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"disk\",\"size\":-1}]}}";
    expect_scene(dir, "size.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "light 0");
}

static void test_uris(void** state) {
    (void)state;
    const char* dir = ts_dir("uris");
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = -1};
    ts_bin bin;
    ts_scene_bin(&s, &bin);
    /* Positive control: the buffer as a file next to the scene, and in a subfolder. */
    ts_write(dir, "tri.bin", bin.bytes, bin.size);
    s.buffer_uri = "tri.bin";
    char* json = ts_scene_json(&s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "ok.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s", err);
    assert_int_equal(scene->primitives[0].vertex_count, 3);
    rtpbr_gltf_destroy(scene);
    /* From memory the same file is refused without base_dir, found with it. */
    rtpbr_gltf_load_desc desc = {0};
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    assert_int_equal(rtpbr_gltf_load_memory(json, strlen(json), &desc, &scene), RTPBR_GLTF_ERROR_URI_REJECTED);
    desc.base_dir = dir;
    assert_int_equal(rtpbr_gltf_load_memory(json, strlen(json), &desc, &scene), RTPBR_GLTF_SUCCESS);
    rtpbr_gltf_destroy(scene);
    free(json);

    /* A real file one level up: '..' must be refused, not followed. */
    char* parent_file = ts_path(dir, "../secret.bin");
    FILE* f = fopen(parent_file, "wb");
    assert_non_null(f);
    fwrite(bin.bytes, 1, bin.size, f);
    fclose(f);
    s.buffer_uri = "../secret.bin";
    expect_scene(dir, "dotdot.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "..");
    s.buffer_uri = "sub/../../secret.bin";
    expect_scene(dir, "dotdot2.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "..");
    s.buffer_uri = "%2e%2e/secret.bin"; /* percent-encoded '..' */
    expect_scene(dir, "dotdot3.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "..");

    /* Shell expansion: must be refused and never executed. */
    char* pwned = ts_path(dir, "pwned");
    char uri_text[4200];
    snprintf(uri_text, sizeof uri_text, "$(touch %s).bin", pwned);
    s.buffer_uri = uri_text;
    expect_scene(dir, "shell.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");
    assert_false(ts_exists(pwned));
    snprintf(uri_text, sizeof uri_text, "`touch %s`.bin", pwned);
    s.buffer_uri = uri_text;
    expect_scene(dir, "backtick.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");
    assert_false(ts_exists(pwned));
    s.buffer_uri = "~/tri.bin";
    expect_scene(dir, "tilde.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");
    s.buffer_uri = "$HOME/tri.bin";
    expect_scene(dir, "var.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");

    /* Absolute paths and other schemes. */
    char* uri = ts_path(dir, "tri.bin"); /* exists, but absolute */
    s.buffer_uri = uri;
    expect_scene(dir, "absolute.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "absolute");
    free(uri);
    s.buffer_uri = "/etc/passwd";
    expect_scene(dir, "passwd.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "absolute");
    s.buffer_uri = "file:///etc/passwd";
    expect_scene(dir, "scheme.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "relative");

    /* A symbolic link inside the folder that points outside of it. */
    char* link = ts_path(dir, "link.bin");
    assert_int_equal(symlink(parent_file, link), 0);
    s.buffer_uri = "link.bin";
    expect_scene(dir, "symlink.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "outside");

    /* Missing external file, and a directory as a buffer. */
    s.buffer_uri = "nothere.bin";
    expect_scene(dir, "nothere.gltf", &s, RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "nothere.bin");
    char* sub = ts_path(dir, "adir");
    assert_int_equal(mkdir(sub, 0755), 0);
    s.buffer_uri = "adir";
    expect_scene(dir, "dirbuf.gltf", &s, RTPBR_GLTF_ERROR_IO, "adir");

    /* A short external buffer: byteLength mismatch. */
    ts_write(dir, "short.bin", bin.bytes, 8);
    s.buffer_uri = "short.bin";
    expect_scene(dir, "shortbin.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, NULL);

    unlink(parent_file);
    free(sub);
    free(link);
    free(pwned);
    free(parent_file);
}

static void test_limits(void** state) {
    (void)state;
    const char* dir = ts_dir("limits");
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = -1,
                  .nodes = "{\"mesh\":0},{\"mesh\":0}", .scene_nodes = "0,1"};
    rtpbr_gltf_load_desc desc = {0};
    desc.max_vertices = 5; /* two instances need 6 */
    char* json = ts_scene_json(&s);
    expect(dir, "vertices.gltf", json, &desc, RTPBR_GLTF_ERROR_TOO_MANY_VERTICES, "limit of 5");
    desc.max_vertices = 6;
    char err[256];
    rtpbr_gltf_scene* scene = NULL;
    assert_int_equal(ts_load_text(dir, "vertices.gltf", json, &desc, &scene, err, sizeof err), RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->primitive_count, 2);
    rtpbr_gltf_destroy(scene);
    free(json);
    /* Negative radiance scale is a caller error. */
    desc.area_light_radiance_scale = -1.0f;
    json = ts_scene_json(&s);
    expect(dir, "scale.gltf", json, &desc, RTPBR_GLTF_ERROR_INVALID_ARGUMENT, "area_light_radiance_scale");
    free(json);
}

/* ---- allocator and logger callbacks ---- */
typedef struct counting {
    size_t allocs, frees, errors, warnings;
} counting;

static void* count_alloc(size_t size, void* user) {
    ((counting*)user)->allocs++;
    return malloc(size);
}
static void count_free(void* p, void* user) {
    ((counting*)user)->frees++;
    free(p);
}
static void count_log(rtpbr_gltf_log_level level, const char* message, void* user) {
    assert_non_null(message);
    if (level == RTPBR_GLTF_LOG_ERROR) ((counting*)user)->errors++;
    if (level == RTPBR_GLTF_LOG_WARNING) ((counting*)user)->warnings++;
}

static void test_callbacks(void** state) {
    (void)state;
    const char* dir = ts_dir("callbacks");
    counting c = {0};
    rtpbr_gltf_load_desc desc = {0};
    desc.allocator.alloc = count_alloc;
    desc.allocator.free = count_free;
    desc.allocator.user_data = &c;
    desc.logger.func = count_log;
    desc.logger.user_data = &c;
    const uint32_t idx[] = {0, 1, 2, 0, 0, 1}; /* second triangle degenerate → warning */
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = idx, .index_count = 6, .material = 0,
                  .materials = "{\"emissiveFactor\":[1,1,1]}"};
    char* json = ts_scene_json(&s);
    char err[256];
    rtpbr_gltf_scene* scene = NULL;
    assert_int_equal(ts_load_text(dir, "cb.gltf", json, &desc, &scene, err, sizeof err), RTPBR_GLTF_SUCCESS);
    assert_string_equal(err, "");
    assert_true(c.allocs > 0);
    assert_true(c.warnings >= 1);
    assert_int_equal(scene->light_count, 1);
    rtpbr_gltf_destroy(scene);
    assert_int_equal(c.allocs, c.frees);
    free(json);

    char* missing = ts_path(dir, "missing.gltf");
    assert_int_equal(rtpbr_gltf_load(missing, &desc, &scene), RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    assert_int_equal(c.errors, 1);
    assert_int_equal(c.allocs, c.frees);
    free(missing);

    rtpbr_gltf_destroy(NULL);
    for (int r = 0; r < RTPBR_GLTF_RESULT_COUNT; ++r) {
        const char* name = rtpbr_gltf_result_string((rtpbr_gltf_result)r);
        assert_non_null(strstr(name, "RTPBR_GLTF_"));
        assert_null(strstr(name, "UNKNOWN"));
    }
    assert_non_null(strstr(rtpbr_gltf_result_string(RTPBR_GLTF_RESULT_COUNT), "UNKNOWN"));
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_files),
                cmocka_unit_test(test_accessors),
                cmocka_unit_test(test_indices_and_values),
                cmocka_unit_test(test_uris),
                cmocka_unit_test(test_limits),
                cmocka_unit_test(test_callbacks))
