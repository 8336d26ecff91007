/* rtpbr tests: the Vulkan host bootstrap (see vk_host.h). */
#include "vk_host.h"

#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"

const char *vk_host_result_string(vk_host_result r) {
    switch (r) {
    case VK_HOST_OK: return "ok";
    case VK_HOST_NO_DRIVER: return "no Vulkan driver or device";
    case VK_HOST_NO_VALIDATION: return "Vulkan validation layer or debug utils missing";
    case VK_HOST_NO_QUEUE: return "no queue family with the asked flags";
    case VK_HOST_VULKAN_ERROR: return "Vulkan call failed";
    case VK_HOST_OUT_OF_MEMORY: return "out of host memory";
    }
    return "unknown result";
}

const char *vk_host_vk_result_name(VkResult r) {
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

static vk_host_result fail(char *error, size_t error_size, vk_host_result r, const char *fmt, ...) {
    if (error && error_size > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(error, error_size, fmt, ap);
        va_end(ap);
    }
    return r;
}

/* Every message the messenger is given counts: WARNING and ERROR severities, of every type
 * (general, validation, performance). VERBOSE and INFO are not asked for: at INFO the layer
 * reports its own status (the settings it runs with on every vkCreateInstance; "Cannot open
 * shader validation cache ... (it may not exist yet)" on a machine that never ran it), the
 * loader reports what it loaded; none of it is a finding about the tests' Vulkan use, and a
 * test must not pass or fail by what is in $HOME. */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user_data) {
    vk_host *h = user_data;
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
        return VK_FALSE; /* not asked for (see messenger_info); a layer that sends it anyway */
    h->messages++;
    fprintf(stderr, "vulkan message (severity 0x%x, type 0x%x): %s: %s\n", (unsigned)severity, (unsigned)type,
            data && data->pMessageIdName ? data->pMessageIdName : "-", data && data->pMessage ? data->pMessage : "-");
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

vk_host_result vk_host_init_instance(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size) {
    const vk_host_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    const bool validation = !desc->without_validation;
    /* Missing validation is a failure, never a skip: the tests' promise depends on it. */
    if (validation && !has_layer(VALIDATION_LAYER))
        return fail(error, error_size, VK_HOST_NO_VALIDATION, "%s is not installed (vulkan-validationlayers)",
                    VALIDATION_LAYER);
    if (validation && (!has_instance_extension(VALIDATION_LAYER, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
                       !has_instance_extension(VALIDATION_LAYER, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)))
        return fail(error, error_size, VK_HOST_NO_VALIDATION, "%s or %s is not available",
                    VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);

    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    /* No shader validation cache: the layer would read and write
     * $XDG_CACHE_HOME/shader_validation_cache-0.bin (~/.cache), so a test's validation would
     * depend on what earlier runs left in $HOME. Every shader is validated on every run
     * instead; on lavapipe that costs nothing measurable (test_gpu: 16.9 s without the
     * cache, 17.5 s with a warm one). */
    const VkValidationFeatureDisableEXT disables[] = {VK_VALIDATION_FEATURE_DISABLE_SHADER_VALIDATION_CACHE_EXT};
    /* The same messenger description twice: chained into VkInstanceCreateInfo it covers
     * vkCreateInstance / vkDestroyInstance; created as an object it covers the rest. */
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = h,
    };
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger_info,
        .enabledValidationFeatureCount = (uint32_t)(sizeof(enables) / sizeof(enables[0])),
        .pEnabledValidationFeatures = enables,
        .disabledValidationFeatureCount = (uint32_t)(sizeof(disables) / sizeof(disables[0])),
        .pDisabledValidationFeatures = disables,
    };
    const char *layers[] = {VALIDATION_LAYER};
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = desc->app_name ? desc->app_name : "rtpbr-test",
        .apiVersion = desc->api_version ? desc->api_version : VK_API_VERSION_1_1,
    };
    VkInstanceCreateInfo instance_info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? &features : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1 : 0,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = validation ? 2 : 0,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateInstance(&instance_info, NULL, &h->instance);
    if (vr != VK_SUCCESS)
        h->instance = VK_NULL_HANDLE;
    if (vr == VK_ERROR_INCOMPATIBLE_DRIVER)
        return fail(error, error_size, VK_HOST_NO_DRIVER, "vkCreateInstance: no Vulkan driver (VK_ERROR_INCOMPATIBLE_DRIVER)");
    if (vr != VK_SUCCESS) {
        return fail(error, error_size, VK_HOST_VULKAN_ERROR, "vkCreateInstance: %s", vk_host_vk_result_name(vr));
    }
    if (!validation)
        return VK_HOST_OK;

    PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkCreateDebugUtilsMessengerEXT");
    h->destroy_messenger =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkDestroyDebugUtilsMessengerEXT");
    if (!create_messenger || !h->destroy_messenger)
        return fail(error, error_size, VK_HOST_NO_VALIDATION, "vkCreateDebugUtilsMessengerEXT is not available");
    messenger_info.pNext = NULL;
    vr = create_messenger(h->instance, &messenger_info, NULL, &h->messenger);
    if (vr != VK_SUCCESS) {
        h->messenger = VK_NULL_HANDLE;
        return fail(error, error_size, VK_HOST_VULKAN_ERROR, "vkCreateDebugUtilsMessengerEXT: %s",
                    vk_host_vk_result_name(vr));
    }
    return VK_HOST_OK;
}

