// The Vulkan host code the samples share (rtpbr-embed, rtpbr-sample-host; the viewer uses the
// validation callback): what a host engine already has before it embeds rtpbr.
#ifndef RTPBR_SAMPLE_VK_H
#define RTPBR_SAMPLE_VK_H

#include <rtpbr/rtpbr.h> // rtpbr_vulkan_device
#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

// Formats a message into error (error_size bytes); returns 1.
int sample_vk_fail(char *error, size_t error_size, const char *fmt, ...);
// In a function with parameters `char *error, size_t error_size` returning int: a Vulkan call
// that fails returns 1, its name and VkResult in error.
#define SAMPLE_VK(call)                                                                            \
    do {                                                                                           \
        VkResult sample_vk_result_ = (call);                                                       \
        if (sample_vk_result_ != VK_SUCCESS)                                                       \
            return sample_vk_fail(error, error_size, "%s failed (VkResult %d)", #call, (int)sample_vk_result_); \
    } while (0)

// The validation layer's messenger callback: warnings and errors printed to stderr and
// counted in *(uint32_t *)user.
VKAPI_ATTR VkBool32 VKAPI_CALL sample_vk_on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT type, const VkDebugUtilsMessengerCallbackDataEXT *data, void *user);

// A Vulkan 1.3 instance with the given extensions (a window system's) and, with validation,
// VK_LAYER_KHRONOS_validation (with sync_validation, its synchronization validation too) and a
// messenger through sample_vk_on_validation counting into *messages. Non-zero on failure.
int sample_vk_create_instance(const char *app_name, const char *const *extensions, uint32_t extension_count, int validation,
                              int sync_validation, uint32_t *messages, VkInstance *instance,
                              VkDebugUtilsMessengerEXT *messenger, char *error, size_t error_size);
void sample_vk_destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger);
// The first Vulkan 1.3 device with a graphics + compute queue family (that can present to
// surface, unless VK_NULL_HANDLE). Non-zero if there is none.
int sample_vk_pick_device(VkInstance instance, VkSurfaceKHR surface, VkPhysicalDevice *device, uint32_t *family);

// A host's instance and device. vk is what rtpbr_context_desc.embedded takes (its
// enabled_features points into this struct: do not copy a created sample_device).
typedef struct sample_device {
    rtpbr_vulkan_device vk;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDeviceVulkan13Features features13; // what the host enabled (rtpbr reads it)
    VkPhysicalDeviceFeatures2 features;
    // Where the device has them, ray queries (rtpbr traces its shadow rays with them on a GPU:
    // rtpbr_context_desc.shadow_ray_query): their extensions enabled and these chained too.
    VkPhysicalDeviceVulkan12Features features12;
    VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration_structure;
    VkPhysicalDeviceRayQueryFeaturesKHR ray_query;
    uint32_t validation_messages;                // warnings and errors of the validation layer
} sample_device;

// Instance, the first device with Vulkan 1.3 and a graphics + compute queue, and a device with
// dynamicRendering enabled (rtpbr's one requirement), and ray queries where the device has
// them (VK_KHR_ray_query, VK_KHR_acceleration_structure, VK_KHR_deferred_host_operations,
// bufferDeviceAddress: what rtpbr's ray-query shadows need). validation: VK_LAYER_KHRONOS_validation
// (and, with sync_validation, its synchronization validation), messages through
// sample_vk_on_validation into validation_messages. Non-zero on failure, the reason in error;
// sample_device_destroy is safe after a failure.
int sample_device_create(sample_device *d, const char *app_name, int validation, int sync_validation, char *error,
                         size_t error_size);
void sample_device_destroy(sample_device *d);

#endif
