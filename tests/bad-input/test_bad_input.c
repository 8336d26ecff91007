/* Bad-input suite (issue 10): every malformed, hostile or oversized input gets a specific
 * rtpbr_gltf_result and a message naming the problem; nothing crashes and nothing leaks
 * (the suite runs under ASan+UBSan in CI; a counting allocator checks the scene's own
 * memory here too). Inputs are generated at run time; the fuzzers' regression inputs are
 * run by load_bad_files.c. */
#define _DEFAULT_SOURCE
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

/* ---- a counting allocator: every scene allocation must be freed ---------- */
typedef struct counts {
    long live;
    long warnings;
} counts;

static void* count_alloc(size_t size, void* user) {
    ((counts*)user)->live++;
    return malloc(size);
}
static void count_free(void* p, void* user) {
    if (p) ((counts*)user)->live--;
    free(p);
}
static void count_log(rtpbr_gltf_log_level level, const char* message, void* user) {
    assert_non_null(message);
    if (level == RTPBR_GLTF_LOG_WARNING) ((counts*)user)->warnings++;
}

typedef struct loaded {
    rtpbr_gltf_result result;
    char message[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_scene* scene;
    counts counts;
} loaded;

static rtpbr_gltf_load_desc make_desc(loaded* out, const rtpbr_gltf_load_desc* base) {
    rtpbr_gltf_load_desc desc = {0};
    if (base) desc = *base;
    desc.allocator.alloc = count_alloc;
    desc.allocator.free = count_free;
    desc.allocator.user_data = &out->counts;
    desc.logger.func = count_log;
    desc.logger.user_data = &out->counts;
    desc.error_message = out->message;
    desc.error_message_size = sizeof out->message;
    return desc;
}

static void finish(loaded* l, const char* name) {
    if (l->result != RTPBR_GLTF_SUCCESS) {
        if (l->scene) fail_msg("%s: a scene returned with %s", name, rtpbr_gltf_result_string(l->result));
        if (!l->message[0]) fail_msg("%s: %s without a message", name, rtpbr_gltf_result_string(l->result));
        if (l->counts.live != 0) fail_msg("%s: %ld scene allocations not freed on failure", name, l->counts.live);
    }
}

/* `l` must stay where it is until release(): the scene's allocator points into it. */
static void load_path(loaded* l, const char* path, const rtpbr_gltf_load_desc* base) {
    memset(l, 0, sizeof *l);
    rtpbr_gltf_load_desc desc = make_desc(l, base);
    l->scene = (rtpbr_gltf_scene*)(uintptr_t)1; /* must be overwritten */
    l->result = rtpbr_gltf_load(path, &desc, &l->scene);
    finish(l, path);
}

static void load_memory(loaded* l, const void* data, size_t size, const rtpbr_gltf_load_desc* base) {
    memset(l, 0, sizeof *l);
    rtpbr_gltf_load_desc desc = make_desc(l, base);
    l->scene = (rtpbr_gltf_scene*)(uintptr_t)1;
    l->result = rtpbr_gltf_load_memory(data, size, &desc, &l->scene);
    finish(l, "memory");
}

static void release(loaded* l) {
    rtpbr_gltf_destroy(l->scene);
    l->scene = NULL;
    assert_int_equal(l->counts.live, 0);
}

/* Writes text as dir/name, loads it, expects want and a message containing needle. */
static void expect_text(const char* dir, const char* name, const char* text, const rtpbr_gltf_load_desc* desc,
                        rtpbr_gltf_result want, const char* needle) {
    ts_write(dir, name, text, strlen(text));
    char* path = ts_path(dir, name);
    loaded l;
    load_path(&l, path, desc);
    if (l.result != want)
        fail_msg("%s: got %s (%s), expected %s", name, rtpbr_gltf_result_string(l.result), l.message,
                 rtpbr_gltf_result_string(want));
    if (needle && !strstr(l.message, needle)) fail_msg("%s: message '%s' lacks '%s'", name, l.message, needle);
    release(&l);
    free(path);
}

static void expect_scene(const char* dir, const char* name, const ts_scene* s, rtpbr_gltf_result want,
                         const char* needle) {
    char* json = ts_scene_json(s);
    expect_text(dir, name, json, NULL, want, needle);
    free(json);
}

static ts_scene triangle(void) {
    ts_scene s = {.positions = kTri, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = -1};
    return s;
}

/* A GLB (header, JSON chunk, BIN chunk) of a one-triangle scene; malloc'd. */
static unsigned char* triangle_glb(size_t* size) {
    ts_scene s = triangle();
    ts_bin* bin = malloc(sizeof *bin);
    ts_scene_bin(&s, bin);
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
        "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":12}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
        bin->size);
    size_t json_len = (strlen(json) + 3) / 4 * 4, bin_len = (bin->size + 3) / 4 * 4;
    *size = 12 + 8 + json_len + 8 + bin_len;
    unsigned char* g = calloc(1, *size);
    uint32_t head[5] = {0x46546C67u, 2, (uint32_t)*size, (uint32_t)json_len, 0x4E4F534Au};
    memcpy(g, head, sizeof head); /* little-endian host (x86-64, aarch64) */
    memset(g + 20, ' ', json_len);
    memcpy(g + 20, json, strlen(json));
    uint32_t bin_head[2] = {(uint32_t)bin_len, 0x004E4942u};
    memcpy(g + 20 + json_len, bin_head, sizeof bin_head);
    memcpy(g + 28 + json_len, bin->bytes, bin->size);
    free(json);
    free(bin);
    return g;
}

/* ---- truncated files and wrong magic ---------------------------------------- */
static void test_truncated(void** state) {
    (void)state;
    size_t size = 0;
    unsigned char* glb = triangle_glb(&size);
    loaded whole;
    load_memory(&whole, glb, size, NULL);
    if (whole.result != RTPBR_GLTF_SUCCESS) fail_msg("control GLB: %s", whole.message);
    assert_int_equal(whole.scene->primitive_count, 1);
    release(&whole);
    /* Every proper prefix of the GLB: the header length no longer matches. */
    for (size_t cut = 0; cut < size; ++cut) {
        loaded l;
    load_memory(&l, glb, cut, NULL);
        rtpbr_gltf_result want = cut < 4 ? RTPBR_GLTF_ERROR_INVALID_JSON : RTPBR_GLTF_ERROR_INVALID_GLB;
        if (l.result != want)
            fail_msg("GLB cut at %zu of %zu: %s (%s)", cut, size, rtpbr_gltf_result_string(l.result), l.message);
        release(&l);
    }
    /* The same through a .glb path: short files are GLB errors from the first byte. */
    const char* dir = ts_dir("truncated");
    ts_write(dir, "cut.glb", glb, size / 2);
    char* path = ts_path(dir, "cut.glb");
    loaded l;
    load_path(&l, path, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(l.message, "exceeds"));
    release(&l);
    free(path);
    free(glb);

    /* JSON cut before its closing brace, at every 5th byte. */
    ts_scene s = triangle();
    char* json = ts_scene_json(&s);
    const size_t len = strlen(json);
    for (size_t cut = 0; cut + 1 < len; cut += 5) {
        loaded t;
    load_memory(&t, json, cut, NULL);
        if (t.result != RTPBR_GLTF_ERROR_INVALID_JSON)
            fail_msg("JSON cut at %zu: %s (%s)", cut, rtpbr_gltf_result_string(t.result), t.message);
        release(&t);
    }
    free(json);
}

