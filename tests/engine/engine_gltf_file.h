// Engine tests of scenes written to a temporary .gltf file and loaded through the glTF loader
// (test_engine_alpha.c, test_engine_textures.c, test_engine_api.c). Include after
// engine_test.h, with _DEFAULT_SOURCE defined before any header (for mkstemps).
#ifndef RTPBR_ENGINE_GLTF_FILE_H
#define RTPBR_ENGINE_GLTF_FILE_H

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "engine_test.h"

// Writes a scene to path; 0 on success.
typedef int (*test_gltf_writer)(const void *user, const char *path);

// The writer of a glTF given as text (user: the NUL-terminated JSON).
static inline int test_gltf_text(const void *user, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    int ok = fputs(user, f) >= 0;
    return fclose(f) == 0 && ok ? 0 : -1;
}

// A new temporary file named after `path` (a template ending in XXXXXX.gltf, overwritten with
// the file's name) holding the scene `write` wrote. The caller removes it.
static inline void test_gltf_file(char *path, test_gltf_writer write, const void *user)
{
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(write(user, path), 0);
}

// The scene `write` writes, loaded from a temporary file and rendered by a renderer of `rd` with
// `desc`: its radiance read back into `out` (size bytes). In the group's context where the test
// runs as a test_env_shared_case (engine_test.h; its teardown checks the messages), else in a
// context of its own (test_context, destroyed by test_context_done).
static inline void test_render_gltf(test_gltf_writer write, const void *user, const rtpbr_renderer_desc *rd,
                                    const rtpbr_render_desc *desc, float *out, size_t size)
{
    char path[] = "/tmp/rtpbr-engine-scene-XXXXXX.gltf";
    test_gltf_file(path, write, user);
    test_log own_log = {0};
    test_log *log = test_env_shared ? &test_env_shared->log : &own_log;
    rtpbr_context *ctx = test_env_shared ? test_env_shared->ctx : test_context(&own_log);
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_result r = rtpbr_gpu_scene_load_gltf(ctx, path, &scene);
    unlink(path);
    if (r != RTPBR_SUCCESS) fprintf(stderr, "load: %s\n", log->last_error);
    assert_int_equal(r, RTPBR_SUCCESS);
    rtpbr_renderer *renderer = test_renderer(ctx, rd);
    assert_int_equal(rtpbr_render(renderer, scene, desc), RTPBR_SUCCESS);
    assert_int_equal(test_read_radiance(renderer, out, size), RTPBR_SUCCESS);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    if (!test_env_shared) test_context_done(ctx, &own_log);
}

#endif
