// Vulkan instance and device: standalone creation (with optional validation) or adoption of
// the host's objects (embedded mode).
#include <string.h>

#include "internal.h"

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
    const VkDebugUtilsMessengerCallbackDataEXT *data, void *user_data)
{
    (void)types;
    rtpbr_context *ctx = user_data;
    bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    ctx->validation_messages++;
    rtpbr_log(&ctx->host, error ? RTPBR_LOG_ERROR : RTPBR_LOG_WARNING, "validation: %s",
              data && data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

// *found: whether the instance layer is installed. Fails only when out of host memory.
static rtpbr_result has_layer(rtpbr_context *ctx, const char *name, bool *found)
{
    *found = false;
    rtpbr_result result = RTPBR_SUCCESS;
    VkLayerProperties *layers = NULL;
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, NULL) != VK_SUCCESS || count == 0) return RTPBR_SUCCESS;
    RTPBR_ALLOC(&ctx->host, layers, count * sizeof *layers);
    if (vkEnumerateInstanceLayerProperties(&count, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !*found; ++i) *found = strcmp(layers[i].layerName, name) == 0;
cleanup:
    rtpbr_free(&ctx->host, layers);
    return result;
}

// *family: a queue family with graphics and compute, or UINT32_MAX. Fails only when out of
// host memory.
static rtpbr_result find_queue_family(rtpbr_context *ctx, VkPhysicalDevice pd, uint32_t *family)
{
    *family = UINT32_MAX;
    rtpbr_result result = RTPBR_SUCCESS;
    VkQueueFamilyProperties *families = NULL;
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, NULL);
    RTPBR_ALLOC(&ctx->host, families, (count ? count : 1) * sizeof *families);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families);
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < count && *family == UINT32_MAX; ++i)
        if ((families[i].queueFlags & need) == need && families[i].queueCount > 0) *family = i;
cleanup:
    rtpbr_free(&ctx->host, families);
    return result;
}

static bool supports_dynamic_rendering(VkPhysicalDevice pd)
{
    VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f13};
    vkGetPhysicalDeviceFeatures2(pd, &f);
    return f13.dynamicRendering;
}

// Rank of a device type in the documented choice rule (lower is preferred).
static int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

// Material textures' anisotropy: up to 16x where samplerAnisotropy is enabled on the device.
static void set_max_anisotropy(rtpbr_context *ctx, bool enabled)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    float limit = props.limits.maxSamplerAnisotropy;
    ctx->max_anisotropy = enabled ? (limit < 16.0f ? limit : 16.0f) : 0.0f;
}

static void adopt_physical_device(rtpbr_context *ctx, VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    memcpy(ctx->device_name, props.deviceName, sizeof ctx->device_name);
    ctx->device_name[sizeof ctx->device_name - 1] = '\0';
    vkGetPhysicalDeviceMemoryProperties(pd, &ctx->memory_properties);
    ctx->physical_device = pd;
}

static rtpbr_result create_instance(rtpbr_context *ctx, bool validation)
{
    rtpbr_result result = RTPBR_SUCCESS;
    bool layer = false;
    if (validation && (result = has_layer(ctx, VALIDATION_LAYER, &layer)) != RTPBR_SUCCESS) return result;
    if (validation && !layer) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "validation requested but %s is not installed", VALIDATION_LAYER);
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pEngineName = "rtpbr",
        .engineVersion = VK_MAKE_VERSION(0, 1, 0),
        .apiVersion = VK_API_VERSION_1_3,
    };
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    // WARNING and ERROR of every type, never INFO (the layer's and loader's own state, e.g. a
    // shader validation cache not yet in ~/.cache): the same rule as tests/common/vk_host.h
    // and the samples' messengers.
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation_message,
        .pUserData = ctx,
    };
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger_info,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    const char *layers[] = {VALIDATION_LAYER};
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? &features : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1 : 0,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = validation ? 1 : 0,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateInstance(&info, NULL, &ctx->instance);
    if (vr == VK_ERROR_INCOMPATIBLE_DRIVER) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "no Vulkan implementation found (vkCreateInstance: %s)",
                  rtpbr_vk_result_name(vr));
        return RTPBR_ERROR_NO_DEVICE;
    }
    RTPBR_VK(&ctx->host, vr);
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create_messenger) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "vkCreateDebugUtilsMessengerEXT not available");
            return RTPBR_ERROR_MISSING_FEATURE;
        }
        RTPBR_VK(&ctx->host, create_messenger(ctx->instance, &messenger_info, NULL, &ctx->messenger));
    }
