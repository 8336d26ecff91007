/* rtpbr GPU test: a minimal Vulkan compute harness (see vk_compute.h). */
#include "vk_compute.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

#define VKC_VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"

struct vkc_context {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger;
    VkPhysicalDevice physical;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties mem_props;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    uint32_t messages;
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

static const char *vk_result_name(VkResult r) {
    switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_INVALID_SHADER_NV: return "VK_ERROR_INVALID_SHADER_NV";
    default: return "VkResult (other)";
    }
}

static void set_error(char *buf, size_t size, const char *fmt, ...) {
    if (!buf || size == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, size, fmt, ap);
    va_end(ap);
}

/* The validation layer announces itself and its settings at INFO severity with this id on
 * every vkCreateInstance: a status report, not a finding. */
#define VKC_LAYER_STATUS_ID "UNASSIGNED-khronos-validation-createinstance-status-message"

/* Every message counts except verbose output, the loader's / layer's own info-level chatter
 * (GENERAL type at INFO severity) and the layer's status announcement; validation and
 * performance messages count at every severity from INFO up. */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                 void *user_data) {
    vkc_context *ctx = user_data;
    bool counts = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT ||
                  (severity == VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT &&
                   (type & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT)) &&
                   !(data && data->pMessageIdName && strcmp(data->pMessageIdName, VKC_LAYER_STATUS_ID) == 0));
    if (counts) {
        ctx->messages++;
        fprintf(stderr, "vulkan message (severity 0x%x, type 0x%x): %s: %s\n", (unsigned)severity,
                (unsigned)type, data && data->pMessageIdName ? data->pMessageIdName : "-",
                data && data->pMessage ? data->pMessage : "-");
    }
    return VK_FALSE;
}

static bool has_layer(const char *name) {
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, NULL) != VK_SUCCESS || n == 0)
        return false;
    VkLayerProperties *layers = calloc(n, sizeof(*layers));
    if (!layers)
        return false;
    bool found = false;
    if (vkEnumerateInstanceLayerProperties(&n, layers) == VK_SUCCESS) {
        for (uint32_t i = 0; i < n && !found; i++)
            found = strcmp(layers[i].layerName, name) == 0;
    }
    free(layers);
    return found;
}

/* Is the instance extension `ext` offered by the loader/ICDs or by `layer`? */
static bool has_instance_extension(const char *layer, const char *ext) {
    for (int pass = 0; pass < 2; pass++) {
        const char *from = pass == 0 ? NULL : layer;
        uint32_t n = 0;
        if (vkEnumerateInstanceExtensionProperties(from, &n, NULL) != VK_SUCCESS || n == 0)
            continue;
        VkExtensionProperties *exts = calloc(n, sizeof(*exts));
        if (!exts)
            return false;
        bool found = false;
        if (vkEnumerateInstanceExtensionProperties(from, &n, exts) == VK_SUCCESS) {
            for (uint32_t i = 0; i < n && !found; i++)
                found = strcmp(exts[i].extensionName, ext) == 0;
        }
        free(exts);
        if (found)
            return true;
    }
    return false;
}

