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

// One frame recorded into the caller's command buffer: the scene's lights into the light set
// (its mapped memory: the previous frame must be complete), the geometry pass,
// rtpbr_lighting_record, the tone mapping into r->ldr (bgra: channels stored B, G, R, A, to be
// copied as bytes into a BGRA swapchain image). Leaves r->ldr and r->hdr in
// TRANSFER_SRC_OPTIMAL, their writes visible to transfers. The window's frame (windowed.c) and
// sh_render_frame both use it.
int sh_record_frame(sh_renderer *r, VkCommandBuffer cmd, const sh_scene *scene, float exposure, int bgra, char *error,
                    size_t error_size);

// One frame: the scene's lights into the light set, then one command buffer (geometry pass,
// rtpbr_lighting_record, tone mapping, copies to the readback buffers), submitted and waited
// for. hdr (optional): width x height x RGBA float linear radiance, top row first; ldr
// (optional): RGBA8 sRGB after Reinhard on luminance with 2^exposure.
int sh_render_frame(sh_renderer *r, const sh_scene *scene, float exposure, float *hdr, uint8_t *ldr,
                    char *error, size_t error_size);

// ---------------------------------------------------------------------------------------------
// The host's controls (controls.c): what a key does to the scene, shared by the window and by
// --keys (scripted, headless too). Keys are spelled as --keys spells them: upper-case letters,
// digits, - and = as themselves; l r u d = Left Right Up Down, p n = PgUp PgDn, t = Tab,
// h = Home. The window's own keys (P, H, Esc) are windowed.c's.

#define SH_MOVE_STEP 0.1f  // metres per arrow key
#define SH_EXPOSURE_STEP 0.5f

typedef struct sh_controls {
    uint32_t light;      // the selected light (Tab)
    float exposure;      // EV (E / D)
    int animate;         // A: every light moves on a circle and turns its hue, one step a frame
    uint32_t frame;      // animation steps taken
    sh_camera home;      // the mesh file's camera (Home)
    uint32_t colour[SH_MAX_LIGHTS]; // the palette entry C gave each light last
} sh_controls;

// Starts with the scene's camera as home and the given exposure.
void sh_controls_init(sh_controls *c, const sh_scene *scene, float exposure);
// Applies one key; returns 0, or 1 for a character that is no key here.
int sh_controls_key(sh_controls *c, sh_scene *scene, char key);
// Before each frame: one animation step when animate is on.
void sh_controls_frame(sh_controls *c, sh_scene *scene);
// The orbit camera (the viewer's mouse): turn about the target by yaw and pitch (radians), pan
// the target in the view's plane by (right, up) in units of the distance, zoom by a factor.
void sh_camera_orbit(sh_camera *camera, float yaw, float pitch);
void sh_camera_pan(sh_camera *camera, float right, float up);
void sh_camera_zoom(sh_camera *camera, float factor);
// The controls' help (one key per line).
extern const char sh_controls_help[];

// ---------------------------------------------------------------------------------------------
// The window (windowed.c; built when GLFW is found, SH_HAVE_WINDOW)

typedef struct sh_window_options {
    uint32_t frames;          // render this many frames, then close (0: until the window closes)
    const char *screenshot;   // with frames: the last frame as presented, as a PNG
    int validation;           // validation layer with synchronization validation; a message fails
    sh_camera_mode camera_mode;
} sh_window_options;

// Runs the host's frame in a window: a GLFW window and swapchain on a device of the window's,
// rtpbr embedded in it, the display image copied into each swapchain image; the viewer's
// mouse (left drag orbit, right drag pan, wheel zoom) and sh_controls' keys. Resizing the
// window re-creates the renderer at the new size. Returns 0, or 1 with a message on stderr.
int sh_run_window(sh_scene *scene, sh_controls *controls, const sh_window_options *options);

#endif