cleanup:
    return result;
}

static rtpbr_result choose_physical_device(rtpbr_context *ctx, uint32_t device_index)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkPhysicalDevice *devices = NULL;
    uint32_t count = 0;
    RTPBR_VK(&ctx->host, vkEnumeratePhysicalDevices(ctx->instance, &count, NULL));
    if (count == 0) RTPBR_FAIL(&ctx->host, RTPBR_ERROR_NO_DEVICE, "no Vulkan physical device");
    RTPBR_ALLOC(&ctx->host, devices, count * sizeof *devices);
    RTPBR_VK(&ctx->host, vkEnumeratePhysicalDevices(ctx->instance, &count, devices));

    VkPhysicalDevice best = VK_NULL_HANDLE;
    int best_rank = 99;
    uint32_t suitable = 0;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        uint32_t family = UINT32_MAX;
        RTPBR_TRY(find_queue_family(ctx, devices[i], &family));
        bool ok = props.apiVersion >= VK_API_VERSION_1_3 && supports_dynamic_rendering(devices[i]) &&
                  family != UINT32_MAX && props.limits.maxColorAttachments >= RTPBR_GBUFFER_COUNT;
        rtpbr_log(&ctx->host, RTPBR_LOG_DEBUG, "device %u: %s (%s)", i, props.deviceName, ok ? "suitable" : "unsuitable");
        if (!ok) continue;
        ++suitable;
        if (device_index != RTPBR_DEVICE_AUTO) {
            if (suitable == device_index) best = devices[i];
        } else if (type_rank(props.deviceType) < best_rank) {
            best_rank = type_rank(props.deviceType);
            best = devices[i];
        }
    }
    if (best == VK_NULL_HANDLE) {
        if (device_index != RTPBR_DEVICE_AUTO && suitable > 0)
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "device_index %u requested but only %u suitable device(s)",
                      device_index, suitable);
        else
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "no Vulkan device with Vulkan 1.3, dynamicRendering, a graphics+compute queue and %d "
                      "colour attachments (the G-buffer's)",
                      RTPBR_GBUFFER_COUNT);
        result = RTPBR_ERROR_NO_DEVICE;
        goto cleanup;
    }
    adopt_physical_device(ctx, best);
cleanup:
    rtpbr_free(&ctx->host, devices);
    return result;
}

// ---------------------------------------------------------------------------------------------
// Shadow rays by VK_KHR_ray_query (rtpbr_context_desc.shadow_ray_query; accel.c builds the
// acceleration structures, passes/shadow.c traces).

static const char *const ray_query_extensions[] = {VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                                   VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                                   VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
enum { RAY_QUERY_EXTENSION_COUNT = sizeof ray_query_extensions / sizeof ray_query_extensions[0] };

// Whether the physical device has the extensions and features the ray-query shadows need.
// Fails only when out of host memory.
static rtpbr_result device_supports_ray_query(rtpbr_context *ctx, VkPhysicalDevice pd, bool *supported)
{
    *supported = false;
    rtpbr_result result = RTPBR_SUCCESS;
    VkExtensionProperties *extensions = NULL;
    uint32_t count = 0;
    if (vkEnumerateDeviceExtensionProperties(pd, NULL, &count, NULL) != VK_SUCCESS || count == 0) return RTPBR_SUCCESS;
    RTPBR_ALLOC(&ctx->host, extensions, count * sizeof *extensions);
    if (vkEnumerateDeviceExtensionProperties(pd, NULL, &count, extensions) != VK_SUCCESS) goto cleanup;
    uint32_t found = 0;
    for (uint32_t e = 0; e < RAY_QUERY_EXTENSION_COUNT; ++e)
        for (uint32_t i = 0; i < count; ++i)
            if (strcmp(extensions[i].extensionName, ray_query_extensions[e]) == 0) {
                ++found;
                break;
            }
    if (found != RAY_QUERY_EXTENSION_COUNT) goto cleanup;
    VkPhysicalDeviceRayQueryFeaturesKHR rq = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &rq};
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, .pNext = &as};
    VkPhysicalDeviceFeatures2 f = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12};
    vkGetPhysicalDeviceFeatures2(pd, &f);
    *supported = rq.rayQuery && as.accelerationStructure && f12.bufferDeviceAddress;
