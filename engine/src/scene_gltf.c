// Scenes from the glTF loader (scene): the loader's plain data mapped onto
// rtpbr_gpu_scene_desc.
//
// Material mapping (loader field -> engine), one table:
//   base_color.rgb            -> base_color
//   alpha_mode, base_color[3], alpha_cutoff -> alpha_mode, alpha, alpha_cutoff (0 -> flag
//                               RTPBR_MATERIAL_NO_ALPHA_CUTOFF: nothing is cut; MASK cuts out,
//                               BLEND is drawn forward)
//   metallic, roughness       -> metallic, roughness   (perceptual; alpha = r^2)
//   emission                  -> emission              (emissiveFactor x emissive_strength:
//                                                       a product, so neither factor's name)
//   ior.ior                   -> ior                   (0, Fresnel 1 in KHR_materials_ior, ->
//                                                       flag RTPBR_MATERIAL_FRESNEL_ONE)
//   specular.specular_factor  -> specular_factor       (0 -> flag RTPBR_MATERIAL_NO_SPECULAR)
//   specular.specular_color_factor -> specular_color   (black: no lobe, the same flag)
//   double_sided              -> double_sided          (emission on both sides)
//   base_color / metallic_roughness / emission textures -> the same, each with its
//                               *_texture_transform (KHR_texture_transform, texCoord 0 or 1)
//   texture wrap_s/t, nearest, min_filter -> the texture's sampler (minFilter absent:
//                               trilinear; mipmaps built at upload)
//   normal texture, normal_scale -> the same (tangents from the loader)
//   clearcoat.*               -> clearcoat_factor, clearcoat_roughness_factor (KHR_materials_clearcoat)
//   anisotropy.*              -> anisotropy_strength, anisotropy_rotation (KHR_materials_anisotropy)
//   sheen.*                   -> sheen_color_factor, sheen_roughness_factor (KHR_materials_sheen)
//   clearcoat, clearcoat roughness, sheen colour and roughness, specular and specular colour
//                             textures -> the *_texture of the same name, each with its
//                               transform (metallic-roughness materials; clearcoatNormalTexture
//                               is ignored, as the loader warns)
//   has_disney, disney.*      -> model DISNEY, disney.* (Burley 2012; specular 0 -> flag
//                                                       RTPBR_MATERIAL_DISNEY_NO_SPECULAR)
// Every value is copied as the loader holds it (the loader checked and clamped it, with a
// warning; rtpbr_gltf.h): the desc's defaults never apply, and the loader's zeros that mean
// something else than the desc's default become flags.
// The material rules (roughness floor, ior, coat and Disney mappings) are applied by the
// shaders through shaderlib/rtpbr/material.h, as in the oracle. specular_color is applied to
// the Schlick F0 of the specular lobe; the oracle's exact dielectric Fresnel ignores it (a
// difference only for coloured specular).
// Lights: every loader light (emissive primitives, EXT_lights_area rectangles) becomes a
// polygonal light with its radiance and sidedness, and its derived facts (normal, centre,
// area, bounding sphere) as the loader computed them; EXT_lights_area disks become disk
// lights (RTPBR_LIGHT_DISK: shaded as the disk, not its octagon);
// KHR_lights_punctual lights follow them as point, spot and directional lights.
#include <math.h>
#include <string.h>

#include "internal.h"
#include "rtpbr/rtpbr_gltf.h"

// The loader's vertex limit is the engine's (rtpbr.h's is the source of truth).
_Static_assert(RTPBR_GLTF_MAX_POLYGON_VERTICES == RTPBR_MAX_POLYGON_VERTICES,
               "RTPBR_GLTF_MAX_POLYGON_VERTICES (rtpbr_gltf.h) differs from RTPBR_MAX_POLYGON_VERTICES (rtpbr.h)");

// 1-based engine texture index of a loader texture index; 0 (none) for -1, out-of-range
// indices and textures without decoded texels.
static uint32_t texture_ref(const rtpbr_gltf_scene *loaded, int32_t index)
{
    if (index < 0 || (uint32_t)index >= loaded->texture_count || !loaded->textures[index].pixels) return 0;
    return (uint32_t)index + 1;
}

