// The viewer's split view, checked against the engine's own images: rtpbr-render writes the
// reference (linear EXR, Beckmann) and two tone-mapped PNGs of the same view (GGX, Beckmann);
// the viewer, in its default GGX mode with --reference, must show the GGX picture left of the
// split and the Beckmann reference, tone-mapped by the viewer's own code, right of it.
//   usage: test_split_view RTPBR_RENDER RTPBR_VIEWER XVFB_RUN SCENE OUTDIR
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "test_main.h"

#include "sample_test.h"
#include <stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

enum { W = 480, H = 360 };
static char **args;

// Fraction of pixels in columns [x0, x1) whose channels differ by more than 3 / 255.
static double differing(const unsigned char *a, const unsigned char *b, int x0, int x1)
{
    size_t count = 0, total = 0;
    for (int y = 0; y < H; ++y)
        for (int x = x0; x < x1; ++x, ++total)
            for (int c = 0; c < 3; ++c) {
                int d = a[4 * (y * W + x) + c] - b[4 * (y * W + x) + c];
                if (d > 3 || d < -3) {
                    ++count;
                    break;
                }
            }
    return (double)count / (double)total;
}

static void test_split_view(void **state)
{
    (void)state;
    char ref_exr[512], ggx_png[512], beckmann_png[512], shot[512], size_w[16], size_h[16];
    snprintf(ref_exr, sizeof ref_exr, "%s/split_reference.exr", args[5]);
    snprintf(ggx_png, sizeof ggx_png, "%s/split_ggx.png", args[5]);
    snprintf(beckmann_png, sizeof beckmann_png, "%s/split_beckmann.png", args[5]);
    snprintf(shot, sizeof shot, "%s/split_viewer.png", args[5]);
    snprintf(size_w, sizeof size_w, "%d", W);
    snprintf(size_h, sizeof size_h, "%d", H);
    sample_run_ok((char *[]){args[1], args[4], "-o", ref_exr, "--width", size_w, "--height", size_h, "--ndf", "beckmann", NULL});
    sample_run_ok((char *[]){args[1], args[4], "-o", beckmann_png, "--width", size_w, "--height", size_h, "--ndf", "beckmann", NULL});
    sample_run_ok((char *[]){args[1], args[4], "-o", ggx_png, "--width", size_w, "--height", size_h, NULL});
    sample_run_ok((char *[]){args[3], "-a", "-s", "-screen 0 1024x768x24", args[2], args[4], "--reference", ref_exr,
                   "--width", size_w, "--height", size_h, "--frames", "2", "--screenshot", shot, "--validation", "--no-ui",
                   NULL});
    unsigned char *ggx = sample_load_rgba(ggx_png, W, H), *beckmann = sample_load_rgba(beckmann_png, W, H),
                  *viewer = sample_load_rgba(shot, W, H);
    double left = differing(viewer, ggx, 0, W / 2), right = differing(viewer, beckmann, W / 2 + 1, W);
    double models = differing(ggx, beckmann, W / 2 + 1, W); // how much the check can see
    size_t line_white = 0;
    for (int y = 0; y < H; ++y)
        line_white += viewer[4 * (y * W + W / 2)] == 255 && viewer[4 * (y * W + W / 2) + 1] == 255;
    printf("differing pixels: left vs GGX %.4f, right vs Beckmann reference %.4f; GGX vs Beckmann %.4f; "
           "white split-line pixels %zu of %d\n", left, right, models, line_white, H);
    assert_true(models > 0.02);
    assert_true(left < 0.001);
    assert_true(right < 0.001);
    assert_int_equal(line_white, H);
    stbi_image_free(ggx);
    stbi_image_free(beckmann);
    stbi_image_free(viewer);
}

SAMPLE_TEST_MAIN(args, 5, "RTPBR_RENDER RTPBR_VIEWER XVFB_RUN SCENE OUTDIR", test_split_view)
