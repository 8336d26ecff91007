// The viewer's Vulkan host (see window.h). Every failing call prints what failed.
#include "window.h"
#include "sample_vk.h" // the samples' instance, device choice and validation callback

#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *viewer_window_program = "rtpbr-viewer";

#define CHECK(call)                                                                        \
    do {                                                                                   \
        VkResult check_result_ = (call);                                                   \
        if (check_result_ != VK_SUCCESS) {                                                 \
            fprintf(stderr, "%s: %s failed (VkResult %d)\n", viewer_window_program, #call, check_result_); \
            return false;                                                                  \
        }                                                                                  \
    } while (0)

static bool create_instance(viewer_window *w, bool validation, bool sync_validation)
{
    uint32_t glfw_count = 0;
    const char **glfw_exts = glfwGetRequiredInstanceExtensions(&glfw_count);
    if (!glfw_exts) {
        fprintf(stderr, "%s: GLFW found no Vulkan surface support\n", viewer_window_program);
        return false;
    }
    char error[256];
    if (sample_vk_create_instance(viewer_window_program, glfw_exts, glfw_count, validation, sync_validation, &w->validation_messages,
                                  &w->instance, &w->messenger, error, sizeof error)) {
        fprintf(stderr, "%s: %s\n", viewer_window_program, error);
        return false;
    }
    return true;
}

// The first Vulkan 1.3 device with a graphics + compute queue family that can present.
static bool create_device(viewer_window *w)
{
    sample_vk_pick_device(w->instance, w->surface, &w->physical_device, &w->queue_family);
    if (!w->physical_device) {
        fprintf(stderr, "%s: no Vulkan 1.3 device that can present to the window\n", viewer_window_program);
        return false;
    }
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = w->queue_family, .queueCount = 1, .pQueuePriorities = &priority};
    w->features13 = (VkPhysicalDeviceVulkan13Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, .dynamicRendering = VK_TRUE};
    w->features = (VkPhysicalDeviceFeatures2){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                               .pNext = &w->features13};
    const char *ext = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &w->features,
        .queueCreateInfoCount = 1, .pQueueCreateInfos = &queue, .enabledExtensionCount = 1,
        .ppEnabledExtensionNames = &ext};
    CHECK(vkCreateDevice(w->physical_device, &info, NULL, &w->device));
    vkGetDeviceQueue(w->device, w->queue_family, 0, &w->queue);
    VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                    .queueFamilyIndex = w->queue_family};
    CHECK(vkCreateCommandPool(w->device, &pool, NULL, &w->pool));
    VkCommandBufferAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = w->pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    CHECK(vkAllocateCommandBuffers(w->device, &alloc, &w->cmd));
    VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    CHECK(vkCreateFence(w->device, &fence, NULL, &w->fence));
    VkSemaphoreCreateInfo sem = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    CHECK(vkCreateSemaphore(w->device, &sem, NULL, &w->acquired));
    CHECK(vkCreateSemaphore(w->device, &sem, NULL, &w->rendered));
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(w->physical_device, &props);
    VkQueueFamilyProperties families[16];
    uint32_t family_count = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(w->physical_device, &family_count, families);
    if (families[w->queue_family].timestampValidBits >= 32 && props.limits.timestampPeriod > 0.0f) {
        w->ns_per_tick = props.limits.timestampPeriod;
        VkQueryPoolCreateInfo queries = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                         .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 2};
        CHECK(vkCreateQueryPool(w->device, &queries, NULL, &w->ui_queries));
    }
    return true;
}

