// SPIR-V reflection for rtpbr-shader-stats (see spirv_reflect.h). Enumerants and the module
// layout are from the SPIR-V 1.6 specification (Khronos), sections 2.3 and 3.
#include "spirv_reflect.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SPIRV_MAGIC 0x07230203u
#define SPIRV_HEADER_WORDS 5u
#define MAX_TYPE_DEPTH 32

enum spirv_op {
    OP_ENTRY_POINT = 15,
    OP_TYPE_BOOL = 20,
    OP_TYPE_INT = 21,
    OP_TYPE_FLOAT = 22,
    OP_TYPE_VECTOR = 23,
    OP_TYPE_MATRIX = 24,
    OP_TYPE_IMAGE = 25,
    OP_TYPE_SAMPLER = 26,
    OP_TYPE_SAMPLED_IMAGE = 27,
    OP_TYPE_ARRAY = 28,
    OP_TYPE_RUNTIME_ARRAY = 29,
    OP_TYPE_STRUCT = 30,
    OP_TYPE_POINTER = 32,
    OP_CONSTANT = 43,
    OP_SPEC_CONSTANT = 50,
    OP_VARIABLE = 59,
    OP_DECORATE = 71,
    OP_MEMBER_DECORATE = 72,
    OP_TYPE_ACCELERATION_STRUCTURE = 5341,
};

enum spirv_decoration {
    DEC_BLOCK = 2,
    DEC_BUFFER_BLOCK = 3,
    DEC_ARRAY_STRIDE = 6,
    DEC_MATRIX_STRIDE = 7,
    DEC_BUILTIN = 11,
    DEC_LOCATION = 30,
    DEC_BINDING = 33,
    DEC_DESCRIPTOR_SET = 34,
    DEC_OFFSET = 35,
};

enum spirv_storage_class {
    SC_UNIFORM_CONSTANT = 0,
    SC_INPUT = 1,
    SC_UNIFORM = 2,
    SC_OUTPUT = 3,
    SC_PUSH_CONSTANT = 9,
    SC_STORAGE_BUFFER = 12,
};

enum spirv_dim { DIM_BUFFER = 5, DIM_SUBPASS_DATA = 6 };

// What is known about one result id.
typedef struct id_info {
    const uint32_t *insn; // the defining instruction (types, constants, variables), NULL: none
    uint32_t set, binding, location, array_stride;
    bool has_set, has_binding, has_location, builtin, buffer_block;
} id_info;

typedef struct module {
    const uint32_t *words;
    size_t word_count;
    uint32_t bound;
    id_info *ids;
    char *error;
    size_t error_size;
} module;

static bool fail(module *m, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(m->error, m->error_size, format, args);
    va_end(args);
    return false;
}

static uint32_t insn_words(const uint32_t *insn) { return insn[0] >> 16; }
static uint32_t insn_op(const uint32_t *insn) { return insn[0] & 0xffffu; }

// The defining instruction of id if it has the opcode op and at least min_words words.
static const uint32_t *typed(module *m, uint32_t id, uint32_t op, uint32_t min_words)
{
    if (id >= m->bound || !m->ids[id].insn) return NULL;
    const uint32_t *insn = m->ids[id].insn;
    return insn_op(insn) == op && insn_words(insn) >= min_words ? insn : NULL;
}

static uint32_t op_of(module *m, uint32_t id)
{
    return id < m->bound && m->ids[id].insn ? insn_op(m->ids[id].insn) : 0;
}

// A member decoration's literal (OpMemberDecorate struct member decoration literal).
static bool member_decoration(module *m, uint32_t struct_id, uint32_t member, uint32_t decoration, uint32_t *value)
{
    for (size_t pos = SPIRV_HEADER_WORDS; pos < m->word_count; pos += insn_words(m->words + pos)) {
        const uint32_t *insn = m->words + pos;
        if (insn_op(insn) != OP_MEMBER_DECORATE || insn_words(insn) < 4) continue;
        if (insn[1] == struct_id && insn[2] == member && insn[3] == decoration) {
            if (value) *value = insn_words(insn) >= 5 ? insn[4] : 0;
            return true;
        }
    }
    return false;
}

static bool constant_value(module *m, uint32_t id, uint32_t *value)
{
    const uint32_t *c = typed(m, id, OP_CONSTANT, 4);
    if (!c) c = typed(m, id, OP_SPEC_CONSTANT, 4);
    if (!c) return fail(m, "array length %u is not a 32-bit constant", id);
    *value = c[3];
    return true;
}

