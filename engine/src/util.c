// Leaf helpers: versions and result names, host allocation and logging, VkResult names.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util.h"

uint32_t rtpbr_version(void)
{
    return RTPBR_VERSION;
}

const char *rtpbr_result_string(rtpbr_result result)
{
    switch (result) {
    case RTPBR_SUCCESS: return "success";
    case RTPBR_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTPBR_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case RTPBR_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory";
    case RTPBR_ERROR_NO_DEVICE: return "no suitable Vulkan device";
    case RTPBR_ERROR_MISSING_FEATURE: return "missing Vulkan feature";
    case RTPBR_ERROR_LIMIT_EXCEEDED: return "limit exceeded";
    case RTPBR_ERROR_SCENE_LOAD: return "scene could not be loaded";
    case RTPBR_ERROR_IO: return "input/output error";
    case RTPBR_ERROR_DEVICE_LOST: return "Vulkan device lost";
    case RTPBR_ERROR_VULKAN: return "Vulkan error";
    }
    return "unknown result";
}

void *rtpbr_alloc(const rtpbr_host *host, size_t size)
{
    void *p = host->allocator.alloc ? host->allocator.alloc(size, host->allocator.user_data) : malloc(size);
    if (p) memset(p, 0, size);
    else rtpbr_log(host, RTPBR_LOG_ERROR, "out of host memory: an allocation of %zu bytes failed", size);
    return p;
}

void rtpbr_free(const rtpbr_host *host, void *ptr)
{
    if (!ptr) return;
    if (host->allocator.free) host->allocator.free(ptr, host->allocator.user_data);
    else free(ptr);
}

void rtpbr_logv(const rtpbr_host *host, rtpbr_log_level level, const char *fmt, va_list args)
{
    const rtpbr_logger *logger = &host->logger;
    char message[1024];
    vsnprintf(message, sizeof message, fmt, args);
    if (logger->func) logger->func(level, message, logger->user_data);
    else if (level <= RTPBR_LOG_WARNING)
        fprintf(stderr, "rtpbr: %s: %s\n", level == RTPBR_LOG_ERROR ? "error" : "warning", message);
}

void rtpbr_log(const rtpbr_host *host, rtpbr_log_level level, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    rtpbr_logv(host, level, fmt, args);
    va_end(args);
}

const char *rtpbr_vk_result_name(VkResult vr)
{
    switch (vr) {
#define NAME(x) case x: return #x;
    NAME(VK_SUCCESS) NAME(VK_NOT_READY) NAME(VK_TIMEOUT) NAME(VK_INCOMPLETE)
    NAME(VK_ERROR_OUT_OF_HOST_MEMORY) NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    NAME(VK_ERROR_INITIALIZATION_FAILED) NAME(VK_ERROR_DEVICE_LOST)
    NAME(VK_ERROR_MEMORY_MAP_FAILED) NAME(VK_ERROR_LAYER_NOT_PRESENT)
    NAME(VK_ERROR_EXTENSION_NOT_PRESENT) NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    NAME(VK_ERROR_INCOMPATIBLE_DRIVER) NAME(VK_ERROR_TOO_MANY_OBJECTS)
    NAME(VK_ERROR_FORMAT_NOT_SUPPORTED) NAME(VK_ERROR_FRAGMENTED_POOL)
    NAME(VK_ERROR_OUT_OF_POOL_MEMORY) NAME(VK_ERROR_UNKNOWN)
#undef NAME
    default: return "VkResult (unnamed)";
    }
}

rtpbr_result rtpbr_vk_fail(const rtpbr_host *host, VkResult vr, const char *what)
{
    rtpbr_log(host, RTPBR_LOG_ERROR, "%s failed: %s (%d)", what, rtpbr_vk_result_name(vr), (int)vr);
    switch (vr) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return RTPBR_ERROR_OUT_OF_DEVICE_MEMORY;
    case VK_ERROR_DEVICE_LOST: return RTPBR_ERROR_DEVICE_LOST;
    case VK_ERROR_INCOMPATIBLE_DRIVER: return RTPBR_ERROR_NO_DEVICE;
    case VK_ERROR_LAYER_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return RTPBR_ERROR_MISSING_FEATURE;
    default: return RTPBR_ERROR_VULKAN;
    }
}

rtpbr_result rtpbr_null_object(const char *function, const char *object)
{
    rtpbr_log(&(rtpbr_host){0}, RTPBR_LOG_ERROR, "%s: %s is NULL", function, object);
    return RTPBR_ERROR_INVALID_ARGUMENT;
}