static bool create_host_buffer(viewer_window *w, VkDeviceSize size, VkBufferUsageFlags usage, VkBuffer *buffer,
                               VkDeviceMemory *memory, void **mapped)
{
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    CHECK(vkCreateBuffer(w->device, &info, NULL, buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(w->device, *buffer, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(w->physical_device, &props);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) type = i;
    if (type == UINT32_MAX) {
        fprintf(stderr, "%s: no host-visible coherent memory\n", viewer_window_program);
        return false;
    }
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                                  .memoryTypeIndex = type};
    CHECK(vkAllocateMemory(w->device, &alloc, NULL, memory));
    CHECK(vkBindBufferMemory(w->device, *buffer, *memory, 0));
    CHECK(vkMapMemory(w->device, *memory, 0, VK_WHOLE_SIZE, 0, mapped));
    return true;
}

static void destroy_swapchain(viewer_window *w)
{
    for (uint32_t i = 0; i < w->image_count; ++i) vkDestroyImageView(w->device, w->views[i], NULL);
    w->image_count = 0;
    if (w->swapchain) vkDestroySwapchainKHR(w->device, w->swapchain, NULL);
    w->swapchain = VK_NULL_HANDLE;
    if (w->readback) vkDestroyBuffer(w->device, w->readback, NULL);
    if (w->readback_memory) vkFreeMemory(w->device, w->readback_memory, NULL);
    if (w->overlay) vkDestroyBuffer(w->device, w->overlay, NULL);
    if (w->overlay_memory) vkFreeMemory(w->device, w->overlay_memory, NULL);
    w->readback = w->overlay = VK_NULL_HANDLE;
    w->readback_memory = w->overlay_memory = VK_NULL_HANDLE;
}

bool viewer_window_resize(viewer_window *w)
{
    vkDeviceWaitIdle(w->device); // the host's own device: waiting on it is ours to do
    destroy_swapchain(w);
    VkSurfaceCapabilitiesKHR caps;
    CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(w->physical_device, w->surface, &caps));
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if ((caps.supportedUsageFlags & usage) != usage) {
        fprintf(stderr, "%s: the surface does not support transfers to and from its images\n", viewer_window_program);
        return false;
    }
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(w->glfw, &fb_w, &fb_h);
    w->extent = caps.currentExtent;
    if (w->extent.width == UINT32_MAX) w->extent = (VkExtent2D){(uint32_t)fb_w, (uint32_t)fb_h};
    if (w->extent.width == 0 || w->extent.height == 0) return true; // minimised: nothing to draw
    VkSurfaceFormatKHR formats[64];
    uint32_t format_count = 64;
    vkGetPhysicalDeviceSurfaceFormatsKHR(w->physical_device, w->surface, &format_count, formats);
    const VkFormat preferred[] = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM,
                                  VK_FORMAT_R8G8B8A8_UNORM};
    VkSurfaceFormatKHR chosen = {.format = VK_FORMAT_UNDEFINED};
    for (size_t p = 0; p < 4 && chosen.format == VK_FORMAT_UNDEFINED; ++p)
        for (uint32_t i = 0; i < format_count; ++i)
            if (formats[i].format == preferred[p] && formats[i].colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
                chosen = formats[i];
    if (chosen.format == VK_FORMAT_UNDEFINED) {
        fprintf(stderr, "%s: the surface offers no 8-bit RGBA/BGRA format\n", viewer_window_program);
        return false;
    }
    w->format = chosen.format;
    uint32_t images = caps.minImageCount + 1;
    if (caps.maxImageCount && images > caps.maxImageCount) images = caps.maxImageCount;
    VkSwapchainCreateInfoKHR info = {.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR, .surface = w->surface,
        .minImageCount = images, .imageFormat = chosen.format, .imageColorSpace = chosen.colorSpace,
        .imageExtent = w->extent, .imageArrayLayers = 1, .imageUsage = usage,
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE, .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, .presentMode = VK_PRESENT_MODE_FIFO_KHR,
        .clipped = VK_TRUE};
    CHECK(vkCreateSwapchainKHR(w->device, &info, NULL, &w->swapchain));
    w->image_count = VIEWER_MAX_SWAPCHAIN_IMAGES;
    CHECK(vkGetSwapchainImagesKHR(w->device, w->swapchain, &w->image_count, w->images));
    for (uint32_t i = 0; i < w->image_count; ++i) {
        VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = w->images[i],
            .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = w->format,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
        CHECK(vkCreateImageView(w->device, &view, NULL, &w->views[i]));
    }
    VkDeviceSize bytes = (VkDeviceSize)w->extent.width * w->extent.height * 4;
    return create_host_buffer(w, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &w->readback, &w->readback_memory,
                              &w->readback_mapped) &&
           create_host_buffer(w, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &w->overlay, &w->overlay_memory,
                              &w->overlay_mapped);
}