cleanup:
    rtpbr_free(&ctx->host, extensions);
    return result;
}

// Whether the host's VkDeviceCreateInfo feature chain enabled what the ray-query shadows need.
static bool host_enabled_ray_query(const VkPhysicalDeviceFeatures2 *features)
{
    bool rq = false, as = false, address = false;
    for (const VkBaseInStructure *s = features ? (const VkBaseInStructure *)features->pNext : NULL; s; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR)
            rq = rq || ((const VkPhysicalDeviceRayQueryFeaturesKHR *)s)->rayQuery;
        else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR)
            as = as || ((const VkPhysicalDeviceAccelerationStructureFeaturesKHR *)s)->accelerationStructure;
        else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES)
            address = address || ((const VkPhysicalDeviceVulkan12Features *)s)->bufferDeviceAddress;
        else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES)
            address = address || ((const VkPhysicalDeviceBufferDeviceAddressFeatures *)s)->bufferDeviceAddress;
    }
    return rq && as && address;
}

// Whether to trace with ray queries, by the mode and what the device can (`available`); an
// error where the mode is ON and it cannot.
static rtpbr_result choose_ray_query(rtpbr_context *ctx, bool available, const char *missing, bool *use)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    *use = false;
    if (ctx->ray_query_mode == RTPBR_SHADOW_RAY_QUERY_OFF) return RTPBR_SUCCESS;
    if (ctx->ray_query_mode == RTPBR_SHADOW_RAY_QUERY_ON && !available) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "shadow_ray_query ON: %s %s", ctx->device_name, missing);
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    *use = available && (ctx->ray_query_mode == RTPBR_SHADOW_RAY_QUERY_ON || props.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU);
    return RTPBR_SUCCESS;
}

// The extension's entry points and limits, once the device exists with it.
static rtpbr_result load_ray_query(rtpbr_context *ctx)
{
#define LOAD(field, name)                                                                           \
    if (!(ctx->accel.field = (PFN_##name)vkGetDeviceProcAddr(ctx->device, #name))) {               \
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "ray-query shadows: %s not available", #name);       \
        return RTPBR_ERROR_MISSING_FEATURE;                                                         \
    }
    LOAD(create, vkCreateAccelerationStructureKHR)
    LOAD(destroy, vkDestroyAccelerationStructureKHR)
    LOAD(build_sizes, vkGetAccelerationStructureBuildSizesKHR)
    LOAD(cmd_build, vkCmdBuildAccelerationStructuresKHR)
    LOAD(address, vkGetAccelerationStructureDeviceAddressKHR)
#undef LOAD
    VkPhysicalDeviceAccelerationStructurePropertiesKHR as = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &as};
    vkGetPhysicalDeviceProperties2(ctx->physical_device, &props);
    ctx->accel.scratch_alignment = as.minAccelerationStructureScratchOffsetAlignment
                                       ? as.minAccelerationStructureScratchOffsetAlignment
                                       : 1;
    ctx->ray_query = true;
    rtpbr_log(&ctx->host, RTPBR_LOG_INFO, "shadow rays: VK_KHR_ray_query");
    return RTPBR_SUCCESS;
}

rtpbr_result rtpbr_device_init_standalone(rtpbr_context *ctx, const rtpbr_context_desc *desc)
{
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(create_instance(ctx, desc->validation != 0));
    RTPBR_TRY(choose_physical_device(ctx, desc->device_index));
    RTPBR_TRY(find_queue_family(ctx, ctx->physical_device, &ctx->queue_family));

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = ctx->queue_family,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    bool available = false, ray_query = false;
    RTPBR_TRY(device_supports_ray_query(ctx, ctx->physical_device, &available));
    RTPBR_TRY(choose_ray_query(ctx, available,
                               "lacks VK_KHR_ray_query, VK_KHR_acceleration_structure, "
                               "VK_KHR_deferred_host_operations or bufferDeviceAddress",
                               &ray_query));
    VkPhysicalDeviceRayQueryFeaturesKHR rq = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR,
        .rayQuery = VK_TRUE,
    };
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
        .pNext = &rq,
        .accelerationStructure = VK_TRUE,
    };
    VkPhysicalDeviceVulkan12Features f12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &as,
        .bufferDeviceAddress = VK_TRUE,
    };
    VkPhysicalDeviceVulkan13Features f13 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
        .pNext = ray_query ? &f12 : NULL,
        .dynamicRendering = VK_TRUE,
    };
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(ctx->physical_device, &supported);
    VkPhysicalDeviceFeatures2 features = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &f13,
        .features.samplerAnisotropy = supported.samplerAnisotropy,
    };
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &features,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue_info,
        .enabledExtensionCount = ray_query ? RAY_QUERY_EXTENSION_COUNT : 0,
        .ppEnabledExtensionNames = ray_query_extensions,
    };
    RTPBR_VK(&ctx->host, vkCreateDevice(ctx->physical_device, &info, NULL, &ctx->device));
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);
    if (ray_query) RTPBR_TRY(load_ray_query(ctx));
    set_max_anisotropy(ctx, supported.samplerAnisotropy);
    rtpbr_log(&ctx->host, RTPBR_LOG_INFO, "standalone device: %s", ctx->device_name);