// The texture coordinate the emission texture reads at vertex v of primitive p: its set, then
// KHR_texture_transform (rtpbr_gltf.h: uv' = T R S uv).
static void emission_uv_at(const rtpbr_gltf_primitive *p, const rtpbr_gltf_texture_transform *t, uint32_t v,
                           float out[2])
{
    const float *set = t->texcoord == 1 ? p->texcoords1 : p->texcoords;
    float u = set[2 * v], w = set[2 * v + 1];
    if (!t->has_transform) {
        out[0] = u;
        out[1] = w;
        return;
    }
    float c = cosf(t->rotation), s = sinf(t->rotation);
    out[0] = c * t->scale[0] * u + s * t->scale[1] * w + t->offset[0];
    out[1] = -s * t->scale[0] * u + c * t->scale[1] * w + t->offset[1];
}

// A BOUNDED quad light of a primitive whose material has an emission texture (a screen, a
// window): its texture and the coordinates at vertices 0, 1, 3 (rtpbr_light_desc.emission_uv),
// when the quad is a parallelogram each of whose corners is a vertex of the primitive and the
// primitive's coordinates are affine over it (the fourth corner's agree within 1e-3); the
// emission is then the material's (the texture multiplies it per point) instead of the
// texture's mean. Anything else keeps the mean (false).
static bool textured_quad(const rtpbr_gltf_scene *loaded, const rtpbr_gltf_light *l, rtpbr_light_desc *d)
{
    if (l->vertex_count != 4 || l->proxy || l->triangle >= 0 || l->primitive < 0 || l->material < 0 ||
        (uint32_t)l->primitive >= loaded->primitive_count || (uint32_t)l->material >= loaded->material_count)
        return false;
    const rtpbr_gltf_material *m = &loaded->materials[l->material];
    const rtpbr_gltf_primitive *p = &loaded->primitives[l->primitive];
    if (m->emission_texture < 0 || (uint32_t)m->emission_texture >= loaded->texture_count || !p->vertex_count ||
        !(m->emission_texture_transform.texcoord == 1 ? p->has_texcoords1 : p->has_texcoords))
        return false;
    float uv[4][2];
    double extent2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        double e = (double)l->vertices[2][k] - l->vertices[0][k];
        extent2 += e * e;
    }
    for (uint32_t c = 0; c < 4; ++c) {
        // the primitive's vertex at the corner (the merged polygon's corners are its vertices)
        uint32_t best = 0;
        double best2 = INFINITY;
        for (uint32_t v = 0; v < p->vertex_count; ++v) {
            double d2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                double e = (double)p->positions[3 * v + k] - l->vertices[c][k];
                d2 += e * e;
            }
            if (d2 < best2) best2 = d2, best = v;
        }
        if (!(best2 <= 1e-10 * extent2)) return false;
        emission_uv_at(p, &m->emission_texture_transform, best, uv[c]);
    }
    double gap = 0.0, span = 0.0;
    for (int k = 0; k < 2; ++k) {
        double e = (double)uv[0][k] + uv[2][k] - uv[1][k] - uv[3][k];
        gap += e * e;
        span += ((double)uv[2][k] - uv[0][k]) * ((double)uv[2][k] - uv[0][k]);
    }
    double shape = 0.0; // the corners' parallelogram gap, as the engine checks it
    for (int k = 0; k < 3; ++k) {
        double e = (double)l->vertices[0][k] + l->vertices[2][k] - l->vertices[1][k] - l->vertices[3][k];
        shape += e * e;
    }
    if (!(span > 0.0) || gap > 1e-6 * span || shape > 1e-8 * extent2) return false;
    d->emission_texture = (uint32_t)m->emission_texture + 1u;
    memcpy(d->emission_uv[0], uv[0], sizeof uv[0]);
    memcpy(d->emission_uv[1], uv[1], sizeof uv[1]);
    memcpy(d->emission_uv[2], uv[3], sizeof uv[3]);
    memcpy(d->emission, m->emission, sizeof d->emission);
    return true;
}

