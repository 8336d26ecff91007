/* Scene loader: KHR_lights_punctual (issue 30). Point, spot and directional lights on nodes,
 * in world space; the expected values are worked out by hand in the comments from the JSON
 * written here. Malformed lights are tests/bad-input's. */
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

#define EPS 1e-6
#define TS_PI 3.14159265358979323846

static void assert_near(double a, double b, double eps, const char* what) {
    if (!(fabs(a - b) <= eps)) fail_msg("%s: got %.9g, expected %.9g", what, a, b);
}
static void assert_vec(const float* v, double x, double y, double z, double eps, const char* what) {
    if (!(fabs(v[0] - x) <= eps && fabs(v[1] - y) <= eps && fabs(v[2] - z) <= eps))
        fail_msg("%s: got (%.9g, %.9g, %.9g), expected (%.9g, %.9g, %.9g)", what, v[0], v[1], v[2], x, y, z);
}

/* A document of lights only: `lights` is the KHR_lights_punctual lights array's contents,
 * `nodes` the nodes array's, `roots` the scene's nodes; `extra` more top-level members. */
static char* lights_json(const char* lights, const char* nodes, const char* roots, const char* extra) {
    return ts_format("{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"]%s,"
                     "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[%s]}},"
                     "\"nodes\":[%s],\"scenes\":[{\"nodes\":[%s]}],\"scene\":0}",
                     extra ? extra : "", lights, nodes, roots);
}

/* Nodes 0 .. count-1, node i referencing light i (count <= 8), and the scene's list of them. */
typedef struct light_nodes {
    char nodes[512], roots[32];
} light_nodes;
static light_nodes nodes_for_lights(int count) {
    light_nodes n = {{0}, {0}};
    for (int i = 0; i < count; ++i) {
        char node[80];
        snprintf(node, sizeof node, "%s{\"extensions\":{\"KHR_lights_punctual\":{\"light\":%d}}}", i ? "," : "", i);
        strcat(n.nodes, node);
        snprintf(node, sizeof node, "%s%d", i ? "," : "", i);
        strcat(n.roots, node);
    }
    return n;
}

typedef struct log_counts {
    int warnings, no_lights, range_ignored, radius_ignored, radius_not_number;
    int length_ignored, length_without_radius, length_not_number;
} log_counts;

static void on_log(rtpbr_gltf_log_level level, const char* message, void* user) {
    log_counts* c = user;
    if (level != RTPBR_GLTF_LOG_WARNING) return;
    c->warnings++;
    if (strstr(message, "no lights")) c->no_lights++;
    if (strstr(message, "range ignored")) c->range_ignored++;
    if (strstr(message, "radius ignored")) c->radius_ignored++;
    if (strstr(message, "extras/radius): not a number")) c->radius_not_number++;
    if (strstr(message, "length ignored on a")) c->length_ignored++;
    if (strstr(message, "length ignored without a radius")) c->length_without_radius++;
    if (strstr(message, "extras/length): not a number")) c->length_not_number++;
}

/* Loads text (as a file, then from memory) and returns the file's scene; fails the test when
 * either load fails or the two differ. */
static rtpbr_gltf_scene* load(const char* dir, const char* name, const char* text, const rtpbr_gltf_load_desc* base,
                              log_counts* counts) {
    rtpbr_gltf_load_desc desc = {0};
    if (base) desc = *base;
    log_counts unused;
    memset(counts ? counts : &unused, 0, sizeof unused);
    desc.logger.func = on_log;
    desc.logger.user_data = counts ? counts : &unused;
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, name, text, &desc, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s: %s", name, rtpbr_gltf_result_string(r), err);
    desc.logger.func = NULL;
    rtpbr_gltf_scene* again = NULL;
    r = rtpbr_gltf_load_memory(text, strlen(text), &desc, &again);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s from memory: %s", name, rtpbr_gltf_result_string(r));
    assert_int_equal(again->punctual_light_count, scene->punctual_light_count);
    if (scene->punctual_light_count)
        assert_memory_equal(again->punctual_lights, scene->punctual_lights,
                            scene->punctual_light_count * sizeof *scene->punctual_lights);
    rtpbr_gltf_destroy(again);
    return scene;
}

/* Every type with nothing but its type: the extension's defaults, the identity node's
 * origin and -Z. A spot light without "spot" gets the default cones (tinygltf alone would
 * refuse the file). */