// Bytes a value of type id occupies in an explicitly laid out block (std140/std430 offsets
// and strides come from the decorations). matrix_stride: the member's MatrixStride, 0 if none.
static bool type_size(module *m, uint32_t id, uint32_t matrix_stride, int depth, uint32_t *size)
{
    if (depth > MAX_TYPE_DEPTH) return fail(m, "type nesting deeper than %d", MAX_TYPE_DEPTH);
    const uint32_t *insn;
    uint32_t element;
    switch (op_of(m, id)) {
    case OP_TYPE_BOOL: *size = 4; return true;
    case OP_TYPE_INT:
    case OP_TYPE_FLOAT:
        if (!(insn = typed(m, id, op_of(m, id), 3))) break;
        *size = insn[2] / 8;
        return true;
    case OP_TYPE_VECTOR:
        if (!(insn = typed(m, id, OP_TYPE_VECTOR, 4)) || !type_size(m, insn[2], 0, depth + 1, &element)) break;
        *size = element * insn[3];
        return true;
    case OP_TYPE_MATRIX:
        if (!(insn = typed(m, id, OP_TYPE_MATRIX, 4)) || !type_size(m, insn[2], 0, depth + 1, &element)) break;
        *size = (matrix_stride ? matrix_stride : element) * insn[3];
        return true;
    case OP_TYPE_ARRAY: {
        uint32_t length;
        if (!(insn = typed(m, id, OP_TYPE_ARRAY, 4)) || !constant_value(m, insn[3], &length)) break;
        uint32_t stride = m->ids[id].array_stride;
        if (!stride && !type_size(m, insn[2], matrix_stride, depth + 1, &stride)) break;
        *size = stride * length;
        return true;
    }
    case OP_TYPE_RUNTIME_ARRAY: *size = 0; return true;
    case OP_TYPE_STRUCT: {
        insn = m->ids[id].insn;
        uint32_t end = 0;
        for (uint32_t member = 0; member + 2 < insn_words(insn); ++member) {
            uint32_t offset, member_stride = 0, member_size;
            if (!member_decoration(m, id, member, DEC_OFFSET, &offset))
                return fail(m, "member %u of struct %u has no Offset", member, id);
            member_decoration(m, id, member, DEC_MATRIX_STRIDE, &member_stride);
            if (!type_size(m, insn[2 + member], member_stride, depth + 1, &member_size)) return false;
            if (offset + member_size > end) end = offset + member_size;
        }
        *size = end;
        return true;
    }
    default: break;
    }
    if (!m->error[0]) fail(m, "cannot size type %u", id);
    return false;
}

static bool pointee(module *m, uint32_t variable_type, uint32_t *type)
{
    const uint32_t *ptr = typed(m, variable_type, OP_TYPE_POINTER, 4);
    if (!ptr) return fail(m, "variable type %u is not a pointer", variable_type);
    *type = ptr[3];
    return true;
}

static bool descriptor_type(module *m, uint32_t type, uint32_t storage, VkDescriptorType *out)
{
    const uint32_t *insn;
    switch (op_of(m, type)) {
    case OP_TYPE_SAMPLED_IMAGE: {
        insn = typed(m, type, OP_TYPE_SAMPLED_IMAGE, 3);
        const uint32_t *image = insn ? typed(m, insn[2], OP_TYPE_IMAGE, 9) : NULL;
        if (!image) break;
        *out = image[3] == DIM_BUFFER ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        return true;
    }
    case OP_TYPE_IMAGE: {
        if (!(insn = typed(m, type, OP_TYPE_IMAGE, 9))) break;
        bool storage_image = insn[7] == 2; // Sampled = 2: read/write without a sampler
        if (insn[3] == DIM_SUBPASS_DATA) *out = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
        else if (insn[3] == DIM_BUFFER)
            *out = storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        else *out = storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        return true;
    }
    case OP_TYPE_SAMPLER: *out = VK_DESCRIPTOR_TYPE_SAMPLER; return true;
    case OP_TYPE_STRUCT:
        if (storage == SC_STORAGE_BUFFER || (storage == SC_UNIFORM && m->ids[type].buffer_block))
            *out = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        else if (storage == SC_UNIFORM) *out = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        else break;
        return true;
    case OP_TYPE_ACCELERATION_STRUCTURE: *out = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR; return true;
    default: break;
    }
    return fail(m, "unsupported descriptor type (type id %u, storage class %u)", type, storage);
}

