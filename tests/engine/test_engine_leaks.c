// Engine: the validation layer's object tracker reports, through the library's logger, a
// Vulkan object left alive on the engine's device at rtpbr_context_destroy. Every engine test
// fails on any "validation: " message, so this makes them all checks that the engine destroys
// every Vulkan object it creates. The leaked object is created with the test's own
// VkAllocationCallbacks, so that the test can give its host memory back after the device is
// gone (no host leak for LeakSanitizer or memcheck).
#include <stdlib.h>

#include "engine_test.h"

// VkAllocationCallbacks that remember every live block, so that the test can free what a
// leaked object still holds.
#define MAX_BLOCKS 64
typedef struct tracked_blocks {
    void *ptr[MAX_BLOCKS];
    size_t size[MAX_BLOCKS];
    int allocations; // calls that returned memory
} tracked_blocks;

static int find_block(tracked_blocks *t, const void *ptr)
{
    for (int i = 0; i < MAX_BLOCKS; ++i)
        if (t->ptr[i] == ptr) return i;
    return -1;
}

static void *VKAPI_CALL tracked_alloc(void *user, size_t size, size_t alignment, VkSystemAllocationScope scope)
{
    (void)scope;
    tracked_blocks *t = user;
    int slot = find_block(t, NULL);
    if (alignment < sizeof(void *)) alignment = sizeof(void *);
    // C11 aligned_alloc wants a size that is a multiple of the (power-of-two) alignment.
    void *p = slot < 0 ? NULL : aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment + alignment * !size);
    if (!p) return NULL;
    t->ptr[slot] = p;
    t->size[slot] = size;
    t->allocations++;
    return p;
}

static void VKAPI_CALL tracked_free(void *user, void *ptr)
{
    tracked_blocks *t = user;
    if (!ptr) return;
    int slot = find_block(t, ptr);
    if (slot >= 0) t->ptr[slot] = NULL;
    free(ptr);
}

static void *VKAPI_CALL tracked_realloc(void *user, void *old, size_t size, size_t alignment,
                                        VkSystemAllocationScope scope)
{
    tracked_blocks *t = user;
    if (!old) return tracked_alloc(user, size, alignment, scope);
    if (size == 0) {
        tracked_free(user, old);
        return NULL;
    }
    int slot = find_block(t, old);
    void *p = tracked_alloc(user, size, alignment, scope);
    if (!p || slot < 0) return NULL;
    memcpy(p, old, t->size[slot] < size ? t->size[slot] : size);
    tracked_free(user, old);
    return p;
}

static int live_blocks(const tracked_blocks *t)
{
    int n = 0;
    for (int i = 0; i < MAX_BLOCKS; ++i) n += t->ptr[i] != NULL;
    return n;
}

static void free_all_blocks(tracked_blocks *t)
{
    for (int i = 0; i < MAX_BLOCKS; ++i) {
        free(t->ptr[i]);
        t->ptr[i] = NULL;
    }
}

// The logger: counts validation messages, and those that say a VkSampler was not destroyed.
typedef struct leak_log {
    int validation;
    int sampler_not_destroyed;
} leak_log;

static void leak_log_func(rtpbr_log_level level, const char *message, void *user_data)
{
    (void)level;
    leak_log *log = user_data;
    if (strncmp(message, "validation: ", 12) != 0) return;
    log->validation++;
    fprintf(stderr, "VALIDATION MESSAGE (expected only when the sampler leaks): %s\n", message);
    // VVL's object tracker: "VUID-vkDestroyDevice-device-00378 ... OBJ ERROR : For VkDevice
    // 0x..[], VkSampler 0x..[] has not been destroyed."
    if (strstr(message, "VkSampler") && strstr(message, "has not been destroyed") &&
        strstr(message, "VUID-vkDestroyDevice-device-00378"))
        log->sampler_not_destroyed++;
}

// Creates a context and a VkSampler on its device (with the tracked callbacks); destroys the
// sampler before the context only if destroy_sampler is set.
static void run(bool destroy_sampler, leak_log *log, tracked_blocks *blocks)
{
    rtpbr_context *ctx = NULL;
    rtpbr_context_desc desc = {.logger = {leak_log_func, log}, .validation = 1};
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_SUCCESS);
    rtpbr_vulkan_device vk = rtpbr_context_vulkan_device(ctx);
    assert_non_null(vk.device);
    const VkAllocationCallbacks callbacks = {
        .pUserData = blocks,
        .pfnAllocation = tracked_alloc,
        .pfnReallocation = tracked_realloc,
        .pfnFree = tracked_free,
    };
    VkSamplerCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_NEAREST,
        .minFilter = VK_FILTER_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
    };
    VkSampler sampler = VK_NULL_HANDLE;
    assert_int_equal(vkCreateSampler(vk.device, &info, &callbacks, &sampler), VK_SUCCESS);
    assert_true(sampler != VK_NULL_HANDLE);
    assert_int_equal(log->validation, 0); // nothing to report yet
    if (destroy_sampler) vkDestroySampler(vk.device, sampler, &callbacks);
    rtpbr_context_destroy(ctx);
}

// The leaked sampler is reported at vkDestroyDevice, by name, through the library's logger.
static void leaked_sampler_is_reported(void **state)
{
    (void)state;
    leak_log log = {0};
    tracked_blocks blocks = {0};
    run(false, &log, &blocks);
    // The driver kept the sampler's memory (it came from our callbacks): proof it leaked.
    const int leaked = live_blocks(&blocks);
    free_all_blocks(&blocks);
    assert_true(blocks.allocations > 0);
    assert_true(leaked > 0);
    assert_int_equal(log.sampler_not_destroyed, 1);
    assert_true(log.validation >= 1);
}

// Control: the same steps with the sampler destroyed give no message at all, so the message
// above comes from the leak and not from anything else in the test.
static void destroyed_sampler_is_not_reported(void **state)
{
    (void)state;
    leak_log log = {0};
    tracked_blocks blocks = {0};
    run(true, &log, &blocks);
    const int leaked = live_blocks(&blocks);
    free_all_blocks(&blocks);
    assert_true(blocks.allocations > 0);
    assert_int_equal(leaked, 0);
    assert_int_equal(log.sampler_not_destroyed, 0);
    assert_int_equal(log.validation, 0);
}

RTPBR_TEST_MAIN(cmocka_unit_test(leaked_sampler_is_reported),
                cmocka_unit_test(destroyed_sampler_is_not_reported))