static void test_defaults(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_defaults");
    light_nodes n = nodes_for_lights(4);
    char* json = lights_json("{\"type\":\"point\"},{\"type\":\"spot\"},{\"type\":\"directional\"},"
                             "{\"type\":\"spot\",\"spot\":{}}",
                             n.nodes, n.roots, NULL);
    log_counts counts;
    rtpbr_gltf_scene* scene = load(dir, "defaults.gltf", json, NULL, &counts);
    assert_int_equal(scene->punctual_light_count, 4);
    assert_int_equal(scene->light_count, 0);
    assert_int_equal(counts.no_lights, 0); /* punctual lights are lights */
    const rtpbr_gltf_punctual_type types[] = {RTPBR_GLTF_PUNCTUAL_POINT, RTPBR_GLTF_PUNCTUAL_SPOT,
                                              RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, RTPBR_GLTF_PUNCTUAL_SPOT};
    for (uint32_t i = 0; i < 4; ++i) {
        const rtpbr_gltf_punctual_light* l = &scene->punctual_lights[i];
        assert_int_equal(l->type, types[i]);
        assert_vec(l->position, 0, 0, 0, 0, "default position");
        assert_vec(l->direction, 0, 0, -1, 0, "default direction");
        assert_vec(l->intensity, 1, 1, 1, 0, "default intensity");
        assert_true(l->range == 0.0f);
        assert_true(l->radius == 0.0f); /* no extras: a true point */
        assert_true(l->length == 0.0f);
        assert_vec(l->axis, 1, 0, 0, 0, "default axis (the node's +X)");
        const int spot = l->type == RTPBR_GLTF_PUNCTUAL_SPOT;
        assert_true(l->inner_cone_angle == 0.0f);
        assert_true(l->outer_cone_angle == (spot ? (float)(TS_PI / 4.0) : 0.0f));
        /* the sun's 0.53 degrees (0.53 pi / 180 = 0.0092502 rad) on directional lights only */
        const int directional = l->type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL;
        assert_true(fabs(l->angular_diameter - (directional ? 0.53 * TS_PI / 180.0 : 0.0)) < 1e-6);
        assert_int_equal(l->gltf_node, (int32_t)i);
        assert_int_equal(l->gltf_light, (int32_t)i);
    }
    rtpbr_gltf_destroy(scene);
    free(json);

    /* Required by the file: supported. No light at all: the warning. */
    n = nodes_for_lights(1);
    json = lights_json("{\"type\":\"point\"}", n.nodes, n.roots, ",\"extensionsRequired\":[\"KHR_lights_punctual\"]");
    scene = load(dir, "required.gltf", json, NULL, NULL);
    assert_int_equal(scene->punctual_light_count, 1);
    rtpbr_gltf_destroy(scene);
    free(json);
    json = lights_json("{\"type\":\"point\"}", "{}", "0", NULL);
    scene = load(dir, "unused.gltf", json, NULL, &counts);
    assert_int_equal(scene->punctual_light_count, 0);
    assert_null(scene->punctual_lights);
    assert_int_equal(counts.no_lights, 1);
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* World frame: parent T(1,2,3) S(1,3,1), child T(1,1,0) R_x(45°) S(2,2,2) carrying a spot.
 *   position = T_p + S_p (1,1,0) = (1+1, 2+3, 3+0) = (2, 5, 3);
 *   local -Z under R_x(45°): (0, sin 45°, -cos 45°); S(2) and then S_p = (1,3,1):
 *   (0, 3·sin 45°, -cos 45°) ∝ (0, 3, -1), unit (0, 3, -1)/√10.
 * Scale changes neither intensity, range nor cones. A point light under a node that
 * flattens Z keeps its position; its (unused) direction is (0,0,-1). */
static void test_world_frame(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_frame");
    char* json = lights_json(
        "{\"type\":\"spot\",\"intensity\":7,\"range\":4,\"spot\":{\"innerConeAngle\":0.25,\"outerConeAngle\":0.5}},"
        "{\"type\":\"point\"}",
        "{\"translation\":[1,2,3],\"scale\":[1,3,1],\"children\":[1]},"
        "{\"translation\":[1,1,0],\"rotation\":[0.38268343236508977,0,0,0.92387953251128674],\"scale\":[2,2,2],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"translation\":[-4,0,1],\"scale\":[1,1,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}}",
        "0,2", NULL);
    rtpbr_gltf_scene* scene = load(dir, "frame.gltf", json, NULL, NULL);
    assert_int_equal(scene->punctual_light_count, 2);
    const rtpbr_gltf_punctual_light* s = &scene->punctual_lights[0];
    assert_int_equal(s->gltf_node, 1);
    assert_vec(s->position, 2, 5, 3, 1e-6, "child position");
    const double r10 = sqrt(10.0);
    assert_vec(s->direction, 0, 3 / r10, -1 / r10, 1e-6, "child direction");
    assert_near(sqrt(s->direction[0] * s->direction[0] + s->direction[1] * s->direction[1] +
                     s->direction[2] * s->direction[2]),
                1.0, 1e-6, "|direction|");
    assert_vec(s->intensity, 7, 7, 7, 0, "intensity unscaled by the node");
    assert_true(s->range == 4.0f);
    assert_true(s->inner_cone_angle == 0.25f && s->outer_cone_angle == 0.5f);
    const rtpbr_gltf_punctual_light* p = &scene->punctual_lights[1];
    assert_int_equal(p->gltf_node, 2);
    assert_vec(p->position, -4, 0, 1, 0, "flattened point position");
    assert_vec(p->direction, 0, 0, -1, 0, "flattened point direction");
    /* Punctual lights are not in the bounds (no geometry here: all zero). */
    for (int k = 0; k < 3; ++k) assert_true(scene->bounds_min[k] == 0.0f && scene->bounds_max[k] == 0.0f);
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* intensity = color × intensity × area_light_radiance_scale (0 = 1); range as given, 0 when
 * absent and for a directional light (ignored with a warning). */
static void test_intensity_and_range(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_intensity");
    const light_nodes n = nodes_for_lights(2);
    char* json = lights_json("{\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":100,\"range\":10},"
                             "{\"type\":\"directional\",\"color\":[0,1,0.75],\"intensity\":3,\"range\":5}",
                             n.nodes, n.roots, NULL);
    log_counts counts;
    rtpbr_gltf_scene* scene = load(dir, "intensity.gltf", json, NULL, &counts);
    assert_vec(scene->punctual_lights[0].intensity, 100, 50, 25, 0, "point intensity, scale 1");
    assert_true(scene->punctual_lights[0].range == 10.0f);
    assert_vec(scene->punctual_lights[1].intensity, 0, 3, 2.25, 0, "directional intensity, scale 1");
    assert_true(scene->punctual_lights[1].range == 0.0f);
    assert_int_equal(counts.range_ignored, 1);
    rtpbr_gltf_destroy(scene);
    rtpbr_gltf_load_desc desc = {0};
    desc.area_light_radiance_scale = 0.25f;
    scene = load(dir, "intensity.gltf", json, &desc, NULL);
    assert_vec(scene->punctual_lights[0].intensity, 25, 12.5, 6.25, 1e-5, "point intensity, scale 1/4");
    assert_vec(scene->punctual_lights[1].intensity, 0, 0.75, 0.5625, 1e-6, "directional intensity, scale 1/4");
    assert_true(scene->punctual_lights[0].range == 10.0f); /* the scale is not a unit of length */
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* Cones as written; the widest (pi/2, also as the schema's own 1.570796326794897) loads. */
static void test_spot_cones(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_cones");
    const light_nodes n = nodes_for_lights(4);
    char* json = lights_json("{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.6}},"
                             "{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":1.5707963267948966}},"
                             "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":1.5,\"outerConeAngle\":1.570796326794897}},"
                             "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.7}}",
                             n.nodes, n.roots, NULL);
    rtpbr_gltf_scene* scene = load(dir, "cones.gltf", json, NULL, NULL);
    const rtpbr_gltf_punctual_light* l = scene->punctual_lights;
    assert_true(l[0].inner_cone_angle == 0.2f && l[0].outer_cone_angle == 0.6f);
    assert_true(l[1].inner_cone_angle == 0.0f && l[1].outer_cone_angle == (float)(TS_PI / 2.0));
    assert_true(l[2].inner_cone_angle == 1.5f && l[2].outer_cone_angle == (float)(TS_PI / 2.0));
    assert_true(l[3].inner_cone_angle == 0.7f && l[3].outer_cone_angle == (float)(TS_PI / 4.0));
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* Two nodes referencing one light: two lights, in node traversal order (the scene lists
 * node 1 first; node 2 is node 0's child). */
static void test_shared_light(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_shared");
    char* json = lights_json("{\"type\":\"point\",\"intensity\":2},{\"type\":\"directional\"}",
                             "{\"translation\":[1,0,0],\"children\":[2]},"
                             "{\"translation\":[0,5,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                             "{\"translation\":[0,0,2],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}",
                             "1,0", NULL);
    rtpbr_gltf_scene* scene = load(dir, "shared.gltf", json, NULL, NULL);
    assert_int_equal(scene->punctual_light_count, 2);
    assert_int_equal(scene->punctual_lights[0].gltf_node, 1);
    assert_int_equal(scene->punctual_lights[1].gltf_node, 2);
    assert_int_equal(scene->punctual_lights[0].gltf_light, 0);
    assert_int_equal(scene->punctual_lights[1].gltf_light, 0);
    assert_vec(scene->punctual_lights[0].position, 0, 5, 0, 0, "first instance");
    assert_vec(scene->punctual_lights[1].position, 1, 0, 2, 0, "second instance");
    assert_vec(scene->punctual_lights[1].intensity, 2, 2, 2, 0, "shared intensity");
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* Area and punctual lights share the light limit. */
static void test_light_limit(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_limit");
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\",\"EXT_lights_area\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\"}]},"
        "\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\",\"size\":1}]}},"
        "\"nodes\":[{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],"
        "\"scenes\":[{\"nodes\":[0,1,2]}]}");
    rtpbr_gltf_load_desc desc = {0};
    desc.max_lights = 3;
    rtpbr_gltf_scene* scene = load(dir, "limit.gltf", json, &desc, NULL);
    assert_int_equal(scene->light_count, 1);
    assert_int_equal(scene->punctual_light_count, 2);
    rtpbr_gltf_destroy(scene);
    desc.max_lights = 2;
    char err[512];
    scene = NULL;
    assert_int_equal(ts_load_text(dir, "limit.gltf", json, &desc, &scene, err, sizeof err),
                     RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS);
    assert_null(scene);
    assert_non_null(strstr(err, "node 2: more than 2 lights"));
    free(json);
}

/* A GLB whose spot light has no "spot" object: tinygltf is given the document with an empty
 * one, in a rebuilt container that keeps the BIN chunk (the mesh, one unindexed triangle,
 * must load unchanged), or drops an unknown second chunk as before. */
static void test_glb_spot_defaults(void** state) {
    (void)state;
    static const float tri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],\"extensionsUsed\":[\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\",\"intensity\":3}]}},"
        "\"nodes\":[{\"mesh\":0,\"translation\":[0,0,-2]},{\"rotation\":[0,0.70710678118654752,0,0.70710678118654752],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],\"scenes\":[{\"nodes\":[0,1]}]}",
        sizeof tri, sizeof tri);
    size_t total;
    unsigned char* glb = ts_glb(json, tri, sizeof tri, &total);
    rtpbr_gltf_scene* scene = NULL;
    assert_int_equal(rtpbr_gltf_load_memory(glb, total, NULL, &scene), RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->primitive_count, 1);
    assert_int_equal(scene->primitives[0].index_count, 3);
    assert_near(scene->primitives[0].positions[3], 1.0, 0, "mesh x");
    assert_near(scene->primitives[0].positions[5], -2.0, 0, "mesh z");
    assert_int_equal(scene->punctual_light_count, 1);
    const rtpbr_gltf_punctual_light* l = scene->punctual_lights;
    assert_true(l->type == RTPBR_GLTF_PUNCTUAL_SPOT && l->outer_cone_angle == (float)(TS_PI / 4.0));
    /* R_y(90°) turns -Z into -X. */
    assert_vec(l->direction, -1, 0, 0, 1e-6, "R_y(90) direction");
    assert_vec(l->intensity, 3, 3, 3, 0, "intensity");
    rtpbr_gltf_destroy(scene);
    free(glb);

    /* The same JSON before a chunk of unknown type (and no BIN): still the light. */
    const light_nodes n = nodes_for_lights(1);
    char* lights_only = lights_json("{\"type\":\"spot\"}", n.nodes, n.roots, NULL);
    static const unsigned char unknown[8] = {'a', 'b', 'c', 'd', 'e', 'f', 'g', 'h'};
    const size_t jlen = (strlen(lights_only) + 3) / 4 * 4;
    total = 20 + jlen + 8 + sizeof unknown;
    glb = calloc(1, total);
    const uint32_t head[5] = {0x46546C67u, 2, (uint32_t)total, (uint32_t)jlen, 0x4E4F534Au};
    const uint32_t chunk[2] = {sizeof unknown, 0x4B4E5558u}; /* "XUNK" */
    memcpy(glb, head, sizeof head);
    memset(glb + 20, ' ', jlen);
    memcpy(glb + 20, lights_only, strlen(lights_only));
    memcpy(glb + 20 + jlen, chunk, sizeof chunk);
    memcpy(glb + 28 + jlen, unknown, sizeof unknown);
    assert_int_equal(rtpbr_gltf_load_memory(glb, total, NULL, &scene), RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->punctual_light_count, 1);
    assert_true(scene->punctual_lights[0].outer_cone_angle == (float)(TS_PI / 4.0));
    rtpbr_gltf_destroy(scene);
    free(glb);
    free(lights_only);
    free(json);
}

/* A light the loader refuses, on a node of its own: the result and words in the message. */
typedef struct refusal {
    const char* light;
    rtpbr_gltf_result result;
    const char* words;
} refusal;
static void expect_refused(const char* dir, const refusal* cases, size_t count) {
    const light_nodes n = nodes_for_lights(1);
    for (size_t i = 0; i < count; ++i) {
        char* json = lights_json(cases[i].light, n.nodes, n.roots, NULL);
        char err[512] = "";
        rtpbr_gltf_scene* scene = NULL;
        const rtpbr_gltf_result r = ts_load_text(dir, "bad.gltf", json, NULL, &scene, err, sizeof err);
        printf("  %s: %s: %s\n", cases[i].light, rtpbr_gltf_result_string(r), err);
        if (r != cases[i].result || !strstr(err, cases[i].words))
            fail_msg("%s: %s (%s), expected %s with \"%s\"", cases[i].light, rtpbr_gltf_result_string(r), err,
                     rtpbr_gltf_result_string(cases[i].result), cases[i].words);
        assert_null(scene);
        free(json);
    }
}

/* A point light's radius, from the light's "extras": {"radius": r}: the sphere's, in metres,
 * unchanged by the node's scale (node 0 scales by 3; node 8 carries light 0 too); integer
 * literals (which tinygltf would cast to int) read as written; 0 when absent. On a spot or a
 * directional light it is ignored, with a warning (one per light that has a non-zero one); a
 * radius that is not a number is ignored with a warning (extras are free-form). */
static void test_radius(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_radius");
    char* json = lights_json("{\"type\":\"point\",\"intensity\":5,\"extras\":{\"radius\":0.25,\"other\":\"x\"}},"
                             "{\"type\":\"point\"},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":3000000000}},"
                             "{\"type\":\"spot\",\"extras\":{\"radius\":0.5}},"
                             "{\"type\":\"directional\",\"extras\":{\"radius\":2}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":\"0.3\"}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0}},"
                             "{\"type\":\"spot\",\"extras\":{\"radius\":0}}",
                             "{\"scale\":[3,3,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":4}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":5}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":6}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":7}}},"
                             "{\"translation\":[0,1,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}",
                             "0,1,2,3,4,5,6,7,8", NULL);
    log_counts counts;
    rtpbr_gltf_scene* scene = load(dir, "radius.gltf", json, NULL, &counts);
    assert_int_equal(scene->punctual_light_count, 9);
    const rtpbr_gltf_punctual_light* l = scene->punctual_lights;
    const float want[9] = {0.25f, 0.0f, 3e9f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.25f};
    for (int i = 0; i < 9; ++i)
        if (l[i].radius != want[i]) fail_msg("light on node %d: radius %.9g, expected %.9g", i, l[i].radius, want[i]);
    assert_vec(l[0].intensity, 5, 5, 5, 0, "a sphere's intensity as written");
    assert_true(l[4].angular_diameter > 0.0f); /* the directional light stays the sun's disk */
    assert_int_equal(counts.radius_ignored, 2);
    assert_int_equal(counts.radius_not_number, 1);
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* A point light's radius is held to the rules of the extension's numbers: >= 0 (-0 is no
 * radius), finite as written, and its sphere's area pi r^2 and radiance I / (pi r^2) floats. */
