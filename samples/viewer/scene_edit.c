// The viewer's editable scene (see scene_edit.h).
#include "scene_edit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void mat4_identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

// m = a * m (column-major 4x4, affine).
static void mat4_premultiply(float m[16], const float a[16])
{
    float r[16];
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float sum = 0.0f;
            for (int k = 0; k < 4; ++k) sum += a[k * 4 + row] * m[c * 4 + k];
            r[c * 4 + row] = sum;
        }
    memcpy(m, r, sizeof r);
}

// The loader's warnings (ignored extensions, a scene without lights, ...) on stderr.
static void on_loader_log(rtpbr_gltf_log_level level, const char *message, void *user)
{
    (void)user;
    if (level <= RTPBR_GLTF_LOG_WARNING)
        fprintf(stderr, "rtpbr-viewer: %s: %s\n", level == RTPBR_GLTF_LOG_ERROR ? "error" : "warning", message);
}

// An emission as colour (max component 1) times intensity (colour x intensity: the emission
// within a float ulp; e / peak * peak is not always e).
static void split_emission(const float emission[3], float color[3], float *intensity)
{
    float peak = fmaxf(emission[0], fmaxf(emission[1], emission[2]));
    *intensity = peak;
    for (int c = 0; c < 3; ++c) color[c] = peak > 0.0f ? emission[c] / peak : 1.0f;
}

// An ellipse's axis made unit and perpendicular to its normal (its part in the plane, as the
// engine takes it); a circle (radius2 0) when that part is zero or not finite.
static void ellipse_axis_in_plane(viewer_light *l)
{
    const float *n = l->normal;
    float an = l->axis[0] * n[0] + l->axis[1] * n[1] + l->axis[2] * n[2], len = 0.0f;
    for (int c = 0; c < 3; ++c) l->axis[c] -= an * n[c], len += l->axis[c] * l->axis[c];
    len = sqrtf(len);
    if (!(len > 1e-6f) || !isfinite(len)) {
        l->radius2 = 0.0f;
        l->axis[0] = l->axis[1] = l->axis[2] = 0.0f;
        return;
    }
    for (int c = 0; c < 3; ++c) l->axis[c] /= len;
}

void viewer_light_from_loaded(const rtpbr_gltf_scene *in, uint32_t i, viewer_light *v)
{
    const rtpbr_gltf_light *l = &in->lights[i];
    memset(v, 0, sizeof *v);
    rtpbr_light_desc engine; // rtpbr_gpu_scene_from_loaded's light: a screen's texture, its emission
    rtpbr_light_desc_from_loaded(in, i, &engine);
    v->emission_texture = engine.emission_texture;
    memcpy(v->emission_uv, engine.emission_uv, sizeof v->emission_uv);
    if (l->shape == RTPBR_GLTF_LIGHT_DISK) { // the disk, as rtpbr_gpu_scene_from_loaded has it (not its octagon)
        v->type = RTPBR_LIGHT_DISK;
        memcpy(v->center, l->facts.center, sizeof v->center);
        memcpy(v->normal, l->facts.normal, sizeof v->normal);
        v->radius = l->radius;
        if (engine.disk_radius2 > 0.0f) { // an ellipse (a disk node scaled unevenly)
            v->radius2 = engine.disk_radius2;
            memcpy(v->axis, engine.disk_axis, sizeof v->axis);
            ellipse_axis_in_plane(v);
        }
    } else {
        v->vertex_count = l->vertex_count;
        memcpy(v->vertices, l->vertices, sizeof v->vertices);
    }
    split_emission(engine.emission, v->color, &v->intensity);
    v->two_sided = l->two_sided;
    v->material = l->material >= 0 && (uint32_t)l->material < in->material_count ? l->material : -1;
    mat4_identity(v->transform);
}

