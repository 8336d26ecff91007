// rtpbr — a plain-C11 Vulkan deferred renderer for physically based materials lit by
// polygonal area lights. One public header, in the style of sokol and cgltf:
//
//   - every object is an opaque pointer; every rtpbr_*_destroy(NULL) is a no-op;
//   - every *_desc struct is meant to be zero-initialised ({0}); a zero field means the
//     default documented next to it;
//   - everything that can fail returns an rtpbr_result; rtpbr_result_string() names it and
//     the log callback receives a readable message saying what failed and why;
//   - no global state: all state hangs off an rtpbr_context; no abort()/exit();
//   - a NULL object where one is required (context, scene, renderer) returns
//     RTPBR_ERROR_INVALID_ARGUMENT with its message on stderr: there is no logger to reach;
//   - every array and struct a function takes (the *_desc structs and what they point to,
//     lights, materials, transforms) is read during the call and copied where it is kept:
//     the caller may free or reuse it as soon as the call returns. The exceptions are said
//     where they apply: the allocator and logger of rtpbr_context_desc (kept, with their
//     user_data, for the context's lifetime) and the host's Vulkan objects (embedded mode,
//     rtpbr_record_desc), which the host keeps alive while they are in use.
//
// Objects and ownership:
//   rtpbr_context    a Vulkan device (standalone: created here; embedded: the host's), the
//                    passes' pipelines and the lookup tables. Owns the scenes and renderers
//                    created from it: rtpbr_context_destroy destroys those still alive.
//   rtpbr_gpu_scene  meshes, materials, polygonal lights, cameras and textures on the GPU,
//                    with a BVH of its triangles for the shadow rays.
//   rtpbr_renderer   the per-resolution targets: G-buffer, shadow ratios, linear radiance,
//                    display image, readback buffers.
//   A scene may be rendered by any renderer of its context, and a renderer may render any
//   scene of its context.
//   rtpbr_light_set, rtpbr_lighting_targets
//                    the lighting-only path (a host's own G-buffer lit in its command buffer:
//                    "The lighting pass inside the host's frame" below); also owned by the
//                    context, which destroys those still alive.
//
// The frame (rtpbr_render / rtpbr_record):
//   1. G-buffer pass: base colour + metallic, world normal + perceptual roughness, emitted
//      radiance + material index, anisotropy direction, depth (every surface is shaded on the
//      side the camera sees; emission is front-side only unless the material is double-sided).
//   1b. With rtpbr_render_desc.shadows on: the shadow passes (compute): per pixel and shadowed
//      light, shadow rays against the scene's BVH, then a denoised shadow ratio per light.
//   2. Lighting (compute, RTPBR_TILE_SIZE_PIXELS-square tiles): a culling dispatch keeps, per
//      tile, the lights that may reach it (rtpbr_render_desc.light_cull_form_factor) and sorts
//      the tile into a class by the materials it holds; then one indirect dispatch per class
//      runs the lighting variant for that class, which sums, per polygonal light, the
//      material's diffuse and specular lobes integrated over the polygon with Linearly
//      Transformed Cosines (shaderlib/rtpbr/ltc.h; GGX or Beckmann, rtpbr_render_desc.ndf),
//      the Kulla-Conty multiple-scattering lobe (kulla_conty.h), clear coat and sheen layers,
//      plus emitted radiance; all BRDF and integration math is the shader library's. With
//      shadows, in each 16 x 16 tile the RTPBR_MAX_SHADOWED_LIGHTS lights that may light it
//      most are multiplied by their shadow ratios at the pixel. rtpbr_render_desc.mc_samples replaces this pass by a Monte
//      Carlo reference of the same integral.
//   3. Tone mapping: radiance * 2^exposure through a documented operator (rtpbr_tonemap),
//      sRGB-encoded into the display target.
//   The linear radiance (before exposure and tone mapping) is kept for rtpbr_read_radiance.
//
// Typical headless use:
//   rtpbr_context *ctx; rtpbr_context_create(&(rtpbr_context_desc){0}, &ctx);
//   rtpbr_gpu_scene *scene; rtpbr_gpu_scene_load_gltf(ctx, "scene.gltf", &scene);
//   rtpbr_renderer *r;  rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 640, .height = 480}, &r);
//   rtpbr_render(r, scene, &(rtpbr_render_desc){0});
//   rtpbr_read_radiance(r, pixels, 640 * 480 * 4 * sizeof(float));
//   rtpbr_renderer_destroy(r); rtpbr_gpu_scene_destroy(scene); rtpbr_context_destroy(ctx);
//
// Threading: an rtpbr_context and everything created from it must be used from one thread
// at a time (the host serialises calls). In embedded mode the host must also not use the
// queue it handed over while an rtpbr call that submits work (rtpbr_gpu_scene_create*,
// rtpbr_renderer_create, rtpbr_render, rtpbr_read_*) is running.
#ifndef RTPBR_H
#define RTPBR_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan_core.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(RTPBR_BUILDING_DLL)
#define RTPBR_API __declspec(dllexport)
#elif defined(__GNUC__)
#define RTPBR_API __attribute__((visibility("default")))
#else
#define RTPBR_API
#endif

// ---------------------------------------------------------------------------------------------
// Version (semantic versioning; CHANGELOG.md says what changed). Before 1.0 a minor release
// may change the ABI: the shared library's soname carries major.minor (librtpbr.so.0.2).
// The build checks these against meson.build's project version.

#define RTPBR_VERSION_MAJOR 0
#define RTPBR_VERSION_MINOR 2
#define RTPBR_VERSION_PATCH 0
#define RTPBR_MAKE_VERSION(major, minor, patch) (((uint32_t)(major) << 22) | ((uint32_t)(minor) << 12) | (uint32_t)(patch))
#define RTPBR_VERSION RTPBR_MAKE_VERSION(RTPBR_VERSION_MAJOR, RTPBR_VERSION_MINOR, RTPBR_VERSION_PATCH)

// The version of the library actually loaded, as RTPBR_MAKE_VERSION(major, minor, patch)
// (the layout of VK_MAKE_API_VERSION without the variant: major >> 22, minor >> 12 & 0x3ff,
// patch & 0xfff). Compare with RTPBR_VERSION, the header's, to detect a mismatched library.
RTPBR_API uint32_t rtpbr_version(void);

// ---------------------------------------------------------------------------------------------
// Results, allocator, logger

typedef enum rtpbr_result {
    RTPBR_SUCCESS = 0,
    RTPBR_ERROR_INVALID_ARGUMENT,    // NULL where an object is required, zero sizes, NaN, ...
    RTPBR_ERROR_OUT_OF_HOST_MEMORY,  // an allocation failed; the log names its size
    RTPBR_ERROR_OUT_OF_DEVICE_MEMORY,
    RTPBR_ERROR_NO_DEVICE,           // no Vulkan implementation or no suitable device
    RTPBR_ERROR_MISSING_FEATURE,     // the device lacks (or the host did not enable) a requirement
    RTPBR_ERROR_LIMIT_EXCEEDED,      // more lights, vertices, ... than the documented limits
    RTPBR_ERROR_SCENE_LOAD,          // a glTF file is missing, malformed or unsupported
    RTPBR_ERROR_IO,                  // a file could not be read or written
    RTPBR_ERROR_DEVICE_LOST,
    RTPBR_ERROR_VULKAN,              // any other failing VkResult (the log says which call)
} rtpbr_result;

// A static English name of the result ("invalid argument"); never NULL.
RTPBR_API const char *rtpbr_result_string(rtpbr_result result);

// Host allocator for the host memory librtpbr allocates: its objects, the scenes' host-side
// data and every temporary array, and on the glTF path the loaded scene the loader returns.
// Not through it: the Vulkan implementation's own allocations (the library passes no
// VkAllocationCallbacks), and tinygltf's parsing of a glTF file (C++ new/delete inside the
// loader, freed before rtpbr_gpu_scene_load_gltf returns). Both functions NULL: malloc/free.
// alloc must return memory aligned for any C type (like malloc), or NULL on failure; every
// failure is then reported as RTPBR_ERROR_OUT_OF_HOST_MEMORY with the size in the log.
typedef struct rtpbr_allocator {
    void *(*alloc)(size_t size, void *user_data);
    void (*free)(void *ptr, void *user_data);
    void *user_data;
} rtpbr_allocator;

typedef enum rtpbr_log_level {
    RTPBR_LOG_ERROR = 0,
    RTPBR_LOG_WARNING,
    RTPBR_LOG_INFO,
    RTPBR_LOG_DEBUG,
} rtpbr_log_level;

