// RADV's null device and pipeline statistics (see null_device.h).
#define _POSIX_C_SOURCE 200809L

#include "null_device.h"

#include <ctype.h>
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

#include "spirv_reflect.h"
#include "vk_host.h"

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"
#define MAX_SETS 8

#define SS_DRIVER_NAME(id, driver_name, column, key) driver_name,
#define SS_COLUMN(id, driver_name, column, key) column,
#define SS_KEY(id, driver_name, column, key) key,
const char *const ss_statistic_driver_names[SS_STAT_COUNT] = {SS_STATISTICS(SS_DRIVER_NAME)};
const char *const ss_statistic_columns[SS_STAT_COUNT] = {SS_STATISTICS(SS_COLUMN)};
const char *const ss_statistic_keys[SS_STAT_COUNT] = {SS_STATISTICS(SS_KEY)};

struct ss_device {
    vk_host host; // the instance and its validation messenger (tests/common); the device is ours
    VkPhysicalDevice physical_device;
    VkDevice device;
    PFN_vkGetPipelineExecutablePropertiesKHR get_executables;
    PFN_vkGetPipelineExecutableStatisticsKHR get_statistics;
    char name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];
    char driver_info[VK_MAX_DRIVER_INFO_SIZE];
};

static void set_error(char *error, size_t error_size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, error_size, format, args);
    va_end(args);
}

// Whether a Vulkan call (named `call`) succeeded; if not, the error says so.
static bool succeeded(VkResult vr, const char *call, char *error, size_t error_size)
{
    if (vr != VK_SUCCESS) set_error(error, error_size, "%s failed (VkResult %d)", call, (int)vr);
    return vr == VK_SUCCESS;
}

// The chip names RADV_FORCE_FAMILY accepts (Mesa 22.3, ac_gpu_info.c's family names, in any
// case); RADV abort()s on any other, so the name is checked before it reaches the driver.
static const char *const known_families[] = {
    "tahiti", "pitcairn", "verde", "oland", "hainan", "bonaire", "kabini", "kaveri", "hawaii", "tonga", "iceland",
    "carrizo", "fiji", "stoney", "polaris10", "polaris11", "polaris12", "vegam", "vega10", "vega12", "vega20",
    "raven", "raven2", "renoir", "arcturus", "aldebaran", "navi10", "navi12", "navi14", "navi21", "navi22",
    "navi23", "navi24", "vangogh", "rembrandt", "gfx1036", "gfx1100", "gfx1101", "gfx1102", "gfx1103",
};

static bool known_family(const char *family)
{
    for (size_t i = 0; i < sizeof known_families / sizeof *known_families; ++i) {
        const char *a = family, *b = known_families[i];
        while (*a && tolower((unsigned char)*a) == *b) ++a, ++b;
        if (*a == '\0' && *b == '\0') return true;
    }
    return false;
}

static bool has_validation_layer(void)
{
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, NULL) != VK_SUCCESS || count == 0) return false;
    VkLayerProperties *layers = calloc(count, sizeof *layers);
    if (!layers) return false;
    bool found = false;
    if (vkEnumerateInstanceLayerProperties(&count, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !found; ++i) found = strcmp(layers[i].layerName, VALIDATION_LAYER) == 0;
    free(layers);
    return found;
}

static bool contains_ignoring_case(const char *haystack, const char *needle)
{
    size_t n = strlen(needle);
    for (; *haystack; ++haystack) {
        size_t i = 0;
        while (i < n && haystack[i] && tolower((unsigned char)haystack[i]) == tolower((unsigned char)needle[i])) ++i;
        if (i == n) return true;
    }
    return false;
}

static ss_open_result create_instance(ss_device *d, bool validation, char *error, size_t error_size)
{
    const vk_host_desc desc = {.app_name = "rtpbr-shader-stats", .api_version = VK_API_VERSION_1_3,
                               .without_validation = !validation};
    switch (vk_host_init_instance(&d->host, &desc, error, error_size)) {
    case VK_HOST_OK: return SS_OPEN_OK;
    case VK_HOST_NO_DRIVER: return SS_OPEN_UNAVAILABLE;
    default: return SS_OPEN_FAILED;
    }
}