bool viewer_scene_load(viewer_scene *s, const char *path)
{
    memset(s, 0, sizeof *s);
    char error[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_load_desc desc = {.error_message = error, .error_message_size = sizeof error,
                                 .logger = {on_loader_log, NULL}};
    rtpbr_gltf_result r = rtpbr_gltf_load(path, &desc, &s->loaded);
    if (r != RTPBR_GLTF_SUCCESS) {
        fprintf(stderr, "rtpbr-viewer: %s: %s: %s\n", path, rtpbr_gltf_result_string(r), error);
        return false;
    }
    const rtpbr_gltf_scene *in = s->loaded;
    s->material_count = in->material_count;
    s->light_count = in->light_count;
    s->punctual_count = in->punctual_light_count;
    s->materials = calloc(in->material_count ? in->material_count : 1, sizeof *s->materials);
    s->lights = calloc(in->light_count ? in->light_count : 1, sizeof *s->lights);
    s->punctual = calloc(in->punctual_light_count ? in->punctual_light_count : 1, sizeof *s->punctual);
    s->primitive_is_light = calloc(in->primitive_count ? in->primitive_count : 1, sizeof *s->primitive_is_light);
    if (!s->materials || !s->lights || !s->punctual || !s->primitive_is_light) {
        fprintf(stderr, "rtpbr-viewer: out of memory\n");
        viewer_scene_destroy(s);
        return false;
    }
    // The glTF mapping of docs/materials.md, rtpbr_gpu_scene_from_loaded's.
    for (uint32_t i = 0; i < in->material_count; ++i) rtpbr_material_desc_from_loaded(in, i, &s->materials[i]);
    for (uint32_t i = 0; i < in->light_count; ++i) {
        const rtpbr_gltf_light *l = &in->lights[i];
        viewer_light_from_loaded(in, i, &s->lights[i]);
        if (l->primitive >= 0 && (uint32_t)l->primitive < in->primitive_count) s->primitive_is_light[l->primitive] = true;
    }
    // rtpbr_gpu_scene_from_loaded's mapping of the punctual lights.
    for (uint32_t i = 0; i < in->punctual_light_count; ++i) {
        const rtpbr_gltf_punctual_light *l = &in->punctual_lights[i];
        viewer_punctual *p = &s->punctual[i];
        p->type = l->type == RTPBR_GLTF_PUNCTUAL_SPOT          ? RTPBR_LIGHT_SPOT
                  : l->type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL ? RTPBR_LIGHT_DIRECTIONAL
                                                               : RTPBR_LIGHT_POINT;
        memcpy(p->position, l->position, sizeof p->position);
        memcpy(p->direction, l->direction, sizeof p->direction);
        split_emission(l->intensity, p->color, &p->intensity);
        p->range = l->range;
        p->inner_cone_angle = l->inner_cone_angle;
        p->outer_cone_angle = l->outer_cone_angle;
        p->angular_diameter = l->angular_diameter;
        p->radius = l->type == RTPBR_GLTF_PUNCTUAL_POINT ? l->radius : 0.0f;
        p->length = p->radius > 0.0f ? l->length : 0.0f;
        memcpy(p->axis, l->axis, sizeof p->axis);
        if (!(p->length > 0.0f)) p->axis[0] = 1.0f, p->axis[1] = p->axis[2] = 0.0f;
    }
    return true;
}

void viewer_scene_destroy(viewer_scene *s)
{
    rtpbr_gltf_destroy(s->loaded);
    free(s->materials);
    free(s->lights);
    free(s->punctual);
    free(s->primitive_is_light);
    memset(s, 0, sizeof *s);
}

// Light i's surface: its source material (as the engine's loader path draws it) with the
// edited emission, or a black emitter.
static rtpbr_material_desc light_material(const viewer_scene *s, uint32_t i)
{
    const viewer_light *l = &s->lights[i];
    rtpbr_material_desc m = {.roughness = 1.0f};
    if (l->material >= 0) m = s->materials[l->material];
    for (int c = 0; c < 3; ++c) m.emission[c] = l->color[c] * l->intensity;
    // a screen's surface carries its coordinates already transformed (emission_uv)
    if (l->emission_texture && l->vertex_count == 4) m.emission_texture_transform = (rtpbr_texture_transform){0};
    m.double_sided = l->two_sided;
    return m;
}

void viewer_scene_light_descs(const viewer_scene *s, rtpbr_light_desc *out)
{
    for (uint32_t i = 0; i < s->light_count; ++i) {
        const viewer_light *l = &s->lights[i];
        rtpbr_light_desc *d = &out[i];
        *d = (rtpbr_light_desc){.two_sided = l->two_sided};
        if (l->type == RTPBR_LIGHT_DISK) {
            d->type = RTPBR_LIGHT_DISK;
            memcpy(d->position, l->center, sizeof d->position);
            memcpy(d->direction, l->normal, sizeof d->direction);
            d->radius = l->radius;
            if (l->radius2 > 0.0f) {
                d->disk_radius2 = l->radius2;
                memcpy(d->disk_axis, l->axis, sizeof d->disk_axis);
            }
        } else {
            d->vertex_count = l->vertex_count;
            memcpy(d->vertices, l->vertices, sizeof d->vertices);
            d->emission_texture = l->vertex_count != 4                 ? 0
                                  : l->emission_texture == VIEWER_TEST_CARD ? s->loaded->texture_count + 1
                                                                           : l->emission_texture;
            memcpy(d->emission_uv, l->emission_uv, sizeof d->emission_uv);
        }
        for (int c = 0; c < 3; ++c) d->emission[c] = l->color[c] * l->intensity;
    }
    for (uint32_t i = 0; i < s->punctual_count; ++i) {
        const viewer_punctual *p = &s->punctual[i];
        rtpbr_light_desc *d = &out[s->light_count + i];
        *d = (rtpbr_light_desc){.type = p->type, .range = p->range, .inner_cone_angle = p->inner_cone_angle,
                                .outer_cone_angle = p->outer_cone_angle,
                                .angular_diameter = p->angular_diameter > 0.0f ? p->angular_diameter : -1.0f,
                                .radius = p->type == RTPBR_LIGHT_POINT ? p->radius : 0.0f};
        memcpy(d->position, p->position, sizeof d->position);
        memcpy(d->direction, p->direction, sizeof d->direction);
        for (int c = 0; c < 3; ++c) d->emission[c] = p->color[c] * p->intensity;
        if (viewer_punctual_is_tube(p)) { // rtpbr_gpu_scene_from_loaded's capsule: radiance 2 I / (pi r (2 r + L))
            double r = p->radius, scale = 2.0 / (3.14159265358979323846 * r * (2.0 * r + p->length));
            d->type = RTPBR_LIGHT_TUBE;
            d->length = p->length;
            memcpy(d->direction, p->axis, sizeof d->direction);
            for (int c = 0; c < 3; ++c) d->emission[c] = (float)(d->emission[c] * scale);
        }
    }
}

// The most vertices of a light's emissive surface: a polygon's, or a disk's inscribed polygon.
#define OUTLINE_MAX (VIEWER_DISK_SEGMENTS > RTPBR_MAX_POLYGON_VERTICES ? VIEWER_DISK_SEGMENTS : RTPBR_MAX_POLYGON_VERTICES)

// A unit tangent frame (t, b) of the unit normal n with t x b = n: angles from t toward b turn
// counter-clockwise seen from the front.
static void tangent_frame(const float n[3], float t[3], float b[3])
{
    // t: the world axis least along n, made perpendicular to it
    int axis = fabsf(n[0]) <= fabsf(n[1]) && fabsf(n[0]) <= fabsf(n[2]) ? 0 : fabsf(n[1]) <= fabsf(n[2]) ? 1 : 2;
    float len = 0.0f;
    for (int c = 0; c < 3; ++c) {
        t[c] = (c == axis ? 1.0f : 0.0f) - n[axis] * n[c];
        len += t[c] * t[c];
    }
    len = sqrtf(len);
    for (int c = 0; c < 3; ++c) t[c] /= len;
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
}

// A disk's frame (t, b), t x b = its normal: an ellipse's t is its axis; a circle's, its normal's
// tangent_frame.
static void disk_frame(const viewer_light *l, float t[3], float b[3])
{
    if (!(l->radius2 > 0.0f)) {
        tangent_frame(l->normal, t, b);
        return;
    }
    const float *n = l->normal;
    memcpy(t, l->axis, 3 * sizeof(float));
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
}

// The outline of light l's emissive surface, counter-clockwise seen from the front: a polygon's
// vertices, or the VIEWER_DISK_SEGMENTS-gon inscribed in a disk (its ellipse: the circle's image
// under the stretch across the axis). Returns the count.
static uint32_t light_outline(const viewer_light *l, float out[OUTLINE_MAX][3])
{
    if (l->type != RTPBR_LIGHT_DISK) {
        memcpy(out, l->vertices, l->vertex_count * sizeof l->vertices[0]);
        return l->vertex_count;
    }
    float t[3], b[3], r2 = l->radius2 > 0.0f ? l->radius2 : l->radius;
    disk_frame(l, t, b);
    for (uint32_t v = 0; v < VIEWER_DISK_SEGMENTS; ++v) {
        float angle = 6.28318530718f * (float)v / (float)VIEWER_DISK_SEGMENTS;
        for (int c = 0; c < 3; ++c)
            out[v][c] = l->center[c] + l->radius * cosf(angle) * t[c] + r2 * sinf(angle) * b[c];
    }
    return VIEWER_DISK_SEGMENTS;
}

rtpbr_result viewer_scene_upload(viewer_scene *s, rtpbr_context *ctx, rtpbr_gpu_scene **out)
{
    const rtpbr_gltf_scene *in = s->loaded;
    rtpbr_texture_desc *textures = calloc(in->texture_count + 1, sizeof *textures);
    uint32_t texture_count = in->texture_count;
    static uint8_t card[VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT * 4]; // the test card, if shown
    bool shows_card = false;
    for (uint32_t i = 0; i < s->light_count; ++i)
        shows_card |= s->lights[i].vertex_count == 4 && s->lights[i].emission_texture == VIEWER_TEST_CARD;
    uint32_t mesh_cap = in->primitive_count + s->light_count;
    rtpbr_mesh_desc *meshes = calloc(mesh_cap ? mesh_cap : 1, sizeof *meshes);
    rtpbr_material_desc *materials = calloc(s->material_count + s->light_count + 1, sizeof *materials);
    uint32_t light_total = s->light_count + s->punctual_count;
    rtpbr_light_desc *lights = calloc(light_total ? light_total : 1, sizeof *lights);
    // Light surfaces as triangle fans: at most OUTLINE_MAX vertices, OUTLINE_MAX - 2 triangles each.
    float *light_positions = calloc((size_t)s->light_count * OUTLINE_MAX * 3 + 1, sizeof(float));
    float *light_normals = calloc((size_t)s->light_count * OUTLINE_MAX * 3 + 1, sizeof(float));
    float *light_uvs = calloc((size_t)s->light_count * OUTLINE_MAX * 2 + 1, sizeof(float));
    uint32_t *light_indices = calloc((size_t)s->light_count * (OUTLINE_MAX - 2) * 3 + 1, sizeof(uint32_t));
    rtpbr_result r = RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    if (!meshes || !materials || !lights || !light_positions || !light_normals || !light_indices || !textures ||
        !light_uvs)
        goto done;
    for (uint32_t i = 0; i < in->texture_count; ++i) rtpbr_texture_desc_from_loaded(in, i, &textures[i]);
    if (shows_card) { // the last texture (viewer_scene_light_descs' index)
        viewer_test_card(card);
        textures[texture_count++] = (rtpbr_texture_desc){.width = VIEWER_TEST_CARD_WIDTH,
            .height = VIEWER_TEST_CARD_HEIGHT, .rgba = card, .srgb = 1, .wrap_s = RTPBR_WRAP_CLAMP_TO_EDGE,
            .wrap_t = RTPBR_WRAP_CLAMP_TO_EDGE};
    }
    memcpy(materials, s->materials, s->material_count * sizeof *materials);
    uint32_t mesh_count = 0;
    for (uint32_t i = 0; i < in->primitive_count; ++i) {
        const rtpbr_gltf_primitive *p = &in->primitives[i];
        if (s->primitive_is_light[i] || p->vertex_count == 0 || p->index_count == 0) continue;
        meshes[mesh_count++] = (rtpbr_mesh_desc){.positions = p->positions, .normals = p->normals,
            .texcoords = p->texcoords, .texcoords1 = p->has_texcoords1 ? p->texcoords1 : NULL, .tangents = p->has_tangents ? p->tangents : NULL, .indices = p->indices,
            .vertex_count = p->vertex_count, .index_count = p->index_count, .material = p->material};
    }
    s->light_mesh_base = mesh_count;
    for (uint32_t i = 0; i < s->light_count; ++i) {
        viewer_light *l = &s->lights[i];
        materials[s->material_count + i] = light_material(s, i);
        mat4_identity(l->transform);
        l->reshaped = false;
        float *pos = light_positions + (size_t)i * OUTLINE_MAX * 3;
        float *nrm = light_normals + (size_t)i * OUTLINE_MAX * 3;
        float *uv = light_uvs + (size_t)i * OUTLINE_MAX * 2;
        uint32_t *idx = light_indices + (size_t)i * (OUTLINE_MAX - 2) * 3;
        float n[3], outline[OUTLINE_MAX][3];
        viewer_light_normal(l, n);
        uint32_t count = light_outline(l, outline);
        for (uint32_t v = 0; v < count; ++v) {
            memcpy(pos + 3 * v, outline[v], 3 * sizeof(float));
            memcpy(nrm + 3 * v, n, 3 * sizeof(float));
        }
        // a screen's surface shows its texture: the corners' coordinates (emission_uv at v0, v1,
        // v3; v2's the parallelogram's fourth)
        bool textured = l->emission_texture && count == 4;
        for (int c = 0; c < 2 && textured; ++c) {
            uv[c] = l->emission_uv[0][c];
            uv[2 + c] = l->emission_uv[1][c];
            uv[4 + c] = l->emission_uv[1][c] + l->emission_uv[2][c] - l->emission_uv[0][c];
            uv[6 + c] = l->emission_uv[2][c];
        }
        for (uint32_t t = 0; t + 2 < count; ++t) {
            idx[3 * t] = 0;
            idx[3 * t + 1] = t + 1;
            idx[3 * t + 2] = t + 2;
        }
        meshes[mesh_count++] = (rtpbr_mesh_desc){.positions = pos, .normals = nrm, .texcoords = textured ? uv : NULL,
            .indices = idx, .vertex_count = count, .index_count = 3 * (count - 2), .material = s->material_count + i};
    }
    viewer_scene_light_descs(s, lights);
    s->lights_restructured = false;
    // No cameras: the viewer always passes its orbit camera to rtpbr_record.
    rtpbr_gpu_scene_desc desc = {.meshes = meshes, .mesh_count = mesh_count, .materials = materials,
        .material_count = s->material_count + s->light_count, .lights = lights, .light_count = light_total,
        .textures = textures, .texture_count = texture_count};
    r = rtpbr_gpu_scene_create(ctx, &desc, out);
done:
    free(textures);
    free(meshes);
    free(materials);
    free(lights);
    free(light_positions);
    free(light_normals);
    free(light_uvs);
    free(light_indices);
    return r;
}

rtpbr_result viewer_scene_update_material(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t material)
{
    if (material >= s->material_count) return RTPBR_ERROR_INVALID_ARGUMENT;
    rtpbr_result r = rtpbr_gpu_scene_set_material(gpu, material, &s->materials[material]);
    // Lights drawn with this material as their surface follow it.
    for (uint32_t i = 0; i < s->light_count && r == RTPBR_SUCCESS; ++i)
        if (s->lights[i].material == (int32_t)material) r = viewer_scene_update_light(s, gpu, i);
    return r;
}

// Area light i's surface: its material and its mesh's transform.
static rtpbr_result update_light_surface(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t i)
{
    rtpbr_material_desc m = light_material(s, i);
    rtpbr_result r = rtpbr_gpu_scene_set_material(gpu, s->material_count + i, &m);
    if (r == RTPBR_SUCCESS) r = rtpbr_gpu_scene_set_transform(gpu, s->light_mesh_base + i, s->lights[i].transform);
    return r;
}

// rtpbr_gpu_scene_set_lights replaces them all: every light, in the upload's order.
static rtpbr_result set_all_lights(const viewer_scene *s, rtpbr_gpu_scene *gpu)
{
    uint32_t total = s->light_count + s->punctual_count;
    rtpbr_light_desc *lights = calloc(total ? total : 1, sizeof *lights);
    if (!lights) return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    viewer_scene_light_descs(s, lights);
    rtpbr_result r = rtpbr_gpu_scene_set_lights(gpu, lights, total);
    free(lights);
    return r;
}

rtpbr_result viewer_scene_update_light(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t light)
{
    if (light >= s->light_count) return RTPBR_ERROR_INVALID_ARGUMENT;
    rtpbr_result r = update_light_surface(s, gpu, light);
    return r == RTPBR_SUCCESS ? set_all_lights(s, gpu) : r;
}

rtpbr_result viewer_scene_update_lights(const viewer_scene *s, rtpbr_gpu_scene *gpu)
{
    rtpbr_result r = RTPBR_SUCCESS;
    for (uint32_t i = 0; i < s->light_count && r == RTPBR_SUCCESS; ++i) r = update_light_surface(s, gpu, i);
    return r == RTPBR_SUCCESS ? set_all_lights(s, gpu) : r;
}

bool viewer_scene_add_light(viewer_scene *s, const viewer_light *light)
{
    viewer_light *grown = realloc(s->lights, (s->light_count + 1) * sizeof *grown);
    if (!grown) return false;
    s->lights = grown;
    viewer_light *l = &s->lights[s->light_count++];
    *l = *light;
    l->material = -1;
    mat4_identity(l->transform);
    l->reshaped = false;
    s->lights_restructured = true;
    return true;
}

bool viewer_scene_add_punctual(viewer_scene *s, const viewer_punctual *light)
{
    viewer_punctual *grown = realloc(s->punctual, (s->punctual_count + 1) * sizeof *grown);
    if (!grown) return false;
    s->punctual = grown;
    s->punctual[s->punctual_count++] = *light;
    viewer_punctual_clamp(&s->punctual[s->punctual_count - 1]);
    s->lights_restructured = true;
    return true;
}

bool viewer_scene_remove_light(viewer_scene *s, uint32_t index)
{
    if (index < s->light_count) {
        memmove(&s->lights[index], &s->lights[index + 1], (s->light_count - index - 1) * sizeof *s->lights);
        --s->light_count;
    } else if (index - s->light_count < s->punctual_count) {
        uint32_t i = index - s->light_count;
        memmove(&s->punctual[i], &s->punctual[i + 1], (s->punctual_count - i - 1) * sizeof *s->punctual);
        --s->punctual_count;
    } else {
        return false;
    }
    s->lights_restructured = true;
    return true;
}

const char *viewer_new_light_name(int kind)
{
    static const char *const names[VIEWER_NEW_LIGHT_KINDS] = {
        [VIEWER_NEW_QUAD] = "quad", [VIEWER_NEW_DISK] = "disk", [VIEWER_NEW_SPHERE] = "sphere",
        [VIEWER_NEW_SPOT] = "spot", [VIEWER_NEW_POINT] = "point", [VIEWER_NEW_DIRECTIONAL] = "directional",
        [VIEWER_NEW_TUBE] = "tube", [VIEWER_NEW_ELLIPSE] = "ellipse", [VIEWER_NEW_SCREEN] = "screen"};
    return kind >= 0 && kind < VIEWER_NEW_LIGHT_KINDS ? names[kind] : "?";
}

// SMPTE-like colour bars (75 %: white, yellow, cyan, green, magenta, red, blue) over the top two
// thirds, a grey ramp from black to white below; sRGB.
void viewer_test_card(uint8_t rgba[VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT * 4])
{
    static const uint8_t bars[7][3] = {{191, 191, 191}, {191, 191, 0}, {0, 191, 191}, {0, 191, 0},
                                       {191, 0, 191},   {191, 0, 0},   {0, 0, 191}};
    for (int y = 0; y < VIEWER_TEST_CARD_HEIGHT; ++y)
        for (int x = 0; x < VIEWER_TEST_CARD_WIDTH; ++x) {
            uint8_t *p = rgba + 4 * (y * VIEWER_TEST_CARD_WIDTH + x);
            if (3 * y < 2 * VIEWER_TEST_CARD_HEIGHT) {
                memcpy(p, bars[x * 7 / VIEWER_TEST_CARD_WIDTH], 3);
            } else {
                p[0] = p[1] = p[2] = (uint8_t)(255 * x / (VIEWER_TEST_CARD_WIDTH - 1));
            }
            p[3] = 255;
        }
}

bool viewer_new_light(int kind, const float at[3], viewer_light *light, viewer_punctual *punctual)
{
    if (kind == VIEWER_NEW_QUAD || kind == VIEWER_NEW_DISK || kind == VIEWER_NEW_ELLIPSE || kind == VIEWER_NEW_SCREEN) {
        memset(light, 0, sizeof *light);
        if (kind == VIEWER_NEW_QUAD || kind == VIEWER_NEW_SCREEN) {
            // Counter-clockwise seen from below: it faces -Y. The screen: 0.8 x 0.45 m, its
            // picture's top row along v0 -> v1 (emission_uv zero: the whole texture).
            bool screen = kind == VIEWER_NEW_SCREEN;
            float hx = screen ? 0.4f : 0.25f, hz = screen ? 0.225f : 0.25f;
            const float corners[4][2] = {{-hx, -hz}, {hx, -hz}, {hx, hz}, {-hx, hz}};
            for (int v = 0; v < 4; ++v) {
                light->vertices[v][0] = at[0] + corners[v][0];
                light->vertices[v][1] = at[1];
                light->vertices[v][2] = at[2] + corners[v][1];
            }
            light->vertex_count = 4;
            if (screen) light->emission_texture = VIEWER_TEST_CARD;
        } else { // the disk: the quad's area, pi r^2 = 0.25 m^2, facing -Y; the ellipse 0.4 x 0.2 m
            light->type = RTPBR_LIGHT_DISK;
            memcpy(light->center, at, sizeof light->center);
            light->normal[1] = -1.0f;
            light->radius = kind == VIEWER_NEW_DISK ? 0.28209479177f : 0.4f; // 0.5 / sqrt(pi)
            if (kind == VIEWER_NEW_ELLIPSE) light->radius2 = 0.2f, light->axis[0] = 1.0f;
        }
        light->color[0] = light->color[1] = light->color[2] = 1.0f;
        light->intensity = 4.0f; // radiance
        light->material = -1;
        mat4_identity(light->transform);
        return true;
    }
    bool spot = kind == VIEWER_NEW_SPOT, directional = kind == VIEWER_NEW_DIRECTIONAL;
    memset(punctual, 0, sizeof *punctual);
    punctual->type = spot ? RTPBR_LIGHT_SPOT : directional ? RTPBR_LIGHT_DIRECTIONAL : RTPBR_LIGHT_POINT;
    memcpy(punctual->position, at, sizeof punctual->position);
    punctual->direction[1] = -1.0f;
    if (directional) punctual->direction[0] = 0.5f, punctual->direction[2] = -0.3f;
    punctual->color[0] = punctual->color[1] = punctual->color[2] = 1.0f;
    punctual->intensity = directional ? 1.0f : spot ? 4.0f : 2.0f; // lux; candela
    punctual->inner_cone_angle = 0.3f;
    punctual->outer_cone_angle = 0.5f;
    punctual->radius = kind == VIEWER_NEW_SPHERE ? 0.1f : kind == VIEWER_NEW_TUBE ? 0.05f : 0.0f;
    punctual->length = kind == VIEWER_NEW_TUBE ? 0.8f : 0.0f;
    punctual->axis[0] = 1.0f;
    punctual->angular_diameter = directional ? RTPBR_SUN_ANGULAR_DIAMETER : 0.0f; // the sun's disk
    viewer_punctual_clamp(punctual); // a unit direction
    return false;
}

bool viewer_scene_needs_upload(const viewer_scene *s)
{
    if (s->lights_restructured) return true;
    for (uint32_t i = 0; i < s->light_count; ++i)
        if (s->lights[i].reshaped) return true;
    return false;
}

// Möller-Trumbore; the hit distance or -1.
static float ray_triangle(const float o[3], const float d[3], const float *a, const float *b, const float *c)
{
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    float det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabsf(det) < 1e-12f) return -1.0f;
    float t0[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    float u = (t0[0] * p[0] + t0[1] * p[1] + t0[2] * p[2]) / det;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    float q[3] = {t0[1] * e1[2] - t0[2] * e1[1], t0[2] * e1[0] - t0[0] * e1[2], t0[0] * e1[1] - t0[1] * e1[0]};
    float v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
}

bool viewer_scene_pick(const viewer_scene *s, const float origin[3], const float dir[3], int32_t *light,
                       int32_t *material)
{
    float best = INFINITY;
    *light = *material = -1;
    const rtpbr_gltf_scene *in = s->loaded;
    for (uint32_t i = 0; i < in->primitive_count; ++i) {
        const rtpbr_gltf_primitive *p = &in->primitives[i];
        if (s->primitive_is_light[i] || !p->indices) continue;
        for (uint32_t k = 0; k + 2 < p->index_count; k += 3) {
            float t = ray_triangle(origin, dir, p->positions + 3 * p->indices[k], p->positions + 3 * p->indices[k + 1],
                                   p->positions + 3 * p->indices[k + 2]);
            if (t > 0.0f && t < best) best = t, *material = (int32_t)p->material, *light = -1;
        }
    }
    for (uint32_t i = 0; i < s->light_count; ++i) {
        float outline[OUTLINE_MAX][3]; // the surface drawn
        uint32_t count = light_outline(&s->lights[i], outline);
        for (uint32_t k = 1; k + 1 < count; ++k) {
            float t = ray_triangle(origin, dir, outline[0], outline[k], outline[k + 1]);
            if (t > 0.0f && t < best) best = t, *light = (int32_t)i, *material = -1;
        }
    }
    return best < INFINITY;
}

// The edited polygon's derived facts, by the loader's one function (rtpbr_gltf_polygon_facts);
// a disk's own.
void viewer_light_center(const viewer_light *l, float out[3])
{
    if (l->type == RTPBR_LIGHT_DISK) {
        memcpy(out, l->center, sizeof l->center);
        return;
    }
    rtpbr_gltf_polygon_facts f;
    rtpbr_gltf_polygon_facts_of(l->vertices, l->vertex_count, &f);
    memcpy(out, f.center, sizeof f.center);
}

void viewer_light_normal(const viewer_light *l, float out[3])
{
    if (l->type == RTPBR_LIGHT_DISK) {
        memcpy(out, l->normal, sizeof l->normal);
        return;
    }
    rtpbr_gltf_polygon_facts f;
    rtpbr_gltf_polygon_facts_of(l->vertices, l->vertex_count, &f);
    memcpy(out, f.normal, sizeof f.normal);
    if (!(f.area > 0.0f)) out[0] = out[2] = 0.0f, out[1] = 1.0f; // no area: +Y
}

void viewer_light_translate(viewer_light *l, const float d[3])
{
    if (l->type == RTPBR_LIGHT_DISK)
        for (int c = 0; c < 3; ++c) l->center[c] += d[c];
    for (uint32_t v = 0; v < l->vertex_count; ++v)
        for (int c = 0; c < 3; ++c) l->vertices[v][c] += d[c];
    float m[16];
    mat4_identity(m);
    memcpy(m + 12, d, 3 * sizeof(float));
    mat4_premultiply(l->transform, m);
}

// transform = T(centre) A T(-centre) transform, for the 3x3 linear map A (row-major a[r][c]).
static void compose_about(viewer_light *l, const float center[3], const float a[3][3])
{
    float m[16];
    mat4_identity(m);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[c * 4 + r] = a[r][c];
        m[12 + r] = center[r] - (a[r][0] * center[0] + a[r][1] * center[1] + a[r][2] * center[2]);
    }
    mat4_premultiply(l->transform, m);
}