// Log callback. func NULL: errors and warnings are written to stderr, the rest is dropped.
// Validation-layer messages (standalone mode with validation on) arrive here too, with
// level ERROR or WARNING and text starting with "validation: ".
typedef struct rtpbr_logger {
    void (*func)(rtpbr_log_level level, const char *message, void *user_data);
    void *user_data;
} rtpbr_logger;

// ---------------------------------------------------------------------------------------------
// Context

// Embedded mode: the host's Vulkan objects. The library only creates (and destroys) its own
// objects on this device and never destroys, reconfigures or waits on anything else of the
// host's (it waits only on its own fences; vkQueueWaitIdle is never called).
// Requirements: the physical device supports Vulkan 1.3 and the host enabled the
// dynamicRendering feature when it created the device; the host states what it enabled by
// passing the VkPhysicalDeviceFeatures2 chain it gave vkCreateDevice (the library looks for
// VkPhysicalDeviceVulkan13Features or VkPhysicalDeviceDynamicRenderingFeatures in it).
// Missing requirement (or enabled_features NULL): RTPBR_ERROR_MISSING_FEATURE.
// queue must belong to queue_family_index, which must support graphics and compute.
typedef struct rtpbr_vulkan_device {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family_index;
    const VkPhysicalDeviceFeatures2 *enabled_features;
} rtpbr_vulkan_device;

// Standalone device choice (the documented rule): among physical devices that support
// Vulkan 1.3, dynamicRendering and a queue family with graphics + compute, take
// device_index if it is not RTPBR_DEVICE_AUTO (0 means AUTO); otherwise the first discrete
// GPU, else the first integrated GPU, else the first virtual GPU, else the first CPU device
// (lavapipe), in enumeration order within each kind. device_index counts only suitable
// devices, starting at 1 (1 = the first suitable device).
#define RTPBR_DEVICE_AUTO 0u

typedef struct rtpbr_context_desc {
    rtpbr_allocator allocator;   // zero: malloc/free
    rtpbr_logger logger;         // zero: errors and warnings to stderr
    // Standalone mode (embedded.device == VK_NULL_HANDLE):
    uint32_t device_index;       // 0: automatic choice (rule above)
    // Non-zero: enable VK_LAYER_KHRONOS_validation with synchronization validation, route
    // its messages to the logger and count them (rtpbr_context_validation_message_count).
    // Fails with RTPBR_ERROR_MISSING_FEATURE if the layer is not installed. Default: off.
    int validation;
    // Embedded mode: all of instance, physical_device, device, queue set. Default: standalone.
    rtpbr_vulkan_device embedded;
    // How the shadow rays are traced (rtpbr_shadow_ray_query). Default (0): hardware ray queries
    // on a GPU that has them, the compute BVH walk otherwise.
    int shadow_ray_query;
} rtpbr_context_desc;

// rtpbr_context_desc.shadow_ray_query. The shadow rays (rtpbr_render_desc.shadows) are traced
// either by the library's own BVH walk in a compute shader (every device) or by VK_KHR_ray_query
// against an acceleration structure of the scene's triangles (VK_KHR_acceleration_structure),
// which the driver builds and traverses (on a GPU with ray tracing hardware, in that hardware).
// Both give the same visibility (the same rays, the same alpha test), up to how each intersects
// a ray with a triangle's edges.
//   AUTO: ray queries where the device supports them (standalone: the context enables
//         VK_KHR_ray_query, VK_KHR_acceleration_structure, VK_KHR_deferred_host_operations and
//         bufferDeviceAddress; embedded: where the host enabled rayQuery, accelerationStructure
//         and bufferDeviceAddress in enabled_features), except on a CPU device, whose compute
//         walk is tuned for it (lavapipe);
//   OFF:  always the compute walk;
//   ON:   ray queries, also on a CPU device; rtpbr_context_create fails with
//         RTPBR_ERROR_MISSING_FEATURE where the device (or, embedded, the host) lacks them.
typedef enum rtpbr_shadow_ray_query {
    RTPBR_SHADOW_RAY_QUERY_AUTO = 0,
    RTPBR_SHADOW_RAY_QUERY_OFF = 1,
    RTPBR_SHADOW_RAY_QUERY_ON = 2,
} rtpbr_shadow_ray_query;

typedef struct rtpbr_context rtpbr_context;

RTPBR_API rtpbr_result rtpbr_context_create(const rtpbr_context_desc *desc, rtpbr_context **out_context);
// Waits for the library's own work, then destroys everything the context created.
// Teardown order: destroy renderers and scenes first, then the context. Scenes and renderers
// still alive are destroyed here (with a warning in the log, since it usually means a leak in
// the host); their handles are then invalid and must not be passed to rtpbr_*_destroy again.
RTPBR_API void rtpbr_context_destroy(rtpbr_context *context);
// Number of warning/error messages the validation layer has reported so far (0 when off).
RTPBR_API uint32_t rtpbr_context_validation_message_count(const rtpbr_context *context);
// The Vulkan objects the context uses (its own in standalone mode, the host's when embedded).
RTPBR_API rtpbr_vulkan_device rtpbr_context_vulkan_device(const rtpbr_context *context);
// Name of the physical device in use ("llvmpipe (LLVM 15.0.6, 256 bits)"); never NULL.
RTPBR_API const char *rtpbr_context_device_name(const rtpbr_context *context);
// Non-zero when the context traces shadow rays with VK_KHR_ray_query (rtpbr_shadow_ray_query).
RTPBR_API int rtpbr_context_shadow_ray_query(const rtpbr_context *context);

// ---------------------------------------------------------------------------------------------
// Scenes
//
// Units and conventions: right-handed world, metres; camera looks down its -Z (glTF).
// Colours are linear Rec.709. Light emission is radiance (W sr^-1 m^-2 per channel).

// Documented limits; exceeding any is RTPBR_ERROR_LIMIT_EXCEEDED.
#define RTPBR_MAX_LIGHTS 1024u           // polygonal lights per scene
// Distinct (texture, coordinates) pairs of textured lights per scene (rtpbr_light_desc.emission_texture).
#define RTPBR_MAX_TEXTURED_LIGHTS 64u
// Vertices per polygonal light: the one source of truth of the vertex limit. Equal to it
// must be RTPBR_GLTF_MAX_POLYGON_VERTICES (rtpbr_gltf.h; checked in engine/src/scene_gltf.c),
// the shaders' RTPBR_SHADER_MAX_POLYGON_VERTICES (checked in engine/src/internal.h) and
// shaderlib's RTPBR_LTC_MAX_VERTICES (checked in engine/shaders/vertex_limit.glsl).
#define RTPBR_MAX_POLYGON_VERTICES 8u
// A directional light's default angular diameter: the sun's mean, 0.53 degrees (radians).
#define RTPBR_SUN_ANGULAR_DIAMETER 0.00925f
// Where a directional light's disk is placed, from the world origin (its parallax at a point
// at distance r from the origin is r / RTPBR_SUN_DISTANCE radians: 1e-5 at 1 km).
#define RTPBR_SUN_DISTANCE 1.0e8f
// Smaller angular diameters are shaded as a true direction (1e-4 rad, 0.0057 degrees).
#define RTPBR_SUN_MIN_ANGULAR_DIAMETER 1.0e-4f
#define RTPBR_MAX_MATERIALS 65536u
#define RTPBR_MAX_RENDER_SIZE 16384u     // width and height of a renderer

// Which BRDF a material uses (docs/materials.md has the full mapping).
typedef enum rtpbr_material_model {
    RTPBR_MATERIAL_METALLIC_ROUGHNESS = 0, // glTF metallic-roughness + KHR clearcoat/specular/ior/anisotropy
    RTPBR_MATERIAL_DISNEY = 1,             // Burley 2012's principled BRDF (rtpbr_disney_params)
} rtpbr_material_model;

// Burley 2012, "Physically-Based Shading at Disney", sec. 5.2: used with RTPBR_MATERIAL_DISNEY
// together with base_color, metallic and roughness of the material. Values are clamped to
// [0, 1] (specular to [0, 12.5]) and taken literally, except specular: zero means Burley's
// default 0.5 (F0 = 0.04); RTPBR_MATERIAL_DISNEY_NO_SPECULAR in the material's flags means 0.
typedef struct rtpbr_disney_params {
    float subsurface;      // blend of Burley diffuse towards the Hanrahan-Krueger shape
    float specular;        // dielectric F0 = 0.08 specular, >= 0; zero: 0.5
    float specular_tint;   // tints the dielectric F0 towards the base hue
    float sheen;           // grazing retro-reflective lobe
    float sheen_tint;      // tints the sheen towards the base hue (Burley's default 0.5)
    float clearcoat;       // GTR1 coat of weight 0.25 clearcoat (not attenuating the base)
    float clearcoat_gloss; // coat alpha = mix(0.1, 0.001, gloss) (Burley's default 1)
    float anisotropic;     // aspect sqrt(1 - 0.9 anisotropic)
} rtpbr_disney_params;