static void test_radius_refused(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_radius_bad");
    static const refusal cases[] = {
        {"{\"type\":\"point\",\"extras\":{\"radius\":-0.5}}", RTPBR_GLTF_ERROR_INVALID_JSON,
         "light 0 (/extensions/KHR_lights_punctual/lights/0/extras/radius): must be >= 0"},
        /* JSON has no NaN; the nearest, a number beyond the double, is a syntax error */
        {"{\"type\":\"point\",\"extras\":{\"radius\":1e999}}", RTPBR_GLTF_ERROR_INVALID_JSON, "overflow"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":1e39}}", RTPBR_GLTF_ERROR_NONFINITE,
         "extras/radius): not representable as a float"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":1e30}}", RTPBR_GLTF_ERROR_NONFINITE,
         "node 0: KHR_lights_punctual light 0: radius 1e+30: the sphere's area"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":1e-50}}", RTPBR_GLTF_ERROR_NONFINITE, "radius 1e-50"},
        {"{\"type\":\"point\",\"intensity\":1e30,\"extras\":{\"radius\":1e-5}}", RTPBR_GLTF_ERROR_NONFINITE,
         "radiance (intensity / area)"},
    };
    expect_refused(dir, cases, sizeof cases / sizeof cases[0]);
    /* -0 is no radius; the largest that fits (pi r^2 < FLT_MAX) and a tiny one (I / (pi r^2)
     * fits) load. */
    const light_nodes three = nodes_for_lights(3);
    char* json = lights_json("{\"type\":\"point\",\"extras\":{\"radius\":-0.0}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":1e19}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":1e-19}}",
                             three.nodes, three.roots, NULL);
    rtpbr_gltf_scene* scene = load(dir, "edges.gltf", json, NULL, NULL);
    assert_true(scene->punctual_lights[0].radius == 0.0f && !signbit(scene->punctual_lights[0].radius));
    assert_true(scene->punctual_lights[1].radius == 1e19f);
    assert_true(scene->punctual_lights[2].radius == 1e-19f);
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* A point light's capsule, from the light's "extras": {"length": L} next to its radius: the
 * length in metres, unchanged by the node's scale, along the node's +X axis in world space,
 * normalised. Node 0 turns 90 degrees about +Z (quaternion (0, 0, sin 45, cos 45)) and scales
 * by 3: +X becomes +Y, the length stays 2. Node 5 turns 90 degrees about +Y and scales x by 2:
 * +X becomes -Z (rotation about Y: (cos, 0, -sin)). Node 6 scales x by 0: no +X, the axis is
 * (1, 0, 0). A length without a radius (light 2), on a spot (3) or not a number (4) is ignored
 * with a warning; 0 is no length (1). */
