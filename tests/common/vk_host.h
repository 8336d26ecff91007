/* rtpbr tests: the Vulkan host bootstrap of the tests (and of the shader-statistics bench).
 *
 * vk_host_init_instance: one instance with VK_LAYER_KHRONOS_validation (required unless the
 * desc says validation is off), synchronization validation on and the shader validation
 * cache off (nothing read from or written to $HOME), and a VK_EXT_debug_utils
 * messenger that prints and counts every WARNING and ERROR message of every type (general,
 * validation, performance); a test fails when vk_host.messages is not 0. VERBOSE and INFO
 * messages are not asked for and never fail a test: at INFO the loader and the layer report
 * their own state (the layer's settings; "Cannot open shader validation cache ... (it may not
 * exist yet)" on a machine where no test ran before, i.e. when $XDG_CACHE_HOME or ~/.cache
 * has no shader_validation_cache-0.bin), which says nothing about the tests' Vulkan use. The
 * engine (engine/src/device.c) and the samples' messengers use the same two severities.
 * vk_host_init_device: one device on lavapipe (a CPU device, or one named llvmpipe; any
 * other device only when there is no lavapipe) with one queue of the family the desc asks
 * for. vk_host_init does both.
 *
 * Caller storage: init fills a zeroed vk_host, vk_host_finish destroys what the inits made
 * (also after a failed init) and keeps h->messages, which then includes the object tracker's
 * reports of anything left alive. Every failure is a result plus a readable message; nothing
 * aborts.
 */
#ifndef RTPBR_TEST_VK_HOST_H
#define RTPBR_TEST_VK_HOST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

typedef enum vk_host_result {
    VK_HOST_OK = 0,
    VK_HOST_NO_DRIVER,     /* no Vulkan ICD, or no physical device: the only "skip" case */
    VK_HOST_NO_VALIDATION, /* VK_LAYER_KHRONOS_validation or its extensions missing */
    VK_HOST_NO_QUEUE,      /* no device has a queue family with the asked flags */
    VK_HOST_VULKAN_ERROR,  /* a Vulkan call failed (the message names it and its VkResult) */
    VK_HOST_OUT_OF_MEMORY, /* host allocation failed */
} vk_host_result;

typedef struct vk_host_desc {
    const char *app_name;     /* NULL: "rtpbr-test" */
    uint32_t api_version;     /* 0: VK_API_VERSION_1_1 */
    bool without_validation;  /* true: no layer, no messenger (a tool's --no-validation) */
    VkQueueFlags queue_flags; /* the queue family has all of these; 0: VK_QUEUE_COMPUTE_BIT */
    const void *device_next;  /* chained into VkDeviceCreateInfo (features), or NULL */
    const char *const *device_extensions; /* enabled on the device (device_extension_count of them) */
    uint32_t device_extension_count;
} vk_host_desc;

typedef struct vk_host {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger; /* VK_NULL_HANDLE without validation */
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger;
    VkPhysicalDevice physical_device;
    VkPhysicalDeviceProperties properties;
    VkDevice device;
    uint32_t queue_family;
    VkQueue queue;
    uint32_t messages; /* validation messages so far (each also printed to stderr) */
} vk_host;

const char *vk_host_result_string(vk_host_result r);
const char *vk_host_vk_result_name(VkResult r);

/* h must be zeroed. On failure, error (if not NULL) says why; call vk_host_finish anyway. */
vk_host_result vk_host_init_instance(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size);
vk_host_result vk_host_init_device(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size);
vk_host_result vk_host_init(vk_host *h, const vk_host_desc *desc, char *error, size_t error_size);

/* Destroys the device, the messenger and the instance (those that exist); NULL is a no-op.
 * Leaves every handle VK_NULL_HANDLE and h->messages as counted. */
void vk_host_finish(vk_host *h);

/* The Vulkan loader dlcloses the driver and the layer when the instance goes; LeakSanitizer
 * runs at exit and would then report their internal allocations from "<unknown module>",
 * which no suppression can name without also matching anything else. Holding one more
 * reference keeps lavapipe (and its LLVM) and the validation layer mapped to the end, so a
 * test's lsan.supp can name exactly those libraries. Call first in main(); the handles are
 * deliberately never closed. */
void vk_host_keep_driver_libraries_loaded(void);

#endif /* RTPBR_TEST_VK_HOST_H */
