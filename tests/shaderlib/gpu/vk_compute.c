/* rtpbr GPU test: a minimal Vulkan compute harness (see vk_compute.h). */
#include "vk_compute.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

#include "vk_host.h"

struct vkc_context {
    vk_host host;
    VkPhysicalDeviceMemoryProperties mem_props;
    char error[512];
};

const char *vkc_result_string(vkc_result r) {
    switch (r) {
    case VKC_OK: return "ok";
    case VKC_NO_DRIVER: return "no Vulkan driver or device";
    case VKC_NO_VALIDATION: return "Vulkan validation layer or debug utils missing";
    case VKC_NO_COMPUTE_QUEUE: return "no compute queue";
    case VKC_NO_MEMORY_TYPE: return "no host-visible memory type";
    case VKC_VULKAN_ERROR: return "Vulkan call failed";
    case VKC_BAD_ARGUMENT: return "bad argument";
    case VKC_OUT_OF_MEMORY: return "out of host memory";
    }
    return "unknown result";
}

static void set_error(char *buf, size_t size, const char *fmt, ...) {
    if (!buf || size == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, size, fmt, ap);
    va_end(ap);
}

static vkc_result from_host_result(vk_host_result r) {
    switch (r) {
    case VK_HOST_OK: return VKC_OK;
    case VK_HOST_NO_DRIVER: return VKC_NO_DRIVER;
    case VK_HOST_NO_VALIDATION: return VKC_NO_VALIDATION;
    case VK_HOST_NO_QUEUE: return VKC_NO_COMPUTE_QUEUE;
    case VK_HOST_VULKAN_ERROR: return VKC_VULKAN_ERROR;
    case VK_HOST_OUT_OF_MEMORY: return VKC_OUT_OF_MEMORY;
    }
    return VKC_VULKAN_ERROR;
}

vkc_result vkc_create(vkc_context **out, char *err, size_t err_size) {
    if (!out) {
        set_error(err, err_size, "vkc_create: out is NULL");
        return VKC_BAD_ARGUMENT;
    }
    *out = NULL;
    vkc_context *ctx = calloc(1, sizeof(*ctx));
    if (!ctx) {
        set_error(err, err_size, "vkc_create: out of host memory");
        return VKC_OUT_OF_MEMORY;
    }
    const vk_host_desc desc = {.app_name = "rtpbr-test-gpu", .queue_flags = VK_QUEUE_COMPUTE_BIT};
    vkc_result res = from_host_result(vk_host_init(&ctx->host, &desc, ctx->error, sizeof(ctx->error)));
    if (res != VKC_OK) {
        set_error(err, err_size, "%s", ctx->error);
        vkc_destroy(ctx, NULL);
        return res;
    }
    vkGetPhysicalDeviceMemoryProperties(ctx->host.physical_device, &ctx->mem_props);
    *out = ctx;
    return VKC_OK;
}

void vkc_destroy(vkc_context *ctx, uint32_t *messages_out) {
    if (!ctx)
        return;
    vk_host_finish(&ctx->host);
    if (messages_out)
        *messages_out = ctx->host.messages;
    free(ctx);
}

const char *vkc_device_name(const vkc_context *ctx) { return ctx ? ctx->host.properties.deviceName : ""; }

uint32_t vkc_message_count(const vkc_context *ctx) { return ctx ? ctx->host.messages : 0; }

const char *vkc_last_error(const vkc_context *ctx) { return ctx ? ctx->error : ""; }

/* ---- one dispatch ---------------------------------------------------------------------- */

typedef struct vkc_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
    bool coherent;
} vkc_buffer;