static void test_length(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_length");
    char* json = lights_json("{\"type\":\"point\",\"intensity\":5,\"extras\":{\"radius\":0.1,\"length\":2}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":0}},"
                             "{\"type\":\"point\",\"extras\":{\"length\":1}},"
                             "{\"type\":\"spot\",\"extras\":{\"radius\":0.1,\"length\":1}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0.2,\"length\":\"1\"}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":3}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":0.5}}",
                             "{\"scale\":[3,3,3],\"rotation\":[0,0,0.70710678118654752,0.70710678118654752],"
                             "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}},"
                             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":4}}},"
                             "{\"scale\":[2,1,1],\"rotation\":[0,0.70710678118654752,0,0.70710678118654752],"
                             "\"extensions\":{\"KHR_lights_punctual\":{\"light\":5}}},"
                             "{\"scale\":[0,1,1],\"extensions\":{\"KHR_lights_punctual\":{\"light\":6}}}",
                             "0,1,2,3,4,5,6", NULL);
    log_counts counts;
    rtpbr_gltf_scene* scene = load(dir, "length.gltf", json, NULL, &counts);
    assert_int_equal(scene->punctual_light_count, 7);
    const rtpbr_gltf_punctual_light* l = scene->punctual_lights;
    const float want_length[7] = {2.0f, 0.0f, 0.0f, 0.0f, 0.0f, 3.0f, 0.5f};
    const float want_radius[7] = {0.1f, 0.1f, 0.0f, 0.0f, 0.2f, 0.1f, 0.1f};
    for (int i = 0; i < 7; ++i) {
        if (l[i].length != want_length[i])
            fail_msg("light on node %d: length %.9g, expected %.9g", i, l[i].length, want_length[i]);
        if (l[i].radius != want_radius[i])
            fail_msg("light on node %d: radius %.9g, expected %.9g", i, l[i].radius, want_radius[i]);
    }
    assert_vec(l[0].axis, 0, 1, 0, EPS, "+X turned about +Z, scaled by 3");
    assert_vec(l[1].axis, 1, 0, 0, 0, "identity node");
    assert_vec(l[5].axis, 0, 0, -1, EPS, "+X turned about +Y, scaled by 2");
    assert_vec(l[6].axis, 1, 0, 0, 0, "a node scaled by 0 along x");
    assert_vec(l[0].intensity, 5, 5, 5, 0, "a capsule's intensity as written");
    assert_int_equal(counts.length_without_radius, 1);
    assert_int_equal(counts.length_ignored, 1);
    assert_int_equal(counts.radius_ignored, 1);
    assert_int_equal(counts.length_not_number, 1);
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* A point light's length is held to the rules of its radius: >= 0 (-0 is no length), finite as
 * written, and its capsule's area 2 pi r (2 r + L) and radiance 2 I / (pi r (2 r + L)) floats. */