// The RADV device of the family, told apart from llvmpipe and any real GPU by driver id and name.
static ss_open_result choose_device(ss_device *d, const char *family, char *error, size_t error_size)
{
    uint32_t count = 0;
    VkResult vr = vkEnumeratePhysicalDevices(d->host.instance, &count, NULL);
    VkPhysicalDevice *devices = count ? calloc(count, sizeof *devices) : NULL;
    if (vr == VK_SUCCESS && devices) vr = vkEnumeratePhysicalDevices(d->host.instance, &count, devices);
    bool radv_seen = false;
    char other[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE] = "";
    for (uint32_t i = 0; devices && vr >= VK_SUCCESS && i < count; ++i) {
        VkPhysicalDeviceDriverProperties driver = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
        vkGetPhysicalDeviceProperties2(devices[i], &props);
        if (driver.driverID != VK_DRIVER_ID_MESA_RADV) continue;
        radv_seen = true;
        const char *name = props.properties.deviceName;
        if (!strstr(name, "Null hardware") || !contains_ignoring_case(name, family)) {
            snprintf(other, sizeof other, "%s", name);
            continue;
        }
        if (props.properties.apiVersion < VK_API_VERSION_1_3) {
            set_error(error, error_size, "%s supports Vulkan %u.%u; 1.3 is needed (dynamic rendering)", name,
                      VK_API_VERSION_MAJOR(props.properties.apiVersion), VK_API_VERSION_MINOR(props.properties.apiVersion));
            free(devices);
            return SS_OPEN_UNAVAILABLE;
        }
        d->physical_device = devices[i];
        snprintf(d->name, sizeof d->name, "%s", name);
        snprintf(d->driver_info, sizeof d->driver_info, "%s", driver.driverInfo);
    }
    free(devices);
    if (d->physical_device) return SS_OPEN_OK;
    if (radv_seen)
        set_error(error, error_size, "RADV lists \"%s\" but no null device for family %s (unknown to this Mesa?)", other,
                  family);
    else
        set_error(error, error_size, "no RADV device (Mesa's radeon Vulkan driver, package mesa-vulkan-drivers) for family %s",
                  family);
    return SS_OPEN_UNAVAILABLE;
}

