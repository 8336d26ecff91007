// The shader list rtpbr-shader-stats and its test read: which SPIR-V files make which
// pipelines. bench/shader-stats/meson.build writes it from the engine's `shader_variants`.
//
// Manifest format: one shader per line, four tab-separated fields
//     name <TAB> stage <TAB> path <TAB> defines
// stage is vert, frag or comp (checked against the module's execution model); defines are
// the glslang -D arguments the module was built with, space-separated (may be empty). Blank
// lines and lines starting with '#' are ignored.
//
// Pipelines: a compute shader is a pipeline of its own, named by the entry. A vertex and a
// fragment shader whose names are equal once the suffixes _vert and _frag are removed make
// one graphics pipeline of that name (gbuffer_vert + gbuffer_frag = gbuffer).
// Per-light builds (defines contain -DRTPBR_STATS_FIXED_LIGHTS=N) are not engine pipelines:
// two of them with the same name and N = 1 and 2 make one per-light row (ss_manifest_pairs).
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#define SS_FIXED_LIGHTS_DEFINE "-DRTPBR_STATS_FIXED_LIGHTS="

typedef struct ss_entry {
    char *name;
    char *stage; // vert, frag, comp
    char *path;
    char *defines;
    int fixed_lights; // N of -DRTPBR_STATS_FIXED_LIGHTS=N, 0 without
    uint32_t *words;  // the module, loaded by ss_manifest_load_modules
    size_t word_count;
} ss_entry;

typedef struct ss_manifest {
    uint32_t count;
    ss_entry *entries;
} ss_manifest;

// A pipeline of the manifest: entry indices (one compute, or vertex then fragment).
typedef struct ss_pipeline {
    char name[128];
    uint32_t shader_count;
    uint32_t entries[2];
} ss_pipeline;

// A per-light pair: entry indices of the N = 1 and N = 2 builds.
typedef struct ss_light_pair {
    uint32_t one, two;
    // Found with the modules loaded (else false / UINT32_MAX): the two builds are the same
    // SPIR-V (the shader ignores RTPBR_STATS_FIXED_LIGHTS), or the 1-light build is the same
    // SPIR-V as that of the earlier pair same_as (a define the shader ignores). Such pairs
    // measure nothing new.
    bool ignores_fixed_lights;
    uint32_t same_as;
} ss_light_pair;

// Appends the manifest file's lines to *m. False (error set) on an unreadable file or a
// malformed line. *m owns everything it holds; ss_manifest_finish frees it.
bool ss_manifest_read(ss_manifest *m, const char *path, char *error, size_t error_size);
// Appends one SPIR-V file given by path (name: its file name without .spv; stage: from the
// module). Loads it at once.
bool ss_manifest_add_spirv(ss_manifest *m, const char *path, char *error, size_t error_size);
// Reads every entry's SPIR-V file (once) and checks its stage.
bool ss_manifest_load_modules(ss_manifest *m, char *error, size_t error_size);
void ss_manifest_finish(ss_manifest *m); // zeroes *m; a zeroed manifest is a no-op

// The engine pipelines (entries without RTPBR_STATS_FIXED_LIGHTS), in manifest order, among
// the entries for which keep(name, user) is true (keep NULL: all). *out is malloc'ed (free()).
bool ss_manifest_pipelines(const ss_manifest *m, bool (*keep)(const char *name, void *user), void *user,
                           ss_pipeline **out, uint32_t *count, char *error, size_t error_size);
// The per-light pairs, in manifest order of their N = 1 entry. *out is malloc'ed (free()).
bool ss_manifest_pairs(const ss_manifest *m, ss_light_pair **out, uint32_t *count, char *error, size_t error_size);
