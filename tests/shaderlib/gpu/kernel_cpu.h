/* rtpbr GPU test: the C++ build of kernel.h, one compilation per model variant
 * (kernel_cpu.cpp with RTPBR_TEST_VARIANT), callable from C. */
#ifndef RTPBR_TEST_KERNEL_CPU_H
#define RTPBR_TEST_KERNEL_CPU_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rtpbr_test_cpu_kernel {
    const char *variant;      /* the variant's name (meson.build) */
    uint32_t outputs;         /* RTPBR_TEST_OUTPUTS */
    const char *const *names; /* outputs names, one per output index */
    /* out[j * count + i] = rtpbr_test_eval(in[2 i], in[2 i + 1], j) for every i < count and
     * every output j: the layout of the compute shaders. */
    void (*eval)(const float *in, uint32_t count, float *out);
} rtpbr_test_cpu_kernel;

#define RTPBR_TEST_DECLARE_VARIANT(v) const rtpbr_test_cpu_kernel *rtpbr_test_cpu_##v(void);
RTPBR_TEST_DECLARE_VARIANT(ggx_hc_schlick)
RTPBR_TEST_DECLARE_VARIANT(beckmann_sep_conductor)
RTPBR_TEST_DECLARE_VARIANT(gtr_fast_dielectric)
#undef RTPBR_TEST_DECLARE_VARIANT

#ifdef __cplusplus
}
#endif

#endif /* RTPBR_TEST_KERNEL_CPU_H */
