// The scene's acceleration structures for shadow rays traced with VK_KHR_ray_query
// (rtpbr_context_desc.shadow_ray_query; passes/shadow.c, shaders/shadow.comp built with
// RTPBR_SHADOW_RAY_QUERY). Made from the BVH's triangles (bvh.c: world space, already in the
// BVH's order, with each triangle's sidedness and alpha flag), so that a ray meets the same
// triangles with the same flags in either walk:
//   - six bottom-level structures, one per class of triangle: double-sided, single-sided or
//     single-sided under a mirroring transform, each opaque or alpha-tested (a class without
//     triangles has none). Facing is per instance and opacity per geometry, so a class is what
//     one instance can say;
//   - a single-sided triangle blocks only the rays that meet its counter-clockwise side
//     (bvh.glsl, v0.w = 1), the front of Vulkan's ray-triangle facing; one whose mesh's
//     transform mirrors (v0.w = -1) the other side, its instance's facing flipped;
//   - the top level holds one instance per class, identity transform, its instanceCustomIndex
//     the first of its triangles in `accel_triangles`, a storage buffer of uints (binding
//     RTPBR_BINDING_SHADOW_ACCEL_TRIANGLES): the BVH triangle of each (the alpha test reads that
//     triangle's vertices and material, the stochastic opacity hashes its index).
// Built at scene creation by one submission, and again where a material's sidedness or alpha
// mode changes (rtpbr_gpu_scene_set_material) or a mesh moves (rtpbr_gpu_scene_set_transform,
// after the BVH's refit).
#include <string.h>

#include "internal.h"

enum { ACCEL_CLASSES = 6 }; // accel_class
// instanceCustomIndex has 24 bits.
#define RTPBR_ACCEL_MAX_TRIANGLES (1u << 24)

// A triangle's class: 2 x its sides (0 both, 1 its front, 2 its back: a single-sided one under
// a mirroring transform) + 1 where its alpha is tested.
static uint32_t accel_class(const rtpbr_shader_bvh_triangle *t)
{
    return 2u * (t->v0[3] == 0.0f ? 0u : t->v0[3] > 0.0f ? 1u : 2u) + (t->e1[3] != 0.0f ? 1u : 0u);
}

static VkDeviceAddress buffer_address(const rtpbr_context *ctx, VkBuffer buffer)
{
    const VkBufferDeviceAddressInfo info = {VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, NULL, buffer};
    return vkGetBufferDeviceAddress(ctx->device, &info);
}

static VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a)
{
    return (v + a - 1) / a * a;
}

typedef struct accel_build {
    VkAccelerationStructureBuildGeometryInfoKHR blas[ACCEL_CLASSES], tlas;
    VkAccelerationStructureGeometryKHR blas_geometry[ACCEL_CLASSES], tlas_geometry;
    VkAccelerationStructureBuildRangeInfoKHR blas_range[ACCEL_CLASSES], tlas_range;
    uint32_t blas_count;
    const rtpbr_context *ctx;
} accel_build;

static void record_build(VkCommandBuffer cmd, void *user)
{
    const accel_build *b = user;
    const VkAccelerationStructureBuildRangeInfoKHR *ranges[ACCEL_CLASSES];
    for (uint32_t i = 0; i < b->blas_count; ++i) ranges[i] = &b->blas_range[i];
    if (b->blas_count) b->ctx->accel.cmd_build(cmd, b->blas_count, b->blas, ranges);
    // The bottom levels before the top level reads them and writes the scratch they wrote (its
    // region starts at theirs); the top level before the trace.
    const VkMemoryBarrier bottom = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                                    VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                                        VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &bottom, 0, NULL, 0, NULL);
    const VkAccelerationStructureBuildRangeInfoKHR *top = &b->tlas_range;
    b->ctx->accel.cmd_build(cmd, 1, &b->tlas, &top);
    const VkMemoryBarrier built = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                                   VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &built, 0, NULL, 0, NULL);
}

