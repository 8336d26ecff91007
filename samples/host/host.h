// rtpbr-sample-host: a C engine's frame with rtpbr as its lighting pass (issue 33).
// The host has its own mesh format (scene.c, documented in samples/README.md), its own Vulkan
// device (sample_vk.h) and geometry pass writing the G-buffer contract (geometry.frag calls GBuffer_Encode),
// then rtpbr_lighting_record in its command buffer, then its own tone mapping (tonemap.comp).
// main.c is the program; tests/samples/test_sample_host.c runs the same code against
// rtpbr_render. Only rtpbr's public API is used.
#ifndef RTPBR_SAMPLE_HOST_H
#define RTPBR_SAMPLE_HOST_H

#include "sample_vk.h" // the host's device (samples/common, shared with rtpbr-embed)

#include <rtpbr/rtpbr.h>
#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

#define SH_MAX_MATERIALS 64u  // the host's material table
#define SH_MAX_LIGHTS 64u     // the host's light-set capacity
#define SH_MAX_TRIANGLES 65536u
#define SH_MAX_SIZE 4096u     // image width and height

// ---------------------------------------------------------------------------------------------
// The host's scene (scene.c)

typedef struct sh_material {
    char name[32];
    float base_color[3], metallic, roughness; // linear base colour; metallic, perceptual roughness in [0, 1]
    float emission[3];                        // emitted radiance
    float clearcoat, clearcoat_roughness;     // KHR_materials_clearcoat factors; 0: none
    float sheen_color[3], sheen_roughness;    // KHR_materials_sheen factors; black: none
} sh_material;

typedef struct sh_vertex { float position[3], normal[3]; } sh_vertex;

// The triangles of one material, consecutive in sh_scene.vertices (three vertices each).
typedef struct sh_draw { uint32_t first_vertex, vertex_count; } sh_draw;

typedef struct sh_light {
    float corners[4][3]; // a planar convex quad, counter-clockwise seen from the lit side
    float radiance[3];
    int two_sided;
} sh_light;

typedef struct sh_camera { float position[3], target[3], yfov; } sh_camera; // yfov in radians; up is +Y

typedef struct sh_scene {
    uint32_t width, height;
    sh_camera camera;
    float background[3];
    sh_material materials[SH_MAX_MATERIALS];
    uint32_t material_count;
    sh_vertex *vertices;                 // grouped by material (draws[m]), file order within
    uint32_t vertex_count;
    sh_draw draws[SH_MAX_MATERIALS];
    sh_light lights[SH_MAX_LIGHTS];
    uint32_t light_count;
} sh_scene;

// Reads a mesh file. On error returns non-zero with "FILE:LINE: what" in error; *scene is
// then empty (sh_scene_free is still safe).
int sh_scene_load(const char *path, sh_scene *scene, char *error, size_t error_size);
void sh_scene_free(sh_scene *scene);

// The host's material and light records in rtpbr's terms (what rtpbr_lighting_targets_desc
// .materials and rtpbr_light_set_update take).
rtpbr_material_desc sh_material_record(const sh_material *m);
rtpbr_light_desc sh_light_record(const sh_light *l);

// The host's camera: world-to-view and view-to-clip matrices, column-major, Vulkan's clip space
// (x right, y down, depth 0 near .. 1 far, or 1 near .. 0 far when reversed_z), and their
// product.
#define SH_ZNEAR 0.05f
#define SH_ZFAR 100.0f
void sh_camera_matrices(const sh_camera *c, float aspect, int reversed_z, float view[16], float projection[16],
                        float view_proj[16]);

// How the host hands its camera to rtpbr_lighting_record: rtpbr's camera description (the
// default; its matrices are the host's, bit for bit), the host's view and projection, or those
// with a reversed-Z projection (depth cleared to 0, compared GREATER_OR_EQUAL; reversed_z set).
typedef enum sh_camera_mode { SH_CAMERA_RTPBR, SH_CAMERA_MATRICES, SH_CAMERA_REVERSED_Z } sh_camera_mode;

// ---------------------------------------------------------------------------------------------
// The host's frame (frame.c): its images and passes, and rtpbr's light set and targets

typedef struct sh_image { VkImage image; VkDeviceMemory memory; VkImageView view; } sh_image;
typedef struct sh_buffer { VkBuffer buffer; VkDeviceMemory memory; void *mapped; } sh_buffer;

typedef struct sh_renderer {
    sample_device *device;
    rtpbr_context *rtpbr;
    uint32_t width, height;
    sh_image gbuffer[4], depth, hdr, ldr;
    sh_buffer vertices, materials, hdr_readback, ldr_readback;
    VkDescriptorSetLayout geometry_set_layout, tonemap_set_layout;
    VkDescriptorPool pool;
    VkDescriptorSet geometry_set, tonemap_set;
    VkPipelineLayout geometry_layout, tonemap_layout;
    VkPipeline geometry_pipeline, tonemap_pipeline;
    VkCommandPool command_pool;
    VkFence fence;
    rtpbr_light_set *lights;
    rtpbr_lighting_targets *targets;
    sh_camera_mode camera_mode; // SH_CAMERA_RTPBR after sh_renderer_create; set it between frames
} sh_renderer;

// Everything the frames use, made once for the scene's size, materials and light capacity.
int sh_renderer_create(sh_renderer *r, sample_device *device, rtpbr_context *rtpbr, const sh_scene *scene,
                       char *error, size_t error_size);
void sh_renderer_destroy(sh_renderer *r);

// The SPIR-V of the host's geometry pass (geometry.vert / .frag) and its sizes in bytes; the
// push constants: mat4 view_proj, vec4 camera (xyz), uint material (84 bytes); the fragment
// shader's set 0 binding 0: the material table (two vec4 per material: base colour and
// metallic, emission and roughness).
extern const uint32_t host_geometry_vert[], host_geometry_frag[];
extern const size_t sh_geometry_vert_size, sh_geometry_frag_size;

// The start of the host's G-buffer pass, recorded: images and views g0 .. g3 (gbuffer.h's
// formats) and D32 depth move from any layout (contents discarded) to the attachment layouts,
// after an execution dependency on VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT (where rtpbr's lighting
// of a previous frame last read them, rtpbr.h); then vkCmdBeginRendering with the four colour
// targets and depth cleared to clear_depth (the background: 1, or 0 for reversed-Z). The caller
// draws and ends the rendering.
void sh_begin_gbuffer_pass(VkCommandBuffer cmd, const VkImage images[5], const VkImageView views[5], uint32_t width,
                           uint32_t height, float clear_depth);

// One frame: the scene's lights into the light set, then one command buffer (geometry pass,
// rtpbr_lighting_record, tone mapping, copies to the readback buffers), submitted and waited
// for. hdr (optional): width x height x RGBA float linear radiance, top row first; ldr
// (optional): RGBA8 sRGB after Reinhard on luminance with 2^exposure.
int sh_render_frame(sh_renderer *r, const sh_scene *scene, float exposure, float *hdr, uint8_t *ldr,
                    char *error, size_t error_size);

#endif
