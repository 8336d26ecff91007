/* Loads each file given on the command line with the scene loader and prints one line per
 * file: "FILE RESULT MESSAGE" (tests/scene/validator_diff.py reads it). Exit 0 unless a
 * file could not be examined at all. */
#include <rtpbr/rtpbr_gltf.h>

#include <stdio.h>

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        char message[RTPBR_GLTF_ERROR_MESSAGE_SIZE] = "";
        rtpbr_gltf_load_desc desc = {0};
        desc.error_message = message;
        desc.error_message_size = sizeof message;
        rtpbr_gltf_scene* scene = NULL;
        rtpbr_gltf_result r = rtpbr_gltf_load(argv[i], &desc, &scene);
        for (char* c = message; *c; ++c)
            if (*c == '\n') *c = ' ';
        printf("%s %s %s\n", argv[i], rtpbr_gltf_result_string(r), message);
        if ((r == RTPBR_GLTF_SUCCESS) != (scene != NULL)) return 1;
        rtpbr_gltf_destroy(scene);
    }
    return 0;
}
