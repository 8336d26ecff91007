// The viewer's light edits (samples/viewer/scene_edit.c) against closed forms: a regular
// n-gon's area, right-handed rotations, areas under scaling, the tracked transform that moves
// the uploaded polygon in place; the loader-to-viewer mapping of the bundled quad_light and
// showcase scenes (numbers read from scenes.json by hand); and picking by ray.
// Punctual lights (issue 30): punctual_lights' three lights as the file gives them, their edits
// (turns, angles, the clamp to what the engine accepts), and on the device (lavapipe,
// validation on: any message fails): the viewer's upload renders the radiance of the engine's
// own rtpbr_gpu_scene_from_loaded, an intensity x2 doubles each light's part of the image, and
// rtpbr_gpu_scene_set_lights through the viewer keeps a mixed scene's area light intact.
// Disk lights (issue 30): light_shapes' EXT_lights_area disks are disks in the viewer (its
// descs, its picking and, on the device, the engine's own image, moved in place too), and the
// disk I adds (its place in I's order, its desc, its edits). Ellipses and screens: the ellipse
// I adds and its edits; a loaded ellipse renders what the engine's loader path renders; the
// screen I adds shows the viewer's test card (its mean and its layout in the light it adds).
#include "engine_test.h" // test_main.h, the validation-counting context, test_render_radiance

#include "scene_edit.h"

static const double pi = 3.14159265358979323846;