static ss_open_result create_device(ss_device *d, char *error, size_t error_size)
{
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_info = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
    };
    VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                            .pNext = &executable_info};
    VkPhysicalDeviceFeatures2 supported = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f13};
    vkGetPhysicalDeviceFeatures2(d->physical_device, &supported);
    if (!executable_info.pipelineExecutableInfo || !f13.dynamicRendering) {
        set_error(error, error_size, "%s lacks pipelineExecutableInfo or dynamicRendering", d->name);
        return SS_OPEN_UNAVAILABLE;
    }
    // The ray-query shadow trace (shadow_ray_query_comp: engine/src/device.c enables these where
    // it traces with ray queries). Enabling them leaves the other pipelines' statistics as they
    // were (measured, Mesa 22.3.6, navi21 and gfx1100: lighting basic, full and tubes, cull,
    // resolve, the shadow list and denoiser, every figure the same).
    VkPhysicalDeviceRayQueryFeaturesKHR rq_supported = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as_supported = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &rq_supported};
    VkPhysicalDeviceVulkan12Features f12_supported = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                                      .pNext = &as_supported};
    VkPhysicalDeviceFeatures2 supported2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12_supported};
    vkGetPhysicalDeviceFeatures2(d->physical_device, &supported2);
    const bool ray_query =
        rq_supported.rayQuery && as_supported.accelerationStructure && f12_supported.bufferDeviceAddress;
    VkPhysicalDeviceRayQueryFeaturesKHR enable_rq = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR,
                                                     .rayQuery = VK_TRUE};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR enable_as = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &enable_rq,
        .accelerationStructure = VK_TRUE};
    VkPhysicalDeviceVulkan12Features enable12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                                 .pNext = &enable_as, .bufferDeviceAddress = VK_TRUE};
    // The features the engine enables (engine/src/device.c: dynamic rendering) and the
    // statistics; nothing else, since features such as robustBufferAccess change the code.
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR enable_info = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
        .pipelineExecutableInfo = VK_TRUE,
    };
    VkPhysicalDeviceVulkan13Features enable13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                                 .pNext = &enable_info,
                                                 .dynamicRendering = VK_TRUE};
    enable_info.pNext = ray_query ? &enable12 : NULL;
    VkPhysicalDeviceFeatures2 enable = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &enable13};
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = 0,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    const char *extensions[] = {VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &enable,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = ray_query ? 4 : 1,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateDevice(d->physical_device, &info, NULL, &d->device);
    if (vr != VK_SUCCESS) {
        set_error(error, error_size, "vkCreateDevice on %s failed (VkResult %d)", d->name, (int)vr);
        return SS_OPEN_FAILED;
    }
    d->get_executables =
        (PFN_vkGetPipelineExecutablePropertiesKHR)vkGetDeviceProcAddr(d->device, "vkGetPipelineExecutablePropertiesKHR");
    d->get_statistics =
        (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(d->device, "vkGetPipelineExecutableStatisticsKHR");
    if (!d->get_executables || !d->get_statistics) {
        set_error(error, error_size, "%s: VK_KHR_pipeline_executable_properties entry points missing", d->name);
        return SS_OPEN_FAILED;
    }
    return SS_OPEN_OK;
}

// lavapipe (which the loader initialises too) leaves static state allocated when the loader
// unloads it at vkDestroyInstance, a leak per instance for LeakSanitizer; the validation
// layer's frames would lose their names. Loaded once more here, both stay until exit.
static void keep_driver_libraries_loaded(void)
{
    static bool done = false;
    static const char *const libraries[] = {"libvulkan_lvp.so", "libvulkan_radeon.so", "libVkLayer_khronos_validation.so"};
    for (size_t i = 0; i < sizeof libraries / sizeof *libraries && !done; ++i)
        (void)dlopen(libraries[i], RTLD_NOW | RTLD_LOCAL); // absent: nothing to keep
    done = true;
}

ss_open_result ss_device_create(const char *family, bool validation, ss_device **out, char *error, size_t error_size)
{
    *out = NULL;
    if (!family || !known_family(family)) {
        set_error(error, error_size, "unknown chip family \"%s\" (RADV_FORCE_FAMILY names: navi21, gfx1100, vega10, ...)",
                  family ? family : "");
        return SS_OPEN_FAILED;
    }
    if (setenv("RADV_FORCE_FAMILY", family, 1) != 0 || setenv("MESA_SHADER_CACHE_DISABLE", "true", 0) != 0) {
        set_error(error, error_size, "setenv failed");
        return SS_OPEN_FAILED;
    }
    keep_driver_libraries_loaded();
    ss_device *d = calloc(1, sizeof *d);
    if (!d) {
        set_error(error, error_size, "out of memory");
        return SS_OPEN_FAILED;
    }
    ss_open_result result = create_instance(d, validation && has_validation_layer(), error, error_size);
    if (result == SS_OPEN_OK) result = choose_device(d, family, error, error_size);
    if (result == SS_OPEN_OK) result = create_device(d, error, error_size);
    if (result == SS_OPEN_OK && d->host.messages > 0) {
        set_error(error, error_size, "validation messages while opening %s", d->name);
        result = SS_OPEN_FAILED;
    }
    if (result != SS_OPEN_OK) {
        ss_device_destroy(d);
        return result;
    }
    *out = d;
    return SS_OPEN_OK;
}

void ss_device_destroy(ss_device *d)
{
    if (!d) return;
    if (d->device) vkDestroyDevice(d->device, NULL);
    vk_host_finish(&d->host);
    free(d);
}

const char *ss_device_name(const ss_device *d) { return d->name; }
const char *ss_device_driver_info(const ss_device *d) { return d->driver_info; }
bool ss_device_validating(const ss_device *d) { return d->host.messenger != VK_NULL_HANDLE; }

// ---- pipelines ----------------------------------------------------------------------------

// Everything one compilation creates; destroy_objects accepts a half-built one.
typedef struct pipeline_objects {
    VkShaderModule modules[2];
    VkDescriptorSetLayout set_layouts[MAX_SETS];
    VkPipelineLayout layout;
    VkPipeline pipeline;
} pipeline_objects;

static void destroy_objects(VkDevice device, pipeline_objects *o)
{
    if (o->pipeline) vkDestroyPipeline(device, o->pipeline, NULL);
    if (o->layout) vkDestroyPipelineLayout(device, o->layout, NULL);
    for (int i = 0; i < MAX_SETS; ++i)
        if (o->set_layouts[i]) vkDestroyDescriptorSetLayout(device, o->set_layouts[i], NULL);
    for (int i = 0; i < 2; ++i)
        if (o->modules[i]) vkDestroyShaderModule(device, o->modules[i], NULL);
}

// The union of the stages' bindings, as set layouts and one pipeline layout.
static bool create_layout(ss_device *d, const ss_reflection *refl, uint32_t count, pipeline_objects *o, char *error,
                          size_t error_size)
{
    VkDescriptorSetLayoutBinding bindings[MAX_SETS][SS_MAX_BINDINGS];
    uint32_t binding_counts[MAX_SETS] = {0};
    uint32_t set_count = 0, push_size = 0;
    VkShaderStageFlags push_stages = 0;
    for (uint32_t s = 0; s < count; ++s) {
        if (refl[s].push_constant_size) {
            push_stages |= refl[s].stage;
            if (refl[s].push_constant_size > push_size) push_size = refl[s].push_constant_size;
        }
        for (uint32_t i = 0; i < refl[s].binding_count; ++i) {
            const ss_binding *b = &refl[s].bindings[i];
            if (b->set >= MAX_SETS) {
                set_error(error, error_size, "descriptor set %u: at most %d sets are supported", b->set, MAX_SETS);
                return false;
            }
            VkDescriptorSetLayoutBinding *list = bindings[b->set];
            uint32_t j = 0;
            while (j < binding_counts[b->set] && list[j].binding != b->binding) ++j;
            if (j == binding_counts[b->set]) {
                if (j == SS_MAX_BINDINGS) {
                    set_error(error, error_size, "set %u: more than %d bindings", b->set, SS_MAX_BINDINGS);
                    return false;
                }
                list[j] = (VkDescriptorSetLayoutBinding){b->binding, b->type, b->count, 0, NULL};
                binding_counts[b->set]++;
            } else if (list[j].descriptorType != b->type || list[j].descriptorCount != b->count) {
                set_error(error, error_size, "set %u binding %u differs between stages", b->set, b->binding);
                return false;
            }
            list[j].stageFlags |= refl[s].stage;
            if (b->set + 1 > set_count) set_count = b->set + 1;
        }
    }
    for (uint32_t set = 0; set < set_count; ++set) {
        VkDescriptorSetLayoutCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
            .bindingCount = binding_counts[set],
            .pBindings = bindings[set],
        };
        if (!succeeded(vkCreateDescriptorSetLayout(d->device, &info, NULL, &o->set_layouts[set]),
                       "vkCreateDescriptorSetLayout", error, error_size))
            return false;
    }
    VkPushConstantRange push = {push_stages, 0, push_size};
    VkPipelineLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = set_count,
        .pSetLayouts = o->set_layouts,
        .pushConstantRangeCount = push_size ? 1 : 0,
        .pPushConstantRanges = &push,
    };
    return succeeded(vkCreatePipelineLayout(d->device, &info, NULL, &o->layout), "vkCreatePipelineLayout", error,
                     error_size);
}

