/* rtpbr tests: the messenger policy of tests/common (vk_host.h). Messages of each severity
 * are injected with vkSubmitDebugUtilsMessageEXT: VERBOSE and INFO never count, WARNING and
 * ERROR count whatever their type; a real validation error counts too. And a fresh instance
 * and device count nothing, even with no shader validation cache in $HOME (CI runs the tests
 * with an empty HOME). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "vk_host.h"

/* vk_host_init, which must succeed; the test is skipped where there is no Vulkan driver. */
static void init_or_skip(vk_host *h) {
    char error[256] = "";
    vk_host_result r = vk_host_init(h, NULL, error, sizeof error);
    if (r == VK_HOST_NO_DRIVER) {
        print_message("skipped: %s\n", error);
        vk_host_finish(h);
        skip();
    }
    if (r != VK_HOST_OK)
        print_error("vk_host_init: %s: %s\n", vk_host_result_string(r), error);
    assert_int_equal(r, VK_HOST_OK);
}

static void submit(vk_host *h, VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type) {
    PFN_vkSubmitDebugUtilsMessageEXT submit_message =
        (PFN_vkSubmitDebugUtilsMessageEXT)vkGetInstanceProcAddr(h->instance, "vkSubmitDebugUtilsMessageEXT");
    assert_non_null(submit_message);
    VkDebugUtilsMessengerCallbackDataEXT data = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CALLBACK_DATA_EXT,
        .pMessageIdName = "rtpbr-test-vk-host",
        .pMessage = "a message injected by test_vk_host (expected on stderr for WARNING and ERROR)",
    };
    submit_message(h->instance, severity, type, &data);
}

static void severities(void **state) {
    (void)state;
    vk_host h = {0};
    init_or_skip(&h);
    assert_int_equal(h.messages, 0); /* instance and device: nothing at WARNING or above */
    const VkDebugUtilsMessageTypeFlagsEXT types[] = {VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT,
                                                      VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
                                                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT};
    uint32_t expected = 0;
    for (size_t t = 0; t < sizeof types / sizeof types[0]; t++) {
        submit(&h, VK_DEBUG_UTILS_MESSAGE_SEVERITY_VERBOSE_BIT_EXT, types[t]);
        submit(&h, VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT, types[t]);
        assert_int_equal(h.messages, expected);
        submit(&h, VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT, types[t]);
        assert_int_equal(h.messages, ++expected);
        submit(&h, VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT, types[t]);
        assert_int_equal(h.messages, ++expected);
    }
    vk_host_finish(&h);
    assert_int_equal(h.messages, expected);
}

/* A buffer of size 0 breaks VUID-VkBufferCreateInfo-size-00912: the layer reports an ERROR. */
static void real_error_counts(void **state) {
    (void)state;
    vk_host h = {0};
    init_or_skip(&h);
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 0,
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    VkBuffer buffer = VK_NULL_HANDLE;
    print_message("expected on stderr: one validation error about a buffer of size 0\n");
    /* The layer may or may not pass the call down after reporting it; either way it reported. */
    if (vkCreateBuffer(h.device, &info, NULL, &buffer) == VK_SUCCESS && buffer != VK_NULL_HANDLE)
        vkDestroyBuffer(h.device, buffer, NULL);
    assert_true(h.messages >= 1);
    vk_host_finish(&h);
}

int main(void) {
    vk_host_keep_driver_libraries_loaded();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(severities),
        cmocka_unit_test(real_error_counts),
    };
    return cmocka_run_group_tests_name("vk_host", tests, NULL, NULL);
}