// Area by the shoelace formula on the polygon's projection onto the plane with normal n.
static double polygon_area(const viewer_light *l)
{
    double c[3] = {0, 0, 0};
    for (uint32_t i = 0; i < l->vertex_count; ++i) {
        const float *a = l->vertices[i], *b = l->vertices[(i + 1) % l->vertex_count];
        c[0] += (double)a[1] * b[2] - (double)a[2] * b[1];
        c[1] += (double)a[2] * b[0] - (double)a[0] * b[2];
        c[2] += (double)a[0] * b[1] - (double)a[1] * b[0];
    }
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

// A 2 x 2 square at height 3 facing down (counter-clockwise seen from below).
static viewer_light square(void)
{
    viewer_light l = {.vertex_count = 4, .color = {1, 1, 1}, .intensity = 1,
                      .transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    const float v[4][3] = {{1, 3, 1}, {-1, 3, 1}, {-1, 3, -1}, {1, 3, -1}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) l.vertices[i][c] = v[i][c];
    return l;
}

static void test_vertex_count(void **state)
{
    (void)state;
    for (uint32_t n = 3; n <= 8; ++n) {
        viewer_light l = square();
        viewer_light_set_vertex_count(&l, n);
        assert_int_equal(l.vertex_count, n);
        float center[3], normal[3];
        viewer_light_center(&l, center);
        viewer_light_normal(&l, normal);
        assert_float_equal(center[0], 0.0f, 1e-5f);
        assert_float_equal(center[1], 3.0f, 1e-5f);
        assert_float_equal(center[2], 0.0f, 1e-5f);
        assert_float_equal(normal[1], -1.0f, 1e-5f); // still facing down
        // Circumradius sqrt(2) (the square's mean radius): area = n/2 R^2 sin(2 pi / n).
        assert_float_equal(polygon_area(&l), 0.5 * n * 2.0 * sin(2.0 * pi / n), 1e-5);
    }
    viewer_light l = square();
    viewer_light_set_vertex_count(&l, 9); // out of range: unchanged
    viewer_light_set_vertex_count(&l, 2);
    assert_int_equal(l.vertex_count, 4);
}

static void test_rotate_scale_translate(void **state)
{
    (void)state;
    viewer_light l = square();
    viewer_light_rotate(&l, 1, (float)(pi / 2)); // about +Y: (1, 0, 1) -> (1, 0, -1) around the centre
    assert_float_equal(l.vertices[0][0], 1.0f, 1e-5f);
    assert_float_equal(l.vertices[0][2], -1.0f, 1e-5f);
    viewer_light_rotate(&l, 0, (float)(pi / 2)); // about +X: the down normal (0, -1, 0) -> (0, 0, -1)
    float normal[3];
    viewer_light_normal(&l, normal);
    assert_float_equal(normal[2], -1.0f, 1e-5f);
    viewer_light_scale(&l, 2.0f);
    assert_float_equal(polygon_area(&l), 16.0, 1e-4);
    viewer_light_translate(&l, (const float[3]){0.5f, -1.0f, 2.0f});
    float center[3];
    viewer_light_center(&l, center);
    assert_float_equal(center[0], 0.5f, 1e-5f);
    assert_float_equal(center[1], 2.0f, 1e-5f);
    assert_float_equal(center[2], 2.0f, 1e-5f);
}

// The transform the edits compose (the light's emissive mesh is drawn with it instead of being
// re-uploaded) maps the polygon as uploaded onto the edited polygon.
static void test_tracked_transform(void **state)
{
    (void)state;
    viewer_light l = square();
    float uploaded[4][3];
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) uploaded[v][c] = l.vertices[v][c];
    viewer_light_rotate(&l, 0, 0.3f);
    viewer_light_translate(&l, (const float[3]){0.25f, -0.5f, 1.0f});
    viewer_light_scale(&l, 1.7f);
    viewer_light_rotate(&l, 2, -1.1f);
    viewer_light_rotate(&l, 1, 2.0f);
    assert_false(l.reshaped);
    for (int v = 0; v < 4; ++v)
        for (int r = 0; r < 3; ++r) {
            float x = l.transform[12 + r]; // column-major: m[col * 4 + row]
            for (int c = 0; c < 3; ++c) x += l.transform[c * 4 + r] * uploaded[v][c];
            assert_float_equal(x, l.vertices[v][r], 1e-5f);
        }
    viewer_light_set_vertex_count(&l, 6); // not affine: needs a new mesh
    assert_true(l.reshaped);
}

static void test_load_quad_light(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/quad_light.gltf"));
    // One light: emissiveFactor (1, 0.95, 0.9) x emissiveStrength 8, a 0.8 x 0.8 quad
    // (corners at +-0.5657 along the diagonals) at y = 1.4, facing down; primitive 1 is it.
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.material_count, 2);
    assert_float_equal(s.lights[0].intensity, 8.0f, 1e-5f);
    assert_float_equal(s.lights[0].color[1], 0.95f, 1e-5f);
    assert_float_equal(polygon_area(&s.lights[0]), 4.0 * 0.5656854249 * 0.5656854249, 1e-5);
    assert_false(s.lights[0].two_sided);
    assert_false(s.primitive_is_light[0]);
    assert_true(s.primitive_is_light[1]);
    assert_float_equal(s.materials[0].roughness, 0.35f, 1e-6f);
    assert_float_equal(s.materials[0].metallic, 1.0f, 1e-6f);
    viewer_scene_destroy(&s);
    assert_false(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/no_such_scene.gltf"));
}

// showcase (scenes.json): five lights, the KHR extensions mapped as the engine's loader path
// maps them (clearcoat roughness = 1 - the loader's gloss), and rays from the camera picking
// the copper sphere, the white quad light and nothing.
static void test_showcase(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/showcase.gltf"));
    assert_int_equal(s.light_count, 5);
    assert_int_equal(s.material_count, 12);
    const rtpbr_material_desc *layered = &s.materials[3], *velvet = &s.materials[5], *steel = &s.materials[6];
    assert_float_equal(layered->clearcoat_factor, 1.0f, 1e-6f);
    assert_float_equal(layered->clearcoat_roughness_factor, 0.05f, 1e-6f);
    assert_float_equal(layered->ior, 1.5f, 1e-6f);
    assert_float_equal(velvet->sheen_color_factor[1], 0.6f, 1e-6f);
    assert_float_equal(velvet->sheen_roughness_factor, 0.35f, 1e-6f);
    assert_float_equal(steel->anisotropy_strength, 0.8f, 1e-6f);
    const float eye[3] = {0.0f, 1.5f, 6.5f};
    const float to_copper[3] = {-1.725f - eye[0], 0.45f - eye[1], 0.0f - eye[2]}; // sphere 1 of 6, spacing 1.15
    int32_t light, material;
    assert_true(viewer_scene_pick(&s, eye, to_copper, &light, &material));
    assert_int_equal(light, -1);
    assert_int_equal(material, 2);
    const float to_quad[3] = {-0.9f - eye[0], 1.8f - eye[1], -2.8f - eye[2]};
    assert_true(viewer_scene_pick(&s, eye, to_quad, &light, &material));
    assert_int_equal(material, -1);
    assert_int_equal(s.lights[light].material, 9); // light_white
    const float up[3] = {0.0f, 1.0f, -0.2f};
    assert_false(viewer_scene_pick(&s, eye, up, &light, &material));
    viewer_scene_destroy(&s);
}

// punctual_lights (tools/make-scenes, KHR_lights_punctual): a warm point light with a range,
// a cool spot, a low sun; no area light. Numbers from the file.
static void test_load_punctual(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/punctual_lights.gltf"));
    assert_int_equal(s.light_count, 0);
    assert_int_equal(s.punctual_count, 3);
    assert_int_equal(viewer_scene_light_total(&s), 3);
    const viewer_punctual *point = &s.punctual[0], *spot = &s.punctual[1], *sun = &s.punctual[2];
    assert_int_equal(point->type, RTPBR_LIGHT_POINT);
    assert_int_equal(spot->type, RTPBR_LIGHT_SPOT);
    assert_int_equal(sun->type, RTPBR_LIGHT_DIRECTIONAL);
    assert_string_equal(viewer_punctual_kind(spot), "spot");
    const float point_position[3] = {-2.2f, 1.8f, 1.2f}, point_color[3] = {1.0f, 0.75f, 0.5f};
    for (int c = 0; c < 3; ++c) {
        assert_float_equal(point->position[c], point_position[c], 1e-6f);
        assert_float_equal(point->color[c], point_color[c], 1e-6f);
    }
    assert_float_equal(point->intensity, 4.0f, 1e-6f);
    assert_float_equal(point->range, 9.0f, 1e-6f);
    assert_float_equal(spot->intensity, 12.0f, 1e-6f);
    assert_float_equal(spot->color[0], 0.55f, 1e-6f);
    assert_float_equal(spot->range, 0.0f, 0.0f); // none in the file: infinite
    assert_float_equal(spot->inner_cone_angle, 0.24434609527920614, 1e-6f);
    assert_float_equal(spot->outer_cone_angle, 0.4188790204786391, 1e-6f);
    assert_float_equal(sun->intensity, 1.2f, 1e-6f);
    assert_float_equal(sun->color[2], 0.88f, 1e-6f);
    float azimuth, elevation;
    viewer_punctual_angles(spot, &azimuth, &elevation);
    assert_true(elevation < -0.5f); // the spot looks down at the floor
    viewer_punctual_angles(sun, &azimuth, &elevation);
    assert_true(elevation < 0.0f && elevation > -0.8f); // a low sun, shining down
    for (uint32_t i = 0; i < 3; ++i) { // colour x intensity = the loader's intensity, within an ulp
        const float *loaded = s.loaded->punctual_lights[i].intensity;
        for (int c = 0; c < 3; ++c)
            assert_float_equal(s.punctual[i].color[c] * s.punctual[i].intensity, loaded[c], 1.2e-7f * loaded[c]);
    }
    viewer_scene_destroy(&s);
}

static void test_punctual_edits(void **state)
{
    (void)state;
    viewer_punctual p = {.type = RTPBR_LIGHT_SPOT, .direction = {0.0f, 0.0f, 1.0f}, .intensity = 1.0f,
                         .inner_cone_angle = 0.2f, .outer_cone_angle = 0.4f};
    viewer_punctual_rotate(&p, 1, (float)(pi / 2)); // about +Y, right-handed: +Z -> +X
    assert_float_equal(p.direction[0], 1.0f, 1e-6f);
    assert_float_equal(p.direction[2], 0.0f, 1e-6f);
    viewer_punctual_rotate(&p, 2, (float)(pi / 2)); // about +Z: +X -> +Y
    assert_float_equal(p.direction[1], 1.0f, 1e-6f);
    // Two angles: (cos e sin a, sin e, cos e cos a), and back.
    viewer_punctual_set_angles(&p, 0.7f, -0.4f);
    assert_float_equal(p.direction[0], cos(-0.4) * sin(0.7), 1e-6f);
    assert_float_equal(p.direction[1], sin(-0.4), 1e-6f);
    assert_float_equal(p.direction[2], cos(-0.4) * cos(0.7), 1e-6f);
    float azimuth, elevation;
    viewer_punctual_angles(&p, &azimuth, &elevation);
    assert_float_equal(azimuth, 0.7f, 1e-5f);
    assert_float_equal(elevation, -0.4f, 1e-5f);
    viewer_punctual_set_angles(&p, 1.0f, (float)(-pi / 2)); // straight down: azimuth 0
    viewer_punctual_angles(&p, &azimuth, &elevation);
    assert_float_equal(elevation, -pi / 2, 1e-5f);
    // The clamp: cones crossed or too wide, a negative intensity and range, a zero direction.
    p = (viewer_punctual){.type = RTPBR_LIGHT_SPOT, .intensity = -1.0f, .range = -2.0f, .color = {2.0f, 0.5f, -1.0f},
                          .inner_cone_angle = 1.0f, .outer_cone_angle = 0.5f};
    viewer_punctual_clamp(&p);
    assert_float_equal(p.intensity, 0.0f, 0.0f);
    assert_float_equal(p.range, 0.0f, 0.0f);
    assert_float_equal(p.color[0], 1.0f, 0.0f);
    assert_float_equal(p.color[2], 0.0f, 0.0f);
    assert_float_equal(p.direction[1], -1.0f, 0.0f);
    assert_true(p.inner_cone_angle >= 0.0f && p.inner_cone_angle < p.outer_cone_angle);
    assert_float_equal(p.outer_cone_angle, 0.5f, 0.0f);
    p.outer_cone_angle = 3.0f;
    p.direction[0] = 3.0f, p.direction[1] = 0.0f, p.direction[2] = 4.0f;
    viewer_punctual_clamp(&p);
    assert_float_equal(p.outer_cone_angle, pi / 2, 1e-6f);
    assert_float_equal(p.direction[0], 0.6f, 1e-6f);
    assert_float_equal(p.direction[2], 0.8f, 1e-6f);
    p.outer_cone_angle = 0.0f;
    viewer_punctual_clamp(&p);
    assert_float_equal(p.outer_cone_angle, VIEWER_MIN_CONE, 0.0f);
    assert_true(p.inner_cone_angle < p.outer_cone_angle);
}

// The order I adds lights in (viewer.c cycles viewer_new_light's kinds 0, 1, ...): a quad, a
// disk, a sphere, a spot, a point, a directional light, a tube, an ellipse and a screen, each of
// the kind its name says (the tube: a point light with a radius and a length, the engine's
// RTPBR_LIGHT_TUBE; the ellipse a disk with a second half-axis; the screen a quad showing the
// viewer's test card).
static void test_new_light_order(void **state)
{
    (void)state;
    static const char *const names[] = {"quad", "disk", "sphere", "spot", "point", "directional", "tube", "ellipse",
                                        "screen"};
    static const char *const area_kinds[] = {[0] = "polygon", [1] = "disk", [7] = "ellipse", [8] = "screen"};
    static const rtpbr_light_type types[] = {RTPBR_LIGHT_POLYGON, RTPBR_LIGHT_DISK, RTPBR_LIGHT_POINT,
                                             RTPBR_LIGHT_SPOT,    RTPBR_LIGHT_POINT, RTPBR_LIGHT_DIRECTIONAL,
                                             RTPBR_LIGHT_POINT,   RTPBR_LIGHT_DISK,  RTPBR_LIGHT_POLYGON};
    assert_int_equal(VIEWER_NEW_LIGHT_KINDS, 9);
    const float at[3] = {1.0f, 2.0f, 3.0f};
    for (int kind = 0; kind < VIEWER_NEW_LIGHT_KINDS; ++kind) {
        assert_string_equal(viewer_new_light_name(kind), names[kind]);
        viewer_light l;
        viewer_punctual p;
        bool area = viewer_new_light(kind, at, &l, &p);
        assert_int_equal(area, kind <= 1 || kind >= 7);
        assert_int_equal(area ? l.type : p.type, types[kind]);
        if (area) assert_string_equal(viewer_light_kind(&l), area_kinds[kind]);
        if (!area) assert_float_equal(p.radius, kind == 2 ? 0.1f : kind == 6 ? 0.05f : 0.0f, 0.0f); // the sphere: radius 0.1
        if (!area) assert_float_equal(p.length, kind == 6 ? 0.8f : 0.0f, 0.0f);
        if (!area) assert_string_equal(viewer_punctual_kind(&p), kind == 6 ? "tube" : kind == 3 ? "spot" : kind == 5 ? "directional" : "point");
    }
    assert_string_equal(viewer_new_light_name(VIEWER_NEW_LIGHT_KINDS), "?");
}

// The disk I adds (issue 30): the quad's twin, facing down at `at` with the quad's area
// (0.25 m^2: radius 0.5 / sqrt(pi)) and radiance 4, so its power; in a scene its desc is an
// RTPBR_LIGHT_DISK with that centre, normal and radius (not a polygon). Moving, turning and
// scaling it move its centre, turn its normal and scale its radius, and the tracked transform
// (its drawn fan's) maps the uploaded disk onto the edited one; the scale stops at the radius
// limits, the transform with it; [ / ] (the vertex count) leaves it alone.
static void test_new_disk(void **state)
{
    (void)state;
    const float at[3] = {0.5f, 2.0f, -1.0f};
    viewer_light l;
    viewer_punctual p;
    assert_true(viewer_new_light(VIEWER_NEW_DISK, at, &l, &p));
    assert_int_equal(l.type, RTPBR_LIGHT_DISK);
    assert_string_equal(viewer_light_kind(&l), "disk");
    assert_float_equal(pi * l.radius * l.radius, 0.25, 1e-6);
    assert_float_equal(l.intensity, 4.0f, 0.0f);
    assert_int_equal(l.vertex_count, 0);
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/quad_light.gltf"));
    assert_true(viewer_scene_add_light(&s, &l));
    assert_int_equal(s.light_count, 2);
    assert_true(viewer_scene_needs_upload(&s));
    rtpbr_light_desc descs[2];
    viewer_scene_light_descs(&s, descs);
    assert_int_equal(descs[0].type, RTPBR_LIGHT_POLYGON); // the file's quad
    const rtpbr_light_desc *d = &descs[1];
    assert_int_equal(d->type, RTPBR_LIGHT_DISK);
    for (int c = 0; c < 3; ++c) {
        assert_float_equal(d->position[c], at[c], 0.0f);
        assert_float_equal(d->direction[c], c == 1 ? -1.0f : 0.0f, 0.0f);
        assert_float_equal(d->emission[c], 4.0f, 0.0f);
    }
    assert_float_equal(d->radius, 0.5 / sqrt(pi), 1e-7);
    assert_false(d->two_sided);

    viewer_light *disk = &s.lights[1];
    const float uploaded_center[3] = {at[0], at[1], at[2]}, uploaded_rim[3] = {at[0] + d->radius, at[1], at[2]};
    viewer_light_translate(disk, (const float[3]){0.25f, -0.5f, 1.0f});
    viewer_light_rotate(disk, 0, (float)(pi / 2)); // about +X: the down normal (0, -1, 0) -> (0, 0, -1)
    viewer_light_scale(disk, 2.0f);
    viewer_scene_light_descs(&s, descs);
    const float moved[3] = {0.75f, 1.5f, 0.0f};
    for (int c = 0; c < 3; ++c) assert_float_equal(d->position[c], moved[c], 1e-6f);
    assert_float_equal(d->direction[0], 0.0f, 1e-6f);
    assert_float_equal(d->direction[1], 0.0f, 1e-6f);
    assert_float_equal(d->direction[2], -1.0f, 1e-6f);
    assert_float_equal(d->radius, 1.0 / sqrt(pi), 1e-6);
    float center[3], normal[3];
    viewer_light_center(disk, center);
    viewer_light_normal(disk, normal);
    assert_float_equal(viewer_light_radius(disk), d->radius, 0.0f);
    for (int c = 0; c < 3; ++c) assert_float_equal(center[c], d->position[c], 0.0f);
    for (int c = 0; c < 3; ++c) assert_float_equal(normal[c], d->direction[c], 0.0f);
    // The transform takes the uploaded centre to the centre and a rim point (+X of it, which
    // the turn about X keeps) to the rim at the new radius.
    float mapped[2][3];
    for (int k = 0; k < 2; ++k) {
        const float *q = k == 0 ? uploaded_center : uploaded_rim;
        for (int r = 0; r < 3; ++r) {
            mapped[k][r] = disk->transform[12 + r];
            for (int c = 0; c < 3; ++c) mapped[k][r] += disk->transform[c * 4 + r] * q[c];
        }
    }
    for (int c = 0; c < 3; ++c) assert_float_equal(mapped[0][c], moved[c], 1e-6f);
    assert_float_equal(mapped[1][0] - mapped[0][0], d->radius, 1e-6f);
    viewer_light_scale(disk, 1e-9f); // stops at the smallest radius, and the transform with it
    assert_float_equal(disk->radius, VIEWER_MIN_DISK_RADIUS, 1e-9f);
    assert_float_equal(disk->transform[0], VIEWER_MIN_DISK_RADIUS / (0.5 / sqrt(pi)), 1e-6f);
    viewer_light_scale(disk, 1e9f);
    assert_float_equal(disk->radius, VIEWER_MAX_DISK_RADIUS, 0.0f);
    viewer_light_set_vertex_count(disk, 5); // a disk has no vertices
    assert_int_equal(disk->type, RTPBR_LIGHT_DISK);
    assert_int_equal(disk->vertex_count, 0);
    assert_false(disk->reshaped);
    viewer_scene_destroy(&s);
}

// The ellipse I adds (issue 30): facing down at `at`, half-axes 0.4 m along +X and 0.2 m across
// (so along Z), radiance 4; its desc an RTPBR_LIGHT_DISK with disk_radius2 0.2 and disk_axis +X.
// Picking follows the ellipse (not its long half-axis' circle): rays from below hit 0.35 m out
// along the axis, and miss 0.3 m out across it (inside that circle), hit 0.15 m across. A turn of
// 90 degrees about +Y turns the axis to -Z (and the picking with it); a scale scales both
// half-axes, and stops when either reaches a limit; set_radius2 stretches a circle into an
// ellipse (axis in its plane, the drawn fan's transform stretched across it: a rim point across
// the axis maps to the new half-axis) and back (r2 = radius: a circle); NaN changes nothing.
static void test_new_ellipse(void **state)
{
    (void)state;
    const float at[3] = {0.5f, 2.0f, -1.0f};
    viewer_light l;
    viewer_punctual p;
    assert_true(viewer_new_light(VIEWER_NEW_ELLIPSE, at, &l, &p));
    assert_string_equal(viewer_light_kind(&l), "ellipse");
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/quad_light.gltf"));
    assert_true(viewer_scene_add_light(&s, &l));
    rtpbr_light_desc descs[2];
    viewer_scene_light_descs(&s, descs);
    const rtpbr_light_desc *d = &descs[1];
    assert_int_equal(d->type, RTPBR_LIGHT_DISK);
    assert_float_equal(d->radius, 0.4f, 0.0f);
    assert_float_equal(d->disk_radius2, 0.2f, 0.0f);
    for (int c = 0; c < 3; ++c) assert_float_equal(d->disk_axis[c], c == 0 ? 1.0f : 0.0f, 0.0f);
    assert_float_equal(d->direction[1], -1.0f, 0.0f);

    // rays straight up from 0.1 m below the centre, offset (dx, dz)
    const float up[3] = {0.0f, 1.0f, 0.0f};
#define PICKS(dx, dz)                                                                                     \
    (viewer_scene_pick(&s, (const float[3]){at[0] + (dx), at[1] - 0.1f, at[2] + (dz)}, up, &light, &material) && \
     light == 1)
    int32_t light, material;
    assert_true(PICKS(0.0f, 0.0f));
    assert_true(PICKS(0.35f, 0.0f));
    assert_true(PICKS(-0.35f, 0.0f));
    assert_true(PICKS(0.0f, 0.15f));
    assert_false(PICKS(0.0f, 0.3f));
    assert_false(PICKS(0.0f, -0.3f));
    viewer_light *e = &s.lights[1];
    viewer_light_rotate(e, 1, (float)(pi / 2)); // about +Y: +X -> -Z
    viewer_scene_light_descs(&s, descs);
    assert_float_equal(d->disk_axis[0], 0.0f, 1e-6f);
    assert_float_equal(d->disk_axis[2], -1.0f, 1e-6f);
    assert_float_equal(d->direction[1], -1.0f, 1e-6f);
    assert_true(PICKS(0.0f, 0.35f));
    assert_false(PICKS(0.3f, 0.0f));
#undef PICKS
    viewer_light_scale(e, 2.0f);
    assert_float_equal(e->radius, 0.8f, 1e-6f);
    assert_float_equal(e->radius2, 0.4f, 1e-6f);
    viewer_light_scale(e, 1e9f); // stops when the long half-axis reaches the largest radius
    assert_float_equal(e->radius, VIEWER_MAX_DISK_RADIUS, 1e-3f);
    assert_float_equal(e->radius2, 0.5f * VIEWER_MAX_DISK_RADIUS, 1e-3f);
    viewer_light_scale(e, 1e-9f); // and the short one the smallest
    assert_float_equal(e->radius2, VIEWER_MIN_DISK_RADIUS, 1e-8f);
    assert_float_equal(e->radius, 2.0f * VIEWER_MIN_DISK_RADIUS, 1e-8f);
    assert_string_equal(viewer_light_kind(e), "ellipse");

    viewer_light c; // a circle stretched into an ellipse, and back
    assert_true(viewer_new_light(VIEWER_NEW_DISK, at, &c, &p));
    float r = c.radius;
    viewer_light_set_radius2(&c, NAN);
    assert_string_equal(viewer_light_kind(&c), "disk");
    viewer_light_set_radius2(&c, 0.5f * r);
    assert_string_equal(viewer_light_kind(&c), "ellipse");
    assert_float_equal(viewer_light_radius2(&c), 0.5f * r, 1e-7f);
    assert_float_equal(c.radius, r, 0.0f);
    float an = c.axis[0] * c.normal[0] + c.axis[1] * c.normal[1] + c.axis[2] * c.normal[2];
    assert_float_equal(an, 0.0f, 1e-6f);
    assert_float_equal(c.axis[0] * c.axis[0] + c.axis[1] * c.axis[1] + c.axis[2] * c.axis[2], 1.0f, 1e-6f);
    const float *n = c.normal; // across = n x axis: a rim point there maps to half its distance
    float across[3] = {n[1] * c.axis[2] - n[2] * c.axis[1], n[2] * c.axis[0] - n[0] * c.axis[2],
                       n[0] * c.axis[1] - n[1] * c.axis[0]};
    float rim[3], along[3], mapped[2][3];
    for (int k = 0; k < 3; ++k) rim[k] = at[k] + r * across[k], along[k] = at[k] + r * c.axis[k];
    for (int q = 0; q < 2; ++q)
        for (int row = 0; row < 3; ++row) {
            const float *x = q == 0 ? rim : along;
            mapped[q][row] = c.transform[12 + row];
            for (int col = 0; col < 3; ++col) mapped[q][row] += c.transform[col * 4 + row] * x[col];
        }
    for (int k = 0; k < 3; ++k) assert_float_equal(mapped[0][k], at[k] + 0.5f * r * across[k], 1e-6f);
    for (int k = 0; k < 3; ++k) assert_float_equal(mapped[1][k], along[k], 1e-6f);
    viewer_light_set_radius2(&c, r);
    assert_string_equal(viewer_light_kind(&c), "disk");
    assert_float_equal(c.transform[0], 1.0f, 1e-6f);
    viewer_scene_destroy(&s);
}

// light_shapes (tools/make-scenes): two EXT_lights_area disks (radius 0.45 and 0.5 m), a rect
// and a sphere. The viewer has each disk as the disk the engine's loader path makes of it
// (rtpbr_gpu_scene_from_loaded: centre, normal and radius as the loader has them), not as the
// loader's octagon; the rect stays a quad. Moving a disk moves the desc's centre; turning it
// turns the desc's normal; a ray from in front at its centre picks it, one just outside its
// rim (inside the octagon's corner) does not.
static void test_load_light_shapes(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/light_shapes.gltf"));
    assert_int_equal(s.light_count, 3);
    assert_int_equal(s.punctual_count, 1);
    const float radii[2] = {0.45f, 0.5f};
    for (uint32_t i = 0; i < 2; ++i) {
        const rtpbr_gltf_light *in = &s.loaded->lights[i];
        const viewer_light *l = &s.lights[i];
        assert_int_equal(in->shape, RTPBR_GLTF_LIGHT_DISK);
        assert_int_equal(l->type, RTPBR_LIGHT_DISK);
        assert_int_equal(l->vertex_count, 0);
        assert_float_equal(l->radius, radii[i], 1e-6f);
        for (int c = 0; c < 3; ++c) {
            assert_float_equal(l->center[c], in->facts.center[c], 0.0f);
            assert_float_equal(l->normal[c], in->facts.normal[c], 0.0f);
        }
    }
    assert_int_equal(s.lights[2].type, RTPBR_LIGHT_POLYGON);
    assert_int_equal(s.lights[2].vertex_count, 4);
    rtpbr_light_desc descs[4];
    viewer_scene_light_descs(&s, descs);
    for (uint32_t i = 0; i < 2; ++i) {
        assert_int_equal(descs[i].type, RTPBR_LIGHT_DISK);
        assert_float_equal(descs[i].radius, s.loaded->lights[i].radius, 0.0f);
        for (int c = 0; c < 3; ++c) {
            assert_float_equal(descs[i].position[c], s.loaded->lights[i].facts.center[c], 0.0f);
            assert_float_equal(descs[i].direction[c], s.loaded->lights[i].facts.normal[c], 0.0f);
        }
    }
    assert_int_equal(descs[2].type, RTPBR_LIGHT_POLYGON);
    assert_int_equal(descs[3].type, RTPBR_LIGHT_POINT);

    // Picking: from 1 m in front of disk 0 (the overhead one), at its centre and 1.02 radii
    // out along a direction in its plane (the equal-area octagon reaches 1.054 radii at its
    // corners: the old octagon would be hit there at some angles, the disk never).
    const viewer_light *disk = &s.lights[0];
    float eye[3], toward[3];
    for (int c = 0; c < 3; ++c) eye[c] = disk->center[c] + disk->normal[c], toward[c] = -disk->normal[c];
    int32_t light, material;
    assert_true(viewer_scene_pick(&s, eye, toward, &light, &material));
    assert_int_equal(light, 0);
    float t[3] = {disk->normal[1], -disk->normal[0], 0.0f}; // in the plane
    float tl = sqrtf(t[0] * t[0] + t[1] * t[1]);
    for (int c = 0; c < 3; ++c) t[c] /= tl;
    int hits = 0;
    for (int k = 0; k < 64; ++k) { // rays 1.02 radii out, all around, none hits the disk
        float angle = 2.0f * (float)pi * (float)k / 64.0f, b[3] = {
            disk->normal[1] * t[2] - disk->normal[2] * t[1], disk->normal[2] * t[0] - disk->normal[0] * t[2],
            disk->normal[0] * t[1] - disk->normal[1] * t[0]};
        float from[3];
        for (int c = 0; c < 3; ++c)
            from[c] = eye[c] + 1.02f * disk->radius * (cosf(angle) * t[c] + sinf(angle) * b[c]);
        hits += viewer_scene_pick(&s, from, toward, &light, &material) && light == 0;
    }
    assert_int_equal(hits, 0);

    viewer_light *moved = &s.lights[0];
    viewer_light_translate(moved, (const float[3]){0.5f, -0.25f, 0.125f});
    viewer_light_rotate(moved, 1, 0.3f);
    viewer_scene_light_descs(&s, descs);
    const float *c0 = s.loaded->lights[0].facts.center, *n0 = s.loaded->lights[0].facts.normal;
    assert_float_equal(descs[0].position[0], c0[0] + 0.5f, 1e-6f);
    assert_float_equal(descs[0].position[1], c0[1] - 0.25f, 1e-6f);
    assert_float_equal(descs[0].position[2], c0[2] + 0.125f, 1e-6f);
    // about +Y, right-handed: (x, z) -> (x cos + z sin, -x sin + z cos)
    assert_float_equal(descs[0].direction[0], n0[0] * cosf(0.3f) + n0[2] * sinf(0.3f), 1e-6f);
    assert_float_equal(descs[0].direction[1], n0[1], 1e-6f);
    assert_float_equal(descs[0].direction[2], -n0[0] * sinf(0.3f) + n0[2] * cosf(0.3f), 1e-6f);
    viewer_scene_destroy(&s);
}

// ---- on the device ------------------------------------------------------------------------

enum { RW = 160, RH = 120 };

// The file's first camera, as rtpbr_gpu_scene_from_loaded maps it (the viewer's upload has no
// cameras: both scenes are rendered from this one).
static rtpbr_camera_desc file_camera(const viewer_scene *s)
{
    const rtpbr_gltf_camera *c = &s->loaded->cameras[0];
    rtpbr_camera_desc d = {.yfov = c->yfov, .znear = c->znear, .zfar = c->zfar};
    for (int k = 0; k < 3; ++k) {
        d.position[k] = c->position[k];
        d.target[k] = c->position[k] + c->forward[k];
        d.up[k] = c->up[k];
    }
    return d;
}

// What each device test starts from: a bundled scene in the viewer, the file's camera, an
// RW x RH renderer on the fixture's context.
typedef struct device_case {
    rtpbr_context *ctx;
    viewer_scene s;
    rtpbr_camera_desc camera;
    rtpbr_renderer *r;
} device_case;

static void device_case_open(device_case *d, void **state, const char *scene)
{
    d->ctx = test_env_context(state);
    assert_true(viewer_scene_load(&d->s, scene));
    d->camera = file_camera(&d->s);
    d->r = test_renderer(d->ctx, &(rtpbr_renderer_desc){.width = RW, .height = RH});
}

static void device_case_close(device_case *d)
{
    rtpbr_renderer_destroy(d->r);
    viewer_scene_destroy(&d->s);
}

// An upload of the viewer's scene as it is now.
static rtpbr_gpu_scene *upload(device_case *d)
{
    rtpbr_gpu_scene *gpu = NULL;
    assert_int_equal(viewer_scene_upload(&d->s, d->ctx, &gpu), RTPBR_SUCCESS);
    return gpu;
}

static float *render(const device_case *d, const rtpbr_gpu_scene *gpu)
{
    return test_render_radiance(d->r, gpu, &(rtpbr_render_desc){.camera = &d->camera}, RW, RH);
}

// Pixels (of RW x RH) whose RGB differ at all; the largest difference relative to the larger
// value's magnitude, in *max_rel.
static size_t pixels_differing(const float *a, const float *b, double *max_rel)
{
    size_t count = 0;
    *max_rel = 0.0;
    for (size_t i = 0; i < (size_t)RW * RH; ++i) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            double x = a[4 * i + c], y = b[4 * i + c], d = fabs(x - y);
            differs |= d != 0.0;
            if (d > 0.0) *max_rel = fmax(*max_rel, d / fmax(fabs(x), fabs(y)));
        }
        count += differs;
    }
    return count;
}

