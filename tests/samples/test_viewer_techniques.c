// The viewer's technique toggles, scripted (--keys) on the showcase scene with the panels
// hidden (--no-ui): each toggle must change the image where its model acts and nowhere else.
// Positions are projected by hand from the scene's camera (tools/make-scenes/scenes.json:
// eye (0, 1.5, 6.5), target (0, 0.7, 0), 45 degrees vertical field of view, +Y up).
//   usage: test_viewer_techniques RTPBR_VIEWER XVFB_RUN SHOWCASE.gltf OUTDIR
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "test_main.h"

#include "sample_test.h"
#include <math.h>
#include <stb_image.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

enum { W = 320, H = 240 };
static char **args;

static unsigned char *shoot(const char *name, const char *keys)
{
    char path[512];
    snprintf(path, sizeof path, "%s/techniques_%s.png", args[4], name);
    char *argv[] = {args[2], "-a", "-s", "-screen 0 1024x768x24", args[1], args[3], "--width", "320", "--height",
                    "240", "--no-ui", "--frames", "2", "--keys", (char *)keys, "--screenshot", path, "--validation",
                    NULL};
    sample_run_ok(argv);
    return sample_load_rgba(path, W, H);
}

// Pixel of a world point through the scene's camera (the engine's look-at pinhole).
static void project(const double p[3], double *px, double *py)
{
    const double eye[3] = {0.0, 1.5, 6.5}, target[3] = {0.0, 0.7, 0.0};
    double f[3], r[3], u[3], d[3];
    for (int k = 0; k < 3; ++k) f[k] = target[k] - eye[k], d[k] = p[k] - eye[k];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; ++k) f[k] /= fl;
    r[0] = -f[2], r[1] = 0.0, r[2] = f[0]; // f x (0, 1, 0)
    double rl = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= rl, r[2] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    double z = d[0] * f[0] + d[1] * f[1] + d[2] * f[2], t = tan(0.5 * 45.0 * 3.14159265358979323846 / 180.0);
    double nx = (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / (z * t * (double)W / H);
    double ny = (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) / (z * t);
    *px = 0.5 * (nx + 1.0) * W, *py = 0.5 * (1.0 - ny) * H;
}