// Point p turned about the world axis through center (right-handed: in the (a, b) plane,
// a = axis + 1, b = axis + 2, from a toward b).
static void rotate_point(float p[3], const float center[3], int axis, float cs, float sn)
{
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    float pa = p[a] - center[a], pb = p[b] - center[b];
    p[a] = center[a] + cs * pa - sn * pb;
    p[b] = center[b] + sn * pa + cs * pb;
}

void viewer_light_rotate(viewer_light *l, int axis, float radians)
{
    float center[3], cs = cosf(radians), sn = sinf(radians);
    viewer_light_center(l, center);
    int a = (axis + 1) % 3, b = (axis + 2) % 3; // rotation in the (a, b) plane
    for (uint32_t v = 0; v < l->vertex_count; ++v) rotate_point(l->vertices[v], center, axis, cs, sn);
    if (l->type == RTPBR_LIGHT_DISK) { // the normal turns about the origin, kept unit
        const float origin[3] = {0.0f, 0.0f, 0.0f};
        rotate_point(l->normal, origin, axis, cs, sn);
        float *n = l->normal, len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; ++c) n[c] /= len;
        if (l->radius2 > 0.0f) { // an ellipse's axis with it
            rotate_point(l->axis, origin, axis, cs, sn);
            ellipse_axis_in_plane(l);
        }
    }
    float m[3][3] = {{0}};
    m[axis][axis] = 1.0f;
    m[a][a] = cs, m[a][b] = -sn, m[b][a] = sn, m[b][b] = cs;
    compose_about(l, center, m);
}