// Pixels with some radiance (any channel above 1e-3: the floor and spheres where lit).
static size_t pixels_lit(const float *a)
{
    size_t count = 0;
    for (size_t i = 0; i < (size_t)RW * RH; ++i)
        count += a[4 * i] > 1e-3f || a[4 * i + 1] > 1e-3f || a[4 * i + 2] > 1e-3f;
    return count;
}

// The viewer's upload of punctual_lights renders the radiance of rtpbr_gpu_scene_from_loaded
// of the same loaded file (what rtpbr-render shows): the same meshes and materials in the same
// order (no area lights, so no light polygons), the lights in the same order; the only
// difference allowed is the emission, which the viewer keeps as colour x intensity (the loader's
// emission divided by its largest component and multiplied back: within one float ulp, at most
// 1.2e-7 relative, of the loader's; the spot's red is one ulp off). Radiance is linear in each
// light's emission, so pixels may differ by a few ulps of their value: 1e-6 relative is allowed
// (measured: 336 of 19,200 pixels differ, by at most 2.2e-7; the others are bit for bit).
// Before issue 30 the viewer uploaded the area lights only: that image is black where this one
// is lit, which the same comparison rejects.
static void test_punctual_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/punctual_lights.gltf");
    rtpbr_gpu_scene *engine = NULL, *viewer = upload(&d);
    assert_int_equal(rtpbr_gpu_scene_from_loaded(d.ctx, d.s.loaded, &engine), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_gpu_scene_light_count(viewer), 3);
    float *want = render(&d, engine), *got = render(&d, viewer);
    double max_rel;
    size_t differing = pixels_differing(want, got, &max_rel), lit = pixels_lit(want);
    printf("viewer upload vs rtpbr_gpu_scene_from_loaded: %zu of %d pixels differ (max relative %.3g); %zu lit\n",
           differing, RW * RH, max_rel, lit);
    assert_true(lit > (size_t)RW * RH / 2);
    assert_true(max_rel <= 1e-6);
    uint32_t punctual_count = d.s.punctual_count; // the upload of the viewer before issue 30
    d.s.punctual_count = 0;
    rtpbr_gpu_scene *area_only = upload(&d);
    d.s.punctual_count = punctual_count;
    float *old = render(&d, area_only);
    assert_true(pixels_lit(old) < lit / 10);
    assert_true(pixels_differing(want, old, &max_rel) > lit / 2 && max_rel > 1e-6);
    free(want);
    free(got);
    free(old);
    rtpbr_gpu_scene_destroy(area_only);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// sphere_lights (point lights with radii, extras.radius): the viewer reads each radius and its