// KHR_texture_transform of one texture slot, and the texture coordinate set it reads:
//   uv' = T R S uv:  u' = cos(r) sx u + sin(r) sy v + ox,  v' = -sin(r) sx u + cos(r) sy v + oy
// (translation x rotation x scale, r counter-clockwise in UV space). All zero: TEXCOORD_0 as is.
typedef struct rtpbr_texture_transform {
    float offset[2];         // ox, oy
    float rotation;          // r, radians
    float scale[2];          // sx, sy; both zero: 1, 1
    uint32_t texcoord;       // 0: the mesh's texcoords (TEXCOORD_0), 1: texcoords1 (TEXCOORD_1)
} rtpbr_texture_transform;

// glTF alphaMode (docs/materials.md, "Alpha"). A surface's coverage is the material's alpha
// times the base colour texture's alpha (at the base colour slot's texture transform).
typedef enum rtpbr_alpha_mode {
    RTPBR_ALPHA_OPAQUE = 0, // coverage ignored
    RTPBR_ALPHA_MASK = 1,   // cut out where coverage < alpha_cutoff: in the G-buffer and the shadow rays
    RTPBR_ALPHA_BLEND = 2,  // not in the G-buffer: shaded by a forward pass after lighting, back to
                            // front, premultiplied over the lit image (colour x a + below x (1 - a));
                            // the shadow rays pass with probability 1 - a
} rtpbr_alpha_mode;

// What a zero field of rtpbr_material_desc cannot say, because zero means the default there
// (rtpbr_material_desc.flags): the glTF values 0 of ior, specular and alphaCutoff, and Burley's
// specular 0. rtpbr_material_desc_from_loaded sets them from the file's zeros.
typedef enum rtpbr_material_flags {
    RTPBR_MATERIAL_FRESNEL_ONE = 1,        // KHR_materials_ior's ior 0: "the effective IOR becomes
                                           // positive infinity and the Fresnel term must evaluate to
                                           // 1" (the specular-glossiness mode); ior is ignored
    RTPBR_MATERIAL_NO_SPECULAR = 2,        // KHR_materials_specular specularFactor 0 (or a black
                                           // specularColorFactor): no dielectric specular lobe;
                                           // specular_factor is ignored
    RTPBR_MATERIAL_NO_ALPHA_CUTOFF = 4,    // glTF alphaCutoff 0: MASK cuts nothing out;
                                           // alpha_cutoff is ignored
    RTPBR_MATERIAL_DISNEY_NO_SPECULAR = 8, // Burley's specular 0; disney.specular is ignored
} rtpbr_material_flags;

// A material. Every field's zero is its default (so {0} is an opaque black dielectric of ior
// 1.5, specular_factor 1 and roughness RTPBR_MIN_ROUGHNESS); the values a zero cannot say are flags.
// Values are checked once, by rtpbr_gpu_scene_create and rtpbr_gpu_scene_set_material (NaN or
// infinite values, a negative ior, specular_factor, alpha_cutoff or disney.specular, an ior in (0, 1):
// RTPBR_ERROR_INVALID_ARGUMENT); the shaders' material resolve (shaderlib/rtpbr/material.h)
// applies the material rules (roughness floor, [0, 1] ranges) to the factors times the textures.
typedef struct rtpbr_material_desc {
    float base_color[3];     // linear albedo (glTF baseColorFactor.rgb); zero is black
    float metallic;          // [0, 1], taken literally (zero: dielectric)
    float roughness;         // perceptual roughness r in [0, 1] (alpha = r^2); zero: RTPBR_MIN_ROUGHNESS
    float emission[3];       // emitted radiance: glTF emissiveFactor x KHR_materials_emissive_strength
                             // (a product, so not named after either factor; the loader's name)
    float ior;               // dielectric index of refraction >= 1 (KHR_materials_ior); zero: 1.5
                             // (KHR's ior 0: RTPBR_MATERIAL_FRESNEL_ONE)
    float specular_factor;   // KHR_materials_specular specularFactor >= 0; zero: 1 (KHR's 0:
                             // RTPBR_MATERIAL_NO_SPECULAR)
    float specular_color[3]; // KHR_materials_specular specularColorFactor; all zero: (1, 1, 1)
    // Textures: 1-based indices into rtpbr_gpu_scene_desc.textures; 0: none. Sampled with each
    // texture's sampler (rtpbr_texture_desc) at the slot's *_transform of its texture
    // coordinate set; they multiply the factors above (glTF):
    uint32_t base_color_texture;         // rgb: base colour (give it srgb = 1)
    uint32_t metallic_roughness_texture; // g: roughness, b: metallic (linear)
    uint32_t emission_texture;           // rgb: emission (give it srgb = 1)
    uint32_t normal_texture;             // rgb: tangent-space normal (linear); needs tangents
    float normal_scale;                  // glTF normalTexture.scale (scales x, y); zero: 1
    rtpbr_texture_transform base_color_texture_transform;
    rtpbr_texture_transform metallic_roughness_texture_transform;
    rtpbr_texture_transform emission_texture_transform;
    rtpbr_texture_transform normal_texture_transform;
    // Non-zero: drawn and emitting on both sides (glTF doubleSided). Default (glTF's
    // single-sided): back faces, where the mesh's winding is clockwise as seen (after its
    // transform; counter-clockwise is front), are culled in the G-buffer and let shadow rays
    // through; emission only on the front side.
    int double_sided;
    // KHR_materials_clearcoat clearcoatFactor: a GGX coat (F0 0.04, f90 1) of weight
    // clearcoat_factor in [0, 1] over the whole material, which it attenuates by
    // 1 - clearcoat_factor F_coat(NoV). Zero: no coat.
    float clearcoat_factor;
    float clearcoat_roughness_factor; // perceptual; zero: RTPBR_MIN_ROUGHNESS
    // KHR_materials_anisotropy anisotropyStrength in [0, 1]: alpha_t = mix(alpha, 1, s^2)
    // along the anisotropy direction, alpha_b = alpha across it. The direction is the mesh's
    // tangent rotated by anisotropy_rotation (radians) toward the bitangent; a mesh without
    // tangents is shaded isotropically at sqrt(alpha_t alpha_b). The LTC pass stretches the
    // isotropic lobe of that alpha along the direction (engine/README.md).
    float anisotropy_strength;
    float anisotropy_rotation;
    // KHR_materials_sheen sheenColorFactor: a Charlie sheen layer (Estevez & Kulla 2017) of this
    // colour in [0, 1] over the material below the coat, which it scales by the KHR albedo
    // scaling 1 - max(sheen_color_factor) E_sheen. All zero: no sheen.
    float sheen_color_factor[3];
    float sheen_roughness_factor;     // perceptual, [0, 1]
    // The extensions' textures (1-based indices into rtpbr_gpu_scene_desc.textures, 0: none),
    // each multiplying its factor above per pixel in the channels glTF names, each with its
    // KHR_texture_transform. A scene whose materials use them renders up to three more
    // G-buffer attachments (engine/README.md); otherwise they cost nothing. Disney materials
    // ignore them, as they ignore the factors.
    uint32_t clearcoat_texture;           // r: x clearcoat_factor (linear)
    uint32_t clearcoat_roughness_texture; // g: x clearcoat_roughness_factor (linear)
    uint32_t sheen_color_texture;         // rgb: x sheen_color_factor (give it srgb = 1)
    uint32_t sheen_roughness_texture;     // a: x sheen_roughness_factor (linear)
    uint32_t specular_texture;            // a: x specular_factor (linear)
    uint32_t specular_color_texture;      // rgb: x specular_color (give it srgb = 1)
    rtpbr_texture_transform clearcoat_texture_transform;
    rtpbr_texture_transform clearcoat_roughness_texture_transform;
    rtpbr_texture_transform sheen_color_texture_transform;
    rtpbr_texture_transform sheen_roughness_texture_transform;
    rtpbr_texture_transform specular_texture_transform;
    rtpbr_texture_transform specular_color_texture_transform;
    rtpbr_material_model model;   // zero: glTF metallic-roughness
    rtpbr_disney_params disney;   // used when model = RTPBR_MATERIAL_DISNEY
    rtpbr_alpha_mode alpha_mode;  // default: opaque
    float alpha;                  // glTF baseColorFactor.a, [0, 1] (clamped), taken literally; MASK and BLEND only
    float alpha_cutoff;           // MASK: >= 0; zero: 0.5 (glTF's default; glTF's 0, nothing is
                                  // cut: RTPBR_MATERIAL_NO_ALPHA_CUTOFF)
    uint32_t flags;               // rtpbr_material_flags bits; zero: none
} rtpbr_material_desc;