void viewer_light_scale(viewer_light *l, float factor)
{
    float center[3];
    viewer_light_center(l, center);
    if (l->type == RTPBR_LIGHT_DISK) { // the factor that keeps both half-axes in range
        float lo = fminf(l->radius, viewer_light_radius2(l)), hi = fmaxf(l->radius, viewer_light_radius2(l));
        factor = fminf(fmaxf(factor, VIEWER_MIN_DISK_RADIUS / lo), VIEWER_MAX_DISK_RADIUS / hi);
        if (!(factor > 0.0f) || !isfinite(factor)) factor = 1.0f; // NaN, or no factor keeps both
        l->radius = fminf(fmaxf(l->radius * factor, VIEWER_MIN_DISK_RADIUS), VIEWER_MAX_DISK_RADIUS);
        if (l->radius2 > 0.0f)
            l->radius2 = fminf(fmaxf(l->radius2 * factor, VIEWER_MIN_DISK_RADIUS), VIEWER_MAX_DISK_RADIUS);
    }
    for (uint32_t v = 0; v < l->vertex_count; ++v)
        for (int c = 0; c < 3; ++c) l->vertices[v][c] = center[c] + factor * (l->vertices[v][c] - center[c]);
    const float m[3][3] = {{factor, 0, 0}, {0, factor, 0}, {0, 0, factor}};
    compose_about(l, center, m);
}