static void test_length_refused(void** state) {
    (void)state;
    const char* dir = ts_dir("punctual_length_bad");
    static const refusal cases[] = {
        {"{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":-0.5}}", RTPBR_GLTF_ERROR_INVALID_JSON,
         "light 0 (/extensions/KHR_lights_punctual/lights/0/extras/length): must be >= 0"},
        /* refused even without a radius: the number is checked before it is found unused */
        {"{\"type\":\"point\",\"extras\":{\"length\":-1}}", RTPBR_GLTF_ERROR_INVALID_JSON, "length): must be >= 0"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":1e39}}", RTPBR_GLTF_ERROR_NONFINITE,
         "extras/length): not representable as a float"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":1e19,\"length\":1e19}}", RTPBR_GLTF_ERROR_NONFINITE,
         "node 0: KHR_lights_punctual light 0: radius 1e+19, length 1e+19: the capsule's area"},
        {"{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":1e-50}}", RTPBR_GLTF_ERROR_NONFINITE,
         "length 1e-50"},
        {"{\"type\":\"point\",\"intensity\":1e30,\"extras\":{\"radius\":1e-5,\"length\":1e-5}}",
         RTPBR_GLTF_ERROR_NONFINITE, "radiance (4 intensity / area)"},
    };
    expect_refused(dir, cases, sizeof cases / sizeof cases[0]);
    /* -0 is no length; the longest that fits with radius 1 (2 pi (2 + L) < FLT_MAX) and a tiny
     * one load; a length on a directional light is only a warning, whatever its sign. */
    const light_nodes four = nodes_for_lights(4);
    char* json = lights_json("{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":-0.0}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":1,\"length\":5e37}},"
                             "{\"type\":\"point\",\"extras\":{\"radius\":0.1,\"length\":1e-30}},"
                             "{\"type\":\"directional\",\"extras\":{\"length\":-1}}",
                             four.nodes, four.roots, NULL);
    log_counts counts;
    rtpbr_gltf_scene* scene = load(dir, "edges.gltf", json, NULL, &counts);
    assert_true(scene->punctual_lights[0].length == 0.0f && !signbit(scene->punctual_lights[0].length));
    assert_true(scene->punctual_lights[1].length == 5e37f);
    assert_true(scene->punctual_lights[2].length == 1e-30f);
    assert_true(scene->punctual_lights[3].length == 0.0f);
    assert_int_equal(counts.length_ignored, 1);
    rtpbr_gltf_destroy(scene);
    free(json);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_defaults),
                cmocka_unit_test(test_world_frame),
                cmocka_unit_test(test_intensity_and_range),
                cmocka_unit_test(test_spot_cones),
                cmocka_unit_test(test_shared_light),
                cmocka_unit_test(test_light_limit),
                cmocka_unit_test(test_glb_spot_defaults),
                cmocka_unit_test(test_radius),
                cmocka_unit_test(test_radius_refused),
                cmocka_unit_test(test_length),
                cmocka_unit_test(test_length_refused))
