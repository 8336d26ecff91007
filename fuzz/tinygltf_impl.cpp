// The tinygltf and stb_image implementations, compiled into the fuzzers with coverage and
// sanitizer instrumentation instead of linking Debian's shared libtinygltf/libstb (same
// header versions: libtinygltf-dev 2.7.0, libstb-dev 2022-09-08).
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