// upload shades the spheres as rtpbr_gpu_scene_from_loaded does; with the radii zeroed (true
// points) the image differs.
static void test_sphere_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/sphere_lights.gltf");
    assert_int_equal(d.s.punctual_count, 3);
    assert_float_equal(d.s.punctual[0].radius, 0.25f, 0.0f);
    assert_float_equal(d.s.punctual[1].radius, 0.4f, 0.0f);
    rtpbr_gpu_scene *engine = NULL, *viewer = upload(&d);
    assert_int_equal(rtpbr_gpu_scene_from_loaded(d.ctx, d.s.loaded, &engine), RTPBR_SUCCESS);
    float *want = render(&d, engine), *got = render(&d, viewer);
    double max_rel;
    size_t differing = pixels_differing(want, got, &max_rel), lit = pixels_lit(want);
    printf("spheres: viewer upload vs rtpbr_gpu_scene_from_loaded: %zu of %d pixels differ (max relative %.3g); %zu lit\n",
           differing, RW * RH, max_rel, lit);
    assert_true(lit > (size_t)RW * RH / 2);
    assert_true(max_rel <= 1e-6);
    for (uint32_t i = 0; i < d.s.punctual_count; ++i) d.s.punctual[i].radius = 0.0f;
    rtpbr_gpu_scene *points = upload(&d);
    float *old = render(&d, points);
    assert_true(pixels_differing(want, old, &max_rel) > lit / 4 && max_rel > 1e-3);
    // the clamp: a negative or NaN radius is 0
    d.s.punctual[0].radius = -1.0f;
    viewer_punctual_clamp(&d.s.punctual[0]);
    assert_float_equal(d.s.punctual[0].radius, 0.0f, 0.0f);
    d.s.punctual[0].radius = NAN;
    viewer_punctual_clamp(&d.s.punctual[0]);
    assert_float_equal(d.s.punctual[0].radius, 0.0f, 0.0f);
    free(want);
    free(got);
    free(old);
    rtpbr_gpu_scene_destroy(points);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// Pixels (of RW x RH) where some channel differs by more than `rel` of the larger value.