static double luma(const unsigned char *img, int x, int y)
{
    const unsigned char *p = img + 4 * (y * W + x);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Mean luma of the (2r+1)^2 pixels around the projection of a world point.
static double patch(const unsigned char *img, const double p[3], int r)
{
    double px, py, sum = 0.0;
    project(p, &px, &py);
    int cx = (int)px, cy = (int)py, n = 0;
    for (int y = cy - r; y <= cy + r; ++y)
        for (int x = cx - r; x <= cx + r; ++x) sum += luma(img, x, y), ++n;
    return sum / n;
}

// Nowhere else: what is black in the base image (the sky, and the far floor, whose dark
// dielectric rounds to 0 there) stays black up to the rounding of that far floor (2 / 255),
// and the sky above the highest light's top (2.4 m at z = -2.8, projected) stays exactly 0.
// A noisy pass (Monte Carlo) is held to the sky only: its samples light far floor pixels that
// the base image rounds to 0.
static void same_background(const unsigned char *base, const unsigned char *other, const char *what, bool noisy)
{
    double top[3] = {0.0, 2.4, -2.8}, px, sky_rows;
    project(top, &px, &sky_rows);
    size_t background = 0, changed = 0, sky_changed = 0;
    for (int i = 0; i < W * H; ++i) {
        const unsigned char *a = base + 4 * i, *b = other + 4 * i;
        if (i / W < (int)sky_rows - 2) sky_changed += a[0] || a[1] || a[2] || b[0] || b[1] || b[2];
        if (a[0] == 0 && a[1] == 0 && a[2] == 0) {
            ++background;
            changed += b[0] > 2 || b[1] > 2 || b[2] > 2;
        }
    }
    printf("%s: %zu background pixels, %zu changed; %d sky rows, %zu sky pixels not black\n", what, background,
           changed, (int)sky_rows - 2, sky_changed);
    assert_true(background > (size_t)W * H / 10); // the check sees something
    assert_true(sky_rows > H / 10);
    if (!noisy) assert_int_equal(changed, 0);
    assert_int_equal(sky_changed, 0);
}

static double changed_fraction(const unsigned char *a, const unsigned char *b)
{
    size_t changed = 0;
    for (int i = 0; i < W * H; ++i)
        for (int c = 0; c < 3; ++c)
            if (abs(a[4 * i + c] - b[4 * i + c]) > 2) {
                ++changed;
                break;
            }
    return (double)changed / (W * H);
}

static const double sphere_y = 0.45, spacing = 1.15;
static void sphere_front(int k, double out[3]) // the point of sphere k facing the camera
{
    double c[3] = {(k - 2.5) * spacing, sphere_y, 0.0}, eye[3] = {0.0, 1.5, 6.5}, d[3], l = 0.0;
    for (int i = 0; i < 3; ++i) d[i] = eye[i] - c[i], l += d[i] * d[i];
    for (int i = 0; i < 3; ++i) out[i] = c[i] + 0.45 * d[i] / sqrt(l);
}

static void test_techniques(void **state)
{
    (void)state;
    unsigned char *base = shoot("base", "");
    unsigned char *kc_off = shoot("kc_off", "K");
    unsigned char *beckmann = shoot("beckmann", "N");
    unsigned char *monte_carlo = shoot("monte_carlo", "R");
    unsigned char *exposure = shoot("exposure", "EE");

    // Kulla-Conty off: a rough metal loses its multiple-scattering energy, so the rough copper
    // sphere (k = 1, roughness 0.55) gets darker; the polished silver one (k = 0, 0.08) has
    // almost none to lose.
    double copper[3], silver[3];
    sphere_front(1, copper);
    sphere_front(0, silver);
    double copper_on = patch(base, copper, 3), copper_off = patch(kc_off, copper, 3);
    double silver_on = patch(base, silver, 3), silver_off = patch(kc_off, silver, 3);
    printf("Kulla-Conty: copper %.2f -> %.2f, silver %.2f -> %.2f\n", copper_on, copper_off, silver_on, silver_off);
    assert_true(copper_off < copper_on - 1.0);
    assert_true(fabs(silver_off - silver_on) < 0.5 * (copper_on - copper_off));
    same_background(base, kc_off, "Kulla-Conty", false);

    // Beckmann instead of GGX: the glossy floor's reflections of the lights change shape
    // (GGX's longer tail); the background stays.
    double frac = changed_fraction(base, beckmann);
    printf("Beckmann: %.1f%% of the pixels changed\n", 100.0 * frac);
    assert_true(frac > 0.05);
    same_background(base, beckmann, "Beckmann", false);

    // The Monte Carlo pass: the same integral with noise: lit surfaces change pixel by pixel,
    // the background stays, and the copper sphere's mean stays within 10% (same model).
    frac = changed_fraction(base, monte_carlo);
    double copper_mc = patch(monte_carlo, copper, 3);
    printf("Monte Carlo: %.1f%% of the pixels changed, copper %.2f -> %.2f\n", 100.0 * frac, copper_on, copper_mc);
    assert_true(frac > 0.05);
    assert_true(fabs(copper_mc - copper_on) < 0.1 * copper_on);
    same_background(base, monte_carlo, "Monte Carlo", true);

    // Exposure +1 EV: every lit pixel brightens, the background stays black.
    double light_centre[3] = {-0.9, 1.8, -2.8}; // the white quad light
    printf("exposure: copper %.2f -> %.2f\n", copper_on, patch(exposure, copper, 3));
    assert_true(patch(exposure, copper, 3) > copper_on + 5.0);
    assert_true(patch(exposure, light_centre, 1) >= patch(base, light_centre, 1));
    same_background(base, exposure, "exposure", false);
    free(base), free(kc_off), free(beckmann), free(monte_carlo), free(exposure);
}

SAMPLE_TEST_MAIN(args, 4, "RTPBR_VIEWER XVFB_RUN SHOWCASE.gltf OUTDIR", test_techniques)
