/* libFuzzer target: the glTF scene loader through its C API (rtpbr_gltf_load_memory; GLB
 * when the input starts with "glTF", else JSON). External URIs resolve under a private
 * temporary folder holding the bundled scenes' .bin buffers, two small images, a
 * subfolder, and a symbolic link that points outside of the folder (must be rejected).
 *
 * Beyond "no crash, no leak, no UB" the target checks what rtpbr_gltf.h promises: on
 * failure *out is NULL and the message is non-empty; on success every index, material and
 * texture reference is in range, light polygons have 3..8 vertices, punctual lights are
 * finite with a unit direction and cones in range, and the limits hold.
 * A broken promise aborts, which libFuzzer records as a crash. */
#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#include <rtpbr/rtpbr_gltf.h>

#include <dirent.h>
#include <ftw.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Limits far below the defaults keep one execution fast: the code paths are the same (the
 * limits are only compared against), but a mutated accessor count or image header that
 * points at the bundled scenes' 66 KB buffers or asks for a big texture is refused at once
 * instead of costing tens of milliseconds of instrumented vertex and pixel work (issue 18:
 * the corpus ran at 42-85 executions per second, dominated by such inputs). */
enum { kFuzzMaxVertices = 1 << 12, kFuzzMaxLights = 256, kFuzzMaxTexture = 64 };
static const uint64_t kFuzzTextureBudget = 1 << 20;

static char g_root[64];      /* private temporary folder */
static char g_base_dir[96];  /* g_root/scene: base_dir of every load */
static int g_verbose;        /* RTPBR_FUZZ_VERBOSE=1: print each result (seed checks) */

static void check(int ok, const char* what) {
    if (ok) return;
    fprintf(stderr, "fuzz_scene: broken promise: %s\n", what);
    abort();
}

static void copy_file(const char* from, const char* to) {
    FILE* in = fopen(from, "rb");
    FILE* out = in ? fopen(to, "wb") : NULL;
    char buf[1 << 14];
    size_t n;
    while (in && out && (n = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, n, out);
    if (in) fclose(in);
    if (out) fclose(out);
}

/* Copies the regular files of `dir` whose name ends in one of the suffixes. */
static void copy_dir(const char* dir, const char* const* suffixes) {
    DIR* d = opendir(dir);
    if (!d) return;
    struct dirent* e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        for (const char* const* s = suffixes; *s; ++s) {
            size_t sl = strlen(*s);
            if (len > sl && strcmp(e->d_name + len - sl, *s) == 0) {
                char from[4096], to[4096];
                snprintf(from, sizeof from, "%s/%s", dir, e->d_name);
                snprintf(to, sizeof to, "%s/%s", g_base_dir, e->d_name);
                copy_file(from, to);
            }
        }
    }
    closedir(d);
}

