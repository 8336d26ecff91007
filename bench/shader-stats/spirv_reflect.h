// A small SPIR-V reflector: what a pipeline needs to be created from a module alone
// (descriptor set layouts, push-constant size, vertex inputs, colour outputs), read from the
// module's decorations and types the way zeux/niagara derives its layouts. Written for
// rtpbr-shader-stats, which must not know the engine's layouts.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#define SS_MAX_BINDINGS 64
#define SS_MAX_LOCATIONS 16

typedef struct ss_binding {
    uint32_t set;
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count; // array length (1 for a single descriptor)
} ss_binding;

// A stage input or output with a Location (built-ins are not listed).
typedef struct ss_location {
    uint32_t location;
    uint32_t components;   // 1..4
    char base;             // 'f' float, 'i' signed int, 'u' unsigned int
    uint32_t width;        // bits per component
} ss_location;

typedef struct ss_reflection {
    VkShaderStageFlagBits stage;
    char entry_point[64];
    uint32_t binding_count;
    ss_binding bindings[SS_MAX_BINDINGS];
    uint32_t push_constant_size; // bytes, 0: none
    uint32_t input_count;
    ss_location inputs[SS_MAX_LOCATIONS];
    uint32_t output_count;
    ss_location outputs[SS_MAX_LOCATIONS];
} ss_reflection;

// Reflects the first entry point of a SPIR-V module (words in host byte order). Returns true
// on success; on failure writes a one-line reason to error (error_size bytes) and returns
// false. Nothing is allocated that outlives the call.
bool ss_reflect(const uint32_t *words, size_t word_count, ss_reflection *out, char *error, size_t error_size);
