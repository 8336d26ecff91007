// Mesa RADV's null device: a Vulkan device for an AMD chip this machine does not have
// (RADV_FORCE_FAMILY), on which pipelines compile through the driver's real back end (ACO)
// and report their statistics (VK_KHR_pipeline_executable_properties). Nothing is ever
// submitted: the null device cannot even create a fence.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

// The statistics this tool reads, one list for the enum, the table header and the JSON keys:
// X(enum suffix, RADV's statistic name (Mesa 22.3, radv_pipeline.c), column, JSON key).
#define SS_STATISTICS(X)                                                                   \
    X(VGPRS, "VGPRs", "VGPRs", "vgprs")                                                    \
    X(SGPRS, "SGPRs", "SGPRs", "sgprs")                                                    \
    X(SPILLED_VGPRS, "Spilled VGPRs", "spilled VGPRs", "spilled_vgprs")                    \
    X(SPILLED_SGPRS, "Spilled SGPRs", "spilled SGPRs", "spilled_sgprs")                    \
    X(SCRATCH, "Scratch size", "scratch B/wave", "scratch_bytes_per_wave")                 \
    X(INSTRUCTIONS, "Instructions", "instructions", "instructions")                        \
    X(CODE_SIZE, "Code size", "code B", "code_bytes")                                      \
    X(LATENCY, "Latency", "latency (cycles)", "latency_cycles")                            \
    X(THROUGHPUT, "Inverse Throughput", "inv. throughput (cycles)", "inverse_throughput")  \
    X(WAVES, "Subgroups per SIMD", "waves/SIMD", "waves_per_simd")

typedef enum ss_statistic {
#define SS_ENUM(id, driver_name, column, key) SS_STAT_##id,
    SS_STATISTICS(SS_ENUM)
#undef SS_ENUM
    SS_STAT_COUNT
} ss_statistic;

extern const char *const ss_statistic_driver_names[SS_STAT_COUNT];
extern const char *const ss_statistic_columns[SS_STAT_COUNT];
extern const char *const ss_statistic_keys[SS_STAT_COUNT];

// One compiled executable of a pipeline (a compute shader, a vertex or a fragment shader).
typedef struct ss_executable {
    char name[64];          // the driver's name, e.g. "Compute Shader"
    uint32_t subgroup_size; // wave size, 32 or 64
    bool has[SS_STAT_COUNT];
    double value[SS_STAT_COUNT];
} ss_executable;

#define SS_MAX_EXECUTABLES 4
typedef struct ss_pipeline_stats {
    uint32_t executable_count;
    ss_executable executables[SS_MAX_EXECUTABLES];
} ss_pipeline_stats;

// One SPIR-V module of a pipeline; the words are only read during ss_device_compile.
typedef struct ss_shader {
    const char *name;
    const uint32_t *words;
    size_t word_count;
} ss_shader;

typedef enum ss_open_result {
    SS_OPEN_OK,
    SS_OPEN_UNAVAILABLE, // no RADV null device for the family here (not an error of ours)
    SS_OPEN_FAILED,      // RADV is there but the instance or device could not be made
} ss_open_result;

typedef struct ss_device ss_device;

// Sets RADV_FORCE_FAMILY=family (and MESA_SHADER_CACHE_DISABLE=true unless already set, so
// that every run compiles) in this process's environment, creates an instance with
// VK_LAYER_KHRONOS_validation when it is installed and validation is true, and a device on
// the RADV null device of that family. On SS_OPEN_OK *out must be freed with
// ss_device_destroy; otherwise *out is NULL and error says why. One device at a time: the
// family is read from the environment when the instance is created.
ss_open_result ss_device_create(const char *family, bool validation, ss_device **out, char *error, size_t error_size);
void ss_device_destroy(ss_device *device); // NULL: no-op

// The device's name ("Null hardware (RADV NAVI21)") and driver info ("Mesa 22.3.6").
const char *ss_device_name(const ss_device *device);
const char *ss_device_driver_info(const ss_device *device);
bool ss_device_validating(const ss_device *device);

// Compiles one pipeline from its modules (one compute shader, or a vertex and a fragment
// shader) with layouts, vertex inputs and attachments derived from the modules' reflection
// (vertex inputs: one binding per location; colour outputs: R16G16B16A16_SFLOAT for float,
// R32G32B32A32_{S,U}INT for integer outputs; a D32_SFLOAT depth test when the vertex shader
// has vertex inputs), and reads every executable's statistics. Fails (false, error set) on a
// bad module, a Vulkan error, or any validation message during the compilation.
bool ss_device_compile(ss_device *device, const ss_shader *shaders, uint32_t shader_count, ss_pipeline_stats *out,
                       char *error, size_t error_size);