rtpbr_result rtpbr_accel_create(rtpbr_gpu_scene *scene)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer scratch = {0};
    if (!ctx->ray_query) return RTPBR_SUCCESS;
    const uint32_t n = scene->bvh_triangle_count;
    if (n >= RTPBR_ACCEL_MAX_TRIANGLES)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED,
                   "the scene has %u triangles; the ray-query shadows hold fewer than %u "
                   "(rtpbr_context_desc.shadow_ray_query OFF traces any number the BVH holds)",
                   n, (unsigned)RTPBR_ACCEL_MAX_TRIANGLES);
    const rtpbr_shader_bvh_triangle *tris = scene->bvh_triangles.mapped;
    uint32_t count[ACCEL_CLASSES] = {0}, first[ACCEL_CLASSES] = {0};
    for (uint32_t i = 0; i < n; ++i) count[accel_class(&tris[i])]++;
    for (uint32_t c = 1; c < ACCEL_CLASSES; ++c) first[c] = first[c - 1] + count[c - 1];

    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                                     VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, (n ? n : 1) * 9 * sizeof(float), input, &scene->accel_vertices));
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, (n ? n : 1) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       &scene->accel_triangles));
    float *vertices = scene->accel_vertices.mapped;
    uint32_t *source = scene->accel_triangles.mapped;
    source[0] = 0;
    uint32_t next[ACCEL_CLASSES];
    memcpy(next, first, sizeof next);
    for (uint32_t i = 0; i < n; ++i) {
        const rtpbr_shader_bvh_triangle *t = &tris[i];
        uint32_t slot = next[accel_class(t)]++;
        float *v = vertices + 9 * (size_t)slot;
        for (int k = 0; k < 3; ++k) {
            v[k] = t->v0[k];
            v[3 + k] = t->v0[k] + t->e1[k];
            v[6 + k] = t->v0[k] + t->e2[k];
        }
        source[slot] = i;
    }

    accel_build b = {.ctx = ctx};
    VkAccelerationStructureBuildSizesInfoKHR blas_size[ACCEL_CLASSES], tlas_size = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    uint32_t class_of[ACCEL_CLASSES];
    const VkDeviceAddress vertex_address = buffer_address(ctx, scene->accel_vertices.buffer);
    for (uint32_t c = 0; c < ACCEL_CLASSES; ++c) {
        if (!count[c]) continue;
        uint32_t k = b.blas_count++;
        class_of[k] = c;
        b.blas_geometry[k] = (VkAccelerationStructureGeometryKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
            .geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR,
            .geometry.triangles = {
                .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
                .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
                .vertexData.deviceAddress = vertex_address + (VkDeviceSize)first[c] * 9 * sizeof(float),
                .vertexStride = 3 * sizeof(float),
                .maxVertex = 3 * count[c] - 1,
                .indexType = VK_INDEX_TYPE_NONE_KHR,
            },
            // Opaque triangles never reach the shader; an alpha-tested one once per ray.
            .flags = (c & 1) ? VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR : VK_GEOMETRY_OPAQUE_BIT_KHR,
        };
        b.blas[k] = (VkAccelerationStructureBuildGeometryInfoKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
            .type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
            .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
            .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
            .geometryCount = 1,
            .pGeometries = &b.blas_geometry[k],
        };
        b.blas_range[k] = (VkAccelerationStructureBuildRangeInfoKHR){.primitiveCount = count[c]};
        blas_size[k] = (VkAccelerationStructureBuildSizesInfoKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
        ctx->accel.build_sizes(ctx->device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b.blas[k], &count[c],
                               &blas_size[k]);
    }
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, ACCEL_CLASSES * sizeof(VkAccelerationStructureInstanceKHR), input,
                                       &scene->accel_instances));
    b.tlas_geometry = (VkAccelerationStructureGeometryKHR){
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .geometry.instances = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR,
                               .data.deviceAddress = buffer_address(ctx, scene->accel_instances.buffer)},
    };
    b.tlas = (VkAccelerationStructureBuildGeometryInfoKHR){
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = &b.tlas_geometry,
    };
    b.tlas_range = (VkAccelerationStructureBuildRangeInfoKHR){.primitiveCount = b.blas_count};
    ctx->accel.build_sizes(ctx->device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b.tlas, &b.blas_count,
                           &tlas_size);

    // One storage buffer for every level (offsets 256-byte aligned, as the spec requires), one
    // scratch buffer with a region per build of a vkCmdBuildAccelerationStructuresKHR call.
    VkDeviceSize storage_offset[ACCEL_CLASSES + 1], scratch_offset[ACCEL_CLASSES + 1];
    VkDeviceSize storage = 0, scratch_size = 0;
    const VkDeviceSize sa = ctx->accel.scratch_alignment;
    for (uint32_t k = 0; k < b.blas_count; ++k) {
        storage_offset[k] = storage;
        storage = align_up(storage + blas_size[k].accelerationStructureSize, 256);
        scratch_offset[k] = scratch_size;
        scratch_size = align_up(scratch_size + blas_size[k].buildScratchSize, sa);
    }
    storage_offset[b.blas_count] = storage;
    storage += tlas_size.accelerationStructureSize;
    scratch_offset[b.blas_count] = 0; // the top level's build follows the bottom levels'
    if (tlas_size.buildScratchSize > scratch_size) scratch_size = tlas_size.buildScratchSize;
    RTPBR_TRY(rtpbr_buffer_create_device(ctx, storage,
                                         VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                                             VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                         &scene->accel_storage));
    RTPBR_TRY(rtpbr_buffer_create_device(ctx, scratch_size + sa,
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                         &scratch));
    const VkDeviceAddress scratch_address = align_up(buffer_address(ctx, scratch.buffer), sa);

    VkAccelerationStructureInstanceKHR *instances = scene->accel_instances.mapped;
    for (uint32_t k = 0; k <= b.blas_count; ++k) {
        bool top = k == b.blas_count;
        VkAccelerationStructureCreateInfoKHR info = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
            .buffer = scene->accel_storage.buffer,
            .offset = storage_offset[k],
            .size = top ? tlas_size.accelerationStructureSize : blas_size[k].accelerationStructureSize,
            .type = top ? VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR : VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
        };
        VkAccelerationStructureKHR *as = top ? &scene->accel_tlas : &scene->accel_blas[k];
        RTPBR_VK(&ctx->host, ctx->accel.create(ctx->device, &info, NULL, as));
        VkAccelerationStructureBuildGeometryInfoKHR *g = top ? &b.tlas : &b.blas[k];
        g->dstAccelerationStructure = *as;
        g->scratchData.deviceAddress = scratch_address + scratch_offset[k];
        if (top) continue;
        const VkAccelerationStructureDeviceAddressInfoKHR address = {
            VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR, NULL, *as};
        uint32_t c = class_of[k];
        instances[k] = (VkAccelerationStructureInstanceKHR){
            .transform.matrix = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}},
            .instanceCustomIndex = first[c],
            .mask = 0xff,
            // Double-sided: every side blocks. Single-sided: ray_query.glsl culls the back
            // faces, and Vulkan's front face (not flipped) is the side bvh.glsl's single-sided
            // triangles block from (measured: flipped, emissive_mesh's shadowed render differed
            // from the BVH walk's in 56 % of its pixels); flipped under a mirroring transform.
            .flags = c / 2 == 0   ? VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR
                     : c / 2 == 2 ? VK_GEOMETRY_INSTANCE_TRIANGLE_FLIP_FACING_BIT_KHR
                                  : 0,
            .accelerationStructureReference = ctx->accel.address(ctx->device, &address),
        };
    }
    RTPBR_TRY(rtpbr_submit_once(ctx, record_build, &b));
cleanup:
    rtpbr_buffer_destroy(ctx, &scratch);
    return result; // the caller destroys a half-built scene (rtpbr_accel_destroy)
}

void rtpbr_accel_destroy(rtpbr_gpu_scene *scene)
{
    rtpbr_context *ctx = scene->context;
    if (ctx->accel.destroy) {
        for (uint32_t k = 0; k < ACCEL_CLASSES; ++k) ctx->accel.destroy(ctx->device, scene->accel_blas[k], NULL);
        ctx->accel.destroy(ctx->device, scene->accel_tlas, NULL);
    }
    memset(scene->accel_blas, 0, sizeof scene->accel_blas);
    scene->accel_tlas = VK_NULL_HANDLE;
    rtpbr_buffer_destroy(ctx, &scene->accel_storage);
    rtpbr_buffer_destroy(ctx, &scene->accel_instances);
    rtpbr_buffer_destroy(ctx, &scene->accel_vertices);
    rtpbr_buffer_destroy(ctx, &scene->accel_triangles);
}