static size_t pixels_beyond(const float *a, const float *b, double rel)
{
    size_t count = 0;
    for (size_t i = 0; i < (size_t)RW * RH; ++i) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            double x = a[4 * i + c], y = b[4 * i + c];
            differs |= fabs(x - y) > rel * fmax(fabs(x), fabs(y));
        }
        count += differs;
    }
    return count;
}

// light_shapes' disks in the viewer are the disks the engine shades (issue 30). The viewer's
// upload renders what rtpbr_gpu_scene_from_loaded renders: no pixel differs beyond 1e-5
// relative (colour x intensity may be one ulp off the loader's radiance). The viewer also
// draws its area lights' surfaces, which rtpbr-render does not for EXT_lights_area lights, but
// from the file's camera all three show their backs (one-sided: culled). The viewer of before,
// which had each disk as the loader's equal-area octagon, differs on most lit pixels (measured:
// 7,268 of 11,152). Moving disk 0 in place (update_lights, no upload) renders what the engine's
// loader path renders for the file with that disk moved (its centre and octagon moved by the
// same offset); the move changes most lit pixels.
// The viewer's upload of d's scene against rtpbr_gpu_scene_from_loaded's: no pixel differs
// beyond 1e-5, and more than RW x RH / min_lit_part pixels are lit. Returns the engine's image
// (want) and both scenes; the number of lit pixels.
static size_t upload_matches_engine(device_case *d, const char *what, size_t min_lit_part, float **want,
                                    rtpbr_gpu_scene **engine, rtpbr_gpu_scene **viewer)
{
    *engine = NULL;
    *viewer = upload(d);
    assert_int_equal(rtpbr_gpu_scene_from_loaded(d->ctx, d->s.loaded, engine), RTPBR_SUCCESS);
    *want = render(d, *engine);
    float *got = render(d, *viewer);
    size_t lit = pixels_lit(*want), differing = pixels_beyond(*want, got, 1e-5);
    printf("%s: viewer upload vs rtpbr_gpu_scene_from_loaded: %zu of %d pixels differ beyond 1e-5; %zu lit\n", what,
           differing, RW * RH, lit);
    assert_true(lit > (size_t)RW * RH / min_lit_part);
    assert_int_equal(differing, 0);
    free(got);
    return lit;
}

static void test_disk_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/light_shapes.gltf");
    rtpbr_gpu_scene *engine, *viewer;
    float *want;
    size_t lit = upload_matches_engine(&d, "light_shapes", 2, &want, &engine, &viewer);

    viewer_scene *s = &d.s; // the viewer of before: the disks as their octagons
    viewer_light disks[2] = {s->lights[0], s->lights[1]};
    for (uint32_t i = 0; i < 2; ++i) {
        const rtpbr_gltf_light *in = &s->loaded->lights[i];
        s->lights[i].type = RTPBR_LIGHT_POLYGON;
        s->lights[i].vertex_count = in->vertex_count;
        memcpy(s->lights[i].vertices, in->vertices, sizeof in->vertices);
    }
    rtpbr_gpu_scene *octagons = upload(&d);
    float *old = render(&d, octagons);
    size_t old_differing = pixels_beyond(want, old, 1e-5);
    printf("light_shapes: the disks as octagons: %zu pixels differ beyond 1e-5\n", old_differing);
    assert_true(old_differing > lit / 2);
    s->lights[0] = disks[0], s->lights[1] = disks[1];

    const float offset[3] = {0.4f, -0.3f, -0.5f};
    viewer_light_translate(&s->lights[0], offset);
    assert_false(viewer_scene_needs_upload(s));
    assert_int_equal(viewer_scene_update_lights(s, viewer), RTPBR_SUCCESS);
    float *moved = render(&d, viewer);
    rtpbr_gltf_light *in = &s->loaded->lights[0]; // the file with disk 0 moved
    for (int c = 0; c < 3; ++c) {
        in->facts.center[c] += offset[c];
        for (uint32_t v = 0; v < in->vertex_count; ++v) in->vertices[v][c] += offset[c];
    }
    rtpbr_gpu_scene *engine_moved = NULL;
    assert_int_equal(rtpbr_gpu_scene_from_loaded(d.ctx, s->loaded, &engine_moved), RTPBR_SUCCESS);
    float *want_moved = render(&d, engine_moved);
    size_t moved_differing = pixels_beyond(want_moved, moved, 1e-5), move_changes = pixels_beyond(want, want_moved, 1e-5);
    printf("light_shapes, disk 0 moved in place: %zu pixels differ from the engine's moved disk beyond 1e-5; the move "
           "changes %zu\n", moved_differing, move_changes);
    assert_int_equal(moved_differing, 0);
    assert_true(move_changes > lit / 2);
    free(want);
    free(old);
    free(moved);
    free(want_moved);
    rtpbr_gpu_scene_destroy(engine_moved);
    rtpbr_gpu_scene_destroy(octagons);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// An EXT_lights_area disk under an uneven node scale is an ellipse (the loader's radius2 and
// axis: tests/scene, test_ext_lights_area_ellipse); the viewer has it as that ellipse (issue
// 30). light_shapes' overhead disk is made one in the loaded scene (its half-axis across an
// in-plane axis halved), and viewer_light_from_loaded maps it again: the viewer's upload renders
// what rtpbr_gpu_scene_from_loaded renders of that loaded scene (no pixel beyond 1e-5), and the
// viewer of before (the circle of its long half-axis: no radius2) differs on many lit pixels.
// Turning the ellipse about its own normal (here: a fresh load, the axis turned by 90 degrees in
// the loaded scene) changes the image.
static void test_ellipse_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/light_shapes.gltf");
    viewer_scene *s = &d.s;
    rtpbr_gltf_light *in = &s->loaded->lights[0];
    assert_int_equal(in->shape, RTPBR_GLTF_LIGHT_DISK);
    const float *n = in->facts.normal;
    float axis[3] = {n[1], -n[0], 0.0f}, len = sqrtf(axis[0] * axis[0] + axis[1] * axis[1]); // in its plane
    for (int c = 0; c < 3; ++c) axis[c] /= len;
    in->radius2 = 0.4f * in->radius;
    memcpy(in->axis, axis, sizeof axis);
    viewer_light_from_loaded(s->loaded, 0, &s->lights[0]);
    assert_string_equal(viewer_light_kind(&s->lights[0]), "ellipse");
    rtpbr_gpu_scene *engine, *viewer;
    float *want;
    size_t lit = upload_matches_engine(&d, "light_shapes, disk 0 an ellipse", 2, &want, &engine, &viewer);

    viewer_light ellipse = s->lights[0];
    s->lights[0].radius2 = 0.0f; // the viewer of before: the circle
    rtpbr_gpu_scene *circle = upload(&d);
    float *old = render(&d, circle);
    size_t old_differing = pixels_beyond(want, old, 1e-5);
    printf("light_shapes, disk 0 an ellipse: as its circle %zu pixels differ beyond 1e-5\n", old_differing);
    assert_true(old_differing > lit / 4);
    s->lights[0] = ellipse;

    float across[3] = {n[1] * axis[2] - n[2] * axis[1], n[2] * axis[0] - n[0] * axis[2], n[0] * axis[1] - n[1] * axis[0]};
    memcpy(in->axis, across, sizeof across); // the same ellipse turned a quarter about its normal
    viewer_light_from_loaded(s->loaded, 0, &s->lights[0]);
    for (int c = 0; c < 3; ++c) assert_float_equal(s->lights[0].axis[c], across[c], 1e-6f);
    rtpbr_gpu_scene *turned = upload(&d);
    float *turned_image = render(&d, turned);
    size_t turn_changes = pixels_beyond(want, turned_image, 1e-5);
    printf("light_shapes, the ellipse turned a quarter about its normal: changes %zu pixels\n", turn_changes);
    assert_true(turn_changes > lit / 4);
    free(want);
    free(old);
    free(turned_image);
    rtpbr_gpu_scene_destroy(turned);
    rtpbr_gpu_scene_destroy(circle);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// sRGB-encoded 8-bit value to linear (IEC 61966-2-1).