// Lower clamp of perceptual roughness (Filament's): RTPBR_MATERIAL_MIN_ROUGHNESS of
// shaderlib/rtpbr/material.h, which applies it (tests/shaderlib/material/test_material.cpp asserts
// that the two are equal).
#define RTPBR_MIN_ROUGHNESS 0.045f

// A texture's sampler (glTF sampler): wrap modes and filters.
typedef enum rtpbr_wrap {
    RTPBR_WRAP_REPEAT = 0,           // glTF 10497
    RTPBR_WRAP_CLAMP_TO_EDGE = 1,    // glTF 33071
    RTPBR_WRAP_MIRRORED_REPEAT = 2,  // glTF 33648
} rtpbr_wrap;
typedef enum rtpbr_filter {
    RTPBR_FILTER_LINEAR = 0,
    RTPBR_FILTER_NEAREST = 1,
} rtpbr_filter;
typedef enum rtpbr_mipmap_mode {
    RTPBR_MIPMAP_LINEAR = 0,  // between the two nearest levels (with a linear min_filter: trilinear)
    RTPBR_MIPMAP_NEAREST = 1, // the nearest level
    RTPBR_MIPMAP_NONE = 2,    // level 0 only (glTF minFilter NEAREST or LINEAR)
} rtpbr_mipmap_mode;

// The mip chain is built at upload (linear blits; sRGB textures are filtered in linear space)
// unless mipmap is RTPBR_MIPMAP_NONE or the device cannot blit the format with linear
// filtering (then level 0 only, with an info message). Sampling is anisotropic (up to 16x)
// with linear filters and mipmaps when the device has samplerAnisotropy enabled (standalone:
// when supported; embedded: when the host enabled it).
typedef struct rtpbr_texture_desc {
    uint32_t width, height;  // required, 1..RTPBR_MAX_RENDER_SIZE
    const uint8_t *rgba;     // required: width * height RGBA8 texels, rows top to bottom
    int srgb;                // non-zero: sRGB-encoded colour; default: linear data
    rtpbr_wrap wrap_s, wrap_t;   // default: repeat
    rtpbr_filter mag_filter;     // default: linear
    rtpbr_filter min_filter;     // default: linear
    rtpbr_mipmap_mode mipmap;    // default: linear (trilinear with the default min_filter)
} rtpbr_texture_desc;

typedef struct rtpbr_mesh_desc {
    const float *positions;   // 3 floats per vertex; required
    const float *normals;     // 3 floats per vertex; NULL: computed (area-weighted smooth)
    const float *texcoords;   // 2 floats per vertex (glTF TEXCOORD_0); NULL: all zero
    const float *texcoords1;  // 2 floats per vertex (glTF TEXCOORD_1); NULL: all zero
    const float *tangents;    // 4 floats per vertex: xyz, w = bitangent sign (B = w N x T, glTF);
                              // NULL: zero, and normal textures have no effect
    const uint32_t *indices;  // 3 per triangle; NULL: vertices taken three at a time
    uint32_t vertex_count;    // required, non-zero
    uint32_t index_count;     // a multiple of 3 when indices is set
    uint32_t material;        // index into rtpbr_gpu_scene_desc.materials; 0 with no materials: grey
    float transform[16];      // world-from-object, column-major; all zero: identity
} rtpbr_mesh_desc;

// What a light is (rtpbr_light_desc.type). Zero: a polygon.
typedef enum rtpbr_light_type {
    RTPBR_LIGHT_POLYGON = 0,     // an area light: vertices, vertex_count, two_sided
    RTPBR_LIGHT_POINT = 1,       // glTF KHR_lights_punctual's, evaluated exactly (no size; a
                                 //   point light may have a radius: a sphere, below):
    RTPBR_LIGHT_SPOT = 2,        //   position, range; a spot's direction and cones;
    RTPBR_LIGHT_DIRECTIONAL = 3, //   a directional light's direction
    RTPBR_LIGHT_DISK = 4,        // an area light: a disk of radius `radius` about position,
                                 //   emitting along direction (its normal), two_sided
    RTPBR_LIGHT_TUBE = 5,        // an area light: a tube (capsule) of radius `radius` around the
                                 //   segment of `length` centred on position along direction
} rtpbr_light_type;

// A light. RTPBR_LIGHT_POLYGON (zero): a convex planar polygon emitting on its front side
// (counter-clockwise vertices seen from the front, normal = right-hand rule), or on both sides.
// The punctual types (docs/materials.md, "Punctual lights"): the radiance a surface reflects
// toward V from a point or spot light at distance d in direction L is
//   f(V, L) (N.L) emission W(d) / d^2  (x the spot's falloff),
// W(d) = clamp(1 - (d / range)^4, 0, 1) (1 without a range); from a directional light
// f(V, L) (N.L) emission, L = -direction.
// RTPBR_LIGHT_DISK: a flat disk of uniform radiance `emission`, shaded exactly (the disk's own
// ellipse under each lobe's LTC, Heitz & Hill 2017; shaderlib/rtpbr/area_light.h,
// AreaLight_AddDisk), not as a polygon: position its centre, direction its normal (the side it
// emits on; need not be unit, non-zero), radius > 0, two_sided as a polygon's. With
// disk_radius2 > 0, an ellipse (half-axes radius along disk_axis, disk_radius2 across it).
// RTPBR_LIGHT_TUBE: a capsule (the segment position +- direction length / 2, direction need not
// be unit, non-zero; swept by the ball of radius `radius` > 0: a cylinder and two hemispherical
// caps) of uniform radiance `emission` over its surface (area 4 pi r^2 + 2 pi r length), shaded
// with the shader library's tube (shaderlib/rtpbr/area_light.h, AreaLight_AddTube: the facing
// quad's LTC and the caps' sphere). length 0: a sphere of radiance `emission` (the point light
// of radius r and intensity emission pi r^2). A range windows its radiance by W(d), d the
// distance from its centre (position), as a sphere's.
typedef struct rtpbr_light_desc {
    float vertices[RTPBR_MAX_POLYGON_VERTICES][3]; // polygon: world space
    uint32_t vertex_count;   // polygon: 3..RTPBR_MAX_POLYGON_VERTICES; punctual: ignored
    float emission[3];       // polygon: radiance; point, spot: intensity (candela, the
                             // renderer's radiance unit x m^2); directional: illuminance (lux,
                             // the radiance unit x sr). Zero: a light that contributes nothing
    int two_sided;           // polygon, disk: non-zero emits on both sides. Default: front only
    rtpbr_light_type type;   // zero: a polygon
    float position[3];       // point, spot: world space; disk, tube: its centre
    float direction[3];      // spot, directional: the way the light travels (need not be unit;
                             // non-zero); disk: its normal, toward the side it emits on; tube:
                             // its axis
    float range;             // point, spot, tube: > 0, where W(d) ends; zero: infinite
    float inner_cone_angle;  // spot: radians, 0 <= inner <= outer <= pi/2; the falloff
    float outer_cone_angle;  // t = clamp((cos - cos outer) / max(cos inner - cos outer, 1e-3),
                             // 0, 1), times t^2 (KHR_lights_punctual); both zero: 0 and pi/4
    float angular_diameter;  // directional: the full apex angle of the light's disk, radians,
                             // < pi/2; zero: RTPBR_SUN_ANGULAR_DIAMETER; negative (or below
                             // RTPBR_SUN_MIN_ANGULAR_DIAMETER): a true direction (a delta
                             // light, evaluated exactly). The disk is shaded
                             // as an equal-area octagon at RTPBR_SUN_DISTANCE from the origin
                             // (a polygon light: soft shadows, glossy highlights of its size),
                             // of the radiance that gives `emission` lux at normal incidence.
                             // Point, spot: ignored
    float radius;            // point: >= 0; > 0 makes it a sphere of that radius (world units)
                             // around position, of uniform radiance emission / (pi radius^2)
                             // (the same intensity far away) times W(d), d the distance from
                             // its centre: an area light (soft shadows, highlights of its size)
                             // shaded with LTC like a polygon. Zero: a true point (exact).
                             // Spot: must be zero (spheres with a cone: not yet). Disk: > 0,
                             // the disk's radius. Tube: > 0, the capsule's radius.
                             // Directional, polygon: ignored
    uint32_t emission_texture; // polygon of 4 vertices, a parallelogram (a screen, a window):
                             // 1 + the index of a scene texture (rtpbr_gpu_scene_desc.textures;
                             // its rgb, sRGB-decoded when srgb, times `emission` is the radiance
                             // over the quad, alpha ignored); 0: none. The quad's point
                             // v0 + s (v1 - v0) + t (v3 - v0), s, t in [0, 1], has the texture
                             // coordinate uv0 + s (uv1 - uv0) + t (uv3 - uv0) (emission_uv; the
                             // texture's wrap modes apply). Shaded with LTC's textured lookup (each
                             // lobe reads a chain prefiltered at load, docs/materials.md). The
                             // texture must stay as it was: rtpbr_gpu_scene_set_lights accepts a
                             // textured light only with a texture and uv the scene was created
                             // with. rtpbr_light_set: not supported (RTPBR_ERROR_INVALID_ARGUMENT)
    float emission_uv[3][2]; // the texture coordinates uv0, uv1, uv3 at vertices 0, 1 and 3;
                             // all zero: (0, 0), (1, 0), (0, 1) (the whole texture, its top row
                             // along v0 -> v1)
    float disk_radius2;      // disk: > 0 makes it an ellipse, `radius` its half-axis along
                             // disk_axis and disk_radius2 the one across it (both in its plane),
                             // shaded exactly as a disk is (its ellipse under each LTC). Zero: a
                             // circle of radius `radius`. Other types: ignored
    float disk_axis[3];      // disk with disk_radius2 > 0: the direction of the half-axis
                             // `radius`; need not be unit nor in the plane (its part in the
                             // plane is used, which must not be zero)
    float length;            // tube: >= 0, the length of its segment (the cylinder's; world
                             // units). Other types: ignored
} rtpbr_light_desc;