static VkFormat vertex_format(const ss_location *loc)
{
    static const VkFormat f[] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R32G32B32_SFLOAT,
                                 VK_FORMAT_R32G32B32A32_SFLOAT};
    static const VkFormat i[] = {VK_FORMAT_R32_SINT, VK_FORMAT_R32G32_SINT, VK_FORMAT_R32G32B32_SINT,
                                 VK_FORMAT_R32G32B32A32_SINT};
    static const VkFormat u[] = {VK_FORMAT_R32_UINT, VK_FORMAT_R32G32_UINT, VK_FORMAT_R32G32B32_UINT,
                                 VK_FORMAT_R32G32B32A32_UINT};
    const VkFormat *table = loc->base == 'f' ? f : loc->base == 'i' ? i : u;
    return table[loc->components - 1];
}

static VkFormat color_format(const ss_location *loc)
{
    return loc->base == 'f' ? VK_FORMAT_R16G16B16A16_SFLOAT
           : loc->base == 'i' ? VK_FORMAT_R32G32B32A32_SINT
                              : VK_FORMAT_R32G32B32A32_UINT;
}

static bool create_graphics(ss_device *d, const ss_reflection *vs, const ss_reflection *fs, pipeline_objects *o,
                            VkShaderModule vs_module, VkShaderModule fs_module, char *error, size_t error_size)
{
    VkVertexInputBindingDescription bindings[SS_MAX_LOCATIONS];
    VkVertexInputAttributeDescription attributes[SS_MAX_LOCATIONS];
    for (uint32_t i = 0; i < vs->input_count; ++i) {
        const ss_location *in = &vs->inputs[i];
        bindings[i] = (VkVertexInputBindingDescription){i, in->components * 4u, VK_VERTEX_INPUT_RATE_VERTEX};
        attributes[i] = (VkVertexInputAttributeDescription){in->location, i, vertex_format(in), 0};
    }
    VkFormat formats[SS_MAX_LOCATIONS];
    VkPipelineColorBlendAttachmentState blend[SS_MAX_LOCATIONS];
    uint32_t attachment_count = 0;
    for (uint32_t i = 0; i < SS_MAX_LOCATIONS; ++i) {
        formats[i] = VK_FORMAT_UNDEFINED;
        blend[i] = (VkPipelineColorBlendAttachmentState){.colorWriteMask = 0};
    }
    for (uint32_t i = 0; i < fs->output_count; ++i) {
        const ss_location *out = &fs->outputs[i];
        if (out->location >= SS_MAX_LOCATIONS) {
            set_error(error, error_size, "fragment output location %u: at most %d attachments", out->location,
                      SS_MAX_LOCATIONS);
            return false;
        }
        formats[out->location] = color_format(out);
        blend[out->location].colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                              VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        if (out->location + 1 > attachment_count) attachment_count = out->location + 1;
    }
    bool depth = vs->input_count > 0; // geometry passes test depth, full-screen passes do not
    VkPipelineRenderingCreateInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = attachment_count,
        .pColorAttachmentFormats = formats,
        .depthAttachmentFormat = depth ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_UNDEFINED,
    };
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vs_module, .pName = vs->entry_point},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = fs_module, .pName = fs->entry_point},
    };
    VkPipelineVertexInputStateCreateInfo vertex_input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = vs->input_count,
        .pVertexBindingDescriptions = bindings,
        .vertexAttributeDescriptionCount = vs->input_count,
        .pVertexAttributeDescriptions = attributes,
    };
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
    };
    VkPipelineViewportStateCreateInfo viewport = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1,
        .scissorCount = 1,
    };
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = VK_CULL_MODE_NONE,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT,
    };
    VkPipelineDepthStencilStateCreateInfo depth_state = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = depth,
        .depthWriteEnable = depth,
        .depthCompareOp = VK_COMPARE_OP_LESS,
    };
    VkPipelineColorBlendStateCreateInfo blend_state = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = attachment_count,
        .pAttachments = blend,
    };
    VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = 2,
        .pDynamicStates = dynamic_states,
    };
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &rendering,
        .flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR,
        .stageCount = 2,
        .pStages = stages,
        .pVertexInputState = &vertex_input,
        .pInputAssemblyState = &assembly,
        .pViewportState = &viewport,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pDepthStencilState = depth ? &depth_state : NULL,
        .pColorBlendState = &blend_state,
        .pDynamicState = &dynamic,
        .layout = o->layout,
    };
    return succeeded(vkCreateGraphicsPipelines(d->device, VK_NULL_HANDLE, 1, &info, NULL, &o->pipeline),
                     "vkCreateGraphicsPipelines", error, error_size);
}

