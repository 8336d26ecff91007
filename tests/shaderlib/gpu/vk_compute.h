/* rtpbr GPU test: a minimal Vulkan compute harness.
 *
 * The tests' Vulkan host (tests/common/vk_host.h): one instance with VK_LAYER_KHRONOS_validation
 * (required) and synchronization validation, a VK_EXT_debug_utils messenger that counts every
 * message that is not plain loader chatter, one device (lavapipe preferred), one compute queue.
 * vkc_dispatch() runs one compute shader over host-visible storage buffers and reads the
 * result back. Every failure is a result code plus a message in the context (or in `err` for
 * vkc_create); nothing aborts.
 */
#ifndef RTPBR_TEST_VK_COMPUTE_H
#define RTPBR_TEST_VK_COMPUTE_H

#include <stddef.h>
#include <stdint.h>

typedef enum vkc_result {
    VKC_OK = 0,
    VKC_NO_DRIVER,        /* no Vulkan ICD, or no physical device: the only "skip" case */
    VKC_NO_VALIDATION,    /* VK_LAYER_KHRONOS_validation or VK_EXT_debug_utils missing */
    VKC_NO_COMPUTE_QUEUE, /* the chosen device has no compute queue */
    VKC_NO_MEMORY_TYPE,   /* no host-visible memory type for a storage buffer */
    VKC_VULKAN_ERROR,     /* a Vulkan call failed (the message names it and its VkResult) */
    VKC_BAD_ARGUMENT,
    VKC_OUT_OF_MEMORY,    /* host allocation failed */
} vkc_result;

const char *vkc_result_string(vkc_result r);

typedef struct vkc_context vkc_context;

/* Creates the instance, messenger and device. On failure *out is NULL and err (if not NULL)
 * holds a readable reason. */
vkc_result vkc_create(vkc_context **out, char *err, size_t err_size);

/* Destroys everything vkc_create made; NULL is a no-op. Validation messages produced while
 * destroying (the object tracker's leak reports) are printed to stderr and counted into
 * *messages_out when it is not NULL. */
void vkc_destroy(vkc_context *ctx, uint32_t *messages_out);

/* The chosen device's name. */
const char *vkc_device_name(const vkc_context *ctx);

/* Number of debug-utils messages received so far (each is also printed to stderr). */
uint32_t vkc_message_count(const vkc_context *ctx);

/* The message of the last failed call. */
const char *vkc_last_error(const vkc_context *ctx);

typedef struct vkc_dispatch_desc {
    const uint32_t *spirv;  /* compute shader, entry point "main" */
    size_t spirv_size;      /* bytes, a multiple of 4 */
    const void *input;      /* bound as storage buffer (set 0, binding 0) */
    size_t input_size;
    void *output;           /* storage buffer (set 0, binding 1), read back after the run */
    size_t output_size;
    uint32_t push_constant; /* one uint32 push constant at offset 0 */
    uint32_t groups[3];     /* workgroup counts */
} vkc_dispatch_desc;

/* Runs one dispatch and waits for it. Every object it creates is destroyed before return. */
vkc_result vkc_dispatch(vkc_context *ctx, const vkc_dispatch_desc *desc);

#endif /* RTPBR_TEST_VK_COMPUTE_H */
