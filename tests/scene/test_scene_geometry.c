/* Scene loader: world transforms, cameras, bounds, emissive-primitive light
 * merging and EXT_lights_area. Expected values are worked out by hand in
 * the comments from the JSON written here. */
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

#define EPS 1e-5
#define TS_PI 3.14159265358979323846

static void assert_near(double a, double b, double eps, const char* what) {
    if (!(fabs(a - b) <= eps)) fail_msg("%s: got %.9g, expected %.9g", what, a, b);
}

static void sub3(const float* a, const float* b, double* o) {
    for (int k = 0; k < 3; ++k) o[k] = (double)a[k] - (double)b[k];
}
static void cross3(const double* a, const double* b, double* o) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Every corner turns left about the light normal (convex, consistent winding). */
static void assert_convex_ccw(const rtpbr_gltf_light* l) {
    assert_true(l->vertex_count >= 3 && l->vertex_count <= 8);
    for (uint32_t i = 0; i < l->vertex_count; ++i) {
        double e1[3], e2[3], c[3];
        sub3(l->vertices[i], l->vertices[(i + l->vertex_count - 1) % l->vertex_count], e1);
        sub3(l->vertices[(i + 1) % l->vertex_count], l->vertices[i], e2);
        cross3(e1, e2, c);
        double d = c[0] * l->facts.normal[0] + c[1] * l->facts.normal[1] + c[2] * l->facts.normal[2];
        if (!(d > 0.0)) fail_msg("light corner %u does not turn about the normal (%g)", i, d);
    }
    assert_near(sqrt(l->facts.normal[0] * l->facts.normal[0] + l->facts.normal[1] * l->facts.normal[1] + l->facts.normal[2] * l->facts.normal[2]),
                1.0, EPS, "|normal|");
}

/* Is point (x,y,z) one of the light's vertices? */
static int has_vertex(const rtpbr_gltf_light* l, double x, double y, double z) {
    for (uint32_t i = 0; i < l->vertex_count; ++i)
        if (fabs(l->vertices[i][0] - x) < EPS && fabs(l->vertices[i][1] - y) < EPS &&
            fabs(l->vertices[i][2] - z) < EPS)
            return 1;
    return 0;
}

/* Unit quad in the XZ plane, counter-clockwise seen from +Y:
 * (v1-v0)×(v2-v0) = (1,0,0)×(1,0,-1) = (0,1,0). */
static const float kQuad[] = {-0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 0, -0.5f, -0.5f, 0, -0.5f};
static const uint32_t kQuadIdx[] = {0, 1, 2, 0, 2, 3};