static bool queue_family_with(VkPhysicalDevice pd, VkQueueFlags flags, uint32_t *family) {
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
        if ((q[i].queueFlags & flags) == flags && q[i].queueCount > 0) {
            *family = i;
            found = true;
        }
    }
    free(q);
    return found;
}

vk_host_result vk_host_init_device(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size) {
    const vk_host_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    const VkQueueFlags flags = desc->queue_flags ? desc->queue_flags : VK_QUEUE_COMPUTE_BIT;
    uint32_t n = 0;
    VkResult vr = vkEnumeratePhysicalDevices(h->instance, &n, NULL);
    if (vr != VK_SUCCESS)
        return fail(error, error_size, VK_HOST_VULKAN_ERROR, "vkEnumeratePhysicalDevices: %s", vk_host_vk_result_name(vr));
    if (n == 0)
        return fail(error, error_size, VK_HOST_NO_DRIVER,
                    "no Vulkan physical device (is mesa-vulkan-drivers / lavapipe installed?)");
    VkPhysicalDevice *devices = calloc(n, sizeof(*devices));
    if (!devices)
        return fail(error, error_size, VK_HOST_OUT_OF_MEMORY, "out of host memory");
    vr = vkEnumeratePhysicalDevices(h->instance, &n, devices);
    /* lavapipe first (a CPU device, or one whose name says llvmpipe), then any device. */
    int best_score = -1;
    for (uint32_t i = 0; vr == VK_SUCCESS && i < n; i++) {
        VkPhysicalDeviceProperties p;
        uint32_t family = 0;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        if (!queue_family_with(devices[i], flags, &family))
            continue;
        int score = (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU || strstr(p.deviceName, "llvmpipe")) ? 2 : 1;
        if (score > best_score) {
            best_score = score;
            h->physical_device = devices[i];
            h->properties = p;
            h->queue_family = family;
        }
    }
    free(devices);
    if (vr != VK_SUCCESS)
        return fail(error, error_size, VK_HOST_VULKAN_ERROR, "vkEnumeratePhysicalDevices: %s", vk_host_vk_result_name(vr));
    if (best_score < 0)
        return fail(error, error_size, VK_HOST_NO_QUEUE, "none of the %u Vulkan devices has a queue family with flags 0x%x",
                    n, (unsigned)flags);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = h->queue_family,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    VkDeviceCreateInfo device_info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = desc->device_next,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue_info,
        .enabledExtensionCount = desc->device_extension_count,
        .ppEnabledExtensionNames = desc->device_extensions,
    };
    vr = vkCreateDevice(h->physical_device, &device_info, NULL, &h->device);
    if (vr != VK_SUCCESS) {
        h->device = VK_NULL_HANDLE;
        return fail(error, error_size, VK_HOST_VULKAN_ERROR, "vkCreateDevice(%s): %s", h->properties.deviceName,
                    vk_host_vk_result_name(vr));
    }
    vkGetDeviceQueue(h->device, h->queue_family, 0, &h->queue);
    return VK_HOST_OK;
}

vk_host_result vk_host_init(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size) {
    vk_host_result r = vk_host_init_instance(h, desc, error, error_size);
    return r == VK_HOST_OK ? vk_host_init_device(h, desc, error, error_size) : r;
}

void vk_host_finish(vk_host *h) {
    if (!h)
        return;
    if (h->device)
        vkDestroyDevice(h->device, NULL); /* the object tracker reports anything left alive */
    if (h->messenger)
        h->destroy_messenger(h->instance, h->messenger, NULL);
    if (h->instance)
        vkDestroyInstance(h->instance, NULL); /* still reports to the chained messenger */
    h->device = VK_NULL_HANDLE;
    h->queue = VK_NULL_HANDLE;
    h->messenger = VK_NULL_HANDLE;
    h->instance = VK_NULL_HANDLE;
    h->physical_device = VK_NULL_HANDLE;
}

void vk_host_keep_driver_libraries_loaded(void) {
    static const char *const libs[] = {"libvulkan_lvp.so", "libVkLayer_khronos_validation.so"};
    for (size_t i = 0; i < sizeof(libs) / sizeof(libs[0]); i++)
        (void)dlopen(libs[i], RTLD_NOW | RTLD_LOCAL); /* absent: nothing to keep */
}
