// The lighting pass inside the host's frame (rtpbr.h, "The lighting pass inside the host's
// frame"; issue 33): light sets in persistently mapped memory, the host's G-buffer targets with
// their descriptor sets made once, and the recording of the engine's cull and LTC dispatches
// (passes/lighting.c) into the host's command buffer.
#include <math.h>
#include <string.h>

#include "internal.h"
#include "passes/passes.h"
#include "rtpbr/rtpbr_gltf.h"

// The light records of one frame region are capacity x rtpbr_shader_light, the region's
// stride rounded up to the device's storage-buffer offset alignment.
struct rtpbr_light_set {
    rtpbr_context *context;
    rtpbr_light_set *prev, *next; // in context->light_sets
    uint64_t serial;              // unique in the context: which set a targets' descriptor points at
    uint32_t capacity, frames;
    VkDeviceSize stride;          // bytes between regions
    rtpbr_buffer buffer;          // frames x stride, host visible, mapped
    uint32_t count[RTPBR_MAX_FRAMES_IN_FLIGHT];
    rtpbr_gltf_polygon_facts *facts; // capacity entries: rtpbr_light_set_update's scratch
};

struct rtpbr_lighting_targets {
    rtpbr_context *context;
    rtpbr_lighting_targets *prev, *next; // in context->lighting_targets
    uint32_t width, height, frames;
    uint32_t tiles_x, tiles_y;
    uint32_t extension_textures;  // RTPBR_EXTENSION_TEXTURES_* of the host's g4 .. g6
    VkImage depth, gbuffer[RTPBR_GBUFFER_TARGETS], output;
    VkImageLayout depth_layout, gbuffer_layout;
    VkDeviceSize frame_stride;    // bytes between the frame-constant regions
    rtpbr_buffer frame;           // frames x frame_stride, host visible
    rtpbr_buffer materials;       // rtpbr_shader_material[material_slots]
    uint32_t material_slots;      // max(material_count, 1)
    rtpbr_buffer tile_masks, tile_lists;
    rtpbr_image shadow_stand_in;  // 1x1, one layer, GENERAL: the shadow-ratio binding (never read)
    VkDescriptorPool pool;
    VkDescriptorSet sets[RTPBR_MAX_FRAMES_IN_FLIGHT];
    uint64_t set_lights[RTPBR_MAX_FRAMES_IN_FLIGHT]; // serial of the light set each set points at; 0: none
};

static VkDeviceSize align_up(VkDeviceSize x, VkDeviceSize a)
{
    return a > 1 ? (x + a - 1) / a * a : x;
}

// ---------------------------------------------------------------------------------------------
// Light sets

void rtpbr_light_set_destroy(rtpbr_light_set *set)
{
    if (!set) return;
    rtpbr_context *ctx = set->context;
    rtpbr_buffer_destroy(ctx, &set->buffer);
    rtpbr_free(&ctx->host, set->facts);
    RTPBR_LIST_UNLINK(ctx->light_sets, set);
    rtpbr_free(&ctx->host, set);
}

rtpbr_result rtpbr_light_set_create(rtpbr_context *ctx, const rtpbr_light_set_desc *desc, rtpbr_light_set **out)
{
    if (out) *out = NULL;
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!desc || !out) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_light_set_create: desc or out_set is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    uint32_t capacity = desc->capacity ? desc->capacity : RTPBR_DEFAULT_LIGHT_SET_CAPACITY;
    uint32_t frames = desc->frames_in_flight ? desc->frames_in_flight : RTPBR_DEFAULT_FRAMES_IN_FLIGHT;
    if (capacity > RTPBR_MAX_LIGHTS || frames > RTPBR_MAX_FRAMES_IN_FLIGHT) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "rtpbr_light_set_create: capacity %u, frames_in_flight %u; at most %u and %u", capacity, frames,
                  RTPBR_MAX_LIGHTS, RTPBR_MAX_FRAMES_IN_FLIGHT);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_light_set *set = NULL;
    RTPBR_ALLOC(&ctx->host, set, sizeof *set);
    set->context = ctx;
    RTPBR_LIST_LINK(ctx->light_sets, set);
    set->serial = ++ctx->serial;
    set->capacity = capacity;
    set->frames = frames;
    // (each frame's records bound as a storage and as a uniform buffer: both offsets aligned)
    VkDeviceSize alignment = props.limits.minStorageBufferOffsetAlignment > props.limits.minUniformBufferOffsetAlignment
                                 ? props.limits.minStorageBufferOffsetAlignment
                                 : props.limits.minUniformBufferOffsetAlignment;
    set->stride = align_up((VkDeviceSize)capacity * sizeof(rtpbr_shader_light), alignment);
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, set->stride * frames,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &set->buffer));
    RTPBR_ALLOC(&ctx->host, set->facts, capacity * sizeof *set->facts);
    *out = set;
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_light_set_destroy(set);
    return result;
}