static void on_glfw_error(int code, const char *message)
{
    fprintf(stderr, "%s: GLFW error %d: %s\n", viewer_window_program, code, message);
}

bool viewer_window_create(viewer_window *w, int width, int height, bool validation, bool sync_validation)
{
    memset(w, 0, sizeof *w);
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        fprintf(stderr, "%s: glfwInit failed (no display?)\n", viewer_window_program);
        return false;
    }
    if (!glfwVulkanSupported()) {
        fprintf(stderr, "%s: GLFW found no Vulkan loader\n", viewer_window_program);
        return false;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    w->glfw = glfwCreateWindow(width, height, viewer_window_program, NULL, NULL);
    if (!w->glfw) {
        fprintf(stderr, "%s: cannot create a %dx%d window\n", viewer_window_program, width, height);
        return false;
    }
    if (!create_instance(w, validation, sync_validation)) return false;
    CHECK(glfwCreateWindowSurface(w->instance, w->glfw, NULL, &w->surface));
    return create_device(w) && viewer_window_resize(w);
}

void viewer_window_destroy(viewer_window *w)
{
    if (w->device) {
        vkDeviceWaitIdle(w->device);
        destroy_swapchain(w);
        if (w->acquired) vkDestroySemaphore(w->device, w->acquired, NULL);
        if (w->rendered) vkDestroySemaphore(w->device, w->rendered, NULL);
        if (w->fence) vkDestroyFence(w->device, w->fence, NULL);
        if (w->pool) vkDestroyCommandPool(w->device, w->pool, NULL);
        if (w->ui_queries) vkDestroyQueryPool(w->device, w->ui_queries, NULL);
        vkDestroyDevice(w->device, NULL);
    }
    if (w->surface) vkDestroySurfaceKHR(w->instance, w->surface, NULL);
    sample_vk_destroy_instance(w->instance, w->messenger);
    if (w->glfw) glfwDestroyWindow(w->glfw);
    glfwTerminate();
    uint32_t messages = w->validation_messages;
    memset(w, 0, sizeof *w);
    w->validation_messages = messages;
}

static void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                          VkAccessFlags src_access, VkAccessFlags dst_access)
{
    VkImageMemoryBarrier barrier = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src_access,
        .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image, .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 0, NULL,
                         1, &barrier);
}