static void test_wrong_magic(void** state) {
    (void)state;
    const char* dir = ts_dir("magic");
    size_t size = 0;
    unsigned char* glb = triangle_glb(&size);
    memcpy(glb, "gltf", 4); /* lower-case: not the GLB magic */
    ts_write(dir, "magic.glb", glb, size);
    char* path = ts_path(dir, "magic.glb");
    loaded l;
    load_path(&l, path, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(l.message, "magic"));
    release(&l);
    free(path);
    /* From memory, no magic means JSON, and binary garbage is not JSON. */
    load_memory(&l, glb, size, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_JSON);
    release(&l);
    /* Version 3 and a BIN chunk where JSON should be. */
    memcpy(glb, "glTF", 4);
    glb[4] = 3;
    load_memory(&l, glb, size, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(l.message, "version 3"));
    release(&l);
    glb[4] = 2;
    memcpy(glb + 16, "BIN", 4);
    load_memory(&l, glb, size, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_GLB);
    assert_non_null(strstr(l.message, "not JSON"));
    release(&l);
    free(glb);
    /* A PNG named .gltf. */
    size_t png_size = 0;
    const unsigned char px[4] = {255, 0, 0, 255};
    unsigned char* png = ts_png(px, 1, 1, &png_size);
    ts_write(dir, "image.gltf", png, png_size);
    path = ts_path(dir, "image.gltf");
    load_path(&l, path, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_JSON);
    release(&l);
    free(path);
    free(png);
}