rtpbr_result rtpbr_light_set_update(rtpbr_light_set *set, uint32_t frame, const rtpbr_light_desc *lights,
                                    uint32_t count)
{
    if (!set) return rtpbr_null_object(__func__, "set");
    const rtpbr_context *ctx = set->context;
    if (frame >= set->frames || (count > 0 && !lights)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_light_set_update: frame %u of %u, %u lights%s", frame, set->frames,
                  count, lights ? "" : " (NULL)");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (count > set->capacity) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_light_set_update: %u lights; the set's capacity is %u", count,
                  set->capacity);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    // Every light checked before any is written: on error the region keeps its lights.
    for (uint32_t i = 0; i < count; ++i) {
        const rtpbr_light_desc *l = &lights[i];
        // (a vertex count out of range fails in rtpbr_light_validate before the facts are read)
        if (l->vertex_count >= 3 && l->vertex_count <= RTPBR_MAX_POLYGON_VERTICES)
            rtpbr_gltf_polygon_facts_of(l->vertices, l->vertex_count, &set->facts[i]);
        rtpbr_result result = rtpbr_light_validate(ctx, l, &set->facts[i], i);
        if (result != RTPBR_SUCCESS) return result;
        if (l->emission_texture) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "rtpbr_light_set_update: light %u has an emission texture; textured lights need a scene "
                      "(rtpbr_gpu_scene_create), a light set has none",
                      i);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    rtpbr_shader_light *region = (rtpbr_shader_light *)((char *)set->buffer.mapped + frame * set->stride);
    for (uint32_t i = 0; i < count; ++i) rtpbr_light_record(&lights[i], &set->facts[i], &region[i]);
    set->count[frame] = count;
    return RTPBR_SUCCESS;
}

uint32_t rtpbr_light_set_capacity(const rtpbr_light_set *set)
{
    return set ? set->capacity : 0;
}

uint32_t rtpbr_light_set_count(const rtpbr_light_set *set, uint32_t frame)
{
    return set && frame < set->frames ? set->count[frame] : 0;
}

// ---------------------------------------------------------------------------------------------
// Targets

_Static_assert(RTPBR_GBUFFER_TARGETS == RTPBR_GBUFFER_COUNT, "the contract's targets are the engine's G-buffers");
static const char *const target_names[RTPBR_GBUFFER_TARGETS] = {"g0", "g1", "g2", "g3", "g4", "g5", "g6"};
// gbuffer.h's formats (RTPBR_GBUFFER_FORMAT_G*; the engine's own, internal.h).
static VkFormat contract_format(uint32_t i)
{
    return rtpbr_gbuffer_formats[i];
}

static bool depth_format_ok(VkFormat f)
{
    return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D16_UNORM;
}

static bool gbuffer_layout_ok(VkImageLayout l)
{
    return l == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL ||
           l == VK_IMAGE_LAYOUT_GENERAL;
}

static bool depth_layout_ok(VkImageLayout l)
{
    return gbuffer_layout_ok(l) || l == VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL ||
           l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
}

