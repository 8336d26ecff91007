/* Helpers for the scene loader tests: glTF text assembled at test time with
 * base64 data: URIs, a minimal PNG writer, files in a per-test folder. */
#ifndef TEST_SCENE_UTIL_H
#define TEST_SCENE_UTIL_H

#include <rtpbr/rtpbr_gltf.h>

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

/* printf into a malloc'd string. */
char* ts_format(const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2), nonnull(1), returns_nonnull))
#endif
    ;

/* "data:application/octet-stream;base64,..." (malloc'd). */
char* ts_data_uri(const char* mime, const void* data, size_t size);

/* Binary buffer builder: appends 4-byte aligned blocks, returns their offsets. */
typedef struct ts_bin {
    unsigned char bytes[1 << 16];
    size_t size;
} ts_bin;
size_t ts_bin_append(ts_bin* bin, const void* data, size_t size);

/* A one-mesh scene: accessor 0 = POSITION (vertex_count VEC3 floats, buffer
 * view 0), accessor 1 = indices (uint32, view 1). Any override replaces the
 * generated JSON fragment (array contents, without brackets). */
typedef struct ts_scene {
    const float* positions;
    size_t vertex_count;
    const uint32_t* indices;
    size_t index_count;
    const float* texcoords; /* optional: vertex_count VEC2, view/accessor 2 */
    const char* buffer_uri; /* NULL = data: URI of the generated buffer */
    const char* accessors;  /* NULL = the two accessors above            */
    const char* meshes;     /* NULL = one primitive using material       */
    int material;           /* for the default mesh, -1 = none           */
    const char* materials;  /* NULL = none                               */
    const char* nodes;      /* NULL = one node with mesh 0               */
    const char* scene_nodes;/* NULL = "0"                                */
    const char* extra;      /* extra top-level members, starting with ',' */
} ts_scene;
char* ts_scene_json(const ts_scene* s);
/* Binary buffer of a ts_scene (positions then indices). */
void ts_scene_bin(const ts_scene* s, ts_bin* bin);

/* GLB container (glTF 2.0 §4.4) of json + optional BIN chunk (malloc'd). */
unsigned char* ts_glb(const char* json, const void* bin, size_t bin_size, size_t* size);

/* RGBA8 image as an uncompressed (stored deflate) PNG (malloc'd). */
unsigned char* ts_png(const unsigned char* rgba, uint32_t width, uint32_t height, size_t* size);

/* Folder for this test under RTPBR_GLTF_TEST_DIR (or /tmp), created fresh. */
const char* ts_dir(const char* name);
char* ts_path(const char* dir, const char* file)
#if defined(__GNUC__)
    __attribute__((returns_nonnull))
#endif
    ;
int ts_exists(const char* path);
void ts_write(const char* dir, const char* file, const void* data, size_t size);

/* Loads text as a file `name` in dir with default options plus an error buffer. */
rtpbr_gltf_result ts_load_text(const char* dir, const char* name, const char* text,
                                const rtpbr_gltf_load_desc* desc, rtpbr_gltf_scene** out,
                                char* err, size_t err_size);

/* ts_scene_json(s) loaded as a file `name` in dir with desc (NULL: defaults): it must load,
 * else the test fails with the loader's result and message. */
rtpbr_gltf_scene* ts_load_scene(const char* dir, const char* name, const ts_scene* s,
                                const rtpbr_gltf_load_desc* desc);

#endif