static bool add_descriptor(module *m, ss_reflection *out, uint32_t variable)
{
    const id_info *info = &m->ids[variable];
    const uint32_t *var = info->insn;
    uint32_t type = 0, count = 1;
    if (!pointee(m, var[1], &type)) return false;
    while (op_of(m, type) == OP_TYPE_ARRAY || op_of(m, type) == OP_TYPE_RUNTIME_ARRAY) {
        if (op_of(m, type) == OP_TYPE_RUNTIME_ARRAY)
            return fail(m, "set %u binding %u: runtime-sized descriptor arrays are not supported", info->set, info->binding);
        const uint32_t *array = typed(m, type, OP_TYPE_ARRAY, 4);
        uint32_t length;
        if (!array || !constant_value(m, array[3], &length)) return false;
        count *= length;
        type = array[2];
    }
    ss_binding b = {.set = info->set, .binding = info->binding, .count = count};
    if (!descriptor_type(m, type, var[3], &b.type)) return false;
    for (uint32_t i = 0; i < out->binding_count; ++i) {
        ss_binding *o = &out->bindings[i];
        if (o->set != b.set || o->binding != b.binding) continue;
        if (o->type != b.type || o->count != b.count)
            return fail(m, "set %u binding %u is declared twice with different types", b.set, b.binding);
        return true; // an alias of a declared binding
    }
    if (out->binding_count == SS_MAX_BINDINGS) return fail(m, "more than %d descriptor bindings", SS_MAX_BINDINGS);
    out->bindings[out->binding_count++] = b;
    return true;
}

// Scalar or vector type: component base type, width and count.
static bool scalar_or_vector(module *m, uint32_t type, ss_location *loc)
{
    loc->components = 1;
    const uint32_t *vec = typed(m, type, OP_TYPE_VECTOR, 4);
    if (vec) {
        loc->components = vec[3];
        type = vec[2];
    }
    const uint32_t *insn;
    if ((insn = typed(m, type, OP_TYPE_FLOAT, 3))) loc->base = 'f';
    else if ((insn = typed(m, type, OP_TYPE_INT, 4))) loc->base = insn[3] ? 'i' : 'u';
    else return fail(m, "unsupported stage interface type %u", type);
    loc->width = insn[2];
    if (loc->components < 1 || loc->components > 4) return fail(m, "vector of %u components", loc->components);
    return true;
}

static bool add_interface(module *m, ss_reflection *out, uint32_t variable)
{
    const id_info *info = &m->ids[variable];
    const uint32_t *var = info->insn;
    bool input = var[3] == SC_INPUT;
    uint32_t type = 0;
    if (!pointee(m, var[1], &type)) return false;
    if (info->builtin) return true;
    if (op_of(m, type) == OP_TYPE_STRUCT && member_decoration(m, type, 0, DEC_BUILTIN, NULL))
        return true; // gl_PerVertex
    if (!info->has_location) return fail(m, "%s variable %u has neither Location nor BuiltIn", input ? "input" : "output", variable);
    // Arrays and matrices occupy consecutive locations, one per element or column.
    uint32_t slots = 1;
    const uint32_t *insn;
    if ((insn = typed(m, type, OP_TYPE_ARRAY, 4))) {
        if (!constant_value(m, insn[3], &slots)) return false;
        type = insn[2];
    }
    if ((insn = typed(m, type, OP_TYPE_MATRIX, 4))) {
        slots *= insn[3];
        type = insn[2];
    }
    ss_location loc = {0};
    if (!scalar_or_vector(m, type, &loc)) return false;
    if (loc.width == 64) return fail(m, "64-bit stage interface variables are not supported");
    uint32_t *count = input ? &out->input_count : &out->output_count;
    ss_location *list = input ? out->inputs : out->outputs;
    for (uint32_t s = 0; s < slots; ++s) {
        if (*count == SS_MAX_LOCATIONS) return fail(m, "more than %d interface locations", SS_MAX_LOCATIONS);
        loc.location = info->location + s;
        list[(*count)++] = loc;
    }
    return true;
}

static bool stage_of(uint32_t model, VkShaderStageFlagBits *stage)
{
    switch (model) {
    case 0: *stage = VK_SHADER_STAGE_VERTEX_BIT; return true;
    case 1: *stage = VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT; return true;
    case 2: *stage = VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT; return true;
    case 3: *stage = VK_SHADER_STAGE_GEOMETRY_BIT; return true;
    case 4: *stage = VK_SHADER_STAGE_FRAGMENT_BIT; return true;
    case 5: *stage = VK_SHADER_STAGE_COMPUTE_BIT; return true;
    default: return false;
    }
}