static bool create_compute(ss_device *d, const ss_reflection *cs, VkShaderModule module, pipeline_objects *o,
                           char *error, size_t error_size)
{
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module, .pName = cs->entry_point},
        .layout = o->layout,
    };
    return succeeded(vkCreateComputePipelines(d->device, VK_NULL_HANDLE, 1, &info, NULL, &o->pipeline),
                     "vkCreateComputePipelines", error, error_size);
}

static bool read_statistics(ss_device *d, VkPipeline pipeline, ss_pipeline_stats *out, char *error, size_t error_size)
{
    VkPipelineInfoKHR pipeline_info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = pipeline};
    VkPipelineExecutablePropertiesKHR executables[SS_MAX_EXECUTABLES];
    for (uint32_t i = 0; i < SS_MAX_EXECUTABLES; ++i)
        executables[i] = (VkPipelineExecutablePropertiesKHR){.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR};
    uint32_t count = SS_MAX_EXECUTABLES;
    VkResult vr = d->get_executables(d->device, &pipeline_info, &count, executables);
    if (vr != VK_SUCCESS) {
        set_error(error, error_size, "vkGetPipelineExecutablePropertiesKHR: VkResult %d", (int)vr);
        return false;
    }
    out->executable_count = count;
    for (uint32_t e = 0; e < count; ++e) {
        ss_executable *x = &out->executables[e];
        // The driver's name, cut to our field (executable names are short: "Compute Shader").
        size_t length = strnlen(executables[e].name, sizeof x->name - 1);
        memcpy(x->name, executables[e].name, length);
        x->name[length] = '\0';
        x->subgroup_size = executables[e].subgroupSize;
        VkPipelineExecutableInfoKHR info = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, .pipeline = pipeline, .executableIndex = e};
        uint32_t stat_count = 0;
        vr = d->get_statistics(d->device, &info, &stat_count, NULL);
        VkPipelineExecutableStatisticKHR *stats = stat_count ? calloc(stat_count, sizeof *stats) : NULL;
        if (vr != VK_SUCCESS || (stat_count && !stats)) {
            free(stats);
            set_error(error, error_size, "vkGetPipelineExecutableStatisticsKHR: VkResult %d", (int)vr);
            return false;
        }
        for (uint32_t i = 0; i < stat_count; ++i) stats[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
        vr = d->get_statistics(d->device, &info, &stat_count, stats);
        for (uint32_t i = 0; vr == VK_SUCCESS && i < stat_count; ++i) {
            for (int k = 0; k < SS_STAT_COUNT; ++k) {
                if (strcmp(stats[i].name, ss_statistic_driver_names[k]) != 0) continue;
                double v;
                switch (stats[i].format) {
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: v = stats[i].value.b32; break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: v = (double)stats[i].value.i64; break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: v = (double)stats[i].value.u64; break;
                default: v = stats[i].value.f64; break;
                }
                x->has[k] = true;
                x->value[k] = v;
            }
        }
        free(stats);
        if (vr != VK_SUCCESS) {
            set_error(error, error_size, "vkGetPipelineExecutableStatisticsKHR: VkResult %d", (int)vr);
            return false;
        }
    }
    return true;
}