static rtpbr_result check_targets(const rtpbr_context *ctx, const rtpbr_lighting_targets_desc *d)
{
#define FAIL(code, ...) do { rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_lighting_targets_create: " __VA_ARGS__); return code; } while (0)
    if (d->width == 0 || d->height == 0) FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "size %ux%u", d->width, d->height);
    if (d->width > RTPBR_MAX_RENDER_SIZE || d->height > RTPBR_MAX_RENDER_SIZE)
        FAIL(RTPBR_ERROR_LIMIT_EXCEEDED, "size %ux%u; at most %u a side", d->width, d->height, RTPBR_MAX_RENDER_SIZE);
    if (d->frames_in_flight > RTPBR_MAX_FRAMES_IN_FLIGHT)
        FAIL(RTPBR_ERROR_LIMIT_EXCEEDED, "frames_in_flight %u; at most %u", d->frames_in_flight,
             RTPBR_MAX_FRAMES_IN_FLIGHT);
    if (!d->depth.image || !d->depth.view) FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "the depth image or view is NULL");
    if (!depth_format_ok(d->depth.format))
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "depth format %d; D32_SFLOAT, X8_D24_UNORM_PACK32 or D16_UNORM",
             (int)d->depth.format);
    for (uint32_t i = 0; i < RTPBR_GBUFFER_TARGETS; ++i) {
        const rtpbr_host_image *g = &d->gbuffer[i];
        bool required = i < RTPBR_GBUFFER_FIRST_EXTENSION;
        if (!g->image && !g->view && !required) continue;
        if (!g->image || !g->view)
            FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "G-buffer target %s: the image or view is NULL%s", target_names[i],
                 required ? " (g0 .. g3 are required)" : "");
        if (g->format != contract_format(i))
            FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "G-buffer target %s has format %d; the contract's is %d (gbuffer.h)",
                 target_names[i], (int)g->format, (int)contract_format(i));
        for (uint32_t j = 0; j < i; ++j)
            if (d->gbuffer[j].view == g->view)
                FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "G-buffer targets %s and %s are the same view", target_names[j],
                     target_names[i]);
    }
    if (!d->gbuffer[5].view != !d->gbuffer[6].view)
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "G-buffer targets g5 and g6 go together (both or neither)");
    if (!d->output.image || !d->output.view) FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "the output image or view is NULL");
    if (d->output.format != RTPBR_RADIANCE_FORMAT)
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "output format %d; it must be R32G32B32A32_SFLOAT (%d)",
             (int)d->output.format, (int)RTPBR_RADIANCE_FORMAT);
    if (d->output.view == d->depth.view) FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "the output is the depth view");
    for (uint32_t i = 0; i < RTPBR_GBUFFER_TARGETS; ++i)
        if (d->gbuffer[i].view && d->gbuffer[i].view == d->output.view)
            FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "the output is G-buffer target %s", target_names[i]);
    if (d->gbuffer_layout && !gbuffer_layout_ok(d->gbuffer_layout))
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "gbuffer_layout %d; SHADER_READ_ONLY_OPTIMAL, READ_ONLY_OPTIMAL or GENERAL",
             (int)d->gbuffer_layout);
    if (d->depth_layout && !depth_layout_ok(d->depth_layout))
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "depth_layout %d is not a read layout of a depth image", (int)d->depth_layout);
    if (d->material_count > RTPBR_MAX_MATERIALS)
        FAIL(RTPBR_ERROR_LIMIT_EXCEEDED, "%u materials; at most %u", d->material_count, RTPBR_MAX_MATERIALS);
    if (d->material_count > 0 && !d->materials)
        FAIL(RTPBR_ERROR_INVALID_ARGUMENT, "material_count is %u but materials is NULL", d->material_count);
    for (uint32_t i = 0; i < d->material_count; ++i) {
        rtpbr_result result = rtpbr_material_validate(ctx, &d->materials[i], i);
        if (result != RTPBR_SUCCESS) return result;
    }
    return RTPBR_SUCCESS;
#undef FAIL
}