static void test_quad_light_over_plane(void** state) {
    (void)state;
    const char* dir = ts_dir("quad_light");
    /* Mesh 0 = floor (material 0), mesh 1 = light (material 1), same accessors.
     * Floor node: scale (10,1,10) → corners (±5, 0, ±5), normal +Y.
     * Light node: T(0,2,0)·R_x(180°): (x,0,z) → (x, 2, -z); faces -Y.
     * Camera node: T(1,1,5)·R_y(90°), q = (0, sin45°, 0, cos45°):
     * forward R·(0,0,-1) = (-1,0,0), up (0,1,0), right R·(1,0,0) = (0,0,-1). */
    ts_scene s = {
        .positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6,
        .meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]},"
                  "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":1}]}",
        .materials = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1]}},"
                     "{\"emissiveFactor\":[1,0.5,0.25],\"extensions\":{\"KHR_materials_emissive_strength\":"
                     "{\"emissiveStrength\":4}}}",
        .nodes = "{\"mesh\":0,\"scale\":[10,1,10]},"
                 "{\"mesh\":1,\"translation\":[0,2,0],\"rotation\":[1,0,0,0]},"
                 "{\"camera\":0,\"translation\":[1,1,5],\"rotation\":[0,0.70710678118654752,0,0.70710678118654752]}",
        .scene_nodes = "0,1,2",
        .extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"aspectRatio\":1.5,"
                 "\"znear\":0.1,\"zfar\":100}}]",
    };
    rtpbr_gltf_scene* scene = ts_load_scene(dir, "scene.gltf", &s, NULL);
    assert_int_equal(scene->primitive_count, 2);
    assert_int_equal(scene->material_count, 2);
    assert_int_equal(scene->camera_count, 1);
    assert_int_equal(scene->light_count, 1);
    assert_int_equal(scene->total_vertex_count, 8);
    assert_int_equal(scene->total_index_count, 12);

    const rtpbr_gltf_primitive* floor = &scene->primitives[0];
    assert_int_equal(floor->vertex_count, 4);
    assert_int_equal(floor->index_count, 6);
    assert_int_equal(floor->material, 0);
    assert_true(floor->normals_generated);
    for (uint32_t v = 0; v < 4; ++v) {
        assert_near(floor->positions[3 * v + 0], 10.0 * kQuad[3 * v + 0], EPS, "floor x");
        assert_near(floor->positions[3 * v + 1], 0.0, EPS, "floor y");
        assert_near(floor->positions[3 * v + 2], 10.0 * kQuad[3 * v + 2], EPS, "floor z");
        assert_near(floor->normals[3 * v + 1], 1.0, EPS, "floor normal y");
    }
    const rtpbr_gltf_primitive* lp = &scene->primitives[1];
    for (uint32_t v = 0; v < 4; ++v) {
        assert_near(lp->positions[3 * v + 0], kQuad[3 * v + 0], EPS, "light x");
        assert_near(lp->positions[3 * v + 1], 2.0, EPS, "light y");
        assert_near(lp->positions[3 * v + 2], -kQuad[3 * v + 2], EPS, "light z");
        assert_near(lp->normals[3 * v + 1], -1.0, EPS, "light normal y");
    }

    /* 2 coplanar triangles → one quad, facing down, radiance (1,.5,.25)×4. */
    const rtpbr_gltf_light* l = &scene->lights[0];
    assert_int_equal(l->shape, RTPBR_GLTF_LIGHT_POLYGON);
    assert_int_equal(l->vertex_count, 4);
    assert_convex_ccw(l);
    assert_near(l->facts.normal[0], 0.0, EPS, "nx");
    assert_near(l->facts.normal[1], -1.0, EPS, "ny");
    assert_near(l->facts.normal[2], 0.0, EPS, "nz");
    assert_true(has_vertex(l, -0.5, 2, -0.5) && has_vertex(l, 0.5, 2, -0.5) &&
                has_vertex(l, 0.5, 2, 0.5) && has_vertex(l, -0.5, 2, 0.5));
    assert_near(l->facts.area, 1.0, EPS, "area");
    assert_near(l->radiance[0], 4.0, EPS, "L_r");
    assert_near(l->radiance[1], 2.0, EPS, "L_g");
    assert_near(l->radiance[2], 1.0, EPS, "L_b");
    assert_false(l->two_sided);
    assert_int_equal(l->primitive, 1);
    assert_int_equal(l->material, 1);
    assert_near(l->facts.center[1], 2.0, EPS, "center y");

    const rtpbr_gltf_camera* c = &scene->cameras[0];
    const double cam[4][3] = {{1, 1, 5}, {-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    for (int k = 0; k < 3; ++k) {
        assert_near(c->position[k], cam[0][k], EPS, "camera position");
        assert_near(c->forward[k], cam[1][k], EPS, "camera forward");
        assert_near(c->up[k], cam[2][k], EPS, "camera up");
        assert_near(c->right[k], cam[3][k], EPS, "camera right");
    }
    assert_near(c->yfov, 0.8, EPS, "yfov");
    assert_near(c->aspect, 1.5, EPS, "aspect");
    assert_near(c->znear, 0.1, EPS, "znear");
    assert_near(c->zfar, 100.0, 1e-4, "zfar");

    const double lo[3] = {-5, 0, -5}, hi[3] = {5, 2, 5};
    for (int k = 0; k < 3; ++k) {
        assert_near(scene->bounds_min[k], lo[k], EPS, "bounds min");
        assert_near(scene->bounds_max[k], hi[k], EPS, "bounds max");
    }
    rtpbr_gltf_destroy(scene);
}

static rtpbr_gltf_scene* load_emissive(const char* name, const float* pos, size_t nv, const uint32_t* idx,
                                  size_t ni, const rtpbr_gltf_load_desc* desc, rtpbr_gltf_result* result) {
    const char* dir = ts_dir(name);
    ts_scene s = {
        .positions = pos, .vertex_count = nv, .indices = idx, .index_count = ni, .material = 0,
        .materials = "{\"emissiveFactor\":[1,1,1],\"doubleSided\":true}",
    };
    char* json = ts_scene_json(&s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    *result = ts_load_text(dir, "scene.gltf", json, desc, &scene, err, sizeof err);
    free(json);
    if (*result != RTPBR_GLTF_SUCCESS && !desc) fail_msg("%s: %s", rtpbr_gltf_result_string(*result), err);
    return scene;
}

static void test_hexagon_fan_is_one_light(void** state) {
    (void)state;
    /* Centre + 6 ring vertices at radius 1 in z = 0, fan counter-clockwise
     * about +Z: one regular hexagon of area 3·sqrt(3)/2. */
    float pos[7 * 3] = {0};
    for (int k = 0; k < 6; ++k) {
        pos[3 * (k + 1) + 0] = (float)cos(k * TS_PI / 3.0);
        pos[3 * (k + 1) + 1] = (float)sin(k * TS_PI / 3.0);
    }
    uint32_t idx[18];
    for (uint32_t k = 0; k < 6; ++k) idx[3 * k] = 0, idx[3 * k + 1] = 1 + k, idx[3 * k + 2] = 1 + (k + 1) % 6;
    rtpbr_gltf_result r;
    rtpbr_gltf_scene* scene = load_emissive("hexagon", pos, 7, idx, 18, NULL, &r);
    assert_int_equal(scene->light_count, 1);
    const rtpbr_gltf_light* l = &scene->lights[0];
    assert_int_equal(l->vertex_count, 6);
    assert_convex_ccw(l);
    assert_near(l->facts.normal[2], 1.0, EPS, "normal z");
    assert_near(l->facts.area, 3.0 * sqrt(3.0) / 2.0, 1e-5, "hexagon area");
    for (int k = 0; k < 6; ++k) assert_true(has_vertex(l, pos[3 * (k + 1)], pos[3 * (k + 1) + 1], 0.0));
    assert_true(l->two_sided);
    rtpbr_gltf_destroy(scene);
}

static void test_unindexed_quad_is_one_light(void** state) {
    (void)state;
    /* Two triangles with their own copies of the shared corners (6 vertices,
     * indices 0..5): vertices are welded by position, giving one quad. */
    const float pos[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 0, 0, 2, 1, 0, 0, 1, 0};
    const uint32_t idx[] = {0, 1, 2, 3, 4, 5};
    rtpbr_gltf_result r;
    rtpbr_gltf_scene* scene = load_emissive("unindexed", pos, 6, idx, 6, NULL, &r);
    assert_int_equal(scene->light_count, 1);
    assert_int_equal(scene->lights[0].vertex_count, 4);
    assert_convex_ccw(&scene->lights[0]);
    assert_near(scene->lights[0].facts.area, 2.0, EPS, "2×1 quad area");
    rtpbr_gltf_destroy(scene);
}

static void test_strip_and_fan_modes(void** state) {
    (void)state;
    /* TRIANGLE_STRIP 0,1,2,3 over (0,0) (1,0) (0,1) (1,1): glTF §3.7.2.1 gives
     * triangles (0,1,2) and (1,3,2), both counter-clockwise about +Z.
     * TRIANGLE_FAN over the hexagon's centre + ring (8 indices, ring closed):
     * 6 triangles (0, k, k+1). Each mesh becomes a single light. */
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const uint32_t idx[] = {0, 1, 2, 3};
    const char* dir = ts_dir("modes");
    ts_scene s = {.positions = pos, .vertex_count = 4, .indices = idx, .index_count = 4,
                  .materials = "{\"emissiveFactor\":[1,1,1]}",
                  .meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":5,"
                            "\"material\":0}]}"};
    rtpbr_gltf_scene* scene = ts_load_scene(dir, "strip.gltf", &s, NULL);
    assert_int_equal(scene->primitives[0].index_count, 6);
    assert_int_equal(scene->light_count, 1);
    assert_int_equal(scene->lights[0].vertex_count, 4);
    assert_convex_ccw(&scene->lights[0]);
    assert_near(scene->lights[0].facts.normal[2], 1.0, EPS, "strip normal");
    assert_near(scene->lights[0].facts.area, 1.0, EPS, "strip area");
    rtpbr_gltf_destroy(scene);

    float hex[7 * 3] = {0};
    for (int k = 0; k < 6; ++k) {
        hex[3 * (k + 1) + 0] = (float)cos(k * TS_PI / 3.0);
        hex[3 * (k + 1) + 1] = (float)sin(k * TS_PI / 3.0);
    }
    const uint32_t fan[] = {0, 1, 2, 3, 4, 5, 6, 1};
    s.positions = hex;
    s.vertex_count = 7;
    s.indices = fan;
    s.index_count = 8;
    s.meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":6,\"material\":0}]}";
    scene = ts_load_scene(dir, "fan.gltf", &s, NULL);
    assert_int_equal(scene->primitives[0].index_count, 18);
    assert_int_equal(scene->light_count, 1);
    assert_int_equal(scene->lights[0].vertex_count, 6);
    assert_near(scene->lights[0].facts.area, 3.0 * sqrt(3.0) / 2.0, 1e-5, "fan hexagon area");
    rtpbr_gltf_destroy(scene);
}

static void test_non_coplanar_triangles_are_separate(void** state) {
    (void)state;
    /* Triangles folded at 90° along the shared edge (0,0,0)-(0,1,0):
     * normals +Z and +X. */
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    rtpbr_gltf_result r;
    rtpbr_gltf_scene* scene = load_emissive("fold", pos, 4, idx, 6, NULL, &r);
    assert_int_equal(scene->light_count, 2);
    int seen_z = 0, seen_x = 0;
    for (uint32_t i = 0; i < 2; ++i) {
        const rtpbr_gltf_light* l = &scene->lights[i];
        assert_int_equal(l->vertex_count, 3);
        assert_convex_ccw(l);
        assert_near(l->facts.area, 0.5, EPS, "triangle area");
        seen_z += fabs(l->facts.normal[2] - 1.0) < EPS;
        seen_x += fabs(l->facts.normal[0] - 1.0) < EPS;
    }
    assert_int_equal(seen_z, 1);
    assert_int_equal(seen_x, 1);
    rtpbr_gltf_destroy(scene);

    /* The same with max_lights = 1: a specific error, no scene. */
    rtpbr_gltf_load_desc desc = {0};
    desc.max_lights = 1;
    scene = load_emissive("fold_limit", pos, 4, idx, 6, &desc, &r);
    assert_int_equal(r, RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS);
    assert_null(scene);
}

static void test_concave_region_splits_into_convex_lights(void** state) {
    (void)state;
    /* L shape of three unit squares on a 3×3 vertex grid (z = 0): concave,
     * so the merge must yield several convex polygons covering area 3. */
    float pos[9 * 3];
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) pos[3 * (y * 3 + x)] = (float)x, pos[3 * (y * 3 + x) + 1] = (float)y,
                                    pos[3 * (y * 3 + x) + 2] = 0.0f;
    const uint32_t idx[] = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6};
    rtpbr_gltf_result r;
    rtpbr_gltf_scene* scene = load_emissive("lshape", pos, 9, idx, 18, NULL, &r);
    assert_true(scene->light_count >= 2 && scene->light_count <= 6);
    double area = 0.0;
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        assert_convex_ccw(&scene->lights[i]);
        area += scene->lights[i].facts.area;
    }
    assert_near(area, 3.0, 1e-5, "total light area");
    rtpbr_gltf_destroy(scene);
}

