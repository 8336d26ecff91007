// The viewer's Dear ImGui panels: drawn over the scene where ui.cpp places them (a 370-pixel
// wide window at (8, 8) and a 300-pixel wide one 8 pixels from the right edge) and nowhere
// else: a screenshot with the panels equals the --no-ui screenshot outside those two columns'
// top part, and differs inside them.
//   usage: test_viewer_panels RTPBR_VIEWER XVFB_RUN SCENE OUTDIR
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "test_main.h"

#include "sample_test.h"
#include <stb_image.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

enum { W = 800, H = 600 };
static char **args;

static unsigned char *shoot(const char *name, bool no_ui)
{
    char path[512];
    snprintf(path, sizeof path, "%s/panels_%s.png", args[4], name);
    char *argv[] = {args[2], "-a", "-s", "-screen 0 1024x768x24", args[1], args[3], "--width", "800", "--height",
                    "600", "--frames", "2", "--screenshot", path, "--validation", no_ui ? "--no-ui" : NULL, NULL};
    sample_run_ok(argv);
    return sample_load_rgba(path, W, H);
}

static void test_panels(void **state)
{
    (void)state;
    unsigned char *scene = shoot("off", true), *panels = shoot("on", false);
    // The panels' columns: [8, 378) and [W - 308, W - 8); their height depends on the font.
    size_t outside_changed = 0, left_changed = 0, left_total = 0, right_changed = 0, right_total = 0;
    int lowest = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const unsigned char *a = scene + 4 * (y * W + x), *b = panels + 4 * (y * W + x);
            bool changed = a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
            bool left = x >= 8 && x < 378, right = x >= W - 308 && x < W - 8;
            if (changed && y > lowest && (left || right)) lowest = y;
            if (!left && !right) outside_changed += changed;
            else if (y >= 8 && y < 200 && left) left_total++, left_changed += changed;
            else if (y >= 8 && y < 200 && right) right_total++, right_changed += changed;
        }
    printf("outside the panels: %zu changed pixels; left panel %.1f%%, right %.1f%% changed; lowest row %d\n",
           outside_changed, 100.0 * left_changed / left_total, 100.0 * right_changed / right_total, lowest);
    assert_int_equal(outside_changed, 0);
    assert_true(left_changed > left_total / 2);   // an opaque-ish panel covers the scene there
    assert_true(right_changed > right_total / 2);
    assert_true(lowest < H - 8);                   // the panels end above the bottom of the view
    free(scene), free(panels);
}

SAMPLE_TEST_MAIN(args, 4, "RTPBR_VIEWER XVFB_RUN SCENE OUTDIR", test_panels)
