// rtpbr embedded in a host's Vulkan device: the smallest complete program. The "host" below
// creates its own instance and device (as a game engine already has), hands them to rtpbr,
// loads a glTF scene, renders one frame and writes it to a PNG.
//   usage: rtpbr-embed [SCENE.gltf [OUT.png [--validation]]]
// --validation: the host enables VK_LAYER_KHRONOS_validation; any message fails the run.
#include <rtpbr/rtpbr.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

enum { WIDTH = 640, HEIGHT = 480 };

typedef struct host {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkPhysicalDeviceVulkan13Features features13; // what the host enabled (rtpbr reads it)
    VkPhysicalDeviceFeatures2 features;
    unsigned validation_messages;
} host;

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT type, const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)type;
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        ((host *)user)->validation_messages++;
        fprintf(stderr, "validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

// Instance, the first device with Vulkan 1.3 and a graphics + compute queue, and a device with
// dynamicRendering enabled (rtpbr's one requirement). Returns 0 on success.
static int host_create(host *h, int validation)
{
    const char *layer = "VK_LAYER_KHRONOS_validation";
    const char *debug_ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation, .pUserData = h};
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "rtpbr-embed",
                             .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo instance_info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app,
        .pNext = validation ? &messenger_info : NULL,
        .enabledLayerCount = validation ? 1 : 0, .ppEnabledLayerNames = &layer,
        .enabledExtensionCount = validation ? 1 : 0, .ppEnabledExtensionNames = &debug_ext};
    if (vkCreateInstance(&instance_info, NULL, &h->instance) != VK_SUCCESS) {
        fprintf(stderr, "rtpbr-embed: no Vulkan 1.3 instance%s\n", validation ? " with validation" : "");
        return 1;
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create = (PFN_vkCreateDebugUtilsMessengerEXT)
            vkGetInstanceProcAddr(h->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create || create(h->instance, &messenger_info, NULL, &h->messenger) != VK_SUCCESS) return 1;
    }
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    vkEnumeratePhysicalDevices(h->instance, &count, devices);
    for (uint32_t i = 0; i < count && !h->physical_device; ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        if (props.apiVersion < VK_API_VERSION_1_3) continue;
        VkQueueFamilyProperties families[16];
        uint32_t family_count = 16;
        vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &family_count, families);
        for (uint32_t f = 0; f < family_count; ++f) {
            if ((families[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                h->physical_device = devices[i];
                h->queue_family = f;
                break;
            }
        }
    }
    if (!h->physical_device) {
        fprintf(stderr, "rtpbr-embed: no Vulkan 1.3 device with a graphics + compute queue\n");
        return 1;
    }
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = h->queue_family, .queueCount = 1, .pQueuePriorities = &priority};
    h->features13 = (VkPhysicalDeviceVulkan13Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, .dynamicRendering = VK_TRUE};
    h->features = (VkPhysicalDeviceFeatures2){.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                               .pNext = &h->features13};
    VkDeviceCreateInfo device_info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &h->features,
        .queueCreateInfoCount = 1, .pQueueCreateInfos = &queue_info};
    if (vkCreateDevice(h->physical_device, &device_info, NULL, &h->device) != VK_SUCCESS) {
        fprintf(stderr, "rtpbr-embed: vkCreateDevice failed\n");
        return 1;
    }
    vkGetDeviceQueue(h->device, h->queue_family, 0, &h->queue);
    return 0;
}

static void host_destroy(host *h)
{
    if (h->device) vkDestroyDevice(h->device, NULL);
    if (h->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)
            vkGetInstanceProcAddr(h->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(h->instance, h->messenger, NULL);
    }
    if (h->instance) vkDestroyInstance(h->instance, NULL);
}

static const char *const usage =
    "usage: rtpbr-embed [SCENE.gltf [OUT.png [--validation]]]\n"
    "rtpbr embedded in a host's own Vulkan instance and device: loads SCENE.gltf (default: the\n"
    "bundled quad_light scene), renders one 640 x 480 frame and writes it to OUT.png (default\n"
    "embed.png).\n"
    "  --validation  the host enables VK_LAYER_KHRONOS_validation; any message fails the run\n"
    "  -h, --help    this text\n";

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return fputs(usage, stdout), 0;
        if (i == 3 ? strcmp(argv[i], "--validation") != 0 : i > 3 || argv[i][0] == '-')
            return fputs(usage, stderr), 2;
    }
    const char *scene_path = argc > 1 ? argv[1] : RTPBR_EMBED_DEFAULT_SCENE;
    const char *out_path = argc > 2 ? argv[2] : "embed.png";
    int validation = argc > 3 && strcmp(argv[3], "--validation") == 0;
    host h = {0};
    rtpbr_context *ctx = NULL;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_renderer *renderer = NULL;
    uint8_t *pixels = NULL;
    int status = 1;
    rtpbr_result r = RTPBR_SUCCESS;
    if (host_create(&h, validation)) goto done;

    // Embedded mode: rtpbr uses the host's device and queue, creates only its own objects.
    rtpbr_context_desc desc = {.embedded = {.instance = h.instance, .physical_device = h.physical_device,
        .device = h.device, .queue = h.queue, .queue_family_index = h.queue_family,
        .enabled_features = &h.features}};
    if ((r = rtpbr_context_create(&desc, &ctx)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_gpu_scene_load_gltf(ctx, scene_path, &scene)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = WIDTH, .height = HEIGHT},
                                   &renderer)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_render(renderer, scene, &(rtpbr_render_desc){0})) != RTPBR_SUCCESS) goto done;
    pixels = malloc((size_t)WIDTH * HEIGHT * 4);
    if (!pixels) goto done;
    if ((r = rtpbr_read_display(renderer, pixels, (size_t)WIDTH * HEIGHT * 4)) != RTPBR_SUCCESS) goto done;
    if (!stbi_write_png(out_path, WIDTH, HEIGHT, 4, pixels, WIDTH * 4)) {
        fprintf(stderr, "rtpbr-embed: cannot write %s\n", out_path);
        goto done;
    }
    printf("rtpbr-embed: wrote %s (%dx%d) on %s\n", out_path, WIDTH, HEIGHT, rtpbr_context_device_name(ctx));
    status = 0;
done:
    if (r != RTPBR_SUCCESS) fprintf(stderr, "rtpbr-embed: %s\n", rtpbr_result_string(r));
    free(pixels);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    host_destroy(&h);
    if (h.validation_messages) {
        fprintf(stderr, "rtpbr-embed: %u validation message(s)\n", h.validation_messages);
        status = 1;
    }
    return status;
}