static void test_non_emissive_and_degenerate(void** state) {
    (void)state;
    /* Triangle 1 repeats a vertex, triangle 2 is collinear: both dropped. */
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
    const uint32_t idx[] = {0, 1, 2, 0, 0, 1, 0, 1, 3};
    const char* dir = ts_dir("degenerate");
    ts_scene s = {.positions = pos, .vertex_count = 4, .indices = idx, .index_count = 9, .material = -1};
    rtpbr_gltf_scene* scene = ts_load_scene(dir, "scene.gltf", &s, NULL);
    assert_int_equal(scene->light_count, 0);
    assert_int_equal(scene->primitives[0].index_count, 3);
    /* No material: a default one (glTF defaults) is appended. */
    assert_int_equal(scene->material_count, 1);
    assert_int_equal(scene->materials[0].gltf_material, -1);
    assert_near(scene->materials[0].metallic, 1.0, 0, "default metallic");
    assert_near(scene->materials[0].roughness, 1.0, 0, "default roughness");
    /* Generated flat normal of triangle (0,1,2): +Z. */
    assert_near(scene->primitives[0].normals[2], 1.0, EPS, "generated normal");
    assert_int_equal(scene->camera_count, 0);
    rtpbr_gltf_destroy(scene);
}

static void test_mirrored_node_keeps_ccw_winding(void** state) {
    (void)state;
    /* scale (-1,1,1) mirrors the quad: winding must be flipped so that the
     * light (facing +Y before and after a mirror in x) stays counter-clockwise. */
    const char* dir = ts_dir("mirror");
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6, .material = 0,
                  .materials = "{\"emissiveFactor\":[1,1,1]}",
                  .nodes = "{\"mesh\":0,\"scale\":[-1,1,1]}"};
    rtpbr_gltf_scene* scene = ts_load_scene(dir, "scene.gltf", &s, NULL);
    assert_int_equal(scene->light_count, 1);
    assert_convex_ccw(&scene->lights[0]);
    assert_near(scene->lights[0].facts.normal[1], 1.0, EPS, "mirrored light normal");
    const rtpbr_gltf_primitive* p = &scene->primitives[0];
    for (uint32_t t = 0; t < p->index_count; t += 3) {
        double e1[3], e2[3], c[3];
        sub3(&p->positions[3 * p->indices[t + 1]], &p->positions[3 * p->indices[t]], e1);
        sub3(&p->positions[3 * p->indices[t + 2]], &p->positions[3 * p->indices[t]], e2);
        cross3(e1, e2, c);
        assert_true(c[1] > 0.0);
    }
    rtpbr_gltf_destroy(scene);
}

