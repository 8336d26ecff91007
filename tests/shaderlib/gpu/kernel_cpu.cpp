// rtpbr GPU test: the C++ build of the test kernel. Compiled once per model variant with the
// same flags as the variant's shaders, plus RTPBR_CPP_VARIANT (so that the inline library
// functions of different variants do not merge) and RTPBR_TEST_VARIANT (the entry point name).
#include "kernel.h"

#include "kernel_cpu.h"

#ifndef RTPBR_TEST_VARIANT
#error "define RTPBR_TEST_VARIANT (the variant name)"
#endif

#define RTPBR_TEST_STR2(x) #x
#define RTPBR_TEST_STR(x) RTPBR_TEST_STR2(x)
#define RTPBR_TEST_CAT2(a, b) a##b
#define RTPBR_TEST_CAT(a, b) RTPBR_TEST_CAT2(a, b)

namespace {

void eval_all(const float *in, uint32_t count, float *out) {
    for (uint32_t i = 0; i < count; i++) {
        const rtpbr::float4 a(in[8 * i + 0], in[8 * i + 1], in[8 * i + 2], in[8 * i + 3]);
        const rtpbr::float4 b(in[8 * i + 4], in[8 * i + 5], in[8 * i + 6], in[8 * i + 7]);
        for (uint32_t j = 0; j < RTPBR_TEST_OUTPUTS; j++)
            out[static_cast<size_t>(j) * count + i] = rtpbr::rtpbr_test_eval(a, b, j);
    }
}

const rtpbr_test_cpu_kernel kernel = {
    RTPBR_TEST_STR(RTPBR_TEST_VARIANT),
    RTPBR_TEST_OUTPUTS,
    rtpbr_test_output_names,
    eval_all,
};

} // namespace

extern "C" const rtpbr_test_cpu_kernel *RTPBR_TEST_CAT(rtpbr_test_cpu_, RTPBR_TEST_VARIANT)(void) {
    return &kernel;
}
