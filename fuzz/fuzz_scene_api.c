/* libFuzzer target: the engine's C scene API (issue 18), rtpbr_gpu_scene_create and
 * rtpbr_gpu_scene_set_lights with descs decoded from the input, on lavapipe with the
 * Vulkan validation layer on.
 *
 * Why a real device and not a mock: the API's checks come first and cost nothing, but the
 * interesting failures are what happens after them (buffer sizes, texture uploads, descriptor
 * writes, half-built scenes destroyed on failure). lavapipe runs headless everywhere the
 * tests run, and the validation layer turns misuse of Vulkan into a finding: any validation
 * message aborts. One context is created at start-up; each input creates a scene, replaces
 * its lights, and destroys it.
 *
 * The input is read as a stream: counts (bounded so one execution stays small), flags that
 * drop required or optional arrays, and the raw bytes of every float and integer field of
 * the descs (so NaN, Inf, huge and negative values, out-of-range indices and enums all
 * occur). Arrays always hold as many elements as their counts say: the API cannot check
 * that, it is the host's promise. Promises checked: a result in range with a name; on
 * failure *out_scene is NULL and an error was logged; on success light_count matches. */
#include <rtpbr/rtpbr.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { kMaxMeshes = 4, kMaxVertices = 48, kMaxIndices = 96, kMaxMaterials = 4, kMaxTextures = 3,
       kMaxTextureSide = 8, kMaxLights = 12, kMaxCameras = 2 };

static rtpbr_context* g_ctx;
static int g_errors, g_validation;
static char g_last[1024];

static void check(int ok, const char* what) {
    if (ok) return;
    fprintf(stderr, "fuzz_scene_api: broken promise: %s (last message: %s)\n", what, g_last);
    abort();
}

static void on_log(rtpbr_log_level level, const char* message, void* user_data) {
    (void)user_data;
    if (strncmp(message, "validation: ", 12) == 0) {
        fprintf(stderr, "fuzz_scene_api: %s\n", message);
        g_validation++;
    }
    if (level == RTPBR_LOG_ERROR) {
        g_errors++;
        snprintf(g_last, sizeof g_last, "%s", message);
    }
}

static void destroy_context(void) { rtpbr_context_destroy(g_ctx); }

int LLVMFuzzerInitialize(int* argc, char*** argv) {
    (void)argc, (void)argv;
    rtpbr_context_desc desc = {.logger = {on_log, NULL}, .validation = getenv("RTPBR_FUZZ_NO_VALIDATION") ? 0 : 1};
    rtpbr_result r = rtpbr_context_create(&desc, &g_ctx);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "fuzz_scene_api: no context: %s: %s\n", rtpbr_result_string(r), g_last);
        abort();
    }
    atexit(destroy_context);
    return 0;
}

/* The input as a stream; past its end everything reads as zero. */
typedef struct reader {
    const uint8_t* p;
    size_t left;
} reader;

static void take(reader* in, void* out, size_t n) {
    size_t k = n < in->left ? n : in->left;
    memcpy(out, in->p, k);
    memset((uint8_t*)out + k, 0, n - k);
    in->p += k, in->left -= k;
}
static uint32_t u8(reader* in) {
    uint8_t v;
    take(in, &v, 1);
    return v;
}

/* Mostly plausible floats (a byte picks a small value or a special), sometimes raw bits. */
static float number(reader* in) {
    static const float kSpecial[] = {0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-30f, 1e30f, 3.4e38f, -3.4e38f, 1e19f};
    uint32_t b = u8(in);
    if (b < 160) return ((float)b - 80.0f) / 16.0f;
    if (b < 240) return kSpecial[b % (sizeof kSpecial / sizeof kSpecial[0])];
    if (b < 248) {
        uint32_t bits;
        take(in, &bits, 4);
        float f;
        memcpy(&f, &bits, 4);
        return f;  /* NaN, Inf, denormals, anything */
    }
    return b == 248 ? __builtin_nanf("") : b == 249 ? __builtin_inff() : -__builtin_inff();
}
static void numbers(reader* in, float* out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = number(in);
}

