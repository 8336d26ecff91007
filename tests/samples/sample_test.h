// Shared helpers of the sample tests that run a program (rtpbr-embed, rtpbr-render, the viewer
// under xvfb-run) and read back the PNG it wrote. Include after test_main.h.
#ifndef RTPBR_SAMPLE_TEST_H
#define RTPBR_SAMPLE_TEST_H

#include <stb_image.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

// Runs argv (argv[0] looked up on PATH) to its end: it must exit normally with status 0.
static inline void sample_run_ok(char *const argv[])
{
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        execvp(argv[0], argv);
        _exit(127);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
}

// The image at path as 8-bit RGBA (the caller frees it with stbi_image_free or free); it must
// exist and be w x h.
static inline unsigned char *sample_load_rgba(const char *path, int w, int h)
{
    int width = 0, height = 0, channels = 0;
    unsigned char *p = stbi_load(path, &width, &height, &channels, 4);
    assert_non_null(p);
    assert_int_equal(width, w);
    assert_int_equal(height, h);
    return p;
}

// main() of a sample test whose one test reads `count` arguments (programs, scene, output
// folder) from `args` (args[1] to args[count]); another count prints the usage line and exits 2.
#define SAMPLE_TEST_MAIN(args, count, usage, test)                                                 \
    int main(int argc, char **argv)                                                                \
    {                                                                                              \
        if (argc != (count) + 1) {                                                                 \
            fprintf(stderr, "usage: %s %s\n", argv[0], usage);                                     \
            return 2;                                                                              \
        }                                                                                          \
        args = argv;                                                                               \
        RTPBR_RUN_TESTS(NULL, NULL, cmocka_unit_test(test));                                       \
    }

#endif