static bool queue_family_compute(VkPhysicalDevice pd, uint32_t *family) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
    if (n == 0)
        return false;
    VkQueueFamilyProperties *q = calloc(n, sizeof(*q));
    if (!q)
        return false;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, q);
    bool found = false;
    for (uint32_t i = 0; i < n && !found; i++) {
        if ((q[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && q[i].queueCount > 0) {
            *family = i;
            found = true;
        }
    }
    free(q);
    return found;
}

/* lavapipe first (a CPU device, or one whose name says llvmpipe), then any device with a
 * compute queue. */
static vkc_result pick_device(vkc_context *ctx) {
    uint32_t n = 0;
    VkResult vr = vkEnumeratePhysicalDevices(ctx->instance, &n, NULL);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkEnumeratePhysicalDevices: %s", vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    if (n == 0) {
        set_error(ctx->error, sizeof(ctx->error), "no Vulkan physical device (is mesa-vulkan-drivers / lavapipe installed?)");
        return VKC_NO_DRIVER;
    }
    VkPhysicalDevice *pds = calloc(n, sizeof(*pds));
    if (!pds)
        return VKC_OUT_OF_MEMORY;
    vr = vkEnumeratePhysicalDevices(ctx->instance, &n, pds);
    int best_score = -1;
    for (uint32_t i = 0; vr == VK_SUCCESS && i < n; i++) {
        VkPhysicalDeviceProperties p;
        uint32_t family = 0;
        vkGetPhysicalDeviceProperties(pds[i], &p);
        if (!queue_family_compute(pds[i], &family))
            continue;
        int score = (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU || strstr(p.deviceName, "llvmpipe")) ? 2 : 1;
        if (score > best_score) {
            best_score = score;
            ctx->physical = pds[i];
            ctx->props = p;
            ctx->queue_family = family;
        }
    }
    free(pds);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkEnumeratePhysicalDevices: %s", vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    if (best_score < 0) {
        set_error(ctx->error, sizeof(ctx->error), "none of the %u Vulkan devices has a compute queue", n);
        return VKC_NO_COMPUTE_QUEUE;
    }
    vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->mem_props);
    return VKC_OK;
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
    vkc_result res = VKC_OK;
    VkResult vr;

    /* Missing validation is a failure, never a skip: the test's promise depends on it. */
    if (!has_layer(VKC_VALIDATION_LAYER)) {
        set_error(ctx->error, sizeof(ctx->error), "%s is not installed (vulkan-validationlayers)", VKC_VALIDATION_LAYER);
        res = VKC_NO_VALIDATION;
        goto fail;
    }
    if (!has_instance_extension(VKC_VALIDATION_LAYER, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
        !has_instance_extension(VKC_VALIDATION_LAYER, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
        set_error(ctx->error, sizeof(ctx->error), "%s or %s is not available",
                  VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        res = VKC_NO_VALIDATION;
        goto fail;
    }

    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
    };
    /* The same messenger description twice: chained into VkInstanceCreateInfo it covers
     * vkCreateInstance / vkDestroyInstance; created as an object it covers the rest. */
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = ctx,
    };
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger_info,
        .enabledValidationFeatureCount = (uint32_t)(sizeof(enables) / sizeof(enables[0])),
        .pEnabledValidationFeatures = enables,
    };
    const char *layers[] = {VKC_VALIDATION_LAYER};
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "rtpbr-test-gpu",
        .apiVersion = VK_API_VERSION_1_1,
    };
    VkInstanceCreateInfo instance_info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = &features,
        .pApplicationInfo = &app,
        .enabledLayerCount = 1,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = 2,
        .ppEnabledExtensionNames = extensions,
    };
    vr = vkCreateInstance(&instance_info, NULL, &ctx->instance);
    if (vr == VK_ERROR_INCOMPATIBLE_DRIVER) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateInstance: no Vulkan driver (VK_ERROR_INCOMPATIBLE_DRIVER)");
        res = VKC_NO_DRIVER;
        goto fail;
    }
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateInstance: %s", vk_result_name(vr));
        res = VKC_VULKAN_ERROR;
        goto fail;
    }

    PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->instance, "vkCreateDebugUtilsMessengerEXT");
    ctx->destroy_messenger =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->instance, "vkDestroyDebugUtilsMessengerEXT");
    if (!create_messenger || !ctx->destroy_messenger) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateDebugUtilsMessengerEXT is not available");
        res = VKC_NO_VALIDATION;
        goto fail;
    }
    messenger_info.pNext = NULL;
    vr = create_messenger(ctx->instance, &messenger_info, NULL, &ctx->messenger);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateDebugUtilsMessengerEXT: %s", vk_result_name(vr));
        res = VKC_VULKAN_ERROR;
        goto fail;
    }

    res = pick_device(ctx);
    if (res != VKC_OK)
        goto fail;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = ctx->queue_family,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    VkDeviceCreateInfo device_info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue_info,
    };
    vr = vkCreateDevice(ctx->physical, &device_info, NULL, &ctx->device);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateDevice(%s): %s", ctx->props.deviceName, vk_result_name(vr));
        res = VKC_VULKAN_ERROR;
        goto fail;
    }
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);
    *out = ctx;
    return VKC_OK;

fail:
    set_error(err, err_size, "%s", ctx->error);
    vkc_destroy(ctx, NULL);
    return res;
}

void vkc_destroy(vkc_context *ctx, uint32_t *messages_out) {
    if (!ctx)
        return;
    if (ctx->device)
        vkDestroyDevice(ctx->device, NULL);
    if (ctx->messenger)
        ctx->destroy_messenger(ctx->instance, ctx->messenger, NULL);
    if (ctx->instance)
        vkDestroyInstance(ctx->instance, NULL); /* still reports to the chained messenger */
    if (messages_out)
        *messages_out = ctx->messages;
    free(ctx);
}

const char *vkc_device_name(const vkc_context *ctx) { return ctx ? ctx->props.deviceName : ""; }