cleanup:
    return result;
}

// Whether the host's VkDeviceCreateInfo feature chain enabled dynamicRendering.
static bool host_enabled_dynamic_rendering(const VkPhysicalDeviceFeatures2 *features)
{
    for (const VkBaseInStructure *s = features ? (const VkBaseInStructure *)features->pNext : NULL; s; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES &&
            ((const VkPhysicalDeviceVulkan13Features *)s)->dynamicRendering)
            return true;
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES &&
            ((const VkPhysicalDeviceDynamicRenderingFeatures *)s)->dynamicRendering)
            return true;
    }
    return false;
}

rtpbr_result rtpbr_device_init_embedded(rtpbr_context *ctx, const rtpbr_vulkan_device *host)
{
    ctx->embedded = true;
    if (!host->instance || !host->physical_device || !host->device || !host->queue) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "embedded mode needs instance, physical_device, device and queue (one is VK_NULL_HANDLE)");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(host->physical_device, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "embedded device %s supports Vulkan %u.%u; 1.3 is required",
                  props.deviceName, VK_API_VERSION_MAJOR(props.apiVersion), VK_API_VERSION_MINOR(props.apiVersion));
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    if (props.limits.maxColorAttachments < RTPBR_GBUFFER_COUNT) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "embedded device %s has %u colour attachments; the G-buffer needs %d",
                  props.deviceName, props.limits.maxColorAttachments, RTPBR_GBUFFER_COUNT);
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    if (!host_enabled_dynamic_rendering(host->enabled_features)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "embedded device: dynamicRendering was not enabled (enabled_features lists what the "
                  "host passed to vkCreateDevice; it must enable VkPhysicalDeviceVulkan13Features::dynamicRendering)");
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(host->physical_device, &family_count, NULL);
    VkQueueFamilyProperties families[32];
    if (family_count > 32) family_count = 32;
    vkGetPhysicalDeviceQueueFamilyProperties(host->physical_device, &family_count, families);
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (host->queue_family_index >= family_count ||
        (families[host->queue_family_index].queueFlags & need) != need) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "embedded queue family %u does not support graphics and compute",
                  host->queue_family_index);
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    ctx->instance = host->instance;
    ctx->device = host->device;
    ctx->queue = host->queue;
    ctx->queue_family = host->queue_family_index;
    adopt_physical_device(ctx, host->physical_device);
    // Only what the host enabled may be used (enabled_features: what it passed to vkCreateDevice).
    set_max_anisotropy(ctx, host->enabled_features->features.samplerAnisotropy);
    bool ray_query = false;
    rtpbr_result result = choose_ray_query(ctx, host_enabled_ray_query(host->enabled_features),
                                           "(the host's device) was not created with rayQuery, accelerationStructure "
                                           "and bufferDeviceAddress in enabled_features",
                                           &ray_query);
    if (result == RTPBR_SUCCESS && ray_query) result = load_ray_query(ctx);
    if (result != RTPBR_SUCCESS) return result;
    rtpbr_log(&ctx->host, RTPBR_LOG_INFO, "embedded in the host's device: %s", ctx->device_name);
    return RTPBR_SUCCESS;
}

void rtpbr_device_finish(rtpbr_context *ctx)
{
    if (ctx->embedded) return; // the host's objects are the host's
    if (ctx->device) vkDestroyDevice(ctx->device, NULL);
    if (ctx->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy_messenger) destroy_messenger(ctx->instance, ctx->messenger, NULL);
    }
    if (ctx->instance) vkDestroyInstance(ctx->instance, NULL);
    ctx->device = VK_NULL_HANDLE;
    ctx->instance = VK_NULL_HANDLE;
}