static void record_stand_in_layout(VkCommandBuffer cmd, void *user)
{
    const rtpbr_lighting_targets *t = user;
    rtpbr_image_barrier(cmd, t->shadow_stand_in.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void rtpbr_lighting_targets_destroy(rtpbr_lighting_targets *t)
{
    if (!t) return;
    rtpbr_context *ctx = t->context;
    RTPBR_LIST_UNLINK(ctx->lighting_targets, t);
    if (t->pool) vkDestroyDescriptorPool(ctx->device, t->pool, NULL); // frees the sets
    rtpbr_buffer *buffers[] = {&t->frame, &t->materials, &t->tile_masks, &t->tile_lists};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; ++i) rtpbr_buffer_destroy(ctx, buffers[i]);
    rtpbr_image_destroy(ctx, &t->shadow_stand_in);
    rtpbr_free(&ctx->host, t);
}

rtpbr_result rtpbr_lighting_targets_create(rtpbr_context *ctx, const rtpbr_lighting_targets_desc *desc,
                                           rtpbr_lighting_targets **out)
{
    if (out) *out = NULL;
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!desc || !out) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_lighting_targets_create: desc or out_targets is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    rtpbr_result result = check_targets(ctx, desc);
    if (result != RTPBR_SUCCESS) return result;
    rtpbr_lighting_targets *t = NULL;
    RTPBR_ALLOC(&ctx->host, t, sizeof *t);
    t->context = ctx;
    RTPBR_LIST_LINK(ctx->lighting_targets, t);
    t->frames = desc->frames_in_flight ? desc->frames_in_flight : RTPBR_DEFAULT_FRAMES_IN_FLIGHT;
    t->width = desc->width;
    t->height = desc->height;
    t->tiles_x = (desc->width + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    t->tiles_y = (desc->height + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    t->depth = desc->depth.image;
    for (uint32_t i = 0; i < RTPBR_GBUFFER_TARGETS; ++i) t->gbuffer[i] = desc->gbuffer[i].image;
    t->output = desc->output.image;
    t->gbuffer_layout = desc->gbuffer_layout ? desc->gbuffer_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    t->depth_layout = desc->depth_layout ? desc->depth_layout : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    t->extension_textures = (desc->gbuffer[4].view ? RTPBR_EXTENSION_TEXTURES_SPECULAR : 0u) |
                            (desc->gbuffer[5].view ? RTPBR_EXTENSION_TEXTURES_COAT_SHEEN : 0u);

    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    t->frame_stride = align_up(sizeof(rtpbr_shader_frame), props.limits.minUniformBufferOffsetAlignment);
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, t->frame_stride * t->frames, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &t->frame));
    uint32_t slots = desc->material_count ? desc->material_count : 1;
    t->material_slots = slots;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, slots * sizeof(rtpbr_shader_material), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       &t->materials));
    rtpbr_shader_material *records = t->materials.mapped;
    if (desc->material_count == 0) {
        rtpbr_material_desc grey = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 0.5f}; // rtpbr_gpu_scene_create's
        records[0] = rtpbr_material_record(&grey);
    }
    for (uint32_t i = 0; i < desc->material_count; ++i) records[i] = rtpbr_material_record(&desc->materials[i]);
    RTPBR_TRY(rtpbr_lighting_tile_buffers_create(ctx, t->tiles_x, t->tiles_y, &t->tile_masks, &t->tile_lists));
    RTPBR_TRY(rtpbr_image_create_layers(ctx, 1, 1, 1, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT,
                                        &t->shadow_stand_in));
    RTPBR_TRY(rtpbr_submit_once(ctx, record_stand_in_layout, t));

    RTPBR_TRY(rtpbr_lighting_sets_create(ctx, t->frames, &t->pool, t->sets));
    for (uint32_t f = 0; f < t->frames; ++f) {
        VkDescriptorSet set = t->sets[f];
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_FRAME, t->frame.buffer, f * t->frame_stride,
                                    sizeof(rtpbr_shader_frame));
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_MATERIALS, t->materials.buffer, 0, VK_WHOLE_SIZE);
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_TILE_MASKS, t->tile_masks.buffer, 0, VK_WHOLE_SIZE);
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_TILE_LISTS, t->tile_lists.buffer, 0, VK_WHOLE_SIZE);
        for (uint32_t i = 0; i < RTPBR_GBUFFER_TARGETS; ++i) {
            // Absent extension targets (never read: extension_textures says so) hold g0.
            VkImageView view = desc->gbuffer[i].view ? desc->gbuffer[i].view : desc->gbuffer[0].view;
            rtpbr_lighting_write_image(ctx, set, rtpbr_lighting_gbuffer_binding(i), view, t->gbuffer_layout);
        }
        rtpbr_lighting_write_image(ctx, set, RTPBR_BINDING_LIGHT_DEPTH, desc->depth.view, t->depth_layout);
        rtpbr_lighting_write_image(ctx, set, RTPBR_BINDING_LIGHT_RADIANCE, desc->output.view, VK_IMAGE_LAYOUT_GENERAL);
        rtpbr_lighting_write_image(ctx, set, RTPBR_BINDING_LIGHT_SHADOW_RATIO, t->shadow_stand_in.view,
                                   VK_IMAGE_LAYOUT_GENERAL);
        rtpbr_lighting_write_luts(ctx, set);
        // The lights: at the first recording of this frame (the light set is the record's).
    }
    *out = t;
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_lighting_targets_destroy(t);
    return result;
}