// First pass: bounds, the entry point, every id's defining instruction and its decorations.
static bool index_module(module *m, ss_reflection *out)
{
    uint32_t entry_points = 0;
    for (size_t pos = SPIRV_HEADER_WORDS; pos < m->word_count;) {
        const uint32_t *insn = m->words + pos;
        uint32_t wc = insn_words(insn), op = insn_op(insn);
        if (wc == 0 || wc > m->word_count - pos) return fail(m, "malformed instruction at word %zu", pos);
        pos += wc;
        if (op == OP_ENTRY_POINT) {
            if (wc < 4) return fail(m, "short OpEntryPoint");
            if (++entry_points > 1) return fail(m, "modules with several entry points are not supported");
            if (!stage_of(insn[1], &out->stage)) return fail(m, "unsupported execution model %u", insn[1]);
            size_t max = (wc - 3) * 4;
            const char *name = (const char *)(insn + 3);
            const char *nul = memchr(name, '\0', max);
            size_t len = nul ? (size_t)(nul - name) : max;
            if (!nul || len >= sizeof out->entry_point) return fail(m, "bad entry point name");
            memcpy(out->entry_point, name, len + 1);
        } else if (op == OP_DECORATE) {
            if (wc < 3 || insn[1] >= m->bound) return fail(m, "malformed OpDecorate");
            id_info *t = &m->ids[insn[1]];
            uint32_t literal = wc >= 4 ? insn[3] : 0;
            switch (insn[2]) {
            case DEC_DESCRIPTOR_SET: t->set = literal; t->has_set = true; break;
            case DEC_BINDING: t->binding = literal; t->has_binding = true; break;
            case DEC_LOCATION: t->location = literal; t->has_location = true; break;
            case DEC_ARRAY_STRIDE: t->array_stride = literal; break;
            case DEC_BUILTIN: t->builtin = true; break;
            case DEC_BUFFER_BLOCK: t->buffer_block = true; break;
            default: break;
            }
        } else {
            // The result id's position: types declare it first, constants and variables second.
            uint32_t result_word = 0;
            if ((op >= OP_TYPE_BOOL && op <= OP_TYPE_POINTER) || op == OP_TYPE_ACCELERATION_STRUCTURE) result_word = 1;
            else if (op == OP_CONSTANT || op == OP_SPEC_CONSTANT || op == OP_VARIABLE) result_word = 2;
            if (!result_word) continue;
            if (wc <= result_word || insn[result_word] >= m->bound) return fail(m, "malformed instruction %u", op);
            if (op == OP_VARIABLE && wc < 4) return fail(m, "short OpVariable");
            m->ids[insn[result_word]].insn = insn;
        }
    }
    if (entry_points == 0) return fail(m, "no entry point");
    return true;
}

bool ss_reflect(const uint32_t *words, size_t word_count, ss_reflection *out, char *error, size_t error_size)
{
    memset(out, 0, sizeof *out);
    if (error_size) error[0] = '\0';
    module m = {.words = words, .word_count = word_count, .error = error, .error_size = error_size};
    if (word_count < SPIRV_HEADER_WORDS || words[0] != SPIRV_MAGIC) return fail(&m, "not a SPIR-V module");
    m.bound = words[3];
    if (m.bound == 0 || m.bound > 4u * 1024 * 1024) return fail(&m, "implausible id bound %u", m.bound);
    m.ids = calloc(m.bound, sizeof *m.ids);
    if (!m.ids) return fail(&m, "out of memory");
    bool ok = index_module(&m, out);
    for (uint32_t id = 0; ok && id < m.bound; ++id) {
        const uint32_t *var = m.ids[id].insn;
        if (!var || insn_op(var) != OP_VARIABLE) continue;
        switch (var[3]) {
        case SC_UNIFORM_CONSTANT:
        case SC_UNIFORM:
        case SC_STORAGE_BUFFER:
            if (m.ids[id].has_set && m.ids[id].has_binding) ok = add_descriptor(&m, out, id);
            else ok = fail(&m, "resource variable %u lacks DescriptorSet or Binding", id);
            break;
        case SC_INPUT:
        case SC_OUTPUT: ok = add_interface(&m, out, id); break;
        case SC_PUSH_CONSTANT: {
            uint32_t type = 0, size = 0;
            ok = pointee(&m, var[1], &type) && type_size(&m, type, 0, 0, &size);
            if (ok && size > out->push_constant_size) out->push_constant_size = (size + 3u) & ~3u;
            break;
        }
        default: break;
        }
    }
    free(m.ids);
    return ok;
}