static double srgb_to_linear(uint8_t v)
{
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

// The screen I adds (issue 30): a quad showing the viewer's test card, which the upload appends
// to the scene's textures (the desc's emission_texture is 1 + the file's texture count). Lit by
// it from 0.1 m above the floor, the scene gets, per channel, the light of the same quad without
// a texture times about the card's mean linear value (computed here from its texels): the
// image's sum of what the screen adds, card / plain, within 5 % of that mean (measured: 1.4 %;
// the LTC's prefiltered lookup of a picture seen from nearby is not exactly its mean). The
// picture's layout shows on the floor: green over red is larger where the card's left (white,
// yellow, cyan, green bars) shines than where its right (magenta, red, blue) does, so the
// image's halves differ in that ratio (measured 1.04 and 0.47; a texture read as its mean
// would give one ratio).
static void test_screen_test_card(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/quad_light.gltf");
    viewer_scene *s = &d.s;
    uint32_t file_textures = s->loaded->texture_count;
    rtpbr_gpu_scene *base = upload(&d);
    float *base_image = render(&d, base);
    const float at[3] = {0.0f, 0.1f, 0.5f};
    viewer_light l;
    viewer_punctual p;
    assert_true(viewer_new_light(VIEWER_NEW_SCREEN, at, &l, &p));
    assert_int_equal(l.emission_texture, VIEWER_TEST_CARD);
    assert_true(viewer_scene_add_light(s, &l));
    rtpbr_light_desc descs[2];
    viewer_scene_light_descs(s, descs);
    assert_int_equal(descs[1].emission_texture, file_textures + 1);
    rtpbr_gpu_scene *card = upload(&d);
    float *card_image = render(&d, card);
    s->lights[1].emission_texture = 0;
    rtpbr_gpu_scene *plain = upload(&d);
    float *plain_image = render(&d, plain);

    uint8_t texels[VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT * 4];
    viewer_test_card(texels);
    double mean[3] = {0, 0, 0}, got[3] = {0, 0, 0}, want[3] = {0, 0, 0}, half[2][2] = {{0, 0}, {0, 0}};
    for (int i = 0; i < VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT; ++i)
        for (int c = 0; c < 3; ++c) mean[c] += srgb_to_linear(texels[4 * i + c]) / (VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT);
    for (int y = 0; y < RH; ++y)
        for (int x = 0; x < RW; ++x)
            for (int c = 0; c < 3; ++c) {
                size_t i = 4 * ((size_t)y * RW + x) + c;
                double added = card_image[i] - base_image[i];
                got[c] += added;
                want[c] += plain_image[i] - base_image[i];
                if (c < 2) half[x < RW / 2][c] += added; // red, green per half
            }
    for (int c = 0; c < 3; ++c) {
        printf("screen with the test card: channel %d adds %.4g x the plain quad's light; the card's mean %.4g\n", c,
               got[c] / want[c], mean[c]);
        assert_true(want[c] > 0.0);
        assert_true(fabs(got[c] / want[c] - mean[c]) < 0.05 * mean[c]);
    }
    double g_over_r[2] = {half[0][1] / half[0][0], half[1][1] / half[1][0]};
    printf("screen with the test card: green / red, right half %.3f, left half %.3f\n", g_over_r[0], g_over_r[1]);
    assert_true(fmax(g_over_r[0], g_over_r[1]) > 1.2 * fmin(g_over_r[0], g_over_r[1]));
    free(base_image);
    free(card_image);
    free(plain_image);
    rtpbr_gpu_scene_destroy(plain);
    rtpbr_gpu_scene_destroy(card);
    rtpbr_gpu_scene_destroy(base);
    device_case_close(&d);
}

// tube_lights' capsules in the viewer are the tubes the engine shades (issue 30): its upload
// renders what rtpbr_gpu_scene_from_loaded renders (no pixel beyond 1e-5 relative); the viewer of
// before, which dropped the length (each capsule its sphere), differs on most lit pixels. A
// tube turned about Y turns its axis (the viewer's rotate): its desc's direction is the turned
// axis and the image changes; a range keeps it a tube (its desc's range: the engine windows it
// at the distance from its centre), and the viewer with tube 0 given a range of 1.5 m renders
// what the loader path renders for the file with that range (no pixel beyond 1e-5), which the
// range changes; the clamp keeps the length in [0, 100] (NaN 0) and the axis unit.
static void test_tube_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/tube_lights.gltf");
    viewer_scene *s = &d.s;
    assert_int_equal(s->light_count, 0); // (descs[3] below: the punctual lights alone)
    assert_int_equal(s->punctual_count, 3);
    for (uint32_t i = 0; i < 3; ++i) assert_true(viewer_punctual_is_tube(&s->punctual[i]));
    assert_float_equal(s->punctual[0].length, 1.4f, 0.0f);
    assert_float_equal(s->punctual[1].axis[1], 1.0f, 1e-6f); // the upright one: +X turned 90 degrees about Z
    rtpbr_gpu_scene *engine, *viewer;
    float *want;
    size_t lit = upload_matches_engine(&d, "tube_lights", 2, &want, &engine, &viewer);
    rtpbr_light_desc descs[3];
    viewer_scene_light_descs(s, descs);
    for (uint32_t i = 0; i < 3; ++i) {
        const viewer_punctual *p = &s->punctual[i];
        double r = p->radius, L = p->length;
        assert_int_equal(descs[i].type, RTPBR_LIGHT_TUBE);
        assert_float_equal(descs[i].length, L, 0.0f);
        // power 4 pi I over the capsule's area 2 pi r (2 r + L), of a Lambertian surface: pi L_e A
        double want_radiance = 4.0 * pi * p->intensity * p->color[0] / (pi * 2.0 * pi * r * (2.0 * r + L));
        assert_float_equal(descs[i].emission[0], want_radiance, 1e-6 * want_radiance);
    }

    viewer_punctual tubes[3] = {s->punctual[0], s->punctual[1], s->punctual[2]};
    for (uint32_t i = 0; i < 3; ++i) s->punctual[i].length = 0.0f; // the viewer of before: spheres
    rtpbr_gpu_scene *spheres = upload(&d);
    float *old = render(&d, spheres);
    size_t old_differing = pixels_beyond(want, old, 1e-5);
    printf("tube_lights: the capsules as their spheres: %zu pixels differ beyond 1e-5\n", old_differing);
    assert_true(old_differing > lit / 2);
    for (uint32_t i = 0; i < 3; ++i) s->punctual[i] = tubes[i];

    viewer_punctual_rotate(&s->punctual[0], 1, 0.5f); // about Y: the overhead tube's axis turns in the floor's plane
    viewer_scene_light_descs(s, descs);
    assert_float_equal(descs[0].direction[0], cosf(0.5f), 1e-6f);
    assert_float_equal(fabsf(descs[0].direction[2]), sinf(0.5f), 1e-6f);
    assert_false(viewer_scene_needs_upload(s));
    assert_int_equal(viewer_scene_update_lights(s, viewer), RTPBR_SUCCESS);
    float *turned = render(&d, viewer);
    size_t turn_changes = pixels_beyond(want, turned, 1e-5);
    printf("tube_lights, tube 0 turned 0.5 rad about Y: changes %zu pixels\n", turn_changes);
    assert_true(turn_changes > lit / 20);

    s->punctual[0] = tubes[0];
    s->punctual[0].range = 1.5f;
    s->loaded->punctual_lights[0].range = 1.5f; // the file with that range
    assert_true(viewer_punctual_is_tube(&s->punctual[0]));
    assert_string_equal(viewer_punctual_kind(&s->punctual[0]), "tube");
    viewer_scene_light_descs(s, descs);
    assert_int_equal(descs[0].type, RTPBR_LIGHT_TUBE);
    assert_float_equal(descs[0].range, 1.5f, 0.0f);
    rtpbr_gpu_scene *ranged_engine, *ranged_viewer;
    float *ranged_want;
    upload_matches_engine(&d, "tube_lights, tube 0 with a range of 1.5 m", 2, &ranged_want, &ranged_engine,
                          &ranged_viewer);
    size_t range_changes = pixels_beyond(want, ranged_want, 1e-5);
    printf("tube_lights, tube 0 with a range of 1.5 m: changes %zu pixels\n", range_changes);
    assert_true(range_changes > lit / 20);
    free(ranged_want);
    rtpbr_gpu_scene_destroy(ranged_viewer);
    rtpbr_gpu_scene_destroy(ranged_engine);
    viewer_punctual q = tubes[0];
    q.length = NAN;
    q.axis[0] = q.axis[1] = q.axis[2] = 0.0f;
    viewer_punctual_clamp(&q);
    assert_float_equal(q.length, 0.0f, 0.0f);
    assert_float_equal(q.axis[0], 1.0f, 0.0f);
    q.length = 1e9f;
    q.axis[1] = 3.0f;
    viewer_punctual_clamp(&q);
    assert_float_equal(q.length, 100.0f, 0.0f);
    assert_float_equal(q.axis[0] * q.axis[0] + q.axis[1] * q.axis[1] + q.axis[2] * q.axis[2], 1.0f, 1e-6f);
    free(want);
    free(old);
    free(turned);
    rtpbr_gpu_scene_destroy(spheres);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// The loader's radiance of light `in` (a textured emitter's: the texture's mean) as the viewer's
// colour x intensity.
static void split_mean(const rtpbr_gltf_light *in, viewer_light *l)
{
    float m = fmaxf(in->radiance[0], fmaxf(in->radiance[1], in->radiance[2]));
    for (int c = 0; c < 3; ++c) l->color[c] = m > 0.0f ? in->radiance[c] / m : 0.0f;
    l->intensity = m;
}

// textured_light's screen in the viewer is the textured quad the engine shades (issue 30): its
// upload renders what rtpbr_gpu_scene_from_loaded renders (the light and the screen's surface,
// its picture), no pixel beyond 1e-5. The viewer of before lit the screen at the loader's mean
// of its texture and drew its surface at the texel (0, 0): most lit pixels differ. Moving the
// screen in place (set_lights with the creation's texture and coordinates) is accepted and
// changes the image.
static void test_screen_upload_matches_engine(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/textured_light.gltf");
    viewer_scene *s = &d.s;
    assert_true(s->light_count == 1 && s->lights[0].emission_texture != 0);
    rtpbr_gpu_scene *engine, *viewer;
    float *want;
    size_t lit = upload_matches_engine(&d, "textured_light", 4, &want, &engine, &viewer);

    viewer_light screen = s->lights[0]; // the viewer of before: the mean, no texture
    s->lights[0].emission_texture = 0;
    split_mean(&s->loaded->lights[0], &s->lights[0]);
    rtpbr_gpu_scene *mean = upload(&d);
    float *old = render(&d, mean);
    size_t old_differing = pixels_beyond(want, old, 1e-5);
    printf("textured_light: lit at the texture's mean: %zu pixels differ beyond 1e-5\n", old_differing);
    assert_true(old_differing > lit / 2);
    s->lights[0] = screen;

    const float offset[3] = {0.1f, 0.05f, 0.0f};
    viewer_light_translate(&s->lights[0], offset);
    assert_false(viewer_scene_needs_upload(s));
    assert_int_equal(viewer_scene_update_lights(s, viewer), RTPBR_SUCCESS);
    float *moved = render(&d, viewer);
    size_t move_changes = pixels_beyond(want, moved, 1e-5);
    printf("textured_light, the screen moved in place: the move changes %zu pixels\n", move_changes);
    assert_true(move_changes > lit / 4);
    free(want);
    free(old);
    free(moved);
    rtpbr_gpu_scene_destroy(mean);
    rtpbr_gpu_scene_destroy(viewer);
    rtpbr_gpu_scene_destroy(engine);
    device_case_close(&d);
}

// More distinct textured screens than RTPBR_MAX_TEXTURED_LIGHTS: rtpbr_gpu_scene_from_loaded
// lights those past the limit at their texture's mean (a warning) instead of refusing the scene
// (scene creation alone refuses a desc with that many: RTPBR_ERROR_LIMIT_EXCEEDED). The loaded
// textured_light is given RTPBR_MAX_TEXTURED_LIGHTS + 1 copies of its screen, each on a copy of
// its primitive whose coordinates are shifted (a mapping, a chain of its own).
static void test_many_screens(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/textured_light.gltf");
    rtpbr_gltf_scene *in = d.s.loaded;
    const uint32_t n = RTPBR_MAX_TEXTURED_LIGHTS + 1, base = in->primitive_count;
    const rtpbr_gltf_light screen = in->lights[0];
    const rtpbr_gltf_primitive prim = in->primitives[screen.primitive];
    rtpbr_gltf_primitive *prims = malloc((base + n) * sizeof *prims);
    rtpbr_gltf_light *lights = malloc(n * sizeof *lights);
    float *uvs = malloc((size_t)n * prim.vertex_count * 2 * sizeof(float));
    assert_true(prims && lights && uvs);
    memcpy(prims, in->primitives, base * sizeof *prims);
    for (uint32_t k = 0; k < n; ++k) {
        float *uv = uvs + (size_t)k * prim.vertex_count * 2;
        for (uint32_t v = 0; v < 2 * prim.vertex_count; ++v) uv[v] = prim.texcoords[v] + (v % 2 ? 0.0f : 1e-3f * (float)k);
        prims[base + k] = prim;
        prims[base + k].texcoords = uv;
        lights[k] = screen;
        lights[k].primitive = (int32_t)(base + k);
    }
    rtpbr_gltf_primitive *old_prims = in->primitives;
    rtpbr_gltf_light *old_lights = in->lights;
    uint32_t old_prim_count = in->primitive_count, old_light_count = in->light_count;
    in->primitives = prims, in->primitive_count = base + n;
    in->lights = lights, in->light_count = n;
    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_from_loaded(d.ctx, in, &scene), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_gpu_scene_light_count(scene), n + in->punctual_light_count);
    rtpbr_gpu_scene_destroy(scene);
    in->primitives = old_prims, in->primitive_count = old_prim_count;
    in->lights = old_lights, in->light_count = old_light_count;
    free(prims);
    free(lights);
    free(uvs);
    device_case_close(&d);
}

