/* Scene loader robustness: thousands of deterministic mutations of a valid
 * scene (JSON with data: URIs, and GLB) loaded from memory. Every load must
 * return a valid result code; a failure must leave no scene and a message; a
 * success must satisfy the documented invariants. Meant to run under
 * ASan/UBSan as well (a crash or leak fails the test). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include "test_main.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_scene_util.h"

enum { kMutations = 2500 };

static uint64_t rng_state;
static uint32_t rng(void) { /* PCG-style LCG step, high bits */
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(rng_state >> 33);
}

static void check_scene(const rtpbr_gltf_scene* s) {
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const rtpbr_gltf_primitive* p = &s->primitives[i];
        assert_true(p->index_count % 3 == 0);
        assert_true(p->material < s->material_count);
        for (uint32_t k = 0; k < p->index_count; ++k) assert_true(p->indices[k] < p->vertex_count);
        for (uint32_t k = 0; k < 3 * p->vertex_count; ++k) {
            assert_true(isfinite(p->positions[k]));
            assert_true(isfinite(p->normals[k]));
        }
    }
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const rtpbr_gltf_material* m = &s->materials[i];
        const int32_t tex[4] = {m->base_color_texture, m->metallic_roughness_texture, m->normal_texture,
                                m->emission_texture};
        for (int k = 0; k < 4; ++k) assert_true(tex[k] >= -1 && tex[k] < (int32_t)s->texture_count);
    }
    for (uint32_t i = 0; i < s->texture_count; ++i) {
        const rtpbr_gltf_texture* t = &s->textures[i];
        if (t->pixels) assert_true(t->width > 0 && t->height > 0);
    }
    for (uint32_t i = 0; i < s->light_count; ++i) {
        const rtpbr_gltf_light* l = &s->lights[i];
        assert_true(l->vertex_count >= 3 && l->vertex_count <= RTPBR_GLTF_MAX_POLYGON_VERTICES);
        assert_true(l->primitive >= -1 && l->primitive < (int32_t)s->primitive_count);
        for (int k = 0; k < 3; ++k) assert_true(isfinite(l->facts.normal[k]) && isfinite(l->radiance[k]));
    }
}

static void mutate(unsigned char* buf, size_t* size, size_t lo, size_t hi) {
    static const char* const inserts[] = {"-1", "1e40", "4294967295", "0", "[]", "{}", "\"", "..", "9999999"};
    int n = 1 + (int)(rng() % 3);
    for (int k = 0; k < n && hi > lo; ++k) {
        size_t at = lo + rng() % (hi - lo);
        switch (rng() % 6) {
        case 0: buf[at] = (unsigned char)rng(); break;
        case 1: buf[at] ^= (unsigned char)(1u << (rng() % 8)); break;
        case 2:
            if (buf[at] >= '0' && buf[at] <= '9') buf[at] = (unsigned char)('0' + rng() % 10);
            break;
        case 3: /* delete a short range */
            if (hi == *size) {
                size_t len = 1 + rng() % 8;
                if (at + len > *size) len = *size - at;
                memmove(buf + at, buf + at + len, *size - at - len);
                *size -= len;
                hi = *size;
            }
            break;
        case 4: /* insert a token */
            if (hi == *size) {
                const char* t = inserts[rng() % (sizeof inserts / sizeof *inserts)];
                size_t len = strlen(t);
                memmove(buf + at + len, buf + at, *size - at);
                memcpy(buf + at, t, len);
                *size += len;
                hi = *size;
            }
            break;
        default: /* truncate */
            if (hi == *size && rng() % 4 == 0) *size = at, hi = at;
            break;
        }
    }
}

/* The scene: a textured floor, an emissive quad, a camera, a rect area light. */
static const float kQuad[] = {-0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 0, -0.5f, -0.5f, 0, -0.5f};
static const uint32_t kQuadIdx[] = {0, 1, 2, 0, 2, 3};
static const float kUv[] = {0, 0, 1, 0, 1, 1, 0, 1};

