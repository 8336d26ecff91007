// The viewer's editable scene (see scene_edit.h).
#include "scene_edit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool viewer_scene_load(viewer_scene *s, const char *path)
{
    memset(s, 0, sizeof *s);
    char error[RTPBR_SCENE_ERROR_MESSAGE_SIZE];
    rtpbr_scene_load_desc desc = {.error_message = error, .error_message_size = sizeof error};
    rtpbr_scene_result r = rtpbr_scene_load(path, &desc, &s->loaded);
    if (r != RTPBR_SCENE_SUCCESS) {
        fprintf(stderr, "rtpbr-viewer: %s: %s: %s\n", path, rtpbr_scene_result_string(r), error);
        return false;
    }
    const rtpbr_scene *in = s->loaded;
    s->material_count = in->material_count;
    s->light_count = in->light_count;
    s->materials = calloc(in->material_count ? in->material_count : 1, sizeof *s->materials);
    s->lights = calloc(in->light_count ? in->light_count : 1, sizeof *s->lights);
    s->primitive_is_light = calloc(in->primitive_count ? in->primitive_count : 1, sizeof *s->primitive_is_light);
    if (!s->materials || !s->lights || !s->primitive_is_light) {
        fprintf(stderr, "rtpbr-viewer: out of memory\n");
        viewer_scene_destroy(s);
        return false;
    }
    // The glTF mapping of docs/materials.md, restricted to what rtpbr_material_desc has.
    for (uint32_t i = 0; i < in->material_count; ++i) {
        const rtpbr_scene_material *m = &in->materials[i];
        rtpbr_material_desc *d = &s->materials[i];
        memcpy(d->base_color, m->base_color, sizeof d->base_color);
        d->metallic = m->metallic;
        d->roughness = m->roughness;
        memcpy(d->emission, m->emission, sizeof d->emission);
        d->ior = m->ior > 0.0f ? m->ior : 1.5f;
        d->specular = m->specular_factor > 0.0f ? m->specular_factor : -1.0f;
        memcpy(d->specular_color, m->specular_color, sizeof d->specular_color);
        d->double_sided = m->double_sided;
    }
    for (uint32_t i = 0; i < in->light_count; ++i) {
        const rtpbr_scene_light *l = &in->lights[i];
        viewer_light *v = &s->lights[i];
        v->vertex_count = l->vertex_count;
        memcpy(v->vertices, l->vertices, sizeof v->vertices);
        float peak = fmaxf(l->radiance[0], fmaxf(l->radiance[1], l->radiance[2]));
        v->intensity = peak;
        for (int c = 0; c < 3; ++c) v->color[c] = peak > 0.0f ? l->radiance[c] / peak : 1.0f;
        v->two_sided = l->two_sided;
        v->material = l->material >= 0 && (uint32_t)l->material < in->material_count ? l->material : -1;
        if (l->primitive >= 0 && (uint32_t)l->primitive < in->primitive_count) s->primitive_is_light[l->primitive] = true;
    }
    return true;
}

void viewer_scene_destroy(viewer_scene *s)
{
    rtpbr_scene_destroy(s->loaded);
    free(s->materials);
    free(s->lights);
    free(s->primitive_is_light);
    memset(s, 0, sizeof *s);
}