bool viewer_window_frame(viewer_window *w, viewer_record_fn record, viewer_record_fn ui, void *user, int split_x,
                         bool screenshot, bool *out_of_date)
{
    *out_of_date = false;
    if (!w->swapchain) return true;
    uint32_t index = 0;
    VkResult acquired = vkAcquireNextImageKHR(w->device, w->swapchain, UINT64_MAX, w->acquired, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        *out_of_date = true;
        return true;
    }
    if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR) {
        fprintf(stderr, "%s: vkAcquireNextImageKHR failed (VkResult %d)\n", viewer_window_program, acquired);
        return false;
    }
    CHECK(vkResetCommandPool(w->device, w->pool, 0));
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    CHECK(vkBeginCommandBuffer(w->cmd, &begin));
    VkImage image = w->images[index];
    if (!record(w->cmd, image, w->views[index], index, user)) return false;
    if (split_x >= 0 && (uint32_t)split_x < w->extent.width) {
        VkBufferImageCopy region = {.bufferOffset = (VkDeviceSize)split_x * 4, .bufferRowLength = w->extent.width,
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageOffset = {split_x, 0, 0},
            .imageExtent = {w->extent.width - (uint32_t)split_x, w->extent.height, 1}};
        vkCmdCopyBufferToImage(w->cmd, w->overlay, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }
    bool timed = ui && w->ui_queries;
    if (timed) {
        vkCmdResetQueryPool(w->cmd, w->ui_queries, 0, 2);
        vkCmdWriteTimestamp(w->cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, w->ui_queries, 0);
    }
    if (ui && !ui(w->cmd, image, w->views[index], index, user)) return false;
    if (timed) vkCmdWriteTimestamp(w->cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, w->ui_queries, 1);
    if (screenshot) {
        image_barrier(w->cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    .imageExtent = {w->extent.width, w->extent.height, 1}};
        vkCmdCopyImageToBuffer(w->cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->readback, 1, &region);
        VkBufferMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT, .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .buffer = w->readback, .size = VK_WHOLE_SIZE};
        vkCmdPipelineBarrier(w->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1,
                             &to_host, 0, NULL);
    }
    // Presentation needs no access mask: the semaphore makes the writes available.
    image_barrier(w->cmd, image, screenshot ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, screenshot ? 0 : VK_ACCESS_TRANSFER_WRITE_BIT, 0);
    CHECK(vkEndCommandBuffer(w->cmd));
    VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
    VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .waitSemaphoreCount = 1,
        .pWaitSemaphores = &w->acquired, .pWaitDstStageMask = &wait_stage, .commandBufferCount = 1,
        .pCommandBuffers = &w->cmd, .signalSemaphoreCount = 1, .pSignalSemaphores = &w->rendered};
    CHECK(vkResetFences(w->device, 1, &w->fence));
    CHECK(vkQueueSubmit(w->queue, 1, &submit, w->fence));
    VkPresentInfoKHR present = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .waitSemaphoreCount = 1,
        .pWaitSemaphores = &w->rendered, .swapchainCount = 1, .pSwapchains = &w->swapchain, .pImageIndices = &index};
    VkResult presented = vkQueuePresentKHR(w->queue, &present);
    CHECK(vkWaitForFences(w->device, 1, &w->fence, VK_TRUE, UINT64_MAX));
    // One frame in flight, and the present's semaphore wait finished before the next
    // acquire can return this semaphore's image: reuse is safe once the queue is idle.
    CHECK(vkQueueWaitIdle(w->queue));
    uint64_t ticks[2];
    w->ui_gpu_ms = 0.0;
    if (timed && vkGetQueryPoolResults(w->device, w->ui_queries, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                       VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
        w->ui_gpu_ms = (double)(ticks[1] - ticks[0]) * w->ns_per_tick * 1e-6;
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR)
        *out_of_date = true;
    else if (presented != VK_SUCCESS) {
        fprintf(stderr, "%s: vkQueuePresentKHR failed (VkResult %d)\n", viewer_window_program, presented);
        return false;
    }
    return true;
}

uint8_t *viewer_window_overlay(viewer_window *w) { return (uint8_t *)w->overlay_mapped; }

bool viewer_window_bgra(const viewer_window *w)
{
    return w->format == VK_FORMAT_B8G8R8A8_SRGB || w->format == VK_FORMAT_B8G8R8A8_UNORM;
}

bool viewer_window_write_screenshot(const viewer_window *w, const char *path)
{
    size_t n = (size_t)w->extent.width * w->extent.height;
    uint8_t *rgba = malloc(n * 4);
    if (!rgba) return false;
    const uint8_t *src = w->readback_mapped;
    bool bgra = viewer_window_bgra(w);
    for (size_t i = 0; i < n; ++i) {
        rgba[4 * i + 0] = src[4 * i + (bgra ? 2 : 0)];
        rgba[4 * i + 1] = src[4 * i + 1];
        rgba[4 * i + 2] = src[4 * i + (bgra ? 0 : 2)];
        rgba[4 * i + 3] = 255;
    }
    bool ok = stbi_write_png(path, (int)w->extent.width, (int)w->extent.height, 4, rgba, (int)w->extent.width * 4) != 0;
    free(rgba);
    if (!ok) fprintf(stderr, "%s: cannot write %s\n", viewer_window_program, path);
    return ok;
}