void rtpbr_light_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t light, rtpbr_light_desc *d)
{
    if (!d) return;
    *d = (rtpbr_light_desc){0};
    if (!loaded || !loaded->lights || light >= loaded->light_count) return;
    const rtpbr_gltf_light *l = &loaded->lights[light];
    d->vertex_count = l->vertex_count;
    uint32_t n = l->vertex_count <= RTPBR_MAX_POLYGON_VERTICES ? l->vertex_count : RTPBR_MAX_POLYGON_VERTICES;
    memcpy(d->vertices, l->vertices, n * sizeof d->vertices[0]);
    memcpy(d->emission, l->radiance, sizeof d->emission);
    d->two_sided = l->two_sided;
    if (l->shape == RTPBR_GLTF_LIGHT_DISK) { // the disk itself (its octagon stays in vertices)
        d->type = RTPBR_LIGHT_DISK;
        memcpy(d->position, l->facts.center, sizeof d->position);
        memcpy(d->direction, l->facts.normal, sizeof d->direction);
        d->radius = l->radius;
        if (l->radius2 > 0.0f && l->radius2 != l->radius) { // an ellipse (a disk node scaled unevenly)
            d->disk_radius2 = l->radius2;
            memcpy(d->disk_axis, l->axis, sizeof d->disk_axis);
        }
    }
    textured_quad(loaded, l, d);
}

static rtpbr_texture_transform texture_transform(const rtpbr_gltf_texture_transform *t)
{
    rtpbr_texture_transform out = {.texcoord = t->texcoord};
    if (t->has_transform) {
        memcpy(out.offset, t->offset, sizeof out.offset);
        out.rotation = t->rotation;
        memcpy(out.scale, t->scale, sizeof out.scale);
    }
    return out;
}