/* An EXT_lights_area disk under an uneven scale is the circle's image, an ellipse (issue 30):
 * the parent scales x by 2, the child turns by 45 degrees about z and scales y by 0.5, so the
 * world map of the light's plane is S_p R S_c, with a shear. Every image point of the circle of
 * radius 0.5 must lie on the loaded ellipse (centre, axis, radius, radius2, normal), whose area is
 * pi 0.25 |det| = pi / 4; the octagon keeps that area. */
static void test_ext_lights_area_ellipse(void** state) {
    (void)state;
    const char* dir = ts_dir("ext_lights_area_ellipse");
    const char* json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_lights_area\"],"
        "\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"disk\",\"size\":1,\"intensity\":5}]}},"
        "\"nodes\":[{\"scale\":[2,1,1],\"children\":[1]},"
        "{\"rotation\":[0,0,0.38268343236508977,0.9238795325112867],\"scale\":[1,0.5,1],"
        "\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}],"
        "\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "ellipse.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->light_count, 1);
    const rtpbr_gltf_light* e = &scene->lights[0];
    assert_int_equal(e->shape, RTPBR_GLTF_LIGHT_DISK);
    assert_convex_ccw(e);
    assert_true(e->radius >= e->radius2 && e->radius2 > 0.0f);
    assert_near(TS_PI * e->radius * e->radius2, TS_PI / 4.0, 1e-5, "ellipse area");
    assert_near(e->facts.area, TS_PI / 4.0, 1e-5, "octagon area = ellipse area");
    assert_near(e->facts.normal[2], -1.0, EPS, "ellipse normal");
    double a[3] = {e->axis[0], e->axis[1], e->axis[2]}, n[3] = {e->facts.normal[0], e->facts.normal[1], e->facts.normal[2]};
    double b[3];
    cross3(n, a, b);
    assert_near(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0, 1e-6, "axis unit");
    assert_near(a[0] * n[0] + a[1] * n[1] + a[2] * n[2], 0.0, 1e-6, "axis in the plane");
    const double c = 0.9238795325112867 * 0.9238795325112867 - 0.38268343236508977 * 0.38268343236508977; /* cos 45 */
    const double sn = 2.0 * 0.9238795325112867 * 0.38268343236508977;                                  /* sin 45 */
    for (int i = 0; i < 16; ++i) {
        double t = 2.0 * TS_PI * i / 16.0, lx = 0.5 * cos(t), ly = 0.5 * sin(t) * 0.5; /* the child's scale */
        double p[3] = {2.0 * (c * lx - sn * ly), sn * lx + c * ly, 0.0};           /* its turn, the parent's scale */
        double u = (p[0] * a[0] + p[1] * a[1]) / e->radius, v = (p[0] * b[0] + p[1] * b[1]) / e->radius2;
        assert_near(u * u + v * v, 1.0, 1e-5, "circle image on the ellipse");
    }
    rtpbr_gltf_destroy(scene);
}