static void buffer_destroy(vkc_context *ctx, vkc_buffer *b) {
    if (b->mapped)
        vkUnmapMemory(ctx->host.device, b->memory);
    if (b->buffer)
        vkDestroyBuffer(ctx->host.device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(ctx->host.device, b->memory, NULL);
    memset(b, 0, sizeof(*b));
}

/* A host-visible storage buffer (host-coherent when the device has such a type). */
static vkc_result buffer_create(vkc_context *ctx, VkDeviceSize size, vkc_buffer *b) {
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VkResult vr = vkCreateBuffer(ctx->host.device, &info, NULL, &b->buffer);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateBuffer(%llu bytes): %s", (unsigned long long)size, vk_host_vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->host.device, b->buffer, &req);
    uint32_t type = UINT32_MAX;
    for (int pass = 0; pass < 2 && type == UINT32_MAX; pass++) {
        VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                     (pass == 0 ? VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : 0);
        for (uint32_t i = 0; i < ctx->mem_props.memoryTypeCount && type == UINT32_MAX; i++) {
            if ((req.memoryTypeBits & (1u << i)) && (ctx->mem_props.memoryTypes[i].propertyFlags & want) == want)
                type = i;
        }
    }
    if (type == UINT32_MAX) {
        set_error(ctx->error, sizeof(ctx->error), "no host-visible memory type for a storage buffer");
        return VKC_NO_MEMORY_TYPE;
    }
    b->coherent = (ctx->mem_props.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = type,
    };
    vr = vkAllocateMemory(ctx->host.device, &alloc, NULL, &b->memory);
    if (vr == VK_SUCCESS)
        vr = vkBindBufferMemory(ctx->host.device, b->buffer, b->memory, 0);
    if (vr == VK_SUCCESS)
        vr = vkMapMemory(ctx->host.device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "allocating/binding/mapping %llu bytes: %s",
                  (unsigned long long)req.size, vk_host_vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    return VKC_OK;
}

static VkResult buffer_flush(vkc_context *ctx, const vkc_buffer *b) {
    if (b->coherent)
        return VK_SUCCESS;
    VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = b->memory, .size = VK_WHOLE_SIZE};
    return vkFlushMappedMemoryRanges(ctx->host.device, 1, &range);
}

static VkResult buffer_invalidate(vkc_context *ctx, const vkc_buffer *b) {
    if (b->coherent)
        return VK_SUCCESS;
    VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = b->memory, .size = VK_WHOLE_SIZE};
    return vkInvalidateMappedMemoryRanges(ctx->host.device, 1, &range);
}