// An edit of one light's intensity x2, through viewer_scene_update_lights (set_lights, no
// re-upload), doubles that light's part of the radiance: with R0 the image without it
// (intensity 0), R1 with it and R2 with twice its intensity, R2 - R0 = 2 (R1 - R0) at every
// pixel. Colour x intensity doubles exactly (x2 is exact in floats) and the shading is linear
// in emission; what may differ is the rounding of the sum over the three lights: 1e-5 of the
// pixel's value is allowed. Each light must light a good part of the image by itself.
static void test_punctual_intensity_doubles(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/punctual_lights.gltf");
    rtpbr_gpu_scene *gpu = upload(&d);
    for (uint32_t k = 0; k < d.s.punctual_count; ++k) {
        viewer_punctual *p = &d.s.punctual[k];
        float intensity = p->intensity, *images[3];
        for (int step = 0; step < 3; ++step) { // intensity 0, x1, x2
            p->intensity = intensity * (float)step;
            assert_int_equal(viewer_scene_update_lights(&d.s, gpu), RTPBR_SUCCESS);
            images[step] = render(&d, gpu);
        }
        p->intensity = intensity;
        size_t lit = 0, bad = 0;
        double worst = 0.0;
        for (size_t i = 0; i < (size_t)RW * RH; ++i) {
            bool is_lit = false;
            for (int c = 0; c < 3; ++c) {
                double r0 = images[0][4 * i + c], r1 = images[1][4 * i + c], r2 = images[2][4 * i + c];
                double part = r1 - r0, err = fabs((r2 - r0) - 2.0 * part);
                is_lit |= part > 1e-3;
                worst = fmax(worst, err / fmax(r2, 1e-30));
                bad += err > 1e-5 * r2 + 1e-9;
            }
            lit += is_lit;
        }
        printf("%s light: lit %zu of %d pixels by itself; x2: worst relative error %.3g\n",
               viewer_punctual_kind(p), lit, RW * RH, worst);
        assert_int_equal(bad, 0);
        assert_true(lit > (size_t)RW * RH / 20);
        for (int step = 0; step < 3; ++step) free(images[step]);
    }
    rtpbr_gpu_scene_destroy(gpu);
    device_case_close(&d);
}