void rtpbr_material_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t material,
                                     rtpbr_material_desc *d)
{
    if (!d) return;
    *d = (rtpbr_material_desc){0};
    if (!loaded || !loaded->materials || material >= loaded->material_count) return;
    const rtpbr_gltf_material *m = &loaded->materials[material];
    memcpy(d->base_color, m->base_color, sizeof d->base_color);
    d->metallic = m->metallic;
    d->roughness = m->roughness;
    memcpy(d->emission, m->emission, sizeof d->emission);
    d->ior = m->ior.ior;
    d->specular_factor = m->specular.specular_factor;
    memcpy(d->specular_color, m->specular.specular_color_factor, sizeof d->specular_color);
    bool black_specular = d->specular_color[0] == 0.0f && d->specular_color[1] == 0.0f && d->specular_color[2] == 0.0f;
    d->flags = (d->ior == 0.0f ? RTPBR_MATERIAL_FRESNEL_ONE : 0u) |
               (d->specular_factor == 0.0f || black_specular ? RTPBR_MATERIAL_NO_SPECULAR : 0u) |
               (m->alpha_cutoff == 0.0f ? RTPBR_MATERIAL_NO_ALPHA_CUTOFF : 0u) |
               (m->has_disney && m->disney.specular == 0.0f ? RTPBR_MATERIAL_DISNEY_NO_SPECULAR : 0u);
    d->double_sided = m->double_sided;
    d->alpha_mode = m->alpha_mode == RTPBR_GLTF_ALPHA_MASK    ? RTPBR_ALPHA_MASK
                    : m->alpha_mode == RTPBR_GLTF_ALPHA_BLEND ? RTPBR_ALPHA_BLEND
                                                              : RTPBR_ALPHA_OPAQUE;
    d->alpha = m->base_color[3];
    d->alpha_cutoff = m->alpha_cutoff;
    // Loader texture indices are 0-based with -1 for none; the engine's are 1-based.
    d->base_color_texture = texture_ref(loaded, m->base_color_texture);
    d->metallic_roughness_texture = texture_ref(loaded, m->metallic_roughness_texture);
    d->emission_texture = texture_ref(loaded, m->emission_texture);
    d->normal_texture = texture_ref(loaded, m->normal_texture);
    d->base_color_texture_transform = texture_transform(&m->base_color_texture_transform);
    d->metallic_roughness_texture_transform = texture_transform(&m->metallic_roughness_texture_transform);
    d->emission_texture_transform = texture_transform(&m->emission_texture_transform);
    d->normal_texture_transform = texture_transform(&m->normal_texture_transform);
    d->normal_scale = m->normal_scale;
    if (!m->has_disney) {
        d->clearcoat_factor = m->clearcoat.clearcoat_factor;
        d->clearcoat_roughness_factor = m->clearcoat.clearcoat_roughness_factor;
        d->anisotropy_strength = m->anisotropy.anisotropy_strength;
        d->anisotropy_rotation = m->anisotropy.anisotropy_rotation;
        memcpy(d->sheen_color_factor, m->sheen.sheen_color_factor, sizeof d->sheen_color_factor);
        d->sheen_roughness_factor = m->sheen.sheen_roughness_factor;
        // The extensions' textures (the loader leaves them -1 where the extension is absent;
        // clearcoatNormalTexture is ignored, with the loader's warning).
        d->clearcoat_texture = texture_ref(loaded, m->clearcoat.clearcoat_texture);
        d->clearcoat_roughness_texture = texture_ref(loaded, m->clearcoat.clearcoat_roughness_texture);
        d->sheen_color_texture = texture_ref(loaded, m->sheen.sheen_color_texture);
        d->sheen_roughness_texture = texture_ref(loaded, m->sheen.sheen_roughness_texture);
        d->specular_texture = texture_ref(loaded, m->specular.specular_texture);
        d->specular_color_texture = texture_ref(loaded, m->specular.specular_color_texture);
        d->clearcoat_texture_transform = texture_transform(&m->clearcoat.clearcoat_texture_transform);
        d->clearcoat_roughness_texture_transform =
            texture_transform(&m->clearcoat.clearcoat_roughness_texture_transform);
        d->sheen_color_texture_transform = texture_transform(&m->sheen.sheen_color_texture_transform);
        d->sheen_roughness_texture_transform = texture_transform(&m->sheen.sheen_roughness_texture_transform);
        d->specular_texture_transform = texture_transform(&m->specular.specular_texture_transform);
        d->specular_color_texture_transform = texture_transform(&m->specular.specular_color_texture_transform);
    } else {
        const rtpbr_gltf_disney *dn = &m->disney;
        d->model = RTPBR_MATERIAL_DISNEY;
        d->disney = (rtpbr_disney_params){
            .subsurface = dn->subsurface,
            .specular = dn->specular,
            .specular_tint = dn->specular_tint,
            .sheen = dn->sheen,
            .sheen_tint = dn->sheen_tint,
            .clearcoat = dn->clearcoat,
            .clearcoat_gloss = dn->clearcoat_gloss,
            .anisotropic = dn->anisotropic,
        };
    }
}

void rtpbr_texture_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t texture, rtpbr_texture_desc *out)
{
    static const uint8_t white[4] = {255, 255, 255, 255};
    if (!out) return;
    *out = (rtpbr_texture_desc){0};
    if (!loaded || !loaded->textures || texture >= loaded->texture_count) return;
    const rtpbr_gltf_texture *t = &loaded->textures[texture];
    if (!t->pixels) { // textures without texels are never referenced (texture_ref)
        *out = (rtpbr_texture_desc){.width = 1, .height = 1, .rgba = white};
        return;
    }
    static const rtpbr_wrap wraps[] = {
        [RTPBR_GLTF_WRAP_REPEAT] = RTPBR_WRAP_REPEAT,
        [RTPBR_GLTF_WRAP_CLAMP_TO_EDGE] = RTPBR_WRAP_CLAMP_TO_EDGE,
        [RTPBR_GLTF_WRAP_MIRRORED_REPEAT] = RTPBR_WRAP_MIRRORED_REPEAT,
    };
    // glTF minFilter -> min filter and mipmap mode; absent: trilinear.
    static const struct {
        rtpbr_filter filter;
        rtpbr_mipmap_mode mipmap;
    } mins[] = {
        [RTPBR_GLTF_MIN_FILTER_DEFAULT] = {RTPBR_FILTER_LINEAR, RTPBR_MIPMAP_LINEAR},
        [RTPBR_GLTF_MIN_FILTER_NEAREST] = {RTPBR_FILTER_NEAREST, RTPBR_MIPMAP_NONE},
        [RTPBR_GLTF_MIN_FILTER_LINEAR] = {RTPBR_FILTER_LINEAR, RTPBR_MIPMAP_NONE},
        [RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_NEAREST] = {RTPBR_FILTER_NEAREST, RTPBR_MIPMAP_NEAREST},
        [RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_NEAREST] = {RTPBR_FILTER_LINEAR, RTPBR_MIPMAP_NEAREST},
        [RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_LINEAR] = {RTPBR_FILTER_NEAREST, RTPBR_MIPMAP_LINEAR},
        [RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_LINEAR] = {RTPBR_FILTER_LINEAR, RTPBR_MIPMAP_LINEAR},
    };
    unsigned min = (unsigned)t->min_filter < sizeof mins / sizeof mins[0] ? (unsigned)t->min_filter : 0u;
    *out = (rtpbr_texture_desc){
        .width = t->width,
        .height = t->height,
        .rgba = t->pixels,
        .srgb = t->srgb,
        .wrap_s = (unsigned)t->wrap_s < 3u ? wraps[t->wrap_s] : RTPBR_WRAP_REPEAT,
        .wrap_t = (unsigned)t->wrap_t < 3u ? wraps[t->wrap_t] : RTPBR_WRAP_REPEAT,
        .mag_filter = t->nearest ? RTPBR_FILTER_NEAREST : RTPBR_FILTER_LINEAR,
        .min_filter = mins[min].filter,
        .mipmap = mins[min].mipmap,
    };
}