/* An EXT_lights_area rect under an uneven scale is the rect's image (issue 30; before, every side
 * was scaled by the largest column length): the parent scales x by 2 and z by 3 (z: not the
 * rect's plane, so nothing), the child turns by 45 degrees about z and scales y by 0.5. The rect
 * of width 1.5 (local x) and height 1 (local y) maps its corner (u, v) to
 * S_p R (u, 0.5 v): each loaded vertex is one such image, the area is 1.5 |det| = 1.5 (det of
 * the plane's map: 2 x 0.5), and the normal stays -Z. */
static void test_ext_lights_area_rect_scaled(void** state) {
    (void)state;
    const char* dir = ts_dir("ext_lights_area_rect_scaled");
    const char* json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_lights_area\"],"
        "\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"rect\",\"size\":1,\"rect\":{\"aspect\":1.5},"
        "\"intensity\":5}]}},"
        "\"nodes\":[{\"scale\":[2,1,3],\"children\":[1]},"
        "{\"rotation\":[0,0,0.38268343236508977,0.9238795325112867],\"scale\":[1,0.5,1],"
        "\"extensions\":{\"EXT_lights_area\":{\"light\":0}}}],"
        "\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "rect.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->light_count, 1);
    const rtpbr_gltf_light* l = &scene->lights[0];
    assert_int_equal(l->shape, RTPBR_GLTF_LIGHT_POLYGON);
    assert_int_equal(l->vertex_count, 4);
    assert_convex_ccw(l);
    assert_near(l->facts.area, 1.5, 1e-5, "parallelogram area");
    assert_near(l->facts.normal[2], -1.0, EPS, "rect normal");
    const double c = 0.9238795325112867 * 0.9238795325112867 - 0.38268343236508977 * 0.38268343236508977; /* cos 45 */
    const double sn = 2.0 * 0.9238795325112867 * 0.38268343236508977;                                  /* sin 45 */
    for (int i = 0; i < 4; ++i) { /* each corner's image is a vertex */
        double u = (i & 1 ? 0.75 : -0.75), v = (i & 2 ? 0.5 : -0.5) * 0.5; /* the child's scale */
        double p[3] = {2.0 * (c * u - sn * v), sn * u + c * v, 0.0};       /* its turn, the parent's scale */
        double nearest = INFINITY;
        for (uint32_t k = 0; k < 4; ++k) {
            double dx = l->vertices[k][0] - p[0], dy = l->vertices[k][1] - p[1], dz = l->vertices[k][2] - p[2];
            nearest = fmin(nearest, sqrt(dx * dx + dy * dy + dz * dz));
        }
        assert_near(nearest, 0.0, 1e-5, "corner image is a vertex");
    }
    rtpbr_gltf_destroy(scene);
}