typedef struct rtpbr_camera_desc {
    float position[3];
    float target[3];         // the point looked at; equal to position: looks down -Z
    float up[3];             // all zero: +Y
    float yfov;              // vertical field of view, radians; zero: pi/4
    float znear;             // zero: 0.01
    float zfar;              // zero: 1000
} rtpbr_camera_desc;

typedef struct rtpbr_gpu_scene_desc {
    const rtpbr_mesh_desc *meshes;
    uint32_t mesh_count;
    const rtpbr_material_desc *materials;
    uint32_t material_count;
    const rtpbr_light_desc *lights;
    uint32_t light_count;    // <= RTPBR_MAX_LIGHTS
    const rtpbr_camera_desc *cameras;
    uint32_t camera_count;   // zero: one default camera at (0, 0, 5) looking at the origin
    const rtpbr_texture_desc *textures;
    uint32_t texture_count;
} rtpbr_gpu_scene_desc;

typedef struct rtpbr_gpu_scene rtpbr_gpu_scene;
struct rtpbr_gltf_scene; // a scene loaded by the glTF loader (scene/rtpbr/rtpbr_gltf.h)

// Validates everything (finite numbers, index ranges, planar non-degenerate lights) before
// touching the GPU; a scene with no meshes and no lights is valid (renders the background).
// Every array of the desc (meshes and their vertex and index arrays, materials, lights,
// cameras, textures and their texels) is copied during the call; none is kept.
// Lights are not drawn: a light is seen only through an emissive mesh (glTF scenes have one).
RTPBR_API rtpbr_result rtpbr_gpu_scene_create(rtpbr_context *context, const rtpbr_gpu_scene_desc *desc,
                                              rtpbr_gpu_scene **out_scene);
// Loads a glTF 2.0 file through the rtpbr scene loader (scene). Emissive primitives
// and EXT_lights_area lights become polygonal lights; cameras come from the file (none in
// the file: the default camera of rtpbr_gpu_scene_desc). Missing or malformed file:
// RTPBR_ERROR_SCENE_LOAD or RTPBR_ERROR_IO, with the loader's message in the log.
RTPBR_API rtpbr_result rtpbr_gpu_scene_load_gltf(rtpbr_context *context, const char *path,
                                                 rtpbr_gpu_scene **out_scene);
// Uploads a scene the host loaded (or built) with the loader's C API, mapped as
// rtpbr_gpu_scene_load_gltf maps it (docs/materials.md has the table). The loaded scene is
// read during the call and not kept: the host may destroy it as soon as this returns.
// A non-zero count with a NULL array: RTPBR_ERROR_INVALID_ARGUMENT.
RTPBR_API rtpbr_result rtpbr_gpu_scene_from_loaded(rtpbr_context *context, const struct rtpbr_gltf_scene *loaded,
                                                   rtpbr_gpu_scene **out_scene);
// The glTF mapping of rtpbr_gpu_scene_from_loaded for one material and one texture, for hosts
// that build their own rtpbr_gpu_scene_desc from a loaded scene (the viewer edits materials):
// loader texture indices (0-based, -1 none) become 1-based desc indices, 0 for none or for a
// texture without texels. Indices out of range: *out is zeroed.
RTPBR_API void rtpbr_material_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t material,
                                               rtpbr_material_desc *out);
RTPBR_API void rtpbr_texture_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t texture,
                                              rtpbr_texture_desc *out);
// Area light `light` of a loaded scene (its lights[], not the punctual ones) as
// rtpbr_gpu_scene_from_loaded makes it: a polygon, a disk (EXT_lights_area's, not its octagon),
// or a textured quad (a screen: emission_texture, emission_uv; docs/materials.md, "Lights from
// materials"), for hosts that build their own lights (the viewer). Out of range: *out is zeroed.
RTPBR_API void rtpbr_light_desc_from_loaded(const struct rtpbr_gltf_scene *loaded, uint32_t light,
                                            rtpbr_light_desc *out);
RTPBR_API void rtpbr_gpu_scene_destroy(rtpbr_gpu_scene *scene);
RTPBR_API uint32_t rtpbr_gpu_scene_camera_count(const rtpbr_gpu_scene *scene);
RTPBR_API uint32_t rtpbr_gpu_scene_light_count(const rtpbr_gpu_scene *scene);
// Replaces every light (same validation and limits as rtpbr_gpu_scene_create; the array is
// copied). Must not be called while a command buffer recorded with rtpbr_record for this
// scene is pending.
RTPBR_API rtpbr_result rtpbr_gpu_scene_set_lights(rtpbr_gpu_scene *scene, const rtpbr_light_desc *lights,
                                                  uint32_t light_count);
// Edits in place, without re-uploading geometry. Like rtpbr_gpu_scene_set_lights they write
// host-visible memory the frames read: they must not be called while a command buffer
// recorded with rtpbr_record for this scene is pending (rtpbr_render has always finished).
// Replaces material `index` (< the desc's material_count) with *material, validated as by
// rtpbr_gpu_scene_create (finite values, known model, ior, texture indices within the
// scene's textures; textures may change). The desc is copied. Where the context traces shadow
// rays with ray queries (rtpbr_context_shadow_ray_query), a change of the material's sidedness
// or alpha mode rebuilds the scene's acceleration structures (one submission, waited for); if
// that fails (out of memory), the result says so and shadowed renders of the scene are refused
// until a later call (of this or rtpbr_gpu_scene_set_transform) rebuilds them.
RTPBR_API rtpbr_result rtpbr_gpu_scene_set_material(rtpbr_gpu_scene *scene, uint32_t index,
                                                    const rtpbr_material_desc *material);
// Replaces the world-from-object transform (column-major, finite; all zero: identity) of
// mesh `mesh` (< the desc's mesh_count, in the desc's order; for a glTF scene, the loader's
// primitives in order, whose positions are already in world space, so their transform starts
// as the identity). The matrix is copied. Lights do not follow: move them with
// rtpbr_gpu_scene_set_lights. The shadow rays' occluders follow: the BVH's triangles are
// transformed again and its boxes refitted (the tree kept, time linear in the scene's
// triangles; a mesh moved far from where it was leaves boxes larger than a new tree's), and
// with ray-query shadows the acceleration structures are built again (one submission, waited
// for; if that fails, as rtpbr_gpu_scene_set_material's).
RTPBR_API rtpbr_result rtpbr_gpu_scene_set_transform(rtpbr_gpu_scene *scene, uint32_t mesh,
                                                     const float transform[16]);

// ---------------------------------------------------------------------------------------------
// Renderers and rendering