// A mixed scene: quad_light (one polygonal light and its emissive quad) plus a point light
// added to the viewer's scene. The area light's image C (uploaded without the point light)
// must come back bit for bit when the point light's intensity is set to 0 in place (set_lights
// keeps the area light as it was; a zero emission adds exactly 0), the mixed image A when it is
// restored, and A again after an update of the area light (viewer_scene_update_light replaces
// every light: the punctual one must stay).
static void test_mixed_scene_set_lights(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/quad_light.gltf");
    viewer_scene *s = &d.s;
    assert_int_equal(s->light_count, 1);
    assert_int_equal(s->punctual_count, 0);
    rtpbr_gpu_scene *area_only = upload(&d);
    float *area_image = render(&d, area_only);
    viewer_punctual *grown = realloc(s->punctual, sizeof *grown);
    assert_non_null(grown);
    s->punctual = grown;
    s->punctual[0] = (viewer_punctual){.type = RTPBR_LIGHT_POINT, .position = {1.5f, 0.6f, 1.0f},
                                       .color = {1.0f, 0.5f, 0.25f}, .intensity = 2.0f, .range = 4.0f};
    s->punctual_count = 1;
    rtpbr_gpu_scene *mixed = upload(&d);
    assert_int_equal(rtpbr_gpu_scene_light_count(mixed), 2);
    float *mixed_image = render(&d, mixed);
    double max_rel;
    size_t point_lit = pixels_differing(area_image, mixed_image, &max_rel);
    printf("mixed scene: the point light changes %zu of %d pixels\n", point_lit, RW * RH);
    assert_true(point_lit > (size_t)RW * RH / 10);

    s->punctual[0].intensity = 0.0f;
    assert_int_equal(viewer_scene_update_lights(s, mixed), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_gpu_scene_light_count(mixed), 2);
    float *dark = render(&d, mixed);
    size_t differing = pixels_differing(area_image, dark, &max_rel);
    printf("mixed scene, point light off in place vs the area light alone: %zu pixels differ (max relative %.3g)\n",
           differing, max_rel);
    assert_int_equal(differing, 0);

    s->punctual[0].intensity = 2.0f;
    assert_int_equal(viewer_scene_update_lights(s, mixed), RTPBR_SUCCESS);
    float *back = render(&d, mixed);
    assert_int_equal(pixels_differing(mixed_image, back, &max_rel), 0);
    assert_int_equal(viewer_scene_update_light(s, mixed, 0), RTPBR_SUCCESS); // the area light's path
    assert_int_equal(rtpbr_gpu_scene_light_count(mixed), 2);
    float *after_area = render(&d, mixed);
    assert_int_equal(pixels_differing(mixed_image, after_area, &max_rel), 0);
    free(area_image);
    free(mixed_image);
    free(dark);
    free(back);
    free(after_area);
    rtpbr_gpu_scene_destroy(mixed);
    rtpbr_gpu_scene_destroy(area_only);
    device_case_close(&d);
}

// Adding and removing lights (the viewer's I and X keys, its panel's buttons), issue 30: each
// kind viewer_new_light makes is what it says (a quad of 0.25 m^2 facing down, a disk of the
// same area facing down, a sphere of radius 0.1, a spot and a sun pointing down their
// directions, unit length, a tube of radius 0.05 and length 0.8); added to quad_light they make the scene need an upload, which has
// 1 + 7 lights and in which each added light lights pixels of its own (the image with it
// differs from the image without it, removed again); removing every added light (the disk among
// them) gives the scene's own image back bit for bit; a removal out of range is refused.
static void test_add_remove_lights(void **state)
{
    device_case d;
    device_case_open(&d, state, RTPBR_SAMPLES_SCENES "/quad_light.gltf");
    viewer_scene *s = &d.s;
    rtpbr_gpu_scene *base = upload(&d);
    float *base_image = render(&d, base);
    assert_false(viewer_scene_needs_upload(s));
    const float at[3] = {0.0f, 1.5f, 0.5f};
    for (int kind = 0; kind < VIEWER_NEW_LIGHT_KINDS; ++kind) {
        viewer_light l;
        viewer_punctual p;
        bool area = viewer_new_light(kind, at, &l, &p);
        assert_int_equal(area, kind == VIEWER_NEW_QUAD || kind == VIEWER_NEW_DISK || kind == VIEWER_NEW_ELLIPSE ||
                                   kind == VIEWER_NEW_SCREEN);
        if (area) {
            float n[3], c[3];
            viewer_light_normal(&l, n);
            viewer_light_center(&l, c);
            assert_float_equal(n[1], -1.0f, 1e-6f);
            for (int k = 0; k < 3; ++k) assert_float_equal(c[k], at[k], 1e-6f);
            if (kind == VIEWER_NEW_QUAD || kind == VIEWER_NEW_SCREEN)
                assert_float_equal(fabsf((l.vertices[1][0] - l.vertices[0][0]) * (l.vertices[2][2] - l.vertices[1][2])),
                                   kind == VIEWER_NEW_QUAD ? 0.25f : 0.36f, 1e-6f);
            else
                assert_float_equal(pi * l.radius * viewer_light_radius2(&l), kind == VIEWER_NEW_DISK ? 0.25 : pi * 0.08,
                                   1e-6);
            assert_true(viewer_scene_add_light(s, &l));
        } else {
            float len = sqrtf(p.direction[0] * p.direction[0] + p.direction[1] * p.direction[1] +
                              p.direction[2] * p.direction[2]);
            assert_float_equal(len, 1.0f, 1e-6f);
            assert_true(p.direction[1] < 0.0f);
            assert_float_equal(p.radius, kind == VIEWER_NEW_SPHERE ? 0.1f : kind == VIEWER_NEW_TUBE ? 0.05f : 0.0f, 0.0f);
            assert_int_equal(p.type, kind == VIEWER_NEW_SPOT          ? RTPBR_LIGHT_SPOT
                                     : kind == VIEWER_NEW_DIRECTIONAL ? RTPBR_LIGHT_DIRECTIONAL
                                                                      : RTPBR_LIGHT_POINT);
            assert_true(viewer_scene_add_punctual(s, &p));
        }
        assert_true(viewer_scene_needs_upload(s));
    }
    assert_int_equal(s->light_count, 5);
    assert_int_equal(s->punctual_count, 5);
    rtpbr_gpu_scene *all = upload(&d);
    assert_false(viewer_scene_needs_upload(s));
    assert_int_equal(rtpbr_gpu_scene_light_count(all), 10);
    float *all_image = render(&d, all);
    double max_rel;
    // Each added light, removed alone (viewer numbering: area lights first, so light k is the
    // one of kind kinds[k]), changes the image.
    static const int kinds[10] = {-1, VIEWER_NEW_QUAD, VIEWER_NEW_DISK, VIEWER_NEW_ELLIPSE, VIEWER_NEW_SCREEN,
                                  VIEWER_NEW_SPHERE, VIEWER_NEW_SPOT, VIEWER_NEW_POINT, VIEWER_NEW_DIRECTIONAL,
                                  VIEWER_NEW_TUBE};
    for (uint32_t k = 1; k < 10; ++k) {
        viewer_scene copy = *s; // the arrays are shared: remove from a copy of the arrays
        viewer_light *lights = malloc(s->light_count * sizeof *lights);
        viewer_punctual *punctual = malloc(s->punctual_count * sizeof *punctual);
        assert_non_null(lights);
        assert_non_null(punctual);
        memcpy(lights, s->lights, s->light_count * sizeof *lights);
        memcpy(punctual, s->punctual, s->punctual_count * sizeof *punctual);
        copy.lights = lights, copy.punctual = punctual;
        assert_true(viewer_scene_remove_light(&copy, k));
        rtpbr_gpu_scene *without = NULL;
        assert_int_equal(viewer_scene_upload(&copy, d.ctx, &without), RTPBR_SUCCESS);
        assert_int_equal(rtpbr_gpu_scene_light_count(without), 9);
        float *image = render(&d, without);
        size_t changed = pixels_differing(all_image, image, &max_rel);
        printf("added light %u (%s): lights %zu of %d pixels\n", k, viewer_new_light_name(kinds[k]), changed,
               RW * RH);
        assert_true(changed > (size_t)RW * RH / 20 && max_rel > 1e-3);
        free(image);
        rtpbr_gpu_scene_destroy(without);
        free(copy.lights);
        free(copy.punctual);
    }
    assert_false(viewer_scene_remove_light(s, 10));
    while (s->punctual_count) assert_true(viewer_scene_remove_light(s, s->light_count));
    assert_string_equal(viewer_light_kind(&s->lights[4]), "screen");
    assert_true(viewer_scene_remove_light(s, 4));
    assert_string_equal(viewer_light_kind(&s->lights[3]), "ellipse");
    assert_true(viewer_scene_remove_light(s, 3));
    assert_int_equal(s->lights[2].type, RTPBR_LIGHT_DISK);
    assert_true(viewer_scene_remove_light(s, 2)); // the disk
    assert_int_equal(s->lights[1].type, RTPBR_LIGHT_POLYGON);
    assert_true(viewer_scene_remove_light(s, 1));
    assert_int_equal(s->light_count, 1);
    rtpbr_gpu_scene *back = upload(&d);
    float *back_image = render(&d, back);
    assert_int_equal(pixels_differing(base_image, back_image, &max_rel), 0);
    free(base_image);
    free(all_image);
    free(back_image);
    rtpbr_gpu_scene_destroy(back);
    rtpbr_gpu_scene_destroy(all);
    rtpbr_gpu_scene_destroy(base);
    device_case_close(&d);
}

RTPBR_TEST_MAIN_SHARED_ENV(cmocka_unit_test(test_vertex_count),
                cmocka_unit_test(test_rotate_scale_translate),
                cmocka_unit_test(test_tracked_transform),
                cmocka_unit_test(test_load_quad_light),
                cmocka_unit_test(test_showcase),
                cmocka_unit_test(test_load_punctual),
                cmocka_unit_test(test_punctual_edits),
                cmocka_unit_test(test_new_light_order),
                cmocka_unit_test(test_new_disk),
                cmocka_unit_test(test_new_ellipse),
                cmocka_unit_test(test_load_light_shapes),
                test_env_shared_case(test_punctual_upload_matches_engine),
                test_env_shared_case(test_sphere_upload_matches_engine),
                test_env_shared_case(test_disk_upload_matches_engine),
                test_env_shared_case(test_ellipse_upload_matches_engine),
                test_env_shared_case(test_tube_upload_matches_engine),
                test_env_shared_case(test_screen_test_card),
                test_env_shared_case(test_screen_upload_matches_engine),
                test_env_shared_case(test_many_screens),
                test_env_shared_case(test_punctual_intensity_doubles),
                test_env_shared_case(test_mixed_scene_set_lights),
                test_env_shared_case(test_add_remove_lights))