static void read_lights(reader* in, rtpbr_light_desc* lights, uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
        memset(&lights[i], 0, sizeof lights[i]);
        uint32_t b = u8(in);
        lights[i].vertex_count = b < 200 ? 3 + b % 6 : b % 12; /* sometimes 0..2 or > 8 */
        numbers(in, &lights[i].vertices[0][0], 3 * RTPBR_MAX_POLYGON_VERTICES);
        numbers(in, lights[i].emission, 3);
        lights[i].two_sided = (int)(u8(in) % 3) - 1;
        /* mostly polygons; else a punctual light (issue 30), sometimes of no valid type */
        uint32_t t = u8(in);
        if (t >= 160) {
            lights[i].type = (rtpbr_light_type)(t % 5 == 4 ? 200 + t % 50 : 1 + t % 3);
            numbers(in, lights[i].position, 3);
            numbers(in, lights[i].direction, 3);
            lights[i].range = number(in);
            lights[i].inner_cone_angle = number(in);
            lights[i].outer_cone_angle = number(in);
            lights[i].angular_diameter = number(in);
            lights[i].radius = number(in);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    reader in = {data, size};
    static float positions[kMaxMeshes][3 * kMaxVertices], normals[kMaxMeshes][3 * kMaxVertices];
    static float texcoords[kMaxMeshes][2 * kMaxVertices], tangents[kMaxMeshes][4 * kMaxVertices];
    static uint32_t indices[kMaxMeshes][kMaxIndices];
    static uint8_t texels[kMaxTextures][kMaxTextureSide * kMaxTextureSide * 4];
    rtpbr_mesh_desc meshes[kMaxMeshes];
    rtpbr_material_desc materials[kMaxMaterials];
    rtpbr_texture_desc textures[kMaxTextures];
    rtpbr_light_desc lights[kMaxLights], new_lights[kMaxLights];
    rtpbr_camera_desc cameras[kMaxCameras];

    const uint32_t flags = u8(&in) | u8(&in) << 8;
    rtpbr_gpu_scene_desc desc = {
        .mesh_count = u8(&in) % (kMaxMeshes + 1),
        .material_count = u8(&in) % (kMaxMaterials + 1),
        .texture_count = u8(&in) % (kMaxTextures + 1),
        .light_count = u8(&in) % (kMaxLights + 1),
        .camera_count = u8(&in) % (kMaxCameras + 1),
    };
    for (uint32_t m = 0; m < desc.mesh_count; ++m) {
        rtpbr_mesh_desc* d = &meshes[m];
        memset(d, 0, sizeof *d);
        const uint32_t b = u8(&in);
        d->vertex_count = u8(&in) % (kMaxVertices + 1);
        d->index_count = b & 1 ? u8(&in) % (kMaxIndices + 1) : 0;
        numbers(&in, positions[m], 3 * d->vertex_count);
        d->positions = b & 2 ? NULL : positions[m];  /* required */
        if (b & 4) numbers(&in, normals[m], 3 * d->vertex_count), d->normals = normals[m];
        if (b & 8) numbers(&in, texcoords[m], 2 * d->vertex_count), d->texcoords = texcoords[m];
        if (b & 16) numbers(&in, tangents[m], 4 * d->vertex_count), d->tangents = tangents[m];
        if (d->index_count) {
            for (uint32_t i = 0; i < d->index_count; ++i) {
                uint32_t v = u8(&in);
                indices[m][i] = v < 250 || !d->vertex_count ? v % (d->vertex_count + 2) : UINT32_MAX - v % 3;
            }
            d->indices = b & 32 ? NULL : indices[m];
        }
        d->material = u8(&in) % (kMaxMaterials + 2);
        if (b & 64) numbers(&in, d->transform, 16);
    }
    for (uint32_t m = 0; m < desc.material_count; ++m) {
        /* Every field from the input: enums, booleans and texture indices included. */
        take(&in, &materials[m], sizeof materials[m]);
        if (u8(&in) < 200) {  /* mostly plausible factors, so that creation gets past the checks */
            numbers(&in, materials[m].base_color, 3);
            materials[m].metallic = number(&in), materials[m].roughness = number(&in);
            materials[m].base_color_texture %= kMaxTextures + 2;
            materials[m].metallic_roughness_texture %= kMaxTextures + 2;
            materials[m].emission_texture %= kMaxTextures + 2;
            materials[m].normal_texture %= kMaxTextures + 2;
            materials[m].model %= 3;
            materials[m].flags &= RTPBR_MATERIAL_FRESNEL_ONE | RTPBR_MATERIAL_NO_SPECULAR |
                                  RTPBR_MATERIAL_NO_ALPHA_CUTOFF | RTPBR_MATERIAL_DISNEY_NO_SPECULAR;
        }
    }
    for (uint32_t t = 0; t < desc.texture_count; ++t) {
        const uint32_t b = u8(&in);
        textures[t].width = b & 0x80 ? u8(&in) << 24 | u8(&in) : 1 + b % kMaxTextureSide;
        textures[t].height = b & 0x40 ? 0 : 1 + (b >> 3) % kMaxTextureSide;
        take(&in, texels[t], sizeof texels[t]);
        /* Big claimed sizes must be refused before the texels are read: keep them NULL. */
        const int fits = textures[t].width <= kMaxTextureSide && textures[t].height <= kMaxTextureSide;
        textures[t].rgba = fits && !(b & 0x20 && b & 0x10) ? texels[t] : NULL;
        textures[t].srgb = (int)(b & 1);
    }
    read_lights(&in, lights, desc.light_count);
    for (uint32_t c = 0; c < desc.camera_count; ++c) numbers(&in, &cameras[c].position[0], sizeof cameras[c] / 4);
    desc.meshes = flags & 1 && desc.mesh_count ? NULL : meshes;
    desc.materials = flags & 2 && desc.material_count ? NULL : materials;
    desc.textures = flags & 4 && desc.texture_count ? NULL : textures;
    desc.lights = flags & 8 && desc.light_count ? NULL : lights;
    desc.cameras = flags & 16 && desc.camera_count ? NULL : cameras;
    if (flags & 32) desc.light_count += RTPBR_MAX_LIGHTS * (desc.lights == NULL);  /* past the limit, no array */

    g_errors = 0;
    rtpbr_gpu_scene* scene = (rtpbr_gpu_scene*)(uintptr_t)1;
    rtpbr_result r = rtpbr_gpu_scene_create(g_ctx, &desc, &scene);
    check(r >= RTPBR_SUCCESS && r <= RTPBR_ERROR_VULKAN, "result in range");
    check(strcmp(rtpbr_result_string(r), "unknown result") != 0, "result has a name");
    check(g_validation == 0, "no validation message");
    if (r != RTPBR_SUCCESS) {
        check(scene == NULL, "*out_scene NULL on failure");
        check(g_errors > 0, "an error message on failure");
        return 0;
    }
    check(scene != NULL, "a scene on success");
    check(rtpbr_gpu_scene_light_count(scene) == desc.light_count, "light_count after create");
    const uint32_t count = u8(&in) % (kMaxLights + 1);
    read_lights(&in, new_lights, count);
    g_errors = 0;
    r = rtpbr_gpu_scene_set_lights(scene, flags & 64 && count ? NULL : new_lights, count);
    check(g_validation == 0, "no validation message");
    if (r == RTPBR_SUCCESS) check(rtpbr_gpu_scene_light_count(scene) == count, "light_count after set_lights");
    else check(g_errors > 0, "an error message when set_lights fails");
    rtpbr_gpu_scene_destroy(scene);
    check(g_validation == 0, "no validation message");
    return 0;
}
