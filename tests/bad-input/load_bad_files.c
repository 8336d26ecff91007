/* Regression inputs of the fuzzers and hand-made bad files (tests/bad-input/scenes/):
 *   load_bad_files DIR
 * reads DIR/expected.txt, lines "FILE RESULT [MEMORY_RESULT] [: WORDS]" (rtpbr_gltf_result names;
 * MEMORY_RESULT when loading from memory differs, e.g. a .glb with a broken magic is JSON
 * there, "-" = not loadable from memory: a folder, a missing file; WORDS, the rest of the
 * line after " : ", must appear in the message; '#' starts a comment),
 * loads each FILE by path and from memory (base_dir DIR), checks
 * the result, that a message is given and that no scene is returned. A crash, a leak
 * (ASan build) or a wrong result fails the test. */
#define _POSIX_C_SOURCE 200809L
#include <rtpbr/rtpbr_gltf.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check(const char* what, const char* file, rtpbr_gltf_result got, const char* want,
                 const char* words, const rtpbr_gltf_scene* scene, const char* message) {
    int ok = strcmp(rtpbr_gltf_result_string(got), want) == 0 && message[0] != '\0' && strstr(message, words);
    if (got != RTPBR_GLTF_SUCCESS && scene) ok = 0;
    printf("%s %s (%s): %s: %s\n", ok ? "ok  " : "FAIL", file, what, rtpbr_gltf_result_string(got),
           message[0] ? message : "(no message)");
    if (!ok) printf("     expected %s%s%s\n", want, words[0] ? " : " : "", words);
    return ok;
}

static unsigned char* read_all(const char* path, size_t* size) {
    FILE* f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char* data = NULL;
    size_t cap = 0, n = 0, got;
    do {
        if (n == cap) {
            cap = cap ? 2 * cap : 4096;
            unsigned char* grown = realloc(data, cap);
            if (!grown) break;
            data = grown;
        }
        got = fread(data + n, 1, cap - n, f);
        n += got;
    } while (got > 0);
    fclose(f);
    *size = n;
    return data;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: load_bad_files DIR\n");
        return 2;
    }
    const char* dir = argv[1];
    char path[4096];
    snprintf(path, sizeof path, "%s/expected.txt", dir);
    FILE* list = fopen(path, "r");
    if (!list) {
        fprintf(stderr, "load_bad_files: cannot open %s\n", path);
        return 2;
    }
    char line[1024];
    int failures = 0, cases = 0;
    while (fgets(line, sizeof line, list)) {
        char file[512], want[128], want_memory[128];
        const char* words = "";
        char* colon = strstr(line, " : ");
        if (colon) {
            *colon = '\0';
            words = colon + 3;
            colon[3 + strcspn(colon + 3, "\r\n")] = '\0';
        }
        const int fields = line[0] == '#' ? 0 : sscanf(line, "%511s %127s %127s", file, want, want_memory);
        if (fields < 2) continue;
        if (fields == 2) memcpy(want_memory, want, sizeof want);
        ++cases;
        char message[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
        rtpbr_gltf_load_desc desc = {0};
        desc.error_message = message;
        desc.error_message_size = sizeof message;
        snprintf(path, sizeof path, "%s/%s", dir, file);
        rtpbr_gltf_scene* scene = (rtpbr_gltf_scene*)(uintptr_t)1;
        rtpbr_gltf_result r = rtpbr_gltf_load(path, &desc, &scene);
        if (r == RTPBR_GLTF_SUCCESS) snprintf(message, sizeof message, "(loaded)");
        failures += !check("path", file, r, want, words, scene, message);
        if (r == RTPBR_GLTF_SUCCESS) rtpbr_gltf_destroy(scene);

        if (strcmp(want_memory, "-") == 0) continue;
        size_t size = 0;
        unsigned char* data = read_all(path, &size);
        if (!data) {
            printf("FAIL %s: unreadable\n", file);
            ++failures;
            continue;
        }
        desc.base_dir = dir;
        scene = (rtpbr_gltf_scene*)(uintptr_t)1;
        r = rtpbr_gltf_load_memory(data, size, &desc, &scene);
        if (r == RTPBR_GLTF_SUCCESS) snprintf(message, sizeof message, "(loaded)");
        failures += !check("memory", file, r, want_memory, words, scene, message);
        if (r == RTPBR_GLTF_SUCCESS) rtpbr_gltf_destroy(scene);
        free(data);
    }
    fclose(list);
    printf("%d cases, %d failures\n", cases, failures);
    return failures || cases == 0 ? 1 : 0;
}