static void test_ext_lights_area(void** state) {
    (void)state;
    /* Light 0: rect, size 2, aspect 1.5 → width 3 (local x), height 2 (local y),
     *   node T(0,3,0)·R_x(-90°) [q = (-sin45°,0,0,cos45°)]: local y → -z,
     *   local -Z → -Y. Vertices (±1.5, 3, ±1), normal (0,-1,0), area 6,
     *   radiance color × intensity = (100, 50, 25).
     * Light 1: disk, size 1 (diameter), node T(1,1,1)·S(2): radius 1,
     *   normal (0,0,-1), area π; 8-gon of equal area, circumradius
     *   sqrt(π / (2·sqrt 2)).
     * Light 2: the earlier draft's form: shape rect, width 3, height 1,
     *   luminance 10 → area 3, radiance 10. */
    const char* dir = ts_dir("ext_lights_area");
    const char* json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_lights_area\"],"
        "\"extensions\":{\"EXT_lights_area\":{\"lights\":["
        "{\"type\":\"rect\",\"size\":2,\"rect\":{\"aspect\":1.5},\"color\":[1,0.5,0.25],\"intensity\":100},"
        "{\"type\":\"disk\",\"size\":1,\"intensity\":50},"
        "{\"shape\":\"rect\",\"width\":3,\"height\":1,\"luminance\":10}]}},"
        "\"nodes\":[{\"translation\":[0,3,0],\"rotation\":[-0.70710678118654752,0,0,0.70710678118654752],"
        "\"extensions\":{\"EXT_lights_area\":{\"light\":0}}},"
        "{\"translation\":[1,1,1],\"scale\":[2,2,2],\"extensions\":{\"EXT_lights_area\":{\"light\":1}}},"
        "{\"extensions\":{\"EXT_lights_area\":{\"light\":2}}}],"
        "\"scenes\":[{\"nodes\":[0,1,2]}],\"scene\":0}";
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "lights.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->light_count, 3);

    const rtpbr_gltf_light* rect = &scene->lights[0];
    assert_int_equal(rect->shape, RTPBR_GLTF_LIGHT_POLYGON);
    assert_int_equal(rect->vertex_count, 4);
    assert_convex_ccw(rect);
    assert_near(rect->facts.normal[1], -1.0, EPS, "rect normal");
    assert_true(has_vertex(rect, -1.5, 3, -1) && has_vertex(rect, 1.5, 3, -1) && has_vertex(rect, 1.5, 3, 1) &&
                has_vertex(rect, -1.5, 3, 1));
    assert_near(rect->facts.area, 6.0, EPS, "rect area");
    assert_near(rect->radiance[0], 100.0, 1e-4, "rect L_r");
    assert_near(rect->radiance[1], 50.0, 1e-4, "rect L_g");
    assert_near(rect->radiance[2], 25.0, 1e-4, "rect L_b");
    assert_int_equal(rect->primitive, -1);
    assert_int_equal(rect->gltf_node, 0);
    assert_false(rect->two_sided);

    const rtpbr_gltf_light* disk = &scene->lights[1];
    assert_int_equal(disk->shape, RTPBR_GLTF_LIGHT_DISK);
    assert_int_equal(disk->vertex_count, 8);
    assert_convex_ccw(disk);
    assert_near(disk->radius, 1.0, EPS, "disk radius");
    assert_near(disk->facts.normal[2], -1.0, EPS, "disk normal");
    for (int k = 0; k < 3; ++k) assert_near(disk->facts.center[k], 1.0, EPS, "disk centre");
    assert_near(disk->facts.area, TS_PI, 1e-5, "disk area");
    const double R = sqrt(TS_PI / (2.0 * sqrt(2.0)));
    double octagon = 0.0;
    for (uint32_t i = 0; i < 8; ++i) {
        double d[3], e[3], c[3];
        sub3(disk->vertices[i], disk->facts.center, d);
        assert_near(sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), R, 1e-5, "octagon circumradius");
        assert_near(disk->vertices[i][2], 1.0, EPS, "octagon plane");
        sub3(disk->vertices[(i + 1) % 8], disk->facts.center, e);
        cross3(d, e, c);
        octagon += 0.5 * -c[2];
    }
    assert_near(octagon, TS_PI, 1e-5, "octagon area = disk area");
    assert_near(disk->radiance[0], 50.0, 1e-4, "disk radiance");

    const rtpbr_gltf_light* legacy = &scene->lights[2];
    assert_near(legacy->facts.area, 3.0, EPS, "legacy rect area");
    assert_near(legacy->radiance[1], 10.0, EPS, "legacy luminance");
    assert_near(legacy->facts.normal[2], -1.0, EPS, "legacy normal");

    /* Bounds include the lights (no meshes): x from the rect ±1.5; the
     * disk's octagon has a vertex at angle 0, x = 1 + R. */
    assert_near(scene->bounds_min[0], -1.5, EPS, "bounds min x");
    assert_near(scene->bounds_max[0], 1.0 + R, 1e-5, "bounds max x");
    assert_near(scene->bounds_max[1], 3.0, EPS, "bounds max y");
    rtpbr_gltf_destroy(scene);

    /* area_light_radiance_scale multiplies the radiance. */
    rtpbr_gltf_load_desc desc = {0};
    desc.area_light_radiance_scale = 0.25f;
    r = ts_load_text(dir, "lights.gltf", json, &desc, &scene, err, sizeof err);
    assert_int_equal(r, RTPBR_GLTF_SUCCESS);
    assert_near(scene->lights[0].radiance[0], 25.0, 1e-4, "scaled radiance");
    rtpbr_gltf_destroy(scene);
}

static void test_glb_and_memory(void** state) {
    (void)state;
    /* The quad as a GLB: JSON chunk + BIN chunk (glTF 2.0 §4.4). */
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6, .material = -1};
    ts_bin* bin = malloc(sizeof *bin);
    ts_scene_bin(&s, bin);
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"nodes\":[{\"mesh\":0,\"translation\":[0,0,-3]}],\"scenes\":[{\"nodes\":[0]}]}",
        bin->size);
    size_t total;
    unsigned char* glb = ts_glb(json, bin->bytes, bin->size, &total);

    const char* dir = ts_dir("glb");
    ts_write(dir, "quad.glb", glb, total);
    char* path = ts_path(dir, "quad.glb");
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = rtpbr_gltf_load(path, NULL, &scene);
    assert_int_equal(r, RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->primitives[0].vertex_count, 4);
    assert_near(scene->primitives[0].positions[2], 0.5 - 3.0, EPS, "glb translated z");
    rtpbr_gltf_destroy(scene);

    r = rtpbr_gltf_load_memory(glb, total, NULL, &scene);
    assert_int_equal(r, RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->primitives[0].index_count, 6);
    rtpbr_gltf_destroy(scene);

    /* Same JSON with a data: URI, from memory without base_dir. */
    char* text = ts_scene_json(&s);
    r = rtpbr_gltf_load_memory(text, strlen(text), NULL, &scene);
    assert_int_equal(r, RTPBR_GLTF_SUCCESS);
    rtpbr_gltf_destroy(scene);
    free(text);
    free(path);
    free(glb);
    free(json);
    free(bin);
}

