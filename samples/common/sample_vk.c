// The Vulkan host code the samples share (sample_vk.h).
#include "sample_vk.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

int sample_vk_fail(char *error, size_t error_size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(error, error_size, fmt, ap);
    va_end(ap);
    return 1;
}

VKAPI_ATTR VkBool32 VKAPI_CALL sample_vk_on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT type, const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)type;
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        ++*(uint32_t *)user;
        fprintf(stderr, "validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

int sample_vk_create_instance(const char *app_name, const char *const *extensions, uint32_t extension_count, int validation,
                              int sync_validation, uint32_t *messages, VkInstance *instance,
                              VkDebugUtilsMessengerEXT *messenger, char *error, size_t error_size)
{
    *instance = VK_NULL_HANDLE, *messenger = VK_NULL_HANDLE;
    const char *layer = "VK_LAYER_KHRONOS_validation";
    const char *names[18];
    if (extension_count > 16) return sample_vk_fail(error, error_size, "too many instance extensions");
    for (uint32_t i = 0; i < extension_count; ++i) names[i] = extensions[i];
    uint32_t name_count = extension_count;
    if (validation) {
        names[name_count++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        names[name_count++] = VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME;
    }
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = sample_vk_on_validation, .pUserData = messages};
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, .pNext = &messenger_info,
        .enabledValidationFeatureCount = sync_validation ? 1 : 0, .pEnabledValidationFeatures = &sync};
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = app_name,
                             .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo instance_info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app,
        .pNext = validation ? &features : NULL, .enabledLayerCount = validation ? 1 : 0, .ppEnabledLayerNames = &layer,
        .enabledExtensionCount = name_count, .ppEnabledExtensionNames = names};
    if (vkCreateInstance(&instance_info, NULL, instance) != VK_SUCCESS) {
        *instance = VK_NULL_HANDLE;
        return sample_vk_fail(error, error_size, "no Vulkan 1.3 instance%s", validation ? " with the validation layer" : "");
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(*instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create) return sample_vk_fail(error, error_size, "vkCreateDebugUtilsMessengerEXT missing");
        SAMPLE_VK(create(*instance, &messenger_info, NULL, messenger));
    }
    return 0;
}

void sample_vk_destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger)
{
    if (messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(instance, messenger, NULL);
    }
    if (instance) vkDestroyInstance(instance, NULL);
}

int sample_vk_pick_device(VkInstance instance, VkSurfaceKHR surface, VkPhysicalDevice *device, uint32_t *family)
{
    *device = VK_NULL_HANDLE;
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    if (vkEnumeratePhysicalDevices(instance, &count, devices) < 0) count = 0;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        if (props.apiVersion < VK_API_VERSION_1_3) continue;
        VkQueueFamilyProperties families[16];
        uint32_t family_count = 16;
        vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &family_count, families);
        for (uint32_t f = 0; f < family_count; ++f) {
            VkBool32 present = VK_TRUE;
            if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(devices[i], f, surface, &present);
            if (present && (families[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                               (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                *device = devices[i], *family = f;
                return 0;
            }
        }
    }
    return 1;
}

int sample_device_create(sample_device *d, const char *app_name, int validation, int sync_validation, char *error,
                         size_t error_size)
{
    memset(d, 0, sizeof *d);
    if (sample_vk_create_instance(app_name, NULL, 0, validation, sync_validation, &d->validation_messages, &d->vk.instance,
                                  &d->messenger, error, error_size))
        return 1;
    if (sample_vk_pick_device(d->vk.instance, VK_NULL_HANDLE, &d->vk.physical_device, &d->vk.queue_family_index))
        return sample_vk_fail(error, error_size, "no Vulkan 1.3 device with a graphics + compute queue");
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = d->vk.queue_family_index, .queueCount = 1, .pQueuePriorities = &priority};
    // Ray queries where the device has every extension and feature rtpbr's need.
    static const char *const ray_query_extensions[] = {VK_KHR_RAY_QUERY_EXTENSION_NAME,
        VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
    uint32_t found = 0, count = 0;
    vkEnumerateDeviceExtensionProperties(d->vk.physical_device, NULL, &count, NULL);
    VkExtensionProperties *extensions = calloc(count ? count : 1, sizeof *extensions);
    if (extensions && vkEnumerateDeviceExtensionProperties(d->vk.physical_device, NULL, &count, extensions) == VK_SUCCESS)
        for (uint32_t e = 0; e < 3; ++e)
            for (uint32_t i = 0; i < count; ++i)
                if (!strcmp(extensions[i].extensionName, ray_query_extensions[e])) {
                    ++found;
                    break;
                }
    free(extensions);
    d->ray_query = (VkPhysicalDeviceRayQueryFeaturesKHR){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    d->acceleration_structure = (VkPhysicalDeviceAccelerationStructureFeaturesKHR){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &d->ray_query};
    d->features12 = (VkPhysicalDeviceVulkan12Features){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                                      .pNext = &d->acceleration_structure};
    VkPhysicalDeviceFeatures2 supported = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &d->features12};
    if (found == 3) vkGetPhysicalDeviceFeatures2(d->vk.physical_device, &supported);
    bool ray_query = found == 3 && d->ray_query.rayQuery && d->acceleration_structure.accelerationStructure &&
                     d->features12.bufferDeviceAddress;
    // What is enabled: those three (the queried structs hold every supported feature).
    d->ray_query = (VkPhysicalDeviceRayQueryFeaturesKHR){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR,
                                                         .rayQuery = VK_TRUE};
    d->acceleration_structure = (VkPhysicalDeviceAccelerationStructureFeaturesKHR){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &d->ray_query,
        .accelerationStructure = VK_TRUE};
    d->features12 = (VkPhysicalDeviceVulkan12Features){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                                      .pNext = &d->acceleration_structure, .bufferDeviceAddress = VK_TRUE};
    d->features13 = (VkPhysicalDeviceVulkan13Features){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                                      .pNext = ray_query ? &d->features12 : NULL,
                                                      .dynamicRendering = VK_TRUE};
    d->features = (VkPhysicalDeviceFeatures2){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &d->features13};
    SAMPLE_VK(vkCreateDevice(d->vk.physical_device, &(VkDeviceCreateInfo){.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &d->features, .queueCreateInfoCount = 1, .pQueueCreateInfos = &queue_info,
        .enabledExtensionCount = ray_query ? 3 : 0, .ppEnabledExtensionNames = ray_query_extensions}, NULL, &d->vk.device));
    vkGetDeviceQueue(d->vk.device, d->vk.queue_family_index, 0, &d->vk.queue);
    d->vk.enabled_features = &d->features;
    return 0;
}

void sample_device_destroy(sample_device *d)
{
    if (d->vk.device) vkDestroyDevice(d->vk.device, NULL);
    sample_vk_destroy_instance(d->vk.instance, d->messenger);
    d->vk.device = VK_NULL_HANDLE, d->messenger = VK_NULL_HANDLE, d->vk.instance = VK_NULL_HANDLE;
}