// ---------------------------------------------------------------------------------------------
// Recording

// The frame constants of a recording; false for a degenerate or non-finite camera.
static bool frame_constants(const rtpbr_lighting_targets *t, const rtpbr_lighting_record_desc *d, uint32_t light_count,
                            rtpbr_shader_frame *frame)
{
    if (d->camera) {
        if (!rtpbr_finite((const float *)d->camera, sizeof *d->camera / sizeof(float))) return false;
        rtpbr_camera_matrices(d->camera, (float)t->width / (float)t->height, frame->view_proj);
        memcpy(frame->camera_position, d->camera->position, 3 * sizeof(float));
    } else {
        if (!rtpbr_finite(d->view, 16) || !rtpbr_finite(d->projection, 16)) return false;
        float world_from_view[16];
        if (!rtpbr_mat4_invert(world_from_view, d->view)) return false;
        memcpy(frame->camera_position, &world_from_view[12], 3 * sizeof(float)); // the view's origin
        if (world_from_view[15] != 1.0f)
            for (int k = 0; k < 3; ++k) frame->camera_position[k] /= world_from_view[15];
        rtpbr_mat4_mul(frame->view_proj, d->projection, d->view);
    }
    if (!rtpbr_mat4_invert(frame->inv_view_proj, frame->view_proj) ||
        !rtpbr_finite(frame->inv_view_proj, 16))
        return false;
    frame->camera_position[3] = d->reversed_z ? 0.0f : 1.0f; // the background's depth
    memcpy(frame->background, d->background, 3 * sizeof(float));
    frame->size[0] = t->width;
    frame->size[1] = t->height;
    frame->light_count = light_count;
    frame->cull_form_factor = d->light_cull_form_factor == 0.0f ? RTPBR_DEFAULT_CULL_FORM_FACTOR
                                                                 : d->light_cull_form_factor;
    frame->tiles_x = t->tiles_x;
    frame->tile_capacity = t->tiles_x * t->tiles_y;
    frame->shadow_light_count = 0; // no shadows on this path
    frame->extension_textures = t->extension_textures;
    return true;
}