rtpbr_result viewer_scene_upload(const viewer_scene *s, rtpbr_context *ctx, rtpbr_gpu_scene **out)
{
    const rtpbr_scene *in = s->loaded;
    uint32_t mesh_cap = in->primitive_count + s->light_count;
    rtpbr_mesh_desc *meshes = calloc(mesh_cap ? mesh_cap : 1, sizeof *meshes);
    rtpbr_material_desc *materials = calloc(s->material_count + s->light_count + 1, sizeof *materials);
    rtpbr_light_desc *lights = calloc(s->light_count ? s->light_count : 1, sizeof *lights);
    // Light polygons as triangle fans: at most 8 vertices, 6 triangles each.
    float *light_positions = calloc((size_t)s->light_count * RTPBR_MAX_POLYGON_VERTICES * 3 + 1, sizeof(float));
    float *light_normals = calloc((size_t)s->light_count * RTPBR_MAX_POLYGON_VERTICES * 3 + 1, sizeof(float));
    uint32_t *light_indices = calloc((size_t)s->light_count * (RTPBR_MAX_POLYGON_VERTICES - 2) * 3 + 1, sizeof(uint32_t));
    rtpbr_result r = RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    if (!meshes || !materials || !lights || !light_positions || !light_normals || !light_indices) goto done;
    memcpy(materials, s->materials, s->material_count * sizeof *materials);
    uint32_t mesh_count = 0;
    for (uint32_t i = 0; i < in->primitive_count; ++i) {
        const rtpbr_scene_primitive *p = &in->primitives[i];
        if (s->primitive_is_light[i] || p->vertex_count == 0 || p->index_count == 0) continue;
        meshes[mesh_count++] = (rtpbr_mesh_desc){.positions = p->positions, .normals = p->normals,
            .indices = p->indices, .vertex_count = p->vertex_count, .index_count = p->index_count,
            .material = p->material};
    }
    for (uint32_t i = 0; i < s->light_count; ++i) {
        const viewer_light *l = &s->lights[i];
        rtpbr_light_desc *d = &lights[i];
        memcpy(d->vertices, l->vertices, sizeof d->vertices);
        d->vertex_count = l->vertex_count;
        for (int c = 0; c < 3; ++c) d->emission[c] = l->color[c] * l->intensity;
        d->two_sided = l->two_sided;
        // The light's surface: its source material (as the engine's loader path draws it)
        // with the edited emission, or a black emitter.
        rtpbr_material_desc *m = &materials[s->material_count + i];
        if (l->material >= 0) *m = s->materials[l->material];
        else m->roughness = 1.0f;
        memcpy(m->emission, d->emission, sizeof m->emission);
        m->double_sided = l->two_sided;
        float *pos = light_positions + (size_t)i * RTPBR_MAX_POLYGON_VERTICES * 3;
        float *nrm = light_normals + (size_t)i * RTPBR_MAX_POLYGON_VERTICES * 3;
        uint32_t *idx = light_indices + (size_t)i * (RTPBR_MAX_POLYGON_VERTICES - 2) * 3;
        float n[3];
        viewer_light_normal(l, n);
        for (uint32_t v = 0; v < l->vertex_count; ++v) {
            memcpy(pos + 3 * v, l->vertices[v], 3 * sizeof(float));
            memcpy(nrm + 3 * v, n, 3 * sizeof(float));
        }
        for (uint32_t t = 0; t + 2 < l->vertex_count; ++t) {
            idx[3 * t] = 0;
            idx[3 * t + 1] = t + 1;
            idx[3 * t + 2] = t + 2;
        }
        meshes[mesh_count++] = (rtpbr_mesh_desc){.positions = pos, .normals = nrm, .indices = idx,
            .vertex_count = l->vertex_count, .index_count = 3 * (l->vertex_count - 2),
            .material = s->material_count + i};
    }
    // No cameras: the viewer always passes its orbit camera to rtpbr_record.
    rtpbr_gpu_scene_desc desc = {.meshes = meshes, .mesh_count = mesh_count, .materials = materials,
        .material_count = s->material_count + s->light_count, .lights = lights, .light_count = s->light_count};
    r = rtpbr_gpu_scene_create(ctx, &desc, out);
done:
    free(meshes);
    free(materials);
    free(lights);
    free(light_positions);
    free(light_normals);
    free(light_indices);
    return r;
}

void viewer_light_center(const viewer_light *l, float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    for (uint32_t v = 0; v < l->vertex_count; ++v)
        for (int c = 0; c < 3; ++c) out[c] += l->vertices[v][c] / (float)l->vertex_count;
}

void viewer_light_normal(const viewer_light *l, float out[3])
{
    // Newell's normal: the right-hand rule over the whole polygon.
    float n[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t i = 0; i < l->vertex_count; ++i) {
        const float *a = l->vertices[i], *b = l->vertices[(i + 1) % l->vertex_count];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c) out[c] = len > 0.0f ? n[c] / len : (c == 1 ? 1.0f : 0.0f);
}

void viewer_light_translate(viewer_light *l, const float d[3])
{
    for (uint32_t v = 0; v < l->vertex_count; ++v)
        for (int c = 0; c < 3; ++c) l->vertices[v][c] += d[c];
}

void viewer_light_rotate(viewer_light *l, int axis, float radians)
{
    float center[3], cs = cosf(radians), sn = sinf(radians);
    viewer_light_center(l, center);
    int a = (axis + 1) % 3, b = (axis + 2) % 3; // rotation in the (a, b) plane
    for (uint32_t v = 0; v < l->vertex_count; ++v) {
        float pa = l->vertices[v][a] - center[a], pb = l->vertices[v][b] - center[b];
        l->vertices[v][a] = center[a] + cs * pa - sn * pb;
        l->vertices[v][b] = center[b] + sn * pa + cs * pb;
    }
}

void viewer_light_scale(viewer_light *l, float factor)
{
    float center[3];
    viewer_light_center(l, center);
    for (uint32_t v = 0; v < l->vertex_count; ++v)
        for (int c = 0; c < 3; ++c) l->vertices[v][c] = center[c] + factor * (l->vertices[v][c] - center[c]);
}

void viewer_light_set_vertex_count(viewer_light *l, uint32_t n)
{
    if (n < 3 || n > RTPBR_MAX_POLYGON_VERTICES) return;
    float center[3], normal[3], radius = 0.0f;
    viewer_light_center(l, center);
    viewer_light_normal(l, normal);
    for (uint32_t v = 0; v < l->vertex_count; ++v) {
        float d[3] = {l->vertices[v][0] - center[0], l->vertices[v][1] - center[1], l->vertices[v][2] - center[2]};
        radius += sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / (float)l->vertex_count;
    }
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
}