typedef struct rtpbr_renderer_desc {
    uint32_t width;          // required, 1..RTPBR_MAX_RENDER_SIZE
    uint32_t height;         // required, 1..RTPBR_MAX_RENDER_SIZE
    // Anti-aliasing by supersampling: the G-buffer and lighting passes run at (s width) x
    // (s height) and a box filter averages each s x s block into the output (radiance alpha
    // becomes the pixel's coverage). 1..RTPBR_MAX_SUPERSAMPLE; zero: 1 (none). Costs s^2.
    // s width and s height must stay within RTPBR_MAX_RENDER_SIZE.
    uint32_t supersample;
    // Non-zero: every frame writes GPU timestamps around its passes (a query pool of four
    // timestamps), read with rtpbr_renderer_timings. Fails with RTPBR_ERROR_MISSING_FEATURE
    // on a queue family without timestamps. Default: off (no queries recorded).
    int timings;
} rtpbr_renderer_desc;
// A renderer holds, besides its G-buffer and radiance images, the shadow passes' estimates
// and ratios: 3 x 4 bytes per shading pixel and shadowed light (RTPBR_MAX_SHADOWED_LIGHTS),
// 96 bytes per shading pixel, and the trace's work list (4 bytes per 8 x 8 pixels and shadowed
// light: half a byte per pixel), allocated at creation whether or not shadows are used.

#define RTPBR_MAX_SUPERSAMPLE 4u

typedef struct rtpbr_renderer rtpbr_renderer;

RTPBR_API rtpbr_result rtpbr_renderer_create(rtpbr_context *context, const rtpbr_renderer_desc *desc,
                                   rtpbr_renderer **out_renderer);
RTPBR_API void rtpbr_renderer_destroy(rtpbr_renderer *renderer);

// GPU time of each pass of the renderer's last frame, from its timestamps, in milliseconds.
typedef struct rtpbr_timings {
    int valid;          // 0: no frame has completed yet (the other fields are zero)
    double gbuffer_ms;  // G-buffer pass
    double lighting_ms; // lighting: the tile cull and the LTC (or Monte Carlo) pass, with the resolve
    double tonemap_ms;  // tone mapping into the display image or the host's target
    double total_ms;    // the sum of the three
} rtpbr_timings;

// Reads the timestamps of the last frame recorded (rtpbr_render or rtpbr_record) without
// waiting: when that frame has not finished executing, out->valid is 0. After rtpbr_render
// the frame has always finished; after rtpbr_record, call it once the host's submission has
// completed. The renderer must have been created with rtpbr_renderer_desc.timings set
// (otherwise RTPBR_ERROR_INVALID_ARGUMENT).
RTPBR_API rtpbr_result rtpbr_renderer_timings(rtpbr_renderer *renderer, rtpbr_timings *out);

// Shader variants compiled at build time from the shader library's flags.
typedef enum rtpbr_ndf {
    RTPBR_NDF_DEFAULT = 0,   // GGX
    RTPBR_NDF_GGX_MODEL,     // RTPBR_NDF_GGX (Walter et al. 2007)
    RTPBR_NDF_BECKMANN_MODEL,// RTPBR_NDF_BECKMANN
} rtpbr_ndf;

typedef enum rtpbr_multiscatter {
    RTPBR_MULTISCATTER_DEFAULT = 0, // on
    RTPBR_MULTISCATTER_ON,          // Kulla-Conty energy compensation (RTPBR_MULTISCATTER 1)
    RTPBR_MULTISCATTER_OFF,         // single scattering only (RTPBR_MULTISCATTER 0)
} rtpbr_multiscatter;

typedef enum rtpbr_tonemap {
    // ACES filmic fit of Narkowicz 2015 ("ACES Filmic Tone Mapping Curve"):
    // f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1], per channel.
    RTPBR_TONEMAP_DEFAULT = 0,
    RTPBR_TONEMAP_ACES,
    RTPBR_TONEMAP_REINHARD,  // f(x) = x / (1 + x) per channel (Reinhard et al. 2002)
    RTPBR_TONEMAP_LINEAR,    // f(x) = clamp(x, 0, 1)
} rtpbr_tonemap;

typedef enum rtpbr_shadows {
    RTPBR_SHADOWS_DEFAULT = 0, // off
    RTPBR_SHADOWS_OFF,
    RTPBR_SHADOWS_ON,
} rtpbr_shadows;

typedef enum rtpbr_shadow_denoiser {
    RTPBR_SHADOW_DENOISER_DEFAULT = 0, // on
    RTPBR_SHADOW_DENOISER_ON,
    RTPBR_SHADOW_DENOISER_OFF,
} rtpbr_shadow_denoiser;

typedef enum rtpbr_shadow_cull {
    RTPBR_SHADOW_CULL_DEFAULT = 0, // on
    RTPBR_SHADOW_CULL_ON,
    RTPBR_SHADOW_CULL_OFF,
} rtpbr_shadow_cull;

typedef struct rtpbr_render_desc {
    // The camera: if camera is set it is used; otherwise the scene's camera number
    // camera_index (default 0). camera_index out of range: RTPBR_ERROR_INVALID_ARGUMENT.
    const rtpbr_camera_desc *camera;
    uint32_t camera_index;
    float exposure;          // EV stops; the display image shows radiance * 2^exposure. Default 0
    rtpbr_tonemap tonemap;   // default ACES (above)
    rtpbr_ndf ndf;           // default GGX
    rtpbr_multiscatter multiscatter; // default on
    float background[3];     // radiance where no surface is hit; default black
    // Per-tile light culling (RTPBR_TILE_SIZE^2-pixel tiles). A light is skipped for a tile
    // when every point of the tile is behind it (one-sided lights; exact), or when the bound
    // A / (pi d^2) on its form factor at every point of the tile (A its area, d the distance
    // between the tile's bounding box and the light's bounding sphere) is below this value:
    // its diffuse contribution is then below emission * albedo * light_cull_form_factor.
    // Glossy reflections of a culled light are lost with it. Zero: 1e-4; negative: only
    // the exact test. Punctual lights (KHR_lights_punctual) are not held to this bound: they
    // are skipped only where the tile is beyond their range (exact: their window is 0 there).
    float light_cull_form_factor;
    // The lighting pass. Zero (default): LTC (the real-time pass). N > 0: a brute-force Monte
    // Carlo reference pass of the same direct-lighting integral and material model, N samples
    // per pixel per light (light-area and visible-normal sampling combined by MIS; no
    // per-tile culling); noisy, for benchmarks and tests. At most RTPBR_MAX_MC_SAMPLES
    // (more: RTPBR_ERROR_LIMIT_EXCEEDED). Recorded as several dispatches when samples x
    // lights is large (lavapipe's loop budget; engine/README.md): cost grows with it.
    uint32_t mc_samples;
    // Random seed of the Monte Carlo pass (each seed gives an independent image). Default 0.
    uint32_t mc_seed;
    // Area-light shadows (default off): the ratio estimator of Heitz, Hill & McGuire 2018,
    // "Combining Analytic Direct Illumination and Stochastic Shadows". Per pixel and shadowed
    // light, shadow_samples points on the light (uniform by area, stratified) are traced
    // against the scene's triangles (a BVH built at scene creation); the light's result (LTC,
    // or the Monte Carlo pass's) is multiplied by the ratio of the shadowed to the unshadowed
    // estimate of its cosine-weighted irradiance, both from the same samples and each denoised
    // by a depth- and normal-guided spatial filter. Exact in the limit for Lambertian
    // surfaces; glossy lobes get the cosine-weighted visibility of the light. Which lights cast
    // is chosen per 16 x 16 pixel tile: the RTPBR_MAX_SHADOWED_LIGHTS lights of the largest
    // bound on their irradiance at the tile's surface points (luminance; an area light's
    // L min(A / d^2, pi), a point or spot light's I / d^2, a directional light's E; ties: the
    // lower index). The others are unshadowed in that tile.
    // Costs per frame about shadow_samples rays per pixel and shadowed light, none where
    // shadow_cull (below) proves that nothing can block them.
    rtpbr_shadows shadows;
    // Samples per pixel and shadowed light; zero: RTPBR_DEFAULT_SHADOW_SAMPLES. At most
    // RTPBR_MAX_SHADOW_SAMPLES (more: RTPBR_ERROR_LIMIT_EXCEEDED).
    uint32_t shadow_samples;
    // The spatial denoiser of both estimates (default on): a (2 r + 1)^2 window, r =
    // RTPBR_SHADOW_DENOISE_RADIUS, weighted by the neighbours' distance to the pixel's tangent
    // plane and their normals' agreement. Off: each pixel's own ratio.
    rtpbr_shadow_denoiser shadow_denoiser;
    // Random seed of the shadow samples (each seed gives an independent pattern). Default 0.
    uint32_t shadow_seed;
    // Shadow-ray culling (default on): the pixels of a 16 x 16 tile trace no ray toward a
    // shadowed light when no triangle of the scene can cross a segment from any of them to
    // the light (a walk of the BVH per tile and light: a triangle is passed over when its
    // bounding sphere misses the hull of the tile's points and the light's bounding sphere,
    // or the points and the whole light lie on one side of its plane), and the shadow pass
    // does no work at all for the pixels whose estimates no denoiser window then reads.
    // Conservative: those rays would all have been unoccluded, so the image is the same as
    // with culling off. Off: every ray is traced (for tests and benchmarks).
    rtpbr_shadow_cull shadow_cull;
} rtpbr_render_desc;