rtpbr_result rtpbr_gpu_scene_from_loaded(rtpbr_context *ctx, const struct rtpbr_gltf_scene *loaded,
                                         rtpbr_gpu_scene **out_scene)
{
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!loaded || !out_scene) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_from_loaded: loaded or out_scene is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out_scene = NULL;
    // A hand-built or corrupted rtpbr_gltf_scene: every non-zero count needs its array.
    const struct {
        uint32_t count;
        const void *array;
        const char *name;
    } arrays[] = {
        {loaded->primitive_count, loaded->primitives, "primitives"},
        {loaded->material_count, loaded->materials, "materials"},
        {loaded->texture_count, loaded->textures, "textures"},
        {loaded->light_count, loaded->lights, "lights"},
        {loaded->punctual_light_count, loaded->punctual_lights, "punctual_lights"},
        {loaded->camera_count, loaded->cameras, "cameras"},
    };
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
        if (arrays[i].count && !arrays[i].array) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_from_loaded: %s is NULL with %s_count = %u",
                      arrays[i].name, arrays[i].name, arrays[i].count);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    if (loaded->light_count > RTPBR_MAX_LIGHTS || loaded->punctual_light_count > RTPBR_MAX_LIGHTS - loaded->light_count) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "scene has %u area and %u punctual lights; at most RTPBR_MAX_LIGHTS = %u are allowed in all",
                  loaded->light_count, loaded->punctual_light_count, RTPBR_MAX_LIGHTS);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    uint32_t light_count = loaded->light_count + loaded->punctual_light_count;
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_mesh_desc *meshes = NULL;
    rtpbr_material_desc *materials = NULL;
    rtpbr_light_desc *lights = NULL;
    rtpbr_gltf_polygon_facts *light_facts = NULL; // the loader's, passed on (not derived again)
    rtpbr_camera_desc *cameras = NULL;
    rtpbr_texture_desc *textures = NULL;
    if (loaded->texture_count) RTPBR_ALLOC(&ctx->host, textures, loaded->texture_count * sizeof *textures);
    for (uint32_t i = 0; i < loaded->texture_count; ++i) rtpbr_texture_desc_from_loaded(loaded, i, &textures[i]);
    if (loaded->primitive_count) RTPBR_ALLOC(&ctx->host, meshes, loaded->primitive_count * sizeof *meshes);
    if (loaded->material_count) RTPBR_ALLOC(&ctx->host, materials, loaded->material_count * sizeof *materials);
    if (light_count) RTPBR_ALLOC(&ctx->host, lights, light_count * sizeof *lights);
    if (light_count) RTPBR_ALLOC(&ctx->host, light_facts, light_count * sizeof *light_facts);
    if (loaded->camera_count) RTPBR_ALLOC(&ctx->host, cameras, loaded->camera_count * sizeof *cameras);

    for (uint32_t i = 0; i < loaded->primitive_count; ++i) {
        const rtpbr_gltf_primitive *p = &loaded->primitives[i];
        meshes[i] = (rtpbr_mesh_desc){
            .positions = p->positions,
            .normals = p->normals,
            .texcoords = p->texcoords,
            .texcoords1 = p->has_texcoords1 ? p->texcoords1 : NULL,
            .tangents = p->has_tangents ? p->tangents : NULL,
            .indices = p->indices,
            .vertex_count = p->vertex_count,
            .index_count = p->index_count,
            .material = p->material,
        }; // positions are already in world space: identity transform
    }
    for (uint32_t i = 0; i < loaded->material_count; ++i) rtpbr_material_desc_from_loaded(loaded, i, &materials[i]);
    // Textured quads: at most RTPBR_MAX_TEXTURED_LIGHTS distinct textures and mappings (one
    // prefiltered chain each); the others are lit at their texture's mean, as before them.
    uint32_t chains = 0, demoted = 0;
    const rtpbr_light_desc *chain_of[RTPBR_MAX_TEXTURED_LIGHTS];
    for (uint32_t i = 0; i < loaded->light_count; ++i) {
        rtpbr_light_desc *d = &lights[i];
        rtpbr_light_desc_from_loaded(loaded, i, d);
        light_facts[i] = loaded->lights[i].facts;
        if (!d->emission_texture) continue;
        bool known = false;
        for (uint32_t k = 0; k < chains && !known; ++k)
            known = chain_of[k]->emission_texture == d->emission_texture &&
                    memcmp(chain_of[k]->emission_uv, d->emission_uv, sizeof d->emission_uv) == 0;
        if (!known && chains < RTPBR_MAX_TEXTURED_LIGHTS) chain_of[chains++] = d, known = true;
        if (!known) {
            d->emission_texture = 0;
            memcpy(d->emission, loaded->lights[i].radiance, sizeof d->emission);
            ++demoted;
        }
    }
    if (demoted)
        rtpbr_log(&ctx->host, RTPBR_LOG_WARNING,
                  "%u textured quad lights past RTPBR_MAX_TEXTURED_LIGHTS = %u distinct textures and mappings are lit "
                  "at their texture's mean", demoted, RTPBR_MAX_TEXTURED_LIGHTS);
    // KHR_lights_punctual lights after the area lights (with shadows, the order does not
    // matter: each tile's casters are chosen by their irradiance bound); facts: none (all zero).
    for (uint32_t i = 0; i < loaded->punctual_light_count; ++i) {
        const rtpbr_gltf_punctual_light *l = &loaded->punctual_lights[i];
        rtpbr_light_desc *d = &lights[loaded->light_count + i];
        *d = (rtpbr_light_desc){
            .type = l->type == RTPBR_GLTF_PUNCTUAL_SPOT          ? RTPBR_LIGHT_SPOT
                    : l->type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL ? RTPBR_LIGHT_DIRECTIONAL
                                                                 : RTPBR_LIGHT_POINT,
            .range = l->range,
            .inner_cone_angle = l->inner_cone_angle,
            .outer_cone_angle = l->outer_cone_angle,
            // the loader's 0 is a true direction, the desc's zero the default disk
            .angular_diameter = l->angular_diameter > 0.0f ? l->angular_diameter : -1.0f,
            .radius = l->type == RTPBR_GLTF_PUNCTUAL_POINT ? l->radius : 0.0f, // a sphere, or a point at 0
        };
        memcpy(d->emission, l->intensity, sizeof d->emission);
        memcpy(d->position, l->position, sizeof d->position);
        memcpy(d->direction, l->direction, sizeof d->direction);
        memset(&light_facts[loaded->light_count + i], 0, sizeof light_facts[0]);
        // A point light with a radius and a length: the capsule (rtpbr_gltf_punctual_light.length)
        // as a tube of radiance 2 I / (pi r (2 r + L)) (its power 4 pi I over its area
        // 2 pi r (2 r + L), as the loader says), its range (if any) windowing it at the distance
        // from its centre, as the oracle does.
        if (l->type == RTPBR_GLTF_PUNCTUAL_POINT && l->radius > 0.0f && l->length > 0.0f) {
            double r = l->radius, scale = 2.0 / (3.14159265358979323846 * r * (2.0 * r + l->length));
            d->type = RTPBR_LIGHT_TUBE;
            d->length = l->length;
            memcpy(d->direction, l->axis, sizeof d->direction);
            for (int k = 0; k < 3; ++k) d->emission[k] = (float)(l->intensity[k] * scale);
        }
    }
    for (uint32_t i = 0; i < loaded->camera_count; ++i) {
        const rtpbr_gltf_camera *c = &loaded->cameras[i];
        rtpbr_camera_desc *d = &cameras[i];
        memcpy(d->position, c->position, sizeof d->position);
        for (int k = 0; k < 3; ++k) d->target[k] = c->position[k] + c->forward[k];
        memcpy(d->up, c->up, sizeof d->up);
        d->yfov = c->yfov;
        d->znear = c->znear;
        d->zfar = c->zfar; // 0 (infinite in glTF): the engine's default far plane
    }
    rtpbr_gpu_scene_desc desc = {
        .meshes = meshes,
        .mesh_count = loaded->primitive_count,
        .materials = materials,
        .material_count = loaded->material_count,
        .lights = lights,
        .light_count = light_count,
        .cameras = cameras,
        .camera_count = loaded->camera_count,
        .textures = textures,
        .texture_count = loaded->texture_count,
    };
    result = rtpbr_gpu_scene_create_with_light_facts(ctx, &desc, light_facts, out_scene);