uint32_t vkc_message_count(const vkc_context *ctx) { return ctx ? ctx->messages : 0; }

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
        vkUnmapMemory(ctx->device, b->memory);
    if (b->buffer)
        vkDestroyBuffer(ctx->device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(ctx->device, b->memory, NULL);
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
    VkResult vr = vkCreateBuffer(ctx->device, &info, NULL, &b->buffer);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "vkCreateBuffer(%llu bytes): %s", (unsigned long long)size, vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->device, b->buffer, &req);
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
    vr = vkAllocateMemory(ctx->device, &alloc, NULL, &b->memory);
    if (vr == VK_SUCCESS)
        vr = vkBindBufferMemory(ctx->device, b->buffer, b->memory, 0);
    if (vr == VK_SUCCESS)
        vr = vkMapMemory(ctx->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped);
    if (vr != VK_SUCCESS) {
        set_error(ctx->error, sizeof(ctx->error), "allocating/binding/mapping %llu bytes: %s",
                  (unsigned long long)req.size, vk_result_name(vr));
        return VKC_VULKAN_ERROR;
    }
    return VKC_OK;
}

static VkResult buffer_flush(vkc_context *ctx, const vkc_buffer *b) {
    if (b->coherent)
        return VK_SUCCESS;
    VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = b->memory, .size = VK_WHOLE_SIZE};
    return vkFlushMappedMemoryRanges(ctx->device, 1, &range);
}

static VkResult buffer_invalidate(vkc_context *ctx, const vkc_buffer *b) {
    if (b->coherent)
        return VK_SUCCESS;
    VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = b->memory, .size = VK_WHOLE_SIZE};
    return vkInvalidateMappedMemoryRanges(ctx->device, 1, &range);
}

#define VKC_CHECK(call)                                                                        \
    do {                                                                                       \
        VkResult vr_ = (call);                                                                 \
        if (vr_ != VK_SUCCESS) {                                                               \
            set_error(ctx->error, sizeof(ctx->error), "%s: %s", #call, vk_result_name(vr_));   \
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
    const VkPhysicalDeviceLimits *lim = &ctx->props.limits;
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
    VKC_CHECK(vkCreateShaderModule(ctx->device, &module_info, NULL, &module));

    VkDescriptorSetLayoutBinding bindings[2] = {
        {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
    };
    VkDescriptorSetLayoutCreateInfo set_layout_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 2,
        .pBindings = bindings,
    };
    VKC_CHECK(vkCreateDescriptorSetLayout(ctx->device, &set_layout_info, NULL, &set_layout));
    VkPushConstantRange push_range = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0, .size = sizeof(uint32_t)};
    VkPipelineLayoutCreateInfo pipeline_layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push_range,
    };
    VKC_CHECK(vkCreatePipelineLayout(ctx->device, &pipeline_layout_info, NULL, &pipeline_layout));
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
    VKC_CHECK(vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &pipeline_info, NULL, &pipeline));

    VkDescriptorPoolSize pool_size = {.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 2};
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = 1,
        .pPoolSizes = &pool_size,
    };
    VKC_CHECK(vkCreateDescriptorPool(ctx->device, &pool_info, NULL, &pool));
    VkDescriptorSet set;
    VkDescriptorSetAllocateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &set_layout,
    };
    VKC_CHECK(vkAllocateDescriptorSets(ctx->device, &set_info, &set));
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
    vkUpdateDescriptorSets(ctx->device, 2, writes, 0, NULL);

    VkCommandPoolCreateInfo cmd_pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    VKC_CHECK(vkCreateCommandPool(ctx->device, &cmd_pool_info, NULL, &cmd_pool));
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo cmd_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = cmd_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VKC_CHECK(vkAllocateCommandBuffers(ctx->device, &cmd_info, &cmd));
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
    VKC_CHECK(vkCreateFence(ctx->device, &fence_info, NULL, &fence));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &cmd,
    };
    VKC_CHECK(vkQueueSubmit(ctx->queue, 1, &submit, fence));
    submitted = true;
    VKC_CHECK(vkWaitForFences(ctx->device, 1, &fence, VK_TRUE, UINT64_MAX));
    VKC_CHECK(buffer_invalidate(ctx, &out));
    memcpy(d->output, out.mapped, d->output_size);

cleanup:
    if (submitted && res != VKC_OK)
        vkQueueWaitIdle(ctx->queue); /* nothing may be in flight when it is destroyed */
    if (fence)
        vkDestroyFence(ctx->device, fence, NULL);
    if (cmd_pool)
        vkDestroyCommandPool(ctx->device, cmd_pool, NULL); /* frees the command buffer */
    if (pool)
        vkDestroyDescriptorPool(ctx->device, pool, NULL); /* frees the set */
    if (pipeline)
        vkDestroyPipeline(ctx->device, pipeline, NULL);
    if (pipeline_layout)
        vkDestroyPipelineLayout(ctx->device, pipeline_layout, NULL);
    if (set_layout)
        vkDestroyDescriptorSetLayout(ctx->device, set_layout, NULL);
    if (module)
        vkDestroyShaderModule(ctx->device, module, NULL);
    buffer_destroy(ctx, &out);
    buffer_destroy(ctx, &in);
    return res;
}