/* ---- accessors and indices ---------------------------------------------------- */
static void test_accessors_out_of_range(void** state) {
    (void)state;
    const char* dir = ts_dir("accessors");
    ts_scene s = triangle();
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":7,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    /* Every index is resolved before tinygltf reads the file (issue 18). */
    expect_scene(dir, "view.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "bufferView 7");
    s.accessors = "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}";
    expect_scene(dir, "offset.gltf", &s, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor 0");
    s.accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                  "{\"bufferView\":1,\"componentType\":5125,\"count\":4000000000,\"type\":\"SCALAR\"}";
    char* json = ts_scene_json(&s);
    ts_write(dir, "count.gltf", json, strlen(json));
    char* path = ts_path(dir, "count.gltf");
    loaded l;
    load_path(&l, path, NULL);
    assert_true(l.result == RTPBR_GLTF_ERROR_INVALID_ACCESSOR || l.result == RTPBR_GLTF_ERROR_TOO_MANY_VERTICES);
    release(&l);
    free(path);
    free(json);
    /* Mesh attribute naming an accessor that does not exist. */
    s = triangle();
    s.meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":9},\"indices\":1}]}";
    expect_scene(dir, "attr.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, NULL);
    /* A bufferView past the end of its buffer. */
    s = triangle();
    s.extra = NULL;
    json = ts_scene_json(&s);
    char* at = strstr(json, "\"byteLength\":36}");
    assert_non_null(at);
    memcpy(at, "\"byteLength\":99}", 16);
    expect_text(dir, "viewlen.gltf", json, NULL, RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "exceeds buffer 0");
    free(json);
}

static void test_indices_past_vertices(void** state) {
    (void)state;
    const char* dir = ts_dir("indices");
    static const uint32_t past[] = {0, 1, 3};
    ts_scene s = triangle();
    s.indices = past;
    expect_scene(dir, "past.gltf", &s, RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE, "3");
    static const uint32_t huge[] = {0, 1, 0xFFFFFFFFu};
    s.indices = huge;
    expect_scene(dir, "huge.gltf", &s, RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE, NULL);
}

/* ---- NaN / Inf ---------------------------------------------------------------- */
static void test_nonfinite(void** state) {
    (void)state;
    const char* dir = ts_dir("nonfinite");
    float pos[9];
    memcpy(pos, kTri, sizeof pos);
    ts_scene s = triangle();
    s.positions = pos;
    pos[4] = NAN;
    expect_scene(dir, "nan.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "POSITION");
    pos[4] = INFINITY;
    expect_scene(dir, "inf.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "POSITION");
    pos[4] = -INFINITY;
    expect_scene(dir, "ninf.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "POSITION");
    /* Finite positions that overflow once transformed. */
    s = triangle();
    s.nodes = "{\"mesh\":0,\"scale\":[3e38,3e38,3e38],\"translation\":[3e38,0,0]}";
    expect_scene(dir, "overflow.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, NULL);
    /* JSON has no NaN literal; 1e39 is +Inf as a float, 1e400 is not even a double. Where
     * the schema bounds a factor to [0, 1], 1e39 is a schema error (issue 18). */
    s = triangle();
    s.material = 0;
    s.materials = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1e39,0,0,1]}}";
    expect_scene(dir, "colour.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "baseColorFactor");
    s.materials = "{\"emissiveFactor\":[1,-1e39,0]}";
    expect_scene(dir, "emission.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "emissiveFactor");
    /* Factors without an upper bound must not overflow the float they are stored in. */
    s.materials = "{\"extensions\":{\"KHR_materials_specular\":{\"specularColorFactor\":[1,1e39,0]}}}";
    expect_scene(dir, "specular.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "specularColorFactor");
    s.materials = "{\"extensions\":{\"KHR_materials_ior\":{\"ior\":1e39}}}";
    expect_scene(dir, "ior.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "ior");
    s.materials = "{\"emissiveFactor\":[1,1e400,0]}"; /* not even a double: the JSON parser says so */
    expect_scene(dir, "emission-double.gltf", &s, RTPBR_GLTF_ERROR_INVALID_JSON, "1e400");
    s.materials = "{\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
                  "{\"emissiveStrength\":1e39}}}";
    expect_scene(dir, "strength.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, NULL);
    s = triangle();
    s.nodes = "{\"mesh\":0,\"translation\":[0,1e39,0]}";
    expect_scene(dir, "translation.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, NULL);
    s.nodes = "{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}";
    s.scene_nodes = "0";
    s.extra = ",\"extensionsUsed\":[\"EXT_lights_area\"],\"extensions\":{\"EXT_lights_area\":{\"lights\":"
              "[{\"type\":\"rect\",\"color\":[1,1e39,1],\"intensity\":10,\"size\":1}]}}";
    expect_scene(dir, "lightcolour.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "light 0");
    s.extra = ",\"extensionsUsed\":[\"EXT_lights_area\"],\"extensions\":{\"EXT_lights_area\":{\"lights\":"
              "[{\"type\":\"rect\",\"color\":[1,1,1],\"intensity\":1e30,\"size\":1e20}]}}";
    expect_scene(dir, "lightarea.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "not representable");
    s.extra = ",\"extensionsUsed\":[\"EXT_lights_area\"],\"extensions\":{\"EXT_lights_area\":{\"lights\":"
              "[{\"type\":\"disk\",\"color\":[1e20,1,1],\"intensity\":1e20,\"size\":1}]}}";
    expect_scene(dir, "lightradiance.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "not representable");
    s.extra = ",\"extensionsUsed\":[\"EXT_lights_area\"],\"extensions\":{\"EXT_lights_area\":{\"lights\":"
              "[{\"type\":\"rect\",\"intensity\":1,\"size\":1e-30}]}}";
    expect_scene(dir, "lighttiny.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "not representable");
    s = triangle();
    s.nodes = "{\"mesh\":0},{\"camera\":0}";
    s.scene_nodes = "0,1";
    s.extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":1e39}}]";
    expect_scene(dir, "camera.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "camera 0");
}

/* ---- degenerate geometry and lights -------------------------------------------- */
static void test_degenerate(void** state) {
    (void)state;
    const char* dir = ts_dir("degenerate");
    /* Triangle 1 repeats a vertex, triangle 2 is collinear: both dropped, triangle 0 kept. */
    static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
    static const uint32_t idx[] = {0, 1, 2, 0, 0, 1, 0, 1, 3};
    ts_scene s = {.positions = pos, .vertex_count = 4, .indices = idx, .index_count = 9, .material = -1};
    char* json = ts_scene_json(&s);
    ts_write(dir, "degenerate.gltf", json, strlen(json));
    char* path = ts_path(dir, "degenerate.gltf");
    loaded l;
    load_path(&l, path, NULL);
    if (l.result != RTPBR_GLTF_SUCCESS) fail_msg("%s", l.message);
    assert_int_equal(l.scene->primitives[0].index_count, 3);
    assert_true(l.counts.warnings >= 1);
    release(&l);
    free(path);
    free(json);
    /* Only degenerate triangles: loads, with nothing to draw. */
    static const uint32_t none[] = {0, 0, 1, 0, 1, 3};
    s.indices = none;
    s.index_count = 6;
    json = ts_scene_json(&s);
    ts_write(dir, "empty.gltf", json, strlen(json));
    path = ts_path(dir, "empty.gltf");
    load_path(&l, path, NULL);
    if (l.result != RTPBR_GLTF_SUCCESS) fail_msg("%s", l.message);
    assert_int_equal(l.scene->total_index_count, 0);
    assert_int_equal(l.scene->light_count, 0);
    release(&l);
    free(path);
    free(json);
}

static void test_bad_lights(void** state) {
    (void)state;
    const char* dir = ts_dir("lights");
    /* An emissive triangle of zero area: dropped as geometry, so no light. */
    static const float flat[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    ts_scene s = {.positions = flat, .vertex_count = 3, .indices = kTriIdx, .index_count = 3, .material = 0,
                  .materials = "{\"emissiveFactor\":[1,1,1]}"};
    char* json = ts_scene_json(&s);
    ts_write(dir, "zeroarea.gltf", json, strlen(json));
    char* path = ts_path(dir, "zeroarea.gltf");
    loaded l;
    load_path(&l, path, NULL);
    if (l.result != RTPBR_GLTF_SUCCESS) fail_msg("%s", l.message);
    assert_int_equal(l.scene->light_count, 0);
    release(&l);
    free(path);
    free(json);
    /* A non-planar emissive quad (two triangles folded 90°): never one polygon; each
     * triangle becomes its own planar light, with its own normal and area 0.5. */
    static const float fold[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1};
    static const uint32_t fold_idx[] = {0, 1, 2, 0, 3, 1};
    s.positions = fold;
    s.vertex_count = 4;
    s.indices = fold_idx;
    s.index_count = 6;
    json = ts_scene_json(&s);
    ts_write(dir, "fold.gltf", json, strlen(json));
    path = ts_path(dir, "fold.gltf");
    load_path(&l, path, NULL);
    if (l.result != RTPBR_GLTF_SUCCESS) fail_msg("%s", l.message);
    assert_int_equal(l.scene->light_count, 2);
    for (uint32_t i = 0; i < 2; ++i) {
        const rtpbr_gltf_light* L = &l.scene->lights[i];
        assert_int_equal(L->vertex_count, 3);
        assert_float_equal(L->facts.area, 0.5f, 1e-6f);
        /* planar: every vertex on the plane through the centre with the light's normal */
        for (uint32_t v = 0; v < 3; ++v) {
            float d = 0;
            for (int k = 0; k < 3; ++k) d += (L->vertices[v][k] - L->facts.center[k]) * L->facts.normal[k];
            assert_float_equal(d, 0.0f, 1e-6f);
        }
    }
    release(&l);
    free(path);
    free(json);
    /* EXT_lights_area with zero size, and a node scale of zero. */
    ts_scene e = triangle();
    e.nodes = "{\"mesh\":0},{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}";
    e.scene_nodes = "0,1";
    e.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\",\"intensity\":10,\"size\":0}]}}";
    expect_scene(dir, "size0.gltf", &e, RTPBR_GLTF_ERROR_INVALID_JSON, "light 0");
    e.nodes = "{\"mesh\":0},{\"scale\":[0,0,0],\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}";
    e.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\",\"intensity\":10,\"size\":1}]}}";
    expect_scene(dir, "scale0.gltf", &e, RTPBR_GLTF_ERROR_NONFINITE, "degenerate transform");
    /* A light index past the list, and an unknown shape. */
    e.nodes = "{\"mesh\":0},{\"extensions\":{\"EXT_lights_area\":{\"light\":5}}}";
    expect_scene(dir, "index.gltf", &e, RTPBR_GLTF_ERROR_INVALID_REFERENCE, NULL);
    e.nodes = "{\"mesh\":0},{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}";
    e.extra = ",\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"sphere\",\"intensity\":10}]}}";
    expect_scene(dir, "shape.gltf", &e, RTPBR_GLTF_ERROR_UNSUPPORTED, "sphere");
}

/* More lights than RTPBR_GLTF_MAX_LIGHTS (65536): one EXT_lights_area light instanced
 * by 65537 nodes, JSON built at run time (about 3 MB). */
static void test_too_many_lights(void** state) {
    (void)state;
    const unsigned n = RTPBR_GLTF_MAX_LIGHTS + 1;
    const char* node = "{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}},";
    size_t cap = 512 + (size_t)n * (strlen(node) + 8);
    char* json = malloc(cap);
    assert_non_null(json);
    size_t at = (size_t)snprintf(json, cap,
                                 "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_lights_area\"],"
                                 "\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\","
                                 "\"intensity\":1,\"size\":1}]}},\"nodes\":[");
    for (unsigned i = 0; i < n; ++i) {
        memcpy(json + at, node, strlen(node));
        at += strlen(node);
    }
    json[at - 1] = ']';
    at += (size_t)snprintf(json + at, cap - at, ",\"scenes\":[{\"nodes\":[");
    for (unsigned i = 0; i < n; ++i) at += (size_t)snprintf(json + at, cap - at, "%u,", i);
    at--;
    at += (size_t)snprintf(json + at, cap - at, "]}],\"scene\":0}");
    assert_true(at < cap);
    loaded l;
    load_memory(&l, json, at, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS);
    assert_non_null(strstr(l.message, "65536"));
    release(&l);
    /* A host limit below it works the same way, and exactly at the limit loads. */
    rtpbr_gltf_load_desc desc = {0};
    desc.max_lights = n - 1;
    load_memory(&l, json, at, &desc);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS);
    release(&l);
    desc.max_lights = n; /* larger than the hard limit: clamped to it */
    load_memory(&l, json, at, &desc);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS);
    release(&l);
    free(json);
}

/* ---- KHR_lights_punctual (issue 30) ---------------------------------------------- */
/* The files in scenes/ hold the plain cases (each value out of its range, an unknown type, an
 * index past the lights); these are what tinygltf 2.7 would alter or drop before the loader
 * sees it, the checks on lights no node uses, and what only the node or desc can make bad. */
static void test_punctual_lights(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual");
    const char* point = "\"lights\":[{\"type\":\"point\"}]";
    static const struct {
        const char* node;   /* node 1's members after its extensions, or its whole extension object */
        const char* lights; /* extensions.KHR_lights_punctual's members (NULL: no such extension) */
        rtpbr_gltf_result want;
        const char* needle;
    } cases[] = {
        /* tinygltf's Value drops the null (3 numbers), casts 4294967296 to 0, drops a
         * non-object extension (no light at all) */
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\",\"color\":[1,null,1,1]}]", RTPBR_GLTF_ERROR_INVALID_JSON,
         "light 0 (/extensions/KHR_lights_punctual/lights/0/color): must be an array of 3 numbers"},
        {"{\"light\":4294967296}", NULL, RTPBR_GLTF_ERROR_INVALID_JSON,
         "node 1 (/nodes/1/extensions/KHR_lights_punctual/light): integer out of range"},
        {"{\"light\":-1}", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, "/nodes/1/extensions/KHR_lights_punctual/light"},
        {"{\"light\":\"0\"}", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, "must be an integer"},
        {"0", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, "(/nodes/1/extensions/KHR_lights_punctual): must be an object"},
        {"{}", NULL, RTPBR_GLTF_ERROR_INVALID_JSON, "/nodes/1/extensions/KHR_lights_punctual/light): required integer missing"},
        /* the lights array and its elements */
        {"{\"light\":0}", "\"lights\":[3]", RTPBR_GLTF_ERROR_INVALID_JSON, "light 0 (/extensions/KHR_lights_punctual/lights/0): must be an object"},
        {"{\"light\":0}", "\"lights\":[{\"color\":[1,1,1]}]", RTPBR_GLTF_ERROR_INVALID_JSON, "lights/0/type): required string missing"},
        {"{\"light\":0}", "\"lights\":[{\"type\":7}]", RTPBR_GLTF_ERROR_INVALID_JSON, "lights/0/type): must be a string"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"SPOT\"}]", RTPBR_GLTF_ERROR_UNSUPPORTED, "type 'SPOT' not supported"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"spot\",\"spot\":1}]", RTPBR_GLTF_ERROR_INVALID_JSON, "lights/0/spot): must be an object"},
        {"{\"light\":0}", "", RTPBR_GLTF_ERROR_INVALID_JSON, "/extensions/KHR_lights_punctual/lights): required array missing"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\",\"color\":[-1,0,0]}]", RTPBR_GLTF_ERROR_INVALID_JSON, "color): element out of [0, 1]"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\",\"color\":[0,2,0]}]", RTPBR_GLTF_ERROR_INVALID_JSON, "color): element out of [0, 1]"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\",\"color\":[0,\"1\",0]}]", RTPBR_GLTF_ERROR_INVALID_JSON, "color): element is not a number"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":-0.1}}]", RTPBR_GLTF_ERROR_INVALID_JSON,
         "spot/innerConeAngle): must be in [0, pi/2]"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":1}}]", RTPBR_GLTF_ERROR_INVALID_JSON,
         "innerConeAngle must be less than outerConeAngle"},
        /* a light no node uses is checked all the same; no lights at all */
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\"},{\"type\":\"point\",\"intensity\":-1}]", RTPBR_GLTF_ERROR_INVALID_JSON,
         "KHR_lights_punctual light 1 (/extensions/KHR_lights_punctual/lights/1/intensity): must be >= 0"},
        {"{\"light\":0}", "\"lights\":[]", RTPBR_GLTF_ERROR_INVALID_REFERENCE, "light 0 does not exist (0 lights)"},
        /* what the node makes of it */
        {"{\"light\":0}},\"scale\":[1,1,0],\"x\":{", "\"lights\":[{\"type\":\"spot\"}]", RTPBR_GLTF_ERROR_NONFINITE,
         "node 1: KHR_lights_punctual light 0: degenerate transform"},
        {"{\"light\":0}},\"scale\":[0,0,0],\"x\":{", "\"lights\":[{\"type\":\"directional\"}]", RTPBR_GLTF_ERROR_NONFINITE,
         "degenerate transform"},
        {"{\"light\":0}", "\"lights\":[{\"type\":\"point\",\"range\":1e-50}]", RTPBR_GLTF_ERROR_NONFINITE, "range 1e-50 underflows a float"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ts_scene s = triangle();
        char* nodes = ts_format("{\"mesh\":0},{\"extensions\":{\"KHR_lights_punctual\":%s}}", cases[i].node);
        char* extra = cases[i].lights ? ts_format(",\"extensions\":{\"KHR_lights_punctual\":{%s}}", cases[i].lights)
                                      : ts_format(",\"extensions\":{\"KHR_lights_punctual\":{%s}}", point);
        s.nodes = nodes;
        s.scene_nodes = "0,1";
        s.extra = extra;
        char name[32];
        snprintf(name, sizeof name, "case%zu.gltf", i);
        expect_scene(dir, name, &s, cases[i].want, cases[i].needle);
        free(nodes);
        free(extra);
    }
    /* No root extension at all. */
    ts_scene s = triangle();
    s.nodes = "{\"mesh\":0},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}";
    s.scene_nodes = "0,1";
    expect_scene(dir, "noroot.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "light 0 does not exist (0 lights)");
    /* A world position past a float: 3e38 + 2 × 3e38. */
    s.nodes = "{\"mesh\":0},{\"translation\":[3e38,0,0],\"scale\":[2,2,2],\"children\":[2]},"
              "{\"translation\":[3e38,0,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}";
    s.extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\"}]}}";
    expect_scene(dir, "far.gltf", &s, RTPBR_GLTF_ERROR_NONFINITE, "node 2: KHR_lights_punctual light 0: position or intensity");
    s.nodes = "{\"mesh\":0},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}";
    /* color × intensity × desc.area_light_radiance_scale past a float. */
    s.extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"intensity\":1e38}]}}";
    char* json = ts_scene_json(&s);
    rtpbr_gltf_load_desc desc = {0};
    expect_text(dir, "bright.gltf", json, &desc, RTPBR_GLTF_SUCCESS, NULL);
    desc.area_light_radiance_scale = 10.0f;
    expect_text(dir, "bright.gltf", json, &desc, RTPBR_GLTF_ERROR_NONFINITE, "not representable as a float");
    free(json);
    /* Loaded and destroyed through the scene's counting allocator: release() checks that
     * nothing is left, the punctual lights included. */
    s.extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\"}]}}";
    expect_scene(dir, "good.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);
}

/* ---- textures ------------------------------------------------------------------ */
static uint32_t crc32_png(const unsigned char* p, size_t n) {
    uint32_t crc = 0xFFFFFFFFu; /* ISO/IEC 15948 Annex D */
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static void be32(unsigned char* p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8),
    p[3] = (unsigned char)v;
}

/* A PNG whose IHDR claims width × height RGBA8, with a tiny IDAT: 57 bytes. */
static void png_claiming(unsigned char out[57], uint32_t width, uint32_t height) {
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(out, sig, 8);
    be32(out + 8, 13);
    memcpy(out + 12, "IHDR", 4);
    be32(out + 16, width);
    be32(out + 20, height);
    out[24] = 8, out[25] = 6, out[26] = 0, out[27] = 0, out[28] = 0;
    be32(out + 29, crc32_png(out + 12, 17));
    be32(out + 33, 0);
    memcpy(out + 37, "IDAT", 4);
    be32(out + 41, crc32_png(out + 37, 4));
    be32(out + 45, 0);
    memcpy(out + 49, "IEND", 4);
    be32(out + 53, crc32_png(out + 49, 4));
}

static char* textured_json(const char* image_uri) {
    static const float uv[] = {0, 0, 1, 0, 0, 1};
    ts_scene s = triangle();
    s.texcoords = uv;
    s.material = 0;
    s.materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}";
    char* extra = ts_format(",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"%s\"}]", image_uri);
    s.extra = extra;
    char* json = ts_scene_json(&s);
    free(extra);
    return json;
}

static void test_textures(void** state) {
    (void)state;
    const char* dir = ts_dir("textures");
    /* Missing texture file, and a texture naming a missing image. */
    char* json = textured_json("nothere.png");
    expect_text(dir, "missing.gltf", json, NULL, RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "nothere.png");
    free(json);
    static const float uv[] = {0, 0, 1, 0, 0, 1};
    ts_scene s = triangle();
    s.texcoords = uv;
    s.material = 0;
    s.materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}";
    s.extra = ",\"textures\":[{\"source\":3}]";
    expect_scene(dir, "source.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, "3");
    s.extra = NULL;
    expect_scene(dir, "texture.gltf", &s, RTPBR_GLTF_ERROR_INVALID_REFERENCE, NULL);

    /* Absurd sizes: refused from the header, before any pixel memory is reserved. */
    unsigned char png[57];
    png_claiming(png, 100000, 100000);
    ts_write(dir, "huge.png", png, sizeof png);
    json = textured_json("huge.png");
    expect_text(dir, "huge.gltf", json, NULL, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, "100000x100000");
    png_claiming(png, RTPBR_GLTF_MAX_TEXTURE_DIMENSION + 1, 1);
    ts_write(dir, "huge.png", png, sizeof png);
    expect_text(dir, "wide.gltf", json, NULL, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, "16385x1");
    /* Within the limits but no pixel data: a decode error. */
    png_claiming(png, 64, 64);
    ts_write(dir, "huge.png", png, sizeof png);
    expect_text(dir, "empty.gltf", json, NULL, RTPBR_GLTF_ERROR_IMAGE_DECODE, "image 0");
    /* A host limit below a real image. */
    size_t real_size = 0;
    unsigned char px[4 * 4 * 4];
    memset(px, 200, sizeof px);
    unsigned char* real = ts_png(px, 4, 4, &real_size);
    ts_write(dir, "huge.png", real, real_size);
    rtpbr_gltf_load_desc desc = {0};
    desc.max_texture_dimension = 3;
    expect_text(dir, "limit.gltf", json, &desc, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, "4x4");
    desc.max_texture_dimension = 4;
    expect_text(dir, "limit.gltf", json, &desc, RTPBR_GLTF_SUCCESS, NULL);
    free(real);
    /* Not an image at all. */
    ts_write(dir, "huge.png", "hello", 5);
    expect_text(dir, "text.gltf", json, NULL, RTPBR_GLTF_ERROR_IMAGE_DECODE, NULL);
    free(json);
}

/* ---- paths --------------------------------------------------------------------- */
static void test_paths(void** state) {
    (void)state;
    const char* dir = ts_dir("paths");
    char* missing = ts_path(dir, "missing.gltf");
    loaded l;
    load_path(&l, missing, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    assert_non_null(strstr(l.message, "missing.gltf"));
    release(&l);
    free(missing);
    char* through_file = ts_path(dir, "plain.gltf/scene.gltf"); /* a file used as a folder */
    ts_write(dir, "plain.gltf", "{}", 2);
    load_path(&l, through_file, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    release(&l);
    free(through_file);
    load_path(&l, dir, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_IO);
    assert_non_null(strstr(l.message, "directory"));
    release(&l);
    char* folder_glb = ts_path(dir, "folder.glb");
    mkdir(folder_glb, 0755);
    load_path(&l, folder_glb, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_IO);
    release(&l);
    free(folder_glb);
    load_path(&l, "", NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    release(&l);
    /* A FIFO must be refused without opening it (opening would block). */
    char* fifo = ts_path(dir, "fifo.gltf");
    unlink(fifo);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    load_path(&l, fifo, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_IO);
    assert_non_null(strstr(l.message, "regular"));
    release(&l);
    unlink(fifo);
    free(fifo);
    /* base_dir that does not exist. */
    rtpbr_gltf_load_desc desc = {0};
    desc.base_dir = "/nonexistent/rtpbr/base";
    ts_scene s = triangle();
    char* json = ts_scene_json(&s);
    load_memory(&l, json, strlen(json), &desc);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    assert_non_null(strstr(l.message, "/nonexistent/rtpbr/base"));
    release(&l);
    free(json);
}

/* ---- tinygltf safety: URIs stay under the scene folder, no shell expansion ---------- */
static void test_uri_confinement(void** state) {
    (void)state;
    const char* root = ts_dir("confine");
    char* dir = ts_path(root, "scene");
    mkdir(dir, 0755);
    ts_scene s = triangle();
    ts_bin bin;
    ts_scene_bin(&s, &bin);
    ts_write(root, "outside.bin", bin.bytes, bin.size); /* a real target one level up */
    ts_write(dir, "tri.bin", bin.bytes, bin.size);
    char* sub = ts_path(dir, "sub");
    mkdir(sub, 0755);
    ts_write(sub, "tri.bin", bin.bytes, bin.size);

    /* Controls: inside the folder and in a subfolder load. */
    s.buffer_uri = "tri.bin";
    expect_scene(dir, "ok.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);
    s.buffer_uri = "sub/tri.bin";
    expect_scene(dir, "ok-sub.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);
    s.buffer_uri = "sub%2Ftri.bin"; /* percent-encoded '/', decoded like tinygltf */
    char* json = ts_scene_json(&s);
    ts_write(dir, "pct.gltf", json, strlen(json));
    char* path = ts_path(dir, "pct.gltf");
    loaded l;
    load_path(&l, path, NULL);
    assert_true(l.result == RTPBR_GLTF_SUCCESS || l.result == RTPBR_GLTF_ERROR_FILE_NOT_FOUND);
    release(&l);
    free(path);
    free(json);

    /* Escapes. */
    const char* escapes[] = {"../outside.bin", "sub/../../outside.bin", "./../outside.bin", "%2e%2e/outside.bin",
                             "..%2Foutside.bin", "sub/..%2f..%2foutside.bin"};
    for (size_t i = 0; i < sizeof escapes / sizeof *escapes; ++i) {
        s.buffer_uri = escapes[i];
        expect_scene(dir, "escape.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "..");
    }
    char* abs = ts_path(root, "outside.bin");
    s.buffer_uri = abs;
    expect_scene(dir, "absolute.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "absolute");
    s.buffer_uri = "%2Fetc%2Fpasswd";
    expect_scene(dir, "absolute-pct.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "absolute");
    s.buffer_uri = "file:///etc/passwd";
    expect_scene(dir, "file-scheme.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, NULL);
    s.buffer_uri = "http://example.com/tri.bin";
    expect_scene(dir, "http.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, NULL);
    free(abs);

    /* Symbolic links leading out of the folder (to a file and to a folder). */
    char* link = ts_path(dir, "link.bin");
    char* target = ts_path(root, "outside.bin");
    unlink(link);
    assert_int_equal(symlink(target, link), 0);
    s.buffer_uri = "link.bin";
    expect_scene(dir, "symlink.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "outside");
    char* link_dir = ts_path(dir, "up");
    unlink(link_dir);
    assert_int_equal(symlink(root, link_dir), 0);
    s.buffer_uri = "up/outside.bin";
    expect_scene(dir, "symlink-dir.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "outside");
    /* A link that stays inside is fine. */
    char* inner = ts_path(dir, "inner.bin");
    unlink(inner);
    assert_int_equal(symlink("sub/tri.bin", inner), 0);
    s.buffer_uri = "inner.bin";
    expect_scene(dir, "symlink-inner.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);

    /* Shell syntax is never expanded or executed: each is refused, and the commands did
     * not run. A file literally named like the pattern would not be found either. */
    char* pwned = ts_path(root, "pwned");
    unlink(pwned);
    char* subst = ts_format("$(touch %s).bin", pwned);
    char* backtick = ts_format("`touch %s`.bin", pwned);
    char* semicolon = ts_format("tri.bin;touch %s", pwned);
    const char* shell[] = {subst, backtick, semicolon, "~/tri.bin", "~root/tri.bin", "$HOME/tri.bin",
                           "${HOME}/tri.bin", "*.bin", "tri.b?n", "tri.[b]in", "{tri,x}.bin", "tri.bin|cat"};
    for (size_t i = 0; i < sizeof shell / sizeof *shell; ++i) {
        s.buffer_uri = shell[i];
        char* name = ts_format("shell%zu.gltf", i);
        expect_scene(dir, name, &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");
        free(name);
        assert_false(ts_exists(pwned));
    }
    free(subst);
    free(backtick);
    free(semicolon);
    /* Control characters (a JSON-escaped newline) are refused as well. */
    s.buffer_uri = "tri\\n.bin";
    expect_scene(dir, "newline.gltf", &s, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");

    /* Image URIs go through the same confinement as buffers. */
    size_t png_size = 0;
    const unsigned char px[4] = {1, 2, 3, 255};
    unsigned char* png = ts_png(px, 1, 1, &png_size);
    ts_write(root, "outside.png", png, png_size);
    free(png);
    json = textured_json("../outside.png");
    expect_text(dir, "image-escape.gltf", json, NULL, RTPBR_GLTF_ERROR_URI_REJECTED, "..");
    free(json);
    json = textured_json("$(touch pwned).png");
    expect_text(dir, "image-shell.gltf", json, NULL, RTPBR_GLTF_ERROR_URI_REJECTED, "not allowed");
    free(json);

    /* From memory: no base_dir, no external files at all. */
    s.buffer_uri = "tri.bin";
    json = ts_scene_json(&s);
    load_memory(&l, json, strlen(json), NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_URI_REJECTED);
    release(&l);
    free(json);

    unlink(link);
    unlink(link_dir);
    unlink(inner);
    free(inner);
    free(link_dir);
    free(link);
    free(target);
    free(pwned);
    free(sub);
    free(dir);
}

/* ---- issue 18: what the second hostile corpus found --------------------------- */

/* Class 2: a value of the wrong type or out of the schema's range is INVALID_JSON (tinygltf
 * replaced it by the default, and stored 4294967296 in an int as 0). */
static void test_schema_types(void** state) {
    (void)state;
    const char* dir = ts_dir("schema");
    static const struct {
        const char* nodes;
        const char* materials;
        const char* extra;
        const char* pointer;
    } cases[] = {
        {"{\"mesh\":0,\"translation\":[\"NaN\",0,0]}", NULL, NULL, "/nodes/0/translation"},
        {"{\"mesh\":0,\"scale\":null}", NULL, NULL, "/nodes/0/scale"},
        {"{\"mesh\":0,\"rotation\":{\"x\":0}}", NULL, NULL, "/nodes/0/rotation"},
        {"{\"mesh\":0,\"rotation\":[0,0,0,2]}", NULL, NULL, "/nodes/0/rotation"},
        {"{\"mesh\":\"0\"}", NULL, NULL, "/nodes/0/mesh"},
        {"{\"mesh\":4294967296}", NULL, NULL, "/nodes/0/mesh"},
        {"{\"mesh\":0.5}", NULL, NULL, "/nodes/0/mesh"},
        {"{\"mesh\":-1}", NULL, NULL, "/nodes/0/mesh"},
        {"{\"mesh\":0,\"children\":[]}", NULL, NULL, "/nodes/0/children"},
        {NULL, "{\"doubleSided\":\"yes\"}", NULL, "/materials/0/doubleSided"},
        {NULL, "{\"pbrMetallicRoughness\":{\"roughnessFactor\":{}}}", NULL, "roughnessFactor"},
        {NULL, "{\"pbrMetallicRoughness\":{\"metallicFactor\":null}}", NULL, "metallicFactor"},
        {NULL, "{\"alphaMode\":7}", NULL, "alphaMode"},
        {NULL, "{\"normalTexture\":{\"index\":0,\"scale\":\"1\"}}", NULL, "normalTexture"},
        {NULL, NULL, ",\"extensionsRequired\":\"KHR_draco_mesh_compression\"", "/extensionsRequired"},
        {NULL, NULL, ",\"extensionsUsed\":[\"EXT_lights_area\"],\"extensionsRequired\":{\"0\":\"X\"}",
         "/extensionsRequired"},
        {NULL, NULL, ",\"scene\":\"0\"", "/scene"},
        {NULL, NULL, ",\"samplers\":[{\"wrapS\":\"REPEAT\"}]", "/samplers/0/wrapS"},
        {NULL, NULL, ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":\"wide\",\"znear\":1}}]",
         "/cameras/0/perspective/yfov"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ts_scene s = triangle();
        if (cases[i].nodes) s.nodes = cases[i].nodes;
        if (cases[i].materials) s.materials = cases[i].materials, s.material = 0;
        s.extra = cases[i].extra;
        char name[32];
        snprintf(name, sizeof name, "case%zu.gltf", i);
        expect_scene(dir, name, &s, RTPBR_GLTF_ERROR_INVALID_JSON, cases[i].pointer);
    }
    /* The same document with correct types loads (the checks are not over-eager). */
    ts_scene s = triangle();
    s.nodes = "{\"mesh\":0,\"translation\":[1,0,0],\"rotation\":[0,0,0,1],\"scale\":[1,1,1],\"children\":[1]},"
              "{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}";
    s.material = 0;
    s.materials = "{\"doubleSided\":true,\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,"
                  "\"pbrMetallicRoughness\":{\"roughnessFactor\":0.5,\"metallicFactor\":1}}";
    s.extra = ",\"scene\":0,\"samplers\":[{\"wrapS\":33071}]";
    expect_scene(dir, "good.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);
}

/* Class 2: glTF nodes form disjoint strict trees; the depth limit is the documented one. */
static void test_node_forest(void** state) {
    (void)state;
    const char* dir = ts_dir("forest");
    ts_scene s = triangle();
    s.nodes = "{\"mesh\":0,\"children\":[2]},{\"children\":[2]},{\"mesh\":0}";
    s.scene_nodes = "0,1";
    expect_scene(dir, "shared.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "child of both");
    s.nodes = "{\"mesh\":0,\"children\":[1]},{\"mesh\":0}";
    expect_scene(dir, "rootchild.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "root node 1");
    s.nodes = "{\"mesh\":0},{\"children\":[2]},{\"children\":[1]}";
    s.scene_nodes = "0";
    expect_scene(dir, "cycle.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "cycle");
    s.nodes = "{\"mesh\":0,\"children\":[0]}";
    expect_scene(dir, "self.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, NULL);
    /* A chain of RTPBR_GLTF_MAX_NODE_DEPTH nodes loads; one more is refused. */
    for (unsigned levels = RTPBR_GLTF_MAX_NODE_DEPTH; levels <= RTPBR_GLTF_MAX_NODE_DEPTH + 1; ++levels) {
        char* nodes = calloc(levels, 32);
        size_t at = 0;
        for (unsigned i = 0; i < levels; ++i)
            at += (size_t)(i + 1 < levels ? sprintf(nodes + at, "{\"children\":[%u]},", i + 1)
                                          : sprintf(nodes + at, "{\"mesh\":0}"));
        s.nodes = nodes;
        if (levels == RTPBR_GLTF_MAX_NODE_DEPTH) expect_scene(dir, "deep.gltf", &s, RTPBR_GLTF_SUCCESS, NULL);
        else expect_scene(dir, "deeper.gltf", &s, RTPBR_GLTF_ERROR_UNSUPPORTED, "deeper than 256");
        free(nodes);
    }
}

/* GLB of `json` followed by chunks given as (type, length) pairs (zero-filled payloads). */
static unsigned char* glb_with_chunks(const char* json, const uint32_t* chunks, size_t chunk_count, size_t* size) {
    size_t json_len = (strlen(json) + 3) / 4 * 4;
    *size = 20 + json_len;
    for (size_t i = 0; i < chunk_count; ++i) *size += 8 + chunks[2 * i + 1];
    unsigned char* g = calloc(1, *size);
    uint32_t head[5] = {0x46546C67u, 2, (uint32_t)*size, (uint32_t)json_len, 0x4E4F534Au};
    memcpy(g, head, sizeof head);
    memset(g + 20, ' ', json_len);
    memcpy(g + 20, json, strlen(json));
    size_t at = 20 + json_len;
    for (size_t i = 0; i < chunk_count; ++i) {
        uint32_t ch[2] = {chunks[2 * i + 1], chunks[2 * i]};
        memcpy(g + at, ch, sizeof ch);
        at += 8 + chunks[2 * i + 1];
    }
    return g;
}

/* Class 2: glTF 2.0 says readers ignore chunks of unknown types (tinygltf refused one in
 * second position); chunks must still fit in the file, and BIN may only come second. */
static void test_glb_unknown_chunks(void** state) {
    (void)state;
    ts_scene s = triangle(); /* data: URI buffer: no BIN chunk needed */
    char* json = ts_scene_json(&s);
    static const uint32_t unknown_second[] = {0x5A595858u, 16};
    static const uint32_t bin_then_unknown[] = {0x004E4942u, 8, 0x5A595858u, 4};
    static const uint32_t two_unknown[] = {0x5A595858u, 4, 0x12345678u, 0};
    const struct {
        const uint32_t* chunks;
        size_t count;
        rtpbr_gltf_result want;
    } cases[] = {
        {unknown_second, 1, RTPBR_GLTF_SUCCESS},
        {bin_then_unknown, 2, RTPBR_GLTF_SUCCESS},
        {two_unknown, 2, RTPBR_GLTF_SUCCESS},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        size_t size = 0;
        unsigned char* glb = glb_with_chunks(json, cases[i].chunks, cases[i].count, &size);
        loaded l;
        load_memory(&l, glb, size, NULL);
        if (l.result != cases[i].want)
            fail_msg("GLB case %zu: %s (%s)", i, rtpbr_gltf_result_string(l.result), l.message);
        if (l.result == RTPBR_GLTF_SUCCESS) assert_int_equal(l.scene->primitive_count, 1);
        release(&l);
        /* The last chunk's length one past the file end: refused. */
        uint32_t last_len;
        size_t last = size - 8 - cases[i].chunks[2 * cases[i].count - 1];
        memcpy(&last_len, glb + last, 4);
        last_len += 4;
        memcpy(glb + last, &last_len, 4);
        load_memory(&l, glb, size, NULL);
        if (l.result != RTPBR_GLTF_ERROR_INVALID_GLB)
            fail_msg("GLB case %zu, chunk past the end: %s (%s)", i, rtpbr_gltf_result_string(l.result), l.message);
        release(&l);
        free(glb);
    }
    static const uint32_t late_bin[] = {0x5A595858u, 4, 0x004E4942u, 4};
    size_t size = 0;
    unsigned char* glb = glb_with_chunks(json, late_bin, 2, &size);
    loaded l;
    load_memory(&l, glb, size, NULL);
    assert_int_equal(l.result, RTPBR_GLTF_ERROR_INVALID_GLB);
    release(&l);
    free(glb);
    free(json);
}

/* Class 3: only PNG and JPEG are decoded, and decoded texel memory is bounded by a budget
 * checked from the header before decoding. */
static void test_image_formats_and_budget(void** state) {
    (void)state;
    const char* dir = ts_dir("image-budget");
    char* json = textured_json("image.bin");
    /* A 17-byte PPM and an 18-byte TGA header that claim 8000 x 8000 pixels. */
    static const char ppm[] = "P6\n8000 8000\n255\n";
    ts_write(dir, "image.bin", ppm, strlen(ppm));
    expect_text(dir, "ppm.gltf", json, NULL, RTPBR_GLTF_ERROR_IMAGE_DECODE, "neither PNG nor JPEG");
    unsigned char tga[18] = {0, 0, 2};
    tga[12] = 8000 & 0xff, tga[13] = 8000 >> 8, tga[14] = 8000 & 0xff, tga[15] = 8000 >> 8, tga[16] = 32;
    ts_write(dir, "image.bin", tga, sizeof tga);
    expect_text(dir, "tga.gltf", json, NULL, RTPBR_GLTF_ERROR_IMAGE_DECODE, "neither PNG nor JPEG");
    /* A PNG whose header claims 9000 x 9000 (309 MiB decoded): over the default budget of
     * 256 MiB, refused from the header (a decode error would mean it was decoded). */
    unsigned char png[57];
    png_claiming(png, 9000, 9000);
    ts_write(dir, "image.bin", png, sizeof png);
    expect_text(dir, "bomb.gltf", json, NULL, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, "budget");
    /* The budget is the host's: a real 16 x 16 PNG (1 KiB decoded) over a 1000-byte budget. */
    unsigned char px[16 * 16 * 4];
    memset(px, 100, sizeof px);
    size_t real_size = 0;
    unsigned char* real = ts_png(px, 16, 16, &real_size);
    ts_write(dir, "image.bin", real, real_size);
    rtpbr_gltf_load_desc desc = {0};
    desc.texture_memory_budget = 1000;
    expect_text(dir, "budget.gltf", json, &desc, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, "budget");
    expect_text(dir, "default.gltf", json, NULL, RTPBR_GLTF_SUCCESS, NULL);
    free(real);
    free(json);
}

/* Class 4: a node scaled by 0 hides its primitives; they are skipped with a warning and the
 * rest of the scene loads (the engine refused a primitive without triangles). */
static void test_hidden_node(void** state) {
    (void)state;
    const char* dir = ts_dir("hidden");
    ts_scene s = triangle();
    s.nodes = "{\"mesh\":0,\"scale\":[0,0,0]},{\"mesh\":0}";
    s.scene_nodes = "0,1";
    char* json = ts_scene_json(&s);
    ts_write(dir, "hidden.gltf", json, strlen(json));
    char* path = ts_path(dir, "hidden.gltf");
    loaded l;
    load_path(&l, path, NULL);
    if (l.result != RTPBR_GLTF_SUCCESS) fail_msg("%s", l.message);
    assert_int_equal(l.scene->primitive_count, 1);
    assert_int_equal(l.scene->primitives[0].gltf_node, 1);
    assert_true(l.scene->primitives[0].index_count > 0);
    assert_true(l.counts.warnings >= 1);
    release(&l);
    free(path);
    free(json);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_truncated),
                cmocka_unit_test(test_wrong_magic),
                cmocka_unit_test(test_accessors_out_of_range),
                cmocka_unit_test(test_indices_past_vertices),
                cmocka_unit_test(test_nonfinite),
                cmocka_unit_test(test_degenerate),
                cmocka_unit_test(test_bad_lights),
                cmocka_unit_test(test_too_many_lights),
                cmocka_unit_test(test_punctual_lights),
                cmocka_unit_test(test_textures),
                cmocka_unit_test(test_paths),
                cmocka_unit_test(test_uri_confinement),
                cmocka_unit_test(test_schema_types),
                cmocka_unit_test(test_node_forest),
                cmocka_unit_test(test_glb_unknown_chunks),
                cmocka_unit_test(test_image_formats_and_budget),
                cmocka_unit_test(test_hidden_node))