cleanup:
    rtpbr_free(&ctx->host, meshes);
    rtpbr_free(&ctx->host, materials);
    rtpbr_free(&ctx->host, lights);
    rtpbr_free(&ctx->host, light_facts);
    rtpbr_free(&ctx->host, cameras);
    rtpbr_free(&ctx->host, textures);
    return result;
}

static void forward_loader_log(rtpbr_gltf_log_level level, const char *message, void *user_data)
{
    const rtpbr_context *ctx = user_data;
    rtpbr_log(&ctx->host, level == RTPBR_GLTF_LOG_ERROR ? RTPBR_LOG_ERROR
                   : level == RTPBR_GLTF_LOG_WARNING ? RTPBR_LOG_WARNING : RTPBR_LOG_INFO,
              "glTF loader: %s", message);
}

rtpbr_result rtpbr_gpu_scene_load_gltf(rtpbr_context *ctx, const char *path, rtpbr_gpu_scene **out_scene)
{
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!path || !out_scene) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_load_gltf: path or out_scene is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out_scene = NULL;
    char message[RTPBR_GLTF_ERROR_MESSAGE_SIZE] = "";
    rtpbr_gltf_load_desc desc = {
        .allocator = {ctx->host.allocator.alloc, ctx->host.allocator.free, ctx->host.allocator.user_data},
        .logger = {forward_loader_log, ctx},
        .error_message = message,
        .error_message_size = sizeof message,
        .max_lights = RTPBR_MAX_LIGHTS,
        .skip_images = false,
    };
    rtpbr_gltf_scene *loaded = NULL;
    rtpbr_gltf_result sr = rtpbr_gltf_load(path, &desc, &loaded);
    if (sr != RTPBR_GLTF_SUCCESS) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "cannot load %s: %s: %s", path, rtpbr_gltf_result_string(sr), message);
        switch (sr) {
        case RTPBR_GLTF_ERROR_IO: return RTPBR_ERROR_IO;
        case RTPBR_GLTF_ERROR_OUT_OF_MEMORY: return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
        case RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS: return RTPBR_ERROR_LIMIT_EXCEEDED;
        case RTPBR_GLTF_ERROR_INVALID_ARGUMENT: return RTPBR_ERROR_INVALID_ARGUMENT;
        default: return RTPBR_ERROR_SCENE_LOAD;
        }
    }
    rtpbr_result result = rtpbr_gpu_scene_from_loaded(ctx, loaded, out_scene);
    rtpbr_gltf_destroy(loaded);
    return result;
}