static void test_sparse_positions(void** state) {
    (void)state;
    /* Accessor 0 = the +Z unit quad with vertex 2 replaced by (3,2,0) through
     * a sparse substitution (uint16 index 2); accessor 2 = a triangle made
     * only of sparse values over an implicit zero base. */
    const float quad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    const uint16_t sp_idx[] = {2, 0};
    const float sp_val[] = {3, 2, 0};
    const uint16_t tri_idx[] = {1, 2};
    const float tri_val[] = {1, 0, 0, 0, 1, 0};
    ts_bin bin = {.size = 0};
    const size_t o_pos = ts_bin_append(&bin, quad, sizeof quad), o_idx = ts_bin_append(&bin, idx, sizeof idx);
    const size_t o_si = ts_bin_append(&bin, sp_idx, sizeof sp_idx), o_sv = ts_bin_append(&bin, sp_val, sizeof sp_val);
    const size_t o_ti = ts_bin_append(&bin, tri_idx, sizeof tri_idx), o_tv = ts_bin_append(&bin, tri_val, sizeof tri_val);
    char* uri = ts_data_uri("application/octet-stream", bin.bytes, bin.size);
    const char* fmt =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"%s\",\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":24},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":4},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":12},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":4},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":24}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":2,\"componentType\":5123},\"values\":{\"bufferView\":3}}},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\"},"
        "{\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\","
        "\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":4,\"componentType\":5123},\"values\":{\"bufferView\":5}}}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":2}}]}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":1}],\"scenes\":[{\"nodes\":[0,1]}]}";
    char* json = ts_format(fmt, uri, bin.size, o_pos, o_idx, o_si, o_sv, o_ti, o_tv, 3);
    const char* dir = ts_dir("sparse");
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "sparse.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    const float* p = scene->primitives[0].positions;
    assert_near(p[6], 3.0, 0, "sparse x");
    assert_near(p[7], 2.0, 0, "sparse y");
    assert_near(p[3], 1.0, 0, "untouched vertex 1");
    const float* t = scene->primitives[1].positions;
    const float want[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int k = 0; k < 9; ++k) assert_near(t[k], want[k], 0, "zero base + sparse");
    assert_int_equal(scene->primitives[1].index_count, 3);
    rtpbr_gltf_destroy(scene);
    free(json);
    /* count 2 < sparse index 2: rejected, naming the accessor */
    json = ts_format(fmt, uri, bin.size, o_pos, o_idx, o_si, o_sv, o_ti, o_tv, 2);
    r = ts_load_text(dir, "sparse_bad.gltf", json, NULL, &scene, err, sizeof err);
    assert_int_equal(r, RTPBR_GLTF_ERROR_INVALID_ACCESSOR);
    assert_non_null(strstr(err, "accessor 2"));
    free(json);
    free(uri);
}

/* A curved emitter (issue 28): a closed cylinder side of 24 x 6 quads (288 triangles, radius 1,
 * height 2, outward, emission 1, 0.5, 0.25) is not a few polygons. BOUNDED (default): at most
 * RTPBR_GLTF_MAX_EMITTER_CLUSTERS proxy octagons whose power (radiance x area, per channel)
 * sums to the mesh's (the triangles' area x emission, computed here from the vertices), none
 * brighter than the emission; EXACT: every triangle an emitter, each of the 24 coplanar columns
 * of 6 quads merged into one rectangle, no proxy (24 > RTPBR_GLTF_MAX_EXACT_EMITTER_POLYGONS:
 * why BOUNDED clusters it). */