#define RTPBR_MAX_SHADOWED_LIGHTS 8u
#define RTPBR_DEFAULT_SHADOW_SAMPLES 4u
#define RTPBR_MAX_SHADOW_SAMPLES 4096u
#define RTPBR_SHADOW_DENOISE_RADIUS 3u

#define RTPBR_MAX_MC_SAMPLES 65536u

#define RTPBR_DEFAULT_CULL_FORM_FACTOR 1e-4f
#define RTPBR_TILE_SIZE_PIXELS 16

// Records and submits one frame and waits for it: G-buffer, lighting, tone mapping into the
// renderer's own targets, which rtpbr_read_* then read back. The frame copies nothing to the
// host: the first rtpbr_read_radiance (rtpbr_read_display) after a frame copies that image in
// a submission of its own and waits for it, later reads of the same frame only copy memory, so
// a frame that is not read back (a real-time loop) pays for no copy.
RTPBR_API rtpbr_result rtpbr_render(rtpbr_renderer *renderer, const rtpbr_gpu_scene *scene,
                          const rtpbr_render_desc *desc);

// Linear scene radiance of the last rtpbr_render or rtpbr_record (no exposure, no tone
// mapping): RGBA32F, rows top to bottom, width * height * 4 floats (alpha 1 on surfaces, 0 on
// background). size_bytes must be at least width * height * 16. INVALID_ARGUMENT (with a
// message) before the first rtpbr_render or rtpbr_record, like rtpbr_read_display. The
// renderer's first read allocates its host-visible readback buffer (16 bytes a pixel; the
// display's: 4), which a renderer never read back does not hold.
RTPBR_API rtpbr_result rtpbr_read_radiance(rtpbr_renderer *renderer, float *rgba, size_t size_bytes);
// The tone-mapped display image of the last rtpbr_render: 8-bit sRGB-encoded RGBA, rows top to
// bottom. size_bytes must be at least width * height * 4.
RTPBR_API rtpbr_result rtpbr_read_display(rtpbr_renderer *renderer, uint8_t *rgba, size_t size_bytes);

// Recording into the host's command buffer and image (e.g. a swapchain image) instead of
// rtpbr_render. The target must be renderer-sized, created with COLOR_ATTACHMENT usage, of a
// format with colour-attachment support; sRGB formats get hardware encoding, UNORM formats
// are encoded to sRGB by the shader, float formats get the tone-mapped linear value.
typedef struct rtpbr_record_desc {
    VkCommandBuffer command_buffer;   // required, in the recording state, on the context's
                                      // queue family; the host submits it
    VkImage image;                    // required
    VkImageView view;                 // required, 2D, one mip level, one layer
    VkFormat format;                  // required
    VkImageLayout old_layout;         // layout the image is in; zero: UNDEFINED (contents lost)
    VkImageLayout new_layout;         // layout to leave it in; zero: COLOR_ATTACHMENT_OPTIMAL
} rtpbr_record_desc;

// The recorded commands use the renderer's targets and the scene's buffers: the host must
// not destroy them, nor record or render again with this renderer, before the submitted
// command buffer has completed. The linear radiance target is filled too: rtpbr_read_radiance,
// called once that execution has completed, copies it in a submission of its own on the
// context's queue (nothing is copied in the host's command buffer).
RTPBR_API rtpbr_result rtpbr_record(rtpbr_renderer *renderer, const rtpbr_gpu_scene *scene,
                          const rtpbr_render_desc *desc, const rtpbr_record_desc *target);


// ---------------------------------------------------------------------------------------------
// The lighting pass inside the host's frame (issue 33)
//
// A host with its own geometry pass (its meshes, skinning, culling) writes the G-buffer
// contract, shaderlib/rtpbr/gbuffer.h (version RTPBR_GBUFFER_VERSION; docs/gbuffer.md), into
// its own images with its own GLSL or HLSL fragment shader (GBuffer_Encode); rtpbr then records
// its light culling and LTC lighting of that G-buffer into the host's command buffer, writing
// linear radiance into the host's HDR image. The shading is the engine's own (the same
// pipelines as rtpbr_render's lighting pass), so a host G-buffer equal to the engine's gives
// the engine's radiance. engine/README.md, "The lighting pass inside your frame", shows a
// whole frame.
//
//   rtpbr_light_set         the lights, in persistently mapped memory: one region per frame in
//                           flight, each of a capacity the host chose. Updating them writes
//                           that memory only (no Vulkan object, descriptor or allocation).
//   rtpbr_lighting_targets  the host's depth, G-buffer and output images (views and formats),
//                           its material records, and per frame in flight a descriptor set and
//                           the frame's constants; everything rtpbr_lighting_record uses is
//                           made here, once.
//   rtpbr_lighting_record   records the commands: no allocation, no descriptor-set creation,
//                           no queue submission or wait.
//
// Frames in flight: the host numbers its frames in flight 0 .. N-1 (rtpbr_lighting_record_desc
// .frame, rtpbr_light_set_update's frame). Before it updates lights or records for frame f,
// the host must know that its previous submission that used frame f has completed (it waits
// on its own fence of frame f, as for any per-frame host memory). Recordings of different
// frames may be pending at the same time, on the context's queue.
// Not on this path (left for later): shadows (rtpbr knows no host geometry: the frame has no
// shadowed lights; rtpbr_render_desc.shadows has no counterpart), supersampling, the Monte
// Carlo pass, BLEND surfaces, reversed-Z depth.

#define RTPBR_MAX_FRAMES_IN_FLIGHT 8u
#define RTPBR_DEFAULT_LIGHT_SET_CAPACITY 64u
#define RTPBR_DEFAULT_FRAMES_IN_FLIGHT 2u

typedef struct rtpbr_light_set_desc {
    uint32_t capacity;         // lights per frame, 1..RTPBR_MAX_LIGHTS; zero: 64
    uint32_t frames_in_flight; // regions, 1..RTPBR_MAX_FRAMES_IN_FLIGHT; zero: 2
} rtpbr_light_set_desc;

typedef struct rtpbr_light_set rtpbr_light_set;

// One host-visible buffer of frames_in_flight x capacity light records (208 bytes each), mapped
// for the set's lifetime, and the host-side scratch its updates use. Every region starts
// with no lights. Capacity or frames out of range: RTPBR_ERROR_LIMIT_EXCEEDED.
RTPBR_API rtpbr_result rtpbr_light_set_create(rtpbr_context *context, const rtpbr_light_set_desc *desc,
                                              rtpbr_light_set **out_set);
// The host keeps the set alive while a recording that uses it is pending.
RTPBR_API void rtpbr_light_set_destroy(rtpbr_light_set *set);
// Replaces the lights of region `frame` (< frames_in_flight) by lights[0 .. count): moving,
// recolouring, adding and removing lights up to the capacity. Each light is validated as by
// rtpbr_gpu_scene_set_lights (vertex count, finite values, non-negative emission, planar,
// non-zero area) and its derived facts (plane, area, bounding sphere) computed; then its
// record is written into the region's mapped memory. Nothing else: no allocation, no Vulkan call. count > capacity:
// RTPBR_ERROR_LIMIT_EXCEEDED; a bad light: RTPBR_ERROR_INVALID_ARGUMENT (the log names it);
// on any error the region keeps its previous lights. Must not be called while a recording of
// frame `frame` is pending (see "Frames in flight" above).
RTPBR_API rtpbr_result rtpbr_light_set_update(rtpbr_light_set *set, uint32_t frame, const rtpbr_light_desc *lights,
                                              uint32_t count);
RTPBR_API uint32_t rtpbr_light_set_capacity(const rtpbr_light_set *set);
// The number of lights in region `frame` (0 for a frame out of range).
RTPBR_API uint32_t rtpbr_light_set_count(const rtpbr_light_set *set, uint32_t frame);