static int remove_entry(const char* path, const struct stat* st, int flag, struct FTW* ftw) {
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void cleanup(void) {
    if (g_root[0]) nftw(g_root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

int LLVMFuzzerInitialize(int* argc, char*** argv) {
    (void)argc, (void)argv;
    g_verbose = getenv("RTPBR_FUZZ_VERBOSE") != NULL;
    snprintf(g_root, sizeof g_root, "/tmp/rtpbr-fuzz-scene-XXXXXX");
    if (!mkdtemp(g_root)) {
        perror("fuzz_scene: mkdtemp");
        abort();
    }
    atexit(cleanup);
    snprintf(g_base_dir, sizeof g_base_dir, "%s/scene", g_root);
    mkdir(g_base_dir, 0700);
    static const char* const bins[] = {".bin", NULL};
    static const char* const images[] = {".png", ".jpg", NULL};
    copy_dir(RTPBR_FUZZ_SCENES_DIR, bins);
    copy_dir(RTPBR_FUZZ_ASSETS_DIR, images);
    char path[4096], target[4096];
    snprintf(path, sizeof path, "%s/sub", g_base_dir);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/sub/quad_light.bin", g_base_dir);
    snprintf(target, sizeof target, "%s/quad_light.bin", g_base_dir);
    copy_file(target, path);
    snprintf(path, sizeof path, "%s/secret.bin", g_root);
    copy_file(target, path);
    snprintf(path, sizeof path, "%s/outside.bin", g_base_dir);
    if (symlink("../secret.bin", path) != 0) perror("fuzz_scene: symlink");
    return 0;
}

static void on_log(rtpbr_gltf_log_level level, const char* message, void* user_data) {
    (void)user_data;
    check(level <= RTPBR_GLTF_LOG_INFO, "log level in range");
    check(message != NULL && strlen(message) < (1u << 20), "log message NUL-terminated");
}

static int finite3(const float* v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

static void check_scene(const rtpbr_gltf_scene* s) {
    uint64_t vertices = 0;
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const rtpbr_gltf_primitive* p = &s->primitives[i];
        check(p->index_count % 3 == 0 && p->index_count > 0, "index_count a positive multiple of 3");
        check(p->material < s->material_count, "primitive material in range");
        if (p->vertex_count > 0)
            check(p->positions && p->normals && p->texcoords && p->tangents, "vertex arrays present");
        if (p->index_count > 0) check(p->indices != NULL, "index array present");
        for (uint32_t k = 0; k < p->index_count; ++k)
            check(p->indices[k] < p->vertex_count, "index < vertex_count");
        for (uint32_t v = 0; v < p->vertex_count; ++v)
            check(finite3(&p->positions[3 * (size_t)v]), "finite positions");
        vertices += p->vertex_count;
    }
    check(vertices == s->total_vertex_count, "total_vertex_count");
    check(vertices <= kFuzzMaxVertices, "max_vertices");
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const rtpbr_gltf_material* m = &s->materials[i];
        const float values[] = {m->base_color[0], m->base_color[1], m->base_color[2], m->base_color[3],
                                m->metallic, m->roughness, m->ior.ior, m->specular.specular_factor,
                                m->specular.specular_color_factor[0], m->specular.specular_color_factor[1],
                                m->specular.specular_color_factor[2], m->clearcoat.clearcoat_factor,
                                m->clearcoat.clearcoat_roughness_factor, m->sheen.sheen_color_factor[0],
                                m->sheen.sheen_color_factor[1], m->sheen.sheen_color_factor[2],
                                m->sheen.sheen_roughness_factor, m->anisotropy.anisotropy_strength,
                                m->anisotropy.anisotropy_rotation, m->emissive_strength.emissive_strength,
                                m->disney.subsurface, m->disney.specular, m->disney.specular_tint,
                                m->disney.anisotropic, m->disney.sheen, m->disney.sheen_tint, m->disney.clearcoat,
                                m->disney.clearcoat_gloss, m->emission[0], m->emission[1], m->emission[2],
                                m->normal_scale, m->alpha_cutoff};
        for (size_t k = 0; k < sizeof values / sizeof *values; ++k) check(isfinite(values[k]), "finite material");
        const int32_t t[4] = {m->base_color_texture, m->metallic_roughness_texture, m->normal_texture,
                              m->emission_texture};
        for (int k = 0; k < 4; ++k)
            check(t[k] >= -1 && (t[k] < 0 || (uint32_t)t[k] < s->texture_count), "texture index in range");
    }
    for (uint32_t i = 0; i < s->texture_count; ++i) {
        const rtpbr_gltf_texture* t = &s->textures[i];
        check(t->width <= kFuzzMaxTexture && t->height <= kFuzzMaxTexture, "max_texture_dimension");
        check((t->width && t->height) == (t->pixels != NULL), "texture pixels iff a size");
        if (t->pixels) {
            /* Touch the last texel: the buffer must hold width × height × 4 bytes. */
            volatile uint8_t last = t->pixels[(size_t)t->width * t->height * 4 - 1];
            (void)last;
        }
    }
    for (uint32_t i = 0; i < s->camera_count; ++i) {
        const rtpbr_gltf_camera* c = &s->cameras[i];
        check(finite3(c->position) && finite3(c->forward) && finite3(c->up) && finite3(c->right) &&
                  isfinite(c->yfov) && isfinite(c->aspect) && isfinite(c->znear) && isfinite(c->zfar),
              "finite camera");
    }
    check(s->light_count <= kFuzzMaxLights, "max_lights");
    for (uint32_t i = 0; i < s->light_count; ++i) {
        const rtpbr_gltf_light* l = &s->lights[i];
        check(l->vertex_count >= 3 && l->vertex_count <= RTPBR_GLTF_MAX_POLYGON_VERTICES, "light vertex count");
        check(finite3(l->facts.normal) && finite3(l->facts.center) && finite3(l->radiance) && isfinite(l->radius), "finite light");
        for (uint32_t v = 0; v < l->vertex_count; ++v) check(finite3(l->vertices[v]), "finite light vertices");
        check(isfinite(l->facts.area) && l->facts.area > 0.0f, "light area > 0");
        check(l->primitive < 0 || (uint32_t)l->primitive < s->primitive_count, "light primitive in range");
        check(l->material < 0 || (uint32_t)l->material < s->material_count, "light material in range");
    }
    check(s->punctual_light_count <= kFuzzMaxLights - s->light_count, "max_lights, area and punctual lights");
    for (uint32_t i = 0; i < s->punctual_light_count; ++i) {
        const rtpbr_gltf_punctual_light* l = &s->punctual_lights[i];
        check(l->type <= RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, "punctual type in range");
        check(finite3(l->position) && finite3(l->direction) && finite3(l->intensity), "finite punctual light");
        const float len2 = l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                           l->direction[2] * l->direction[2];
        check(fabsf(len2 - 1.0f) < 1e-5f, "unit punctual direction");
        check(l->intensity[0] >= 0.0f && l->intensity[1] >= 0.0f && l->intensity[2] >= 0.0f, "intensity >= 0");
        check(isfinite(l->range) && l->range >= 0.0f, "range >= 0");
        check(l->type != RTPBR_GLTF_PUNCTUAL_DIRECTIONAL || l->range == 0.0f, "directional range 0");
        check(l->inner_cone_angle >= 0.0f && l->inner_cone_angle <= l->outer_cone_angle &&
                  l->outer_cone_angle <= 1.5707964f,
              "cones in range");
        check(l->type == RTPBR_GLTF_PUNCTUAL_SPOT || l->outer_cone_angle == 0.0f, "cones only on spots");
        check(l->type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL ? l->angular_diameter == RTPBR_GLTF_SUN_ANGULAR_DIAMETER
                                                         : l->angular_diameter == 0.0f,
              "the sun's angular diameter on directional lights only");
        check(isfinite(l->radius) && l->radius >= 0.0f, "radius finite, >= 0");
        check(l->type == RTPBR_GLTF_PUNCTUAL_POINT || l->radius == 0.0f, "a radius on point lights only");
        check(isfinite(l->length) && l->length >= 0.0f, "length finite, >= 0");
        check(l->length == 0.0f || l->radius > 0.0f, "a length on spheres only");
        const float axis2 = l->axis[0] * l->axis[0] + l->axis[1] * l->axis[1] + l->axis[2] * l->axis[2];
        check(finite3(l->axis) && fabsf(axis2 - 1.0f) < 1e-5f, "unit punctual axis");
        check(l->gltf_node >= 0 && l->gltf_light >= 0, "punctual sources");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_load_desc desc = {0};
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    desc.logger.func = on_log;
    desc.base_dir = g_base_dir;
    desc.max_vertices = kFuzzMaxVertices;
    desc.max_lights = kFuzzMaxLights;
    desc.max_texture_dimension = kFuzzMaxTexture;
    desc.texture_memory_budget = kFuzzTextureBudget;
    rtpbr_gltf_scene* scene = NULL;
    /* libFuzzer passes a non-NULL pointer even for empty inputs. */
    rtpbr_gltf_result r = rtpbr_gltf_load_memory(data ? (const void*)data : (const void*)"", size, &desc, &scene);
    if (g_verbose)
        fprintf(stderr, "fuzz_scene: %s %s (%u primitives, %u lights, %u textures)\n",
                rtpbr_gltf_result_string(r), err, scene ? scene->primitive_count : 0,
                scene ? scene->light_count : 0, scene ? scene->texture_count : 0);
    check(r >= RTPBR_GLTF_SUCCESS && r < RTPBR_GLTF_RESULT_COUNT, "result in range");
    check(strcmp(rtpbr_gltf_result_string(r), "RTPBR_GLTF_RESULT_UNKNOWN") != 0, "result has a name");
    if (r == RTPBR_GLTF_SUCCESS) {
        check(scene != NULL, "scene on success");
        check(err[0] == '\0', "empty message on success");
        check_scene(scene);
    } else {
        check(scene == NULL, "*out NULL on failure");
        check(err[0] != '\0', "message on failure");
    }
    rtpbr_gltf_destroy(scene);
    return 0;
}