static void test_curved_emitter_bounded_and_exact(void** state) {
    (void)state;
    enum { SEG = 24, RINGS = 6 };
    float pos[(SEG * (RINGS + 1)) * 3];
    uint32_t idx[SEG * RINGS * 6];
    for (int r = 0; r <= RINGS; ++r)
        for (int k = 0; k < SEG; ++k) {
            float* v = &pos[3 * (r * SEG + k)];
            v[0] = (float)cos(2.0 * TS_PI * k / SEG), v[1] = (float)sin(2.0 * TS_PI * k / SEG), v[2] = -1.0f + 2.0f * r / RINGS;
        }
    size_t n = 0;
    double mesh_area = 0.0;
    for (int r = 0; r < RINGS; ++r)
        for (int k = 0; k < SEG; ++k) {
            uint32_t a = (uint32_t)(r * SEG + k), b = (uint32_t)(r * SEG + (k + 1) % SEG), c = a + SEG, d = b + SEG;
            const uint32_t tri[6] = {a, b, d, a, d, c}; /* counter-clockwise seen from outside */
            for (int q = 0; q < 6; ++q) idx[n++] = tri[q];
        }
    for (size_t t = 0; t < n; t += 3) {
        const float *p0 = &pos[3 * idx[t]], *p1 = &pos[3 * idx[t + 1]], *p2 = &pos[3 * idx[t + 2]];
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
        mesh_area += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    const double emission[3] = {1.0, 0.5, 0.25};
    const char* dir = ts_dir("cylinder");
    ts_scene s = {.positions = pos, .vertex_count = SEG * (RINGS + 1), .indices = idx, .index_count = n,
                  .material = 0, .materials = "{\"emissiveFactor\":[1,0.5,0.25]}"};
    char* json = ts_scene_json(&s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "bounded.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s", err);
    assert_true(scene->light_count >= 1 && scene->light_count <= RTPBR_GLTF_MAX_EMITTER_CLUSTERS);
    double power[3] = {0, 0, 0};
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        const rtpbr_gltf_light* l = &scene->lights[i];
        assert_true(l->proxy);
        assert_int_equal(l->triangle, -1);
        assert_int_equal(l->vertex_count, 8);
        assert_convex_ccw(l);
        for (int k = 0; k < 3; ++k) {
            power[k] += (double)l->radiance[k] * l->facts.area;
            assert_true(l->radiance[k] <= emission[k] * (1.0 + 1e-6));
        }
    }
    for (int k = 0; k < 3; ++k) assert_near(power[k], emission[k] * mesh_area, 1e-4 * mesh_area, "cluster power");
    rtpbr_gltf_destroy(scene);

    rtpbr_gltf_load_desc exact = {0};
    exact.emissive_mode = RTPBR_GLTF_EMISSIVE_EXACT;
    r = ts_load_text(dir, "exact.gltf", json, &exact, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s", err);
    assert_int_equal(scene->light_count, SEG);
    assert_true(SEG > RTPBR_GLTF_MAX_EXACT_EMITTER_POLYGONS);
    double area = 0.0;
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        assert_false(scene->lights[i].proxy);
        area += scene->lights[i].facts.area;
    }
    assert_near(area, mesh_area, 1e-4 * mesh_area, "exact area");
    rtpbr_gltf_destroy(scene);
    free(json);
}

/* A textured emissive quad (issue 28): a 1 x 1 sRGB texture (128, 64, 255), emission 1, 1, 0.5.
 * BOUNDED: one exact quad (not a proxy) at emission x the texel in linear (the sRGB transfer
 * function, IEC 61966-2-1, computed here); EXACT: each triangle its own light with its triangle
 * index, at the factor (the path tracer applies the texture). */
static void test_textured_emitter(void** state) {
    (void)state;
    const unsigned char px[4] = {128, 64, 255, 255};
    size_t png_size;
    unsigned char* png = ts_png(px, 1, 1, &png_size);
    char* uri = ts_data_uri("image/png", png, png_size);
    char* extra = ts_format(",\"images\":[{\"uri\":\"%s\"}],\"textures\":[{\"source\":0}]", uri);
    const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const float uv[] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    ts_scene s = {.positions = pos, .vertex_count = 4, .indices = idx, .index_count = 6, .texcoords = uv,
                  .material = 0, .extra = extra,
                  .materials = "{\"emissiveFactor\":[1,1,0.5],\"emissiveTexture\":{\"index\":0}}"};
    char* json = ts_scene_json(&s);
    const char* dir = ts_dir("textured_emitter");
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "bounded.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s", err);
    assert_int_equal(scene->light_count, 1);
    assert_false(scene->lights[0].proxy);
    assert_int_equal(scene->lights[0].vertex_count, 4);
    const double factor[3] = {1.0, 1.0, 0.5};
    for (int k = 0; k < 3; ++k) {
        double c = px[k] / 255.0;
        double lin = c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
        assert_near(scene->lights[0].radiance[k], factor[k] * lin, 1e-5, "texture-averaged radiance");
    }
    rtpbr_gltf_destroy(scene);

    rtpbr_gltf_load_desc exact = {0};
    exact.emissive_mode = RTPBR_GLTF_EMISSIVE_EXACT;
    r = ts_load_text(dir, "exact.gltf", json, &exact, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s", err);
    assert_int_equal(scene->light_count, 2);
    for (uint32_t i = 0; i < 2; ++i) {
        assert_int_equal(scene->lights[i].triangle, (int)i);
        assert_int_equal(scene->lights[i].vertex_count, 3);
        for (int k = 0; k < 3; ++k) assert_near(scene->lights[i].radiance[k], factor[k], 0, "factor");
    }
    rtpbr_gltf_destroy(scene);
    free(json);
    free(extra);
    free(uri);
    free(png);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_quad_light_over_plane),
                cmocka_unit_test(test_hexagon_fan_is_one_light),
                cmocka_unit_test(test_unindexed_quad_is_one_light),
                cmocka_unit_test(test_strip_and_fan_modes),
                cmocka_unit_test(test_non_coplanar_triangles_are_separate),
                cmocka_unit_test(test_concave_region_splits_into_convex_lights),
                cmocka_unit_test(test_curved_emitter_bounded_and_exact),
                cmocka_unit_test(test_textured_emitter),
                cmocka_unit_test(test_non_emissive_and_degenerate),
                cmocka_unit_test(test_mirrored_node_keeps_ccw_winding),
                cmocka_unit_test(test_ext_lights_area),
                cmocka_unit_test(test_ext_lights_area_ellipse),
        cmocka_unit_test(test_ext_lights_area_rect_scaled),
                cmocka_unit_test(test_glb_and_memory),
                cmocka_unit_test(test_sparse_positions))
