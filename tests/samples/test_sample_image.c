// Runs a sample that renders samples/scenes/quad_light.gltf from the file's camera and writes a
// PNG, then checks the picture against where things must be, computed here by hand from the
// glTF's numbers (not from the engine): the copper floor must show the light's reflection
// around the mirror point (only lighting puts anything there: the floor does not emit), the
// highlight must be left-right symmetric (the light is centred on the camera's plane of
// symmetry), the far floor dark, and the image not black. (The light quad itself faces down
// and the camera is above it: seen from behind, a one-sided light shows nothing.)
// With --light-visible the light has been turned to face the camera (rotated -90 degrees about
// X, so it stands vertical at the same centre, facing +Z): its centre must then be near white.
//   usage: test_sample_image [--light-visible] OUT.png COMMAND [ARGS...]   (COMMAND writes OUT.png)
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "test_main.h"

#include "sample_test.h"
#include <math.h>
#include <stb_image.h>
#include <stdbool.h>
#include <string.h>
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *png_path;
static char **command;
static bool light_visible;

// Camera of quad_light.gltf: position (0, 1.6, 4.2), rotation quaternion (x = -0.17067, w =
// 0.98533) about X, i.e. pitched down by theta = 2 asin(0.17067); yfov pi/4.
static void project(const double p[3], int width, int height, double *px, double *py)
{
    const double theta = 2.0 * asin(0.17067232992662074), tan_half = tan(3.14159265358979323846 / 8.0);
    const double forward[3] = {0.0, -sin(theta), -cos(theta)}, up[3] = {0.0, cos(theta), -sin(theta)};
    const double d[3] = {p[0] - 0.0, p[1] - 1.6, p[2] - 4.2};
    double depth = d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2];
    double y = (d[0] * up[0] + d[1] * up[1] + d[2] * up[2]) / depth / tan_half;
    double x = d[0] / depth / (tan_half * (double)width / height); // right = +X
    *px = (x * 0.5 + 0.5) * width;
    *py = (0.5 - y * 0.5) * height;
}

// Mean sRGB-encoded luma (0..1) of a 5x5 block around (x, y).
static double luma_at(const unsigned char *rgba, int width, int height, double x, double y)
{
    double sum = 0.0;
    int n = 0;
    for (int j = (int)y - 2; j <= (int)y + 2; ++j)
        for (int i = (int)x - 2; i <= (int)x + 2; ++i) {
            if (i < 0 || j < 0 || i >= width || j >= height) continue;
            const unsigned char *p = rgba + 4 * ((size_t)j * width + i);
            sum += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
            ++n;
        }
    return n ? sum / n : 0.0;
}

static void test_run_and_check(void **state)
{
    (void)state;
    remove(png_path);
    sample_run_ok(command);

    int width = 0, height = 0, channels = 0;
    unsigned char *rgba = stbi_load(png_path, &width, &height, &channels, 4);
    assert_non_null(rgba);
    double mean = 0.0;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) mean += luma_at(rgba, width, height, i, j) / ((double)width * height);
    double lx, ly, mx, my, fx, fy;
    project((const double[3]){0.0, 1.4, 0.0}, width, height, &lx, &ly);  // light centre
    project((const double[3]){0.0, 0.0, 1.96}, width, height, &mx, &my);  // mirror point: the
    // line from the camera to the light mirrored in y = 0, (0, -1.4, 0), meets the floor at
    // t = 1.6 / 3.0: z = 4.2 (1 - 1.6 / 3) = 1.96
    project((const double[3]){-2.8, 0.0, -2.8}, width, height, &fx, &fy); // far floor corner
    double light = luma_at(rgba, width, height, lx, ly);
    double mirror = luma_at(rgba, width, height, mx, my);
    double far = luma_at(rgba, width, height, fx, fy);
    double left = luma_at(rgba, width, height, mx - 0.15 * width, my);
    double right = luma_at(rgba, width, height, mx + 0.15 * width, my);
    printf("%dx%d: mean luma %.3f, light centre (%.0f, %.0f) %.3f, mirror point (%.0f, %.0f) %.3f, "
           "+-15%% of the width %.3f %.3f, far floor (%.0f, %.0f) %.3f\n",
           width, height, mean, lx, ly, light, mx, my, mirror, left, right, fx, fy, far);
    stbi_image_free(rgba);
    assert_true(mean > 0.05);
    assert_true(mirror > 0.5);
    assert_true(mirror > 4.0 * far);
    assert_true(mirror > left && mirror > right);
    assert_true(fabs(left - right) < 0.05);
    if (light_visible) assert_true(light > 0.9);
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--light-visible") == 0) {
        light_visible = true;
        ++argv, --argc;
    }
    if (argc < 3) {
        fprintf(stderr, "usage: test_sample_image [--light-visible] OUT.png COMMAND [ARGS...]\n");
        return 2;
    }
    png_path = argv[1];
    command = argv + 2;
    RTPBR_RUN_TESTS(NULL, NULL, cmocka_unit_test(test_run_and_check));
}
