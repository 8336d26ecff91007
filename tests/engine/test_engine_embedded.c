// Engine, embedded mode: the test is the host. It creates its own instance (with validation)
// and device, hands them over, renders, destroys the module, then checks that its own objects
// still work and that the validation layer saw no error and no leaked object.
#include <stdlib.h>

#include "engine_test.h"
#include "vk_host.h"

// The host's instance (validation on, every message counted), lavapipe, one graphics+compute
// queue, Vulkan 1.3 with dynamic rendering on or off.
static void host_create(vk_host *h, bool dynamic_rendering, VkPhysicalDeviceVulkan13Features *f13)
{
    memset(h, 0, sizeof *h);
    *f13 = (VkPhysicalDeviceVulkan13Features){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                              .dynamicRendering = dynamic_rendering};
    VkPhysicalDeviceFeatures2 features = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = f13};
    vk_host_desc desc = {.app_name = "rtpbr-test-engine-embedded", .api_version = VK_API_VERSION_1_3,
                         .queue_flags = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT, .device_next = &features};
    char error[512] = "";
    vk_host_result r = vk_host_init(h, &desc, error, sizeof error);
    if (r != VK_HOST_OK) fprintf(stderr, "host: %s\n", error);
    assert_int_equal(r, VK_HOST_OK);
}

static void host_destroy(vk_host *h)
{
    vk_host_finish(h); // the object tracker reports anything rtpbr left behind
}

static rtpbr_vulkan_device handover(const vk_host *h, const VkPhysicalDeviceVulkan13Features *f13,
                                    VkPhysicalDeviceFeatures2 *features)
{
    *features = (VkPhysicalDeviceFeatures2){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                            .pNext = (void *)f13};
    return (rtpbr_vulkan_device){h->instance, h->physical_device, h->device, h->queue, h->queue_family, features};
}

static void embedded_render_leaves_host_untouched(void **state)
{
    (void)state;
    vk_host h;
    VkPhysicalDeviceVulkan13Features f13;
    host_create(&h, true, &f13);

    // The host's own objects, made before the module exists: a buffer it fills on the GPU.
    VkBuffer buffer;
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 256,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    assert_int_equal(vkCreateBuffer(h.device, &bi, NULL, &buffer), VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(h.device, buffer, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(h.physical_device, &mp);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = 0;
    while (!((req.memoryTypeBits & (1u << type)) && (mp.memoryTypes[type].propertyFlags & want) == want)) ++type;
    VkDeviceMemory memory;
    assert_int_equal(vkAllocateMemory(h.device, &(VkMemoryAllocateInfo){VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, NULL, req.size, type},
                                      NULL, &memory),
                     VK_SUCCESS);
    assert_int_equal(vkBindBufferMemory(h.device, buffer, memory, 0), VK_SUCCESS);
    VkCommandPool pool;
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .queueFamilyIndex = h.queue_family};
    assert_int_equal(vkCreateCommandPool(h.device, &pi, NULL, &pool), VK_SUCCESS);
    VkFence fence;
    assert_int_equal(vkCreateFence(h.device, &(VkFenceCreateInfo){.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO}, NULL, &fence),
                     VK_SUCCESS);

    // Hand over, render an emissive square, read it back.
    test_log log = {0};
    VkPhysicalDeviceFeatures2 features;
    rtpbr_context_desc desc = {.logger = {test_log_func, &log}, .embedded = handover(&h, &f13, &features)};
    rtpbr_context *ctx = NULL;
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_SUCCESS);
    rtpbr_vulkan_device used = rtpbr_context_vulkan_device(ctx);
    assert_ptr_equal(used.device, h.device);
    assert_ptr_equal(used.queue, h.queue);
    float positions[12];
    rtpbr_material_desc material = {.emission = {0.25f, 4.0f, 1.0f}};
    rtpbr_mesh_desc mesh = test_square_mesh(1.0f, 0.0f, positions);
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &material, .material_count = 1});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 16, .height = 16});
    for (int i = 0; i < 3; ++i) assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    float px[16 * 16 * 4];
    assert_int_equal(test_read_radiance(r, px, sizeof px), RTPBR_SUCCESS);
    assert_float_equal(px[4 * (8 * 16 + 8) + 1], 4.0f, 0.0f);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    assert_int_equal(log.errors, 0);

    // The host's device, queue and objects still work.
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    assert_int_equal(vkAllocateCommandBuffers(h.device, &ci, &cmd), VK_SUCCESS);
    assert_int_equal(vkBeginCommandBuffer(cmd, &(VkCommandBufferBeginInfo){.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO}),
                     VK_SUCCESS);
    vkCmdFillBuffer(cmd, buffer, 0, 256, 0x2a2a2a2au);
    test_submit_for_host(h.device, h.queue, cmd, fence);
    void *mapped;
    assert_int_equal(vkMapMemory(h.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), VK_SUCCESS);
    for (int i = 0; i < 256; ++i) assert_int_equal(((const uint8_t *)mapped)[i], 0x2a);
    vkUnmapMemory(h.device, memory);
    assert_int_equal(vkDeviceWaitIdle(h.device), VK_SUCCESS);

    vkDestroyFence(h.device, fence, NULL);
    vkDestroyCommandPool(h.device, pool, NULL);
    vkDestroyBuffer(h.device, buffer, NULL);
    vkFreeMemory(h.device, memory, NULL);
    host_destroy(&h);
    assert_int_equal(h.messages, 0);
}

// A host device created without dynamicRendering, or a host that does not say what it
// enabled, is refused with RTPBR_ERROR_MISSING_FEATURE and nothing is created on it.
static void embedded_missing_feature(void **state)
{
    (void)state;
    vk_host h;
    VkPhysicalDeviceVulkan13Features f13;
    host_create(&h, false, &f13);
    test_log log = {0};
    VkPhysicalDeviceFeatures2 features;
    rtpbr_context_desc desc = {.logger = {test_log_func, &log}, .embedded = handover(&h, &f13, &features)};
    rtpbr_context *ctx = (rtpbr_context *)(uintptr_t)1;
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_ERROR_MISSING_FEATURE);
    assert_null(ctx);
    assert_true(strstr(log.last_error, "dynamicRendering") != NULL);
    desc.embedded.enabled_features = NULL;
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_ERROR_MISSING_FEATURE);
    desc.embedded.enabled_features = &features;
    desc.embedded.queue = VK_NULL_HANDLE;
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_ERROR_INVALID_ARGUMENT);
    host_destroy(&h);
    assert_int_equal(h.messages, 0);
}

RTPBR_TEST_MAIN(cmocka_unit_test(embedded_render_leaves_host_untouched),
                cmocka_unit_test(embedded_missing_feature))