bool ss_device_compile(ss_device *d, const ss_shader *shaders, uint32_t shader_count, ss_pipeline_stats *out,
                       char *error, size_t error_size)
{
    memset(out, 0, sizeof *out);
    if (shader_count < 1 || shader_count > 2) {
        set_error(error, error_size, "a pipeline has one compute or two graphics shaders, not %u", shader_count);
        return false;
    }
    uint32_t messages_before = d->host.messages;
    pipeline_objects o = {0};
    ss_reflection refl[2];
    const ss_reflection *vs = NULL, *fs = NULL, *cs = NULL;
    VkShaderModule vs_module = VK_NULL_HANDLE, fs_module = VK_NULL_HANDLE, cs_module = VK_NULL_HANDLE;
    bool ok = true;
    for (uint32_t s = 0; ok && s < shader_count; ++s) {
        char why[256];
        if (!ss_reflect(shaders[s].words, shaders[s].word_count, &refl[s], why, sizeof why)) {
            set_error(error, error_size, "%s: %s", shaders[s].name, why);
            ok = false;
            break;
        }
        VkShaderModuleCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
            .codeSize = shaders[s].word_count * sizeof(uint32_t),
            .pCode = shaders[s].words,
        };
        VkResult vr = vkCreateShaderModule(d->device, &info, NULL, &o.modules[s]);
        if (vr != VK_SUCCESS) {
            set_error(error, error_size, "%s: vkCreateShaderModule failed (VkResult %d)", shaders[s].name, (int)vr);
            ok = false;
            break;
        }
        switch (refl[s].stage) {
        case VK_SHADER_STAGE_VERTEX_BIT: vs = &refl[s]; vs_module = o.modules[s]; break;
        case VK_SHADER_STAGE_FRAGMENT_BIT: fs = &refl[s]; fs_module = o.modules[s]; break;
        case VK_SHADER_STAGE_COMPUTE_BIT: cs = &refl[s]; cs_module = o.modules[s]; break;
        default:
            set_error(error, error_size, "%s: only vertex, fragment and compute shaders are supported", shaders[s].name);
            ok = false;
            break;
        }
    }
    if (ok && !(shader_count == 1 && cs) && !(shader_count == 2 && vs && fs)) {
        set_error(error, error_size, "%s: a pipeline is one compute shader or a vertex and a fragment shader",
                  shaders[0].name);
        ok = false;
    }
    ok = ok && create_layout(d, refl, shader_count, &o, error, error_size);
    if (ok) ok = cs ? create_compute(d, cs, cs_module, &o, error, error_size)
                    : create_graphics(d, vs, fs, &o, vs_module, fs_module, error, error_size);
    ok = ok && read_statistics(d, o.pipeline, out, error, error_size);
    destroy_objects(d->device, &o);
    if (ok && d->host.messages != messages_before) {
        set_error(error, error_size, "%s: %u validation message(s)", shaders[0].name,
                  d->host.messages - messages_before);
        ok = false;
    }
    return ok;
}