// An image of the host's: the image (for barriers) and a view of it. The view is 2D, of one
// mip level and one array layer, of the format stated here, covering the targets' width x
// height; colour views have the colour aspect, the depth view the depth aspect only.
typedef struct rtpbr_host_image {
    VkImage image;
    VkImageView view;
    VkFormat format; // the view's format
} rtpbr_host_image;

// The G-buffer targets g0 .. g6 of the contract, in gbuffer.h's order.
#define RTPBR_GBUFFER_TARGETS 7u

typedef struct rtpbr_lighting_targets_desc {
    uint32_t width, height; // of every image; required, 1..RTPBR_MAX_RENDER_SIZE
    // Depth: D32_SFLOAT, X8_D24_UNORM_PACK32 or D16_UNORM (depth-only formats; a host with a
    // stencil copies depth out or uses its own depth-only image), created with SAMPLED usage.
    // Vulkan's depth range, 0 near .. 1 far, cleared to 1 where no surface is (those pixels
    // get the background): not reversed-Z. Positions are
    // reconstructed from it with the record's camera, so the host's geometry pass must have
    // drawn with the same view-projection.
    rtpbr_host_image depth;
    // g0 .. g3: required, every frame; g4 .. g6 (the KHR extension texels): optional (image,
    // view zero: not read; the materials' factors are used alone, as with texels of 1). Each
    // of the format gbuffer.h states (RTPBR_GBUFFER_FORMAT_G*), created with SAMPLED usage.
    // g5 and g6 go together (both or neither).
    rtpbr_host_image gbuffer[RTPBR_GBUFFER_TARGETS];
    // The HDR output: R32G32B32A32_SFLOAT (gbuffer.h's emission is FP32; the lighting pass
    // writes through an rgba32f storage image), created with STORAGE usage. Every pixel is
    // written: linear radiance, alpha 1 on surfaces and 0 on background.
    rtpbr_host_image output;
    // The layouts rtpbr reads the G-buffer and depth images in (written into the descriptor
    // sets). G-buffer: SHADER_READ_ONLY_OPTIMAL (zero), READ_ONLY_OPTIMAL or GENERAL. Depth:
    // DEPTH_STENCIL_READ_ONLY_OPTIMAL (zero), DEPTH_READ_ONLY_OPTIMAL, SHADER_READ_ONLY_OPTIMAL,
    // READ_ONLY_OPTIMAL or GENERAL.
    VkImageLayout gbuffer_layout;
    VkImageLayout depth_layout;
    // The material records the G-buffer's material index (g2.a) selects: every field but the
    // textures, texture transforms, normal_scale, alpha mode, alpha and alpha_cutoff (the host's
    // geometry pass applied those: base colour, metallic, roughness and emission come from
    // the G-buffer; the record gives the model, ior, KHR specular, clear-coat, sheen,
    // anisotropy strength and Disney factors). Validated as by rtpbr_gpu_scene_create and
    // copied. Zero: one record, rtpbr_gpu_scene_create's default grey. An index past
    // material_count reads past the records: the host's error.
    const rtpbr_material_desc *materials;
    uint32_t material_count;       // <= RTPBR_MAX_MATERIALS
    uint32_t frames_in_flight;     // 1..RTPBR_MAX_FRAMES_IN_FLIGHT; zero: 2
} rtpbr_lighting_targets_desc;

typedef struct rtpbr_lighting_targets rtpbr_lighting_targets;

// Checks the desc (formats against gbuffer.h's, layouts, sizes; a NULL view or image of a
// required target, or g5 without g6: RTPBR_ERROR_INVALID_ARGUMENT, with the target's name in
// the log), then makes what the recordings use: per frame in flight a descriptor set and a
// region of the frame-constant buffer; the tile-culling buffers; the material buffer; a 1x1
// stand-in for the shadow ratios (this path has none). Submits one small command buffer of
// its own and waits for it (the stand-in's layout), like rtpbr_renderer_create. The host's
// images and views are not kept alive by rtpbr: the host destroys the targets first (after
// the recordings that use them completed), then its images. Re-create the targets when the
// host's images change (a resize).
RTPBR_API rtpbr_result rtpbr_lighting_targets_create(rtpbr_context *context, const rtpbr_lighting_targets_desc *desc,
                                                     rtpbr_lighting_targets **out_targets);
// The host keeps the targets alive while a recording that uses them is pending.
RTPBR_API void rtpbr_lighting_targets_destroy(rtpbr_lighting_targets *targets);

typedef struct rtpbr_lighting_record_desc {
    // Required: in the recording state, outside a render pass, on the context's queue family.
    VkCommandBuffer command_buffer;
    uint32_t frame;                 // frame in flight, < the targets' and the light set's frames_in_flight
    const rtpbr_light_set *lights;  // required; its region `frame` is lit (update it first)
    // The camera the host's geometry pass drew with. camera set: rtpbr's camera (its matrices,
    // rtpbr_render's, with the targets' aspect ratio). NULL: view and projection below.
    const rtpbr_camera_desc *camera;
    // Used when camera is NULL: column-major world-to-view and view-to-clip matrices, clip
    // space Vulkan's (x right, y down, depth 0 near .. 1 far, or 1 near .. 0 far with
    // reversed_z), the product invertible.
    float view[16];
    float projection[16];
    float background[3];           // radiance where depth is the far value (1; 0: reversed_z); default black
    rtpbr_ndf ndf;                 // as rtpbr_render_desc
    rtpbr_multiscatter multiscatter;
    float light_cull_form_factor;  // as rtpbr_render_desc (zero: 1e-4, negative: exact test only)
    // The layouts the images are in when the recorded commands start (the host's last use):
    // zero means the read layout of the targets (gbuffer_layout, depth_layout). rtpbr moves
    // them into the read layouts.
    VkImageLayout gbuffer_old_layout;
    VkImageLayout depth_old_layout;
    // The output's layout on entry; zero: UNDEFINED (contents discarded: every pixel is
    // written). And the layout to leave it in; zero: GENERAL.
    VkImageLayout output_old_layout;
    VkImageLayout output_new_layout;
    // Nonzero: the host's depth is reversed-Z (near 1, far 0: the background is where depth is
    // 0), as its projection above maps it; camera must then be NULL (rtpbr's camera maps near
    // to 0). Any depth format of the contract; the position is reconstructed through the
    // inverse of projection x view either way.
    uint32_t reversed_z;
} rtpbr_lighting_record_desc;

// Records, into the host's command buffer, culling and lighting of the targets' G-buffer by
// the light set's region `frame`; writes the frame's constants (camera, light count) into the
// targets' region `frame` (host memory, read when the commands execute). Allocates nothing,
// creates and writes no descriptor set (except, the first time a frame is recorded with a
// light set other than the one it last used, one vkUpdateDescriptorSets pointing that frame's
// set at it), submits nothing and waits for nothing. The first recording with a given ndf /
// multiscatter pair other than the default may compile that variant's pipelines (before
// anything is recorded); record each pair once at start-up to keep compilation out of frames.
//
// Synchronisation (what the commands expect and leave; all on the queue the host submits to):
//   on entry  G-buffer images (g0 .. g6 given) in gbuffer_old_layout and depth in
//             depth_old_layout, their contents written by earlier commands (colour or depth
//             attachment writes, shader writes or transfer writes): rtpbr's first barrier waits
//             for COLOR_ATTACHMENT_OUTPUT, EARLY/LATE_FRAGMENT_TESTS, COMPUTE_SHADER and
//             TRANSFER, makes those writes visible to its compute shaders and moves the images
//             to their read layouts. The output in output_old_layout; rtpbr's barrier waits for
//             ALL_COMMANDS (earlier reads and writes of it) and moves it to GENERAL.
//   inside    compute dispatches only (a transfer update of rtpbr's own tile queues).
//   on exit   G-buffer and depth in their read layouts (gbuffer_layout, depth_layout), last
//             read by COMPUTE_SHADER: a later write to them (the next frame's geometry pass)
//             needs an execution dependency on VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT (render
//             pass external dependency or barrier with that source stage). The output in
//             output_new_layout, its writes made available and visible to every later command
//             (barrier to ALL_COMMANDS, MEMORY_READ | MEMORY_WRITE): the host reads it directly.
// Errors (nothing is recorded): NULL targets, command buffer or light set, a frame out of
// range, a set of another context, an unknown ndf / multiscatter, NaN or infinite values, a
// degenerate camera: RTPBR_ERROR_INVALID_ARGUMENT.
RTPBR_API rtpbr_result rtpbr_lighting_record(rtpbr_lighting_targets *targets, const rtpbr_lighting_record_desc *desc);

#ifdef __cplusplus
}
#endif

#endif // RTPBR_H