void viewer_light_set_radius2(viewer_light *l, float r2)
{
    if (l->type != RTPBR_LIGHT_DISK || !(r2 > 0.0f)) return; // (NaN too)
    r2 = fminf(fmaxf(r2, VIEWER_MIN_DISK_RADIUS), VIEWER_MAX_DISK_RADIUS);
    float t[3], b[3], factor = r2 / viewer_light_radius2(l);
    disk_frame(l, t, b); // a circle's: its drawn outline's
    if (!(l->radius2 > 0.0f)) memcpy(l->axis, t, sizeof l->axis);
    l->radius2 = r2 == l->radius ? 0.0f : r2;
    // the surface drawn: stretched by factor across the axis, A = I + (factor - 1) b b^T
    float a[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[r][c] = (r == c ? 1.0f : 0.0f) + (factor - 1.0f) * b[r] * b[c];
    compose_about(l, l->center, a);
}

const char *viewer_light_kind(const viewer_light *l)
{
    if (l->type == RTPBR_LIGHT_DISK) return l->radius2 > 0.0f ? "ellipse" : "disk";
    return l->vertex_count == 4 && l->emission_texture ? "screen" : "polygon";
}

float viewer_light_radius2(const viewer_light *l)
{
    if (l->type != RTPBR_LIGHT_DISK) return 0.0f;
    return l->radius2 > 0.0f ? l->radius2 : l->radius;
}

float viewer_light_radius(const viewer_light *l)
{
    if (l->type == RTPBR_LIGHT_DISK) return l->radius;
    float center[3], radius = 0.0f;
    viewer_light_center(l, center);
    for (uint32_t v = 0; v < l->vertex_count; ++v) {
        float d[3] = {l->vertices[v][0] - center[0], l->vertices[v][1] - center[1], l->vertices[v][2] - center[2]};
        radius += sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / (float)l->vertex_count;
    }
    return radius;
}

void viewer_light_set_vertex_count(viewer_light *l, uint32_t n)
{
    if (l->type == RTPBR_LIGHT_DISK || n < 3 || n > RTPBR_MAX_POLYGON_VERTICES) return;
    float center[3], normal[3], radius = viewer_light_radius(l);
    viewer_light_center(l, center);
    viewer_light_normal(l, normal);
    // Tangent frame (t, b) with t x b = normal, so increasing angles go counter-clockwise
    // seen from the front.
    float t[3] = {l->vertices[0][0] - center[0], l->vertices[0][1] - center[1], l->vertices[0][2] - center[2]};
    float tl = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    if (!(tl > 0.0f)) return;
    for (int c = 0; c < 3; ++c) t[c] /= tl;
    float b[3] = {normal[1] * t[2] - normal[2] * t[1], normal[2] * t[0] - normal[0] * t[2],
                  normal[0] * t[1] - normal[1] * t[0]};
    for (uint32_t v = 0; v < n; ++v) {
        float angle = 6.28318530718f * (float)v / (float)n;
        for (int c = 0; c < 3; ++c)
            l->vertices[v][c] = center[c] + radius * (cosf(angle) * t[c] + sinf(angle) * b[c]);
    }
    l->vertex_count = n;
    l->reshaped = true;
    l->emission_texture = 0; // (a textured quad no more)
}

bool viewer_punctual_is_tube(const viewer_punctual *p)
{
    return p->type == RTPBR_LIGHT_POINT && p->radius > 0.0f && p->length > 0.0f;
}

const char *viewer_punctual_kind(const viewer_punctual *p)
{
    return p->type == RTPBR_LIGHT_SPOT          ? "spot"
           : p->type == RTPBR_LIGHT_DIRECTIONAL ? "directional"
           : viewer_punctual_is_tube(p)         ? "tube"
                                                : "point";
}

void viewer_punctual_rotate(viewer_punctual *p, int axis, float radians)
{
    if (axis < 0 || axis > 2) return;
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    rotate_point(p->direction, origin, axis, cosf(radians), sinf(radians));
    rotate_point(p->axis, origin, axis, cosf(radians), sinf(radians));
}

void viewer_punctual_angles(const viewer_punctual *p, float *azimuth, float *elevation)
{
    const float *d = p->direction;
    float horizontal = sqrtf(d[0] * d[0] + d[2] * d[2]);
    *elevation = atan2f(d[1], horizontal);
    *azimuth = horizontal > 0.0f ? atan2f(d[0], d[2]) : 0.0f;
}

void viewer_punctual_set_angles(viewer_punctual *p, float azimuth, float elevation)
{
    p->direction[0] = cosf(elevation) * sinf(azimuth);
    p->direction[1] = sinf(elevation);
    p->direction[2] = cosf(elevation) * cosf(azimuth);
}

void viewer_punctual_clamp(viewer_punctual *p)
{
    p->intensity = fmaxf(p->intensity, 0.0f); // fmaxf: NaN -> 0
    p->range = fmaxf(p->range, 0.0f);
    p->angular_diameter = fminf(fmaxf(p->angular_diameter, 0.0f), 0.5f); // at most ~29 degrees
    p->radius = fminf(fmaxf(p->radius, 0.0f), 100.0f);                     // fmaxf: NaN -> 0
    p->length = fminf(fmaxf(p->length, 0.0f), 100.0f);
    float *x = p->axis, xlen = sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (xlen > 0.0f && isfinite(xlen))
        for (int c = 0; c < 3; ++c) x[c] /= xlen;
    else
        x[0] = 1.0f, x[1] = x[2] = 0.0f;
    for (int c = 0; c < 3; ++c) p->color[c] = fminf(fmaxf(p->color[c], 0.0f), 1.0f);
    float *d = p->direction, len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len > 0.0f && isfinite(len))
        for (int c = 0; c < 3; ++c) d[c] /= len;
    else
        d[0] = d[2] = 0.0f, d[1] = -1.0f; // straight down
    if (p->type != RTPBR_LIGHT_SPOT) return;
    const float half_pi = 1.57079632679f;
    p->outer_cone_angle = fminf(fmaxf(p->outer_cone_angle, VIEWER_MIN_CONE), half_pi);
    p->inner_cone_angle = fminf(fmaxf(p->inner_cone_angle, 0.0f), 0.99f * p->outer_cone_angle);
}