#define VKC_CHECK(call)                                                                        \
    do {                                                                                       \
        VkResult vr_ = (call);                                                                 \
        if (vr_ != VK_SUCCESS) {                                                               \
            set_error(ctx->error, sizeof(ctx->error), "%s: %s", #call, vk_host_vk_result_name(vr_));   \
            res = VKC_VULKAN_ERROR;                                                            \
            goto cleanup;                                                                      \
        }                                                                                      \
    } while (0)

static vkc_result check_desc(vkc_context *ctx, const vkc_dispatch_desc *d) {
    if (!d || !d->spirv || d->spirv_size == 0 || d->spirv_size % 4 != 0 || !d->input ||
        d->input_size == 0 || !d->output || d->output_size == 0) {
        set_error(ctx->error, sizeof(ctx->error), "vkc_dispatch: missing shader or buffers, or SPIR-V size not a multiple of 4");
        return VKC_BAD_ARGUMENT;
    }
    const VkPhysicalDeviceLimits *lim = &ctx->host.properties.limits;
    if (d->input_size > lim->maxStorageBufferRange || d->output_size > lim->maxStorageBufferRange) {
        set_error(ctx->error, sizeof(ctx->error), "vkc_dispatch: buffer larger than maxStorageBufferRange (%u)", lim->maxStorageBufferRange);
        return VKC_BAD_ARGUMENT;
    }
    for (int i = 0; i < 3; i++) {
        if (d->groups[i] == 0 || d->groups[i] > lim->maxComputeWorkGroupCount[i]) {
            set_error(ctx->error, sizeof(ctx->error), "vkc_dispatch: workgroup count %u in dimension %d outside [1, %u]",
                      d->groups[i], i, lim->maxComputeWorkGroupCount[i]);
            return VKC_BAD_ARGUMENT;
        }
    }
    return VKC_OK;
}

vkc_result vkc_dispatch(vkc_context *ctx, const vkc_dispatch_desc *d) {
    if (!ctx)
        return VKC_BAD_ARGUMENT;
    vkc_result res = check_desc(ctx, d);
    if (res != VKC_OK)
        return res;

    vkc_buffer in = {0}, out = {0};
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkCommandPool cmd_pool = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    bool submitted = false;

    if ((res = buffer_create(ctx, d->input_size, &in)) != VKC_OK ||
        (res = buffer_create(ctx, d->output_size, &out)) != VKC_OK)
        goto cleanup;
    memcpy(in.mapped, d->input, d->input_size);
    memset(out.mapped, 0xff, d->output_size); /* NaN everywhere: an unwritten output shows */
    VKC_CHECK(buffer_flush(ctx, &in));
    VKC_CHECK(buffer_flush(ctx, &out));

    VkShaderModuleCreateInfo module_info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = d->spirv_size,
        .pCode = d->spirv,
    };
    VKC_CHECK(vkCreateShaderModule(ctx->host.device, &module_info, NULL, &module));

    VkDescriptorSetLayoutBinding bindings[2] = {
        {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
    };
    VkDescriptorSetLayoutCreateInfo set_layout_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 2,
        .pBindings = bindings,
    };
    VKC_CHECK(vkCreateDescriptorSetLayout(ctx->host.device, &set_layout_info, NULL, &set_layout));
    VkPushConstantRange push_range = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0, .size = sizeof(uint32_t)};
    VkPipelineLayoutCreateInfo pipeline_layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push_range,
    };
    VKC_CHECK(vkCreatePipelineLayout(ctx->host.device, &pipeline_layout_info, NULL, &pipeline_layout));
    VkComputePipelineCreateInfo pipeline_info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = module,
            .pName = "main",
        },
        .layout = pipeline_layout,
    };
    VKC_CHECK(vkCreateComputePipelines(ctx->host.device, VK_NULL_HANDLE, 1, &pipeline_info, NULL, &pipeline));

    VkDescriptorPoolSize pool_size = {.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 2};
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = 1,
        .pPoolSizes = &pool_size,
    };
    VKC_CHECK(vkCreateDescriptorPool(ctx->host.device, &pool_info, NULL, &pool));
    VkDescriptorSet set;
    VkDescriptorSetAllocateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &set_layout,
    };
    VKC_CHECK(vkAllocateDescriptorSets(ctx->host.device, &set_info, &set));
    VkDescriptorBufferInfo buffer_infos[2] = {
        {.buffer = in.buffer, .offset = 0, .range = VK_WHOLE_SIZE},
        {.buffer = out.buffer, .offset = 0, .range = VK_WHOLE_SIZE},
    };
    VkWriteDescriptorSet writes[2];
    for (uint32_t i = 0; i < 2; i++) {
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstSet = set,
            .dstBinding = i,
            .descriptorCount = 1,
            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
            .pBufferInfo = &buffer_infos[i],
        };
    }
    vkUpdateDescriptorSets(ctx->host.device, 2, writes, 0, NULL);

    VkCommandPoolCreateInfo cmd_pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
        .queueFamilyIndex = ctx->host.queue_family,
    };
    VKC_CHECK(vkCreateCommandPool(ctx->host.device, &cmd_pool_info, NULL, &cmd_pool));
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo cmd_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = cmd_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VKC_CHECK(vkAllocateCommandBuffers(ctx->host.device, &cmd_info, &cmd));
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VKC_CHECK(vkBeginCommandBuffer(cmd, &begin));
    /* Host writes before vkQueueSubmit are visible to the device (submission is a host
     * memory dependency); the shader's writes must be made available to the host. */
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t), &d->push_constant);
    vkCmdDispatch(cmd, d->groups[0], d->groups[1], d->groups[2]);
    VkBufferMemoryBarrier to_host = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = out.buffer,
        .offset = 0,
        .size = VK_WHOLE_SIZE,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1, &to_host, 0, NULL);
    VKC_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VKC_CHECK(vkCreateFence(ctx->host.device, &fence_info, NULL, &fence));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &cmd,
    };
    VKC_CHECK(vkQueueSubmit(ctx->host.queue, 1, &submit, fence));
    submitted = true;
    VKC_CHECK(vkWaitForFences(ctx->host.device, 1, &fence, VK_TRUE, UINT64_MAX));
    VKC_CHECK(buffer_invalidate(ctx, &out));
    memcpy(d->output, out.mapped, d->output_size);

cleanup:
    if (submitted && res != VKC_OK)
        vkQueueWaitIdle(ctx->host.queue); /* nothing may be in flight when it is destroyed */
    if (fence)
        vkDestroyFence(ctx->host.device, fence, NULL);
    if (cmd_pool)
        vkDestroyCommandPool(ctx->host.device, cmd_pool, NULL); /* frees the command buffer */
    if (pool)
        vkDestroyDescriptorPool(ctx->host.device, pool, NULL); /* frees the set */
    if (pipeline)
        vkDestroyPipeline(ctx->host.device, pipeline, NULL);
    if (pipeline_layout)
        vkDestroyPipelineLayout(ctx->host.device, pipeline_layout, NULL);
    if (set_layout)
        vkDestroyDescriptorSetLayout(ctx->host.device, set_layout, NULL);
    if (module)
        vkDestroyShaderModule(ctx->host.device, module, NULL);
    buffer_destroy(ctx, &out);
    buffer_destroy(ctx, &in);
    return res;
}