// The entry barrier of the host's G-buffer and depth images: after its writes, into the
// read layouts.
static void record_inputs_barrier(const rtpbr_lighting_targets *t, const rtpbr_lighting_record_desc *d,
                                  VkCommandBuffer cmd)
{
    VkImageMemoryBarrier barriers[RTPBR_GBUFFER_TARGETS + 1];
    uint32_t n = 0;
    VkImageLayout gbuffer_old = d->gbuffer_old_layout ? d->gbuffer_old_layout : t->gbuffer_layout;
    VkImageLayout depth_old = d->depth_old_layout ? d->depth_old_layout : t->depth_layout;
    for (uint32_t i = 0; i <= RTPBR_GBUFFER_TARGETS; ++i) {
        bool depth = i == RTPBR_GBUFFER_TARGETS;
        VkImage image = depth ? t->depth : t->gbuffer[i];
        if (!image) continue;
        barriers[n++] = (VkImageMemoryBarrier){
            .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
            .srcAccessMask = (depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT) |
                             VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_SHADER_READ_BIT,
            .oldLayout = depth ? depth_old : gbuffer_old,
            .newLayout = depth ? t->depth_layout : t->gbuffer_layout,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .image = image,
            .subresourceRange = {depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
    }
    vkCmdPipelineBarrier(cmd,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                             VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                             VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, NULL, 0, NULL, n, barriers);
}

rtpbr_result rtpbr_lighting_record(rtpbr_lighting_targets *t, const rtpbr_lighting_record_desc *d)
{
    if (!t) return rtpbr_null_object(__func__, "targets");
    rtpbr_context *ctx = t->context;
#define FAIL(...) do { rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_lighting_record: " __VA_ARGS__); return RTPBR_ERROR_INVALID_ARGUMENT; } while (0)
    if (!d || !d->command_buffer || !d->lights) FAIL("desc, command_buffer or lights is NULL");
    const rtpbr_light_set *lights = d->lights;
    if (lights->context != ctx) FAIL("the light set belongs to another context");
    if (d->frame >= t->frames || d->frame >= lights->frames)
        FAIL("frame %u; the targets have %u frames in flight, the light set %u", d->frame, t->frames, lights->frames);
    if ((unsigned)d->ndf > RTPBR_NDF_BECKMANN_MODEL || (unsigned)d->multiscatter > RTPBR_MULTISCATTER_OFF)
        FAIL("unknown ndf or multiscatter value");
    if (!rtpbr_finite(d->background, 3) || !isfinite(d->light_cull_form_factor))
        FAIL("NaN or infinite background or light_cull_form_factor");
    rtpbr_shader_frame frame = {0};
    if (d->reversed_z && d->camera) FAIL("reversed_z needs the host's view and projection (camera NULL)");
    if (!frame_constants(t, d, lights->count[d->frame], &frame)) FAIL("NaN, infinite or degenerate camera");
    // Before anything is recorded: a variant's first use compiles it, which may fail.
    VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT];
    const rtpbr_shader_light *records = (const rtpbr_shader_light *)((const char *)lights->buffer.mapped + d->frame * lights->stride);
    rtpbr_lighting_needs needs = rtpbr_lighting_needs_of(records, lights->count[d->frame], t->materials.mapped,
                                                         t->material_slots);
    needs.emission = true; // (the host's G-buffer holds the emission its own shader wrote)
    rtpbr_result result = rtpbr_lighting_pipelines_get(ctx, d->ndf, d->multiscatter, &needs, pipelines);
    if (result != RTPBR_SUCCESS) return result;
#undef FAIL

    VkDescriptorSet set = t->sets[d->frame];
    if (t->set_lights[d->frame] != lights->serial) { // this frame's set points at another light set
        VkDeviceSize bytes = lights->capacity * sizeof(rtpbr_shader_light);
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_LIGHTS, lights->buffer.buffer,
                                    d->frame * lights->stride, bytes);
        rtpbr_lighting_write_buffer(ctx, set, RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM, lights->buffer.buffer,
                                    d->frame * lights->stride,
                                    bytes < ctx->lighting.uniform_lights_range ? bytes : ctx->lighting.uniform_lights_range);
        t->set_lights[d->frame] = lights->serial;
    }
    memcpy((char *)t->frame.mapped + d->frame * t->frame_stride, &frame, sizeof frame);

    VkCommandBuffer cmd = d->command_buffer;
    record_inputs_barrier(t, d, cmd);
    rtpbr_lighting_target target = {
        .set = set,
        .tile_lists = t->tile_lists.buffer,
        .tiles_x = t->tiles_x,
        .tiles_y = t->tiles_y,
        .output = t->output,
        .output_old_layout = d->output_old_layout, // zero: UNDEFINED
        .output_src_stages = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
        .output_src_access = VK_ACCESS_MEMORY_WRITE_BIT,
    };
    rtpbr_lighting_record_target(ctx, &target, pipelines, cmd);
    VkImageLayout new_layout = d->output_new_layout ? d->output_new_layout : VK_IMAGE_LAYOUT_GENERAL;
    rtpbr_image_barrier(cmd, t->output, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, new_layout,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    return RTPBR_SUCCESS;
}
