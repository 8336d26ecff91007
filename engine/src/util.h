// Leaf helpers of the engine: host allocation and logging, Vulkan results turned into
// rtpbr_results with a message, 4x4 matrices. Nothing here knows the context, the scenes or
// the renderers; every other engine file may include this one.
#ifndef RTPBR_UTIL_H
#define RTPBR_UTIL_H

#include <stdarg.h>
#include <stdbool.h>

#include "rtpbr/rtpbr.h"

#if defined(__GNUC__)
#define RTPBR_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define RTPBR_PRINTF(f, a)
#endif

// The host's callbacks (rtpbr_context_desc): every allocation and every message goes through
// these. The context holds one; a zero one means malloc/free and stderr.
typedef struct rtpbr_host {
    rtpbr_allocator allocator;
    rtpbr_logger logger;
} rtpbr_host;

// Zeroed; on failure logs "out of host memory" with the size, so every caller's
// RTPBR_ERROR_OUT_OF_HOST_MEMORY has a message.
void *rtpbr_alloc(const rtpbr_host *host, size_t size);
void rtpbr_free(const rtpbr_host *host, void *ptr);
void rtpbr_log(const rtpbr_host *host, rtpbr_log_level level, const char *fmt, ...) RTPBR_PRINTF(3, 4);
void rtpbr_logv(const rtpbr_host *host, rtpbr_log_level level, const char *fmt, va_list args);
// Logs "<what> failed: <VkResult name>" and maps the VkResult to an rtpbr_result.
rtpbr_result rtpbr_vk_fail(const rtpbr_host *host, VkResult vr, const char *what);
const char *rtpbr_vk_result_name(VkResult vr);
// A public function's object argument (context, scene, renderer) is NULL: there is no host
// logger to reach, so the message goes to stderr (the default logger); returns
// RTPBR_ERROR_INVALID_ARGUMENT.
rtpbr_result rtpbr_null_object(const char *function, const char *object);

// The engine's one error idiom: a function that can fail declares `rtpbr_result result`,
// checks every call with these, and ends with a `cleanup:` label that releases what it made
// (destroy functions accept half-built objects). Every failure has been logged by the time it
// reaches cleanup: by rtpbr_vk_fail, by rtpbr_alloc, or by the callee that returned it.
// Checks a VkResult; `host` receives the message.
#define RTPBR_VK(host, call)                                  \
    do {                                                      \
        VkResult vr_ = (call);                                \
        if (vr_ != VK_SUCCESS) {                              \
            result = rtpbr_vk_fail((host), vr_, #call);       \
            goto cleanup;                                     \
        }                                                     \
    } while (0)
// Propagates an rtpbr_result (already logged by whoever produced it).
#define RTPBR_TRY(call)                                       \
    do {                                                      \
        result = (call);                                      \
        if (result != RTPBR_SUCCESS) goto cleanup;            \
    } while (0)
// Allocates zeroed memory into `ptr` (an lvalue), or fails with OUT_OF_HOST_MEMORY (logged
// by rtpbr_alloc).
#define RTPBR_ALLOC(host, ptr, size)                          \
    do {                                                      \
        (ptr) = rtpbr_alloc((host), (size));                  \
        if (!(ptr)) {                                         \
            result = RTPBR_ERROR_OUT_OF_HOST_MEMORY;          \
            goto cleanup;                                     \
        }                                                     \
    } while (0)
// Fails with `code` after logging the message (an ERROR).
#define RTPBR_FAIL(host, code, ...)                           \
    do {                                                      \
        rtpbr_log((host), RTPBR_LOG_ERROR, __VA_ARGS__);      \
        result = (code);                                      \
        goto cleanup;                                         \
    } while (0)

// ---------------------------------------------------------------------------------------------
// Math (math.c): column-major 4x4 matrices

void rtpbr_mat4_identity(float m[16]);
void rtpbr_mat4_mul(float out[16], const float a[16], const float b[16]);
bool rtpbr_mat4_invert(float out[16], const float m[16]);
// Whether the upper 3x3 has a negative determinant (the transform mirrors: windings flip).
bool rtpbr_mat4_mirrors(const float m[16]);
// Vulkan clip space (y down, depth 0..1), right-handed view looking down -Z.
void rtpbr_camera_matrices(const rtpbr_camera_desc *camera, float aspect, float view_proj[16]);
bool rtpbr_finite(const float *v, size_t n);

#endif // RTPBR_UTIL_H