static char* base_json(void) {
    const unsigned char px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    size_t png_size;
    unsigned char* png = ts_png(px, 2, 2, &png_size);
    char* uri = ts_data_uri("image/png", png, png_size);
    char* extra = ts_format(
        ",\"images\":[{\"uri\":\"%s\"}],\"textures\":[{\"source\":0}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}],"
        "\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\",\"size\":1},{\"type\":\"disk\"}]}}",
        uri);
    ts_scene s = {
        .positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6, .texcoords = kUv,
        .meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"indices\":1,\"material\":0}]},"
                  "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":1}]}",
        .materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}},\"normalTexture\":{\"index\":0}},"
                     "{\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
                     "{\"emissiveStrength\":3},\"KHR_materials_sheen\":{\"sheenColorFactor\":[1,0,0]}},"
                     "\"extras\":{\"rtpbr_disney\":{\"subsurface\":0.5}}}",
        .nodes = "{\"mesh\":0,\"scale\":[4,1,4],\"children\":[3]},{\"mesh\":1,\"translation\":[0,2,0],"
                 "\"rotation\":[1,0,0,0]},{\"camera\":0,\"translation\":[0,1,4]},"
                 "{\"extensions\":{\"EXT_lights_area\":{\"light\":0}},\"translation\":[0,3,0]},"
                 "{\"extensions\":{\"EXT_lights_area\":{\"light\":1}}}",
        .scene_nodes = "0,1,2,4",
        .extra = extra,
    };
    char* json = ts_scene_json(&s);
    free(extra);
    free(uri);
    free(png);
    return json;
}

static size_t run(const unsigned char* base, size_t base_size, size_t lo, size_t hi_from_end, int count,
                  int* successes) {
    unsigned char* buf = malloc(base_size + 64 * 16);
    size_t failures = 0;
    for (int i = 0; i < count; ++i) {
        size_t size = base_size;
        memcpy(buf, base, base_size);
        mutate(buf, &size, lo, base_size - hi_from_end);
        char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
        rtpbr_gltf_load_desc desc = {0};
        desc.error_message = err;
        desc.error_message_size = sizeof err;
        rtpbr_gltf_scene* scene = (rtpbr_gltf_scene*)(uintptr_t)1;
        rtpbr_gltf_result r = rtpbr_gltf_load_memory(buf, size, &desc, &scene);
        assert_true(r >= 0 && r < RTPBR_GLTF_RESULT_COUNT);
        if (r == RTPBR_GLTF_SUCCESS) {
            assert_non_null(scene);
            check_scene(scene);
            rtpbr_gltf_destroy(scene);
            ++*successes;
        } else {
            assert_null(scene);
            assert_true(err[0] != '\0');
            ++failures;
        }
    }
    free(buf);
    return failures;
}

static void test_mutated_json(void** state) {
    (void)state;
    rng_state = 12345;
    char* json = base_json();
    rtpbr_gltf_scene* scene = NULL;
    assert_int_equal(rtpbr_gltf_load_memory(json, strlen(json), NULL, &scene), RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->light_count, 3);
    rtpbr_gltf_destroy(scene);
    int ok = 0;
    size_t failed = run((const unsigned char*)json, strlen(json), 0, 0, kMutations, &ok);
    print_message("JSON: %d mutated scenes loaded, %zu rejected\n", ok, failed);
    assert_true(ok > 0 && failed > 0); /* both paths exercised */
    free(json);
}

static void test_mutated_glb(void** state) {
    (void)state;
    rng_state = 777;
    /* GLB with the JSON chunk and the geometry in the BIN chunk: mutate the
     * JSON chunk contents (lengths stay valid) and, separately, the header. */
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6, .texcoords = kUv};
    ts_bin bin;
    ts_scene_bin(&s, &bin);
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24},"
        "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":32}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"}],"
        "\"materials\":[{\"emissiveFactor\":[1,1,1]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"indices\":1,\"material\":0}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}",
        bin.size);
    size_t total;
    unsigned char* glb = ts_glb(json, bin.bytes, bin.size, &total);
    rtpbr_gltf_scene* scene = NULL;
    assert_int_equal(rtpbr_gltf_load_memory(glb, total, NULL, &scene), RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->light_count, 1);
    rtpbr_gltf_destroy(scene);
    int ok = 0;
    /* in-place mutations of the JSON chunk and the BIN payload only */
    size_t failed = run(glb, total, 20, 1, kMutations, &ok);
    failed += run(glb, total, 0, total - 28, kMutations / 5, &ok); /* header and chunk headers */
    print_message("GLB: %d mutated scenes loaded, %zu rejected\n", ok, failed);
    assert_true(ok > 0 && failed > 0);
    free(glb);
    free(json);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_mutated_json),
                cmocka_unit_test(test_mutated_glb))
