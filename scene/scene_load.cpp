// Entry points of the scene loader: reading the file, confining external
// URIs to the scene folder, driving tinygltf, copying the result into
// caller-allocated plain data.
#include "scene_internal.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>

namespace rtpbr_gltf_detail {

namespace {

std::string vformat(const char* fmt, va_list args) {
    va_list copy;
    va_copy(copy, args);
    int n = std::vsnprintf(nullptr, 0, fmt, copy);
    va_end(copy);
    if (n <= 0) return std::string();
    std::string s(static_cast<size_t>(n) + 1, '\0');
    std::vsnprintf(&s[0], s.size(), fmt, args);
    s.resize(static_cast<size_t>(n));
    return s;
}

}  // namespace

bool Context::fail(rtpbr_gltf_result r, const char* fmt, ...) {
    if (result != RTPBR_GLTF_SUCCESS) return false;
    va_list args;
    va_start(args, fmt);
    result = r;
    message = vformat(fmt, args);
    va_end(args);
    return false;
}

void Context::warn(const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    if (desc.logger.func) log(RTPBR_GLTF_LOG_WARNING, vformat(fmt, args));
    va_end(args);
}

void Context::info(const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    if (desc.logger.func) log(RTPBR_GLTF_LOG_INFO, vformat(fmt, args));
    va_end(args);
}

void Context::log(rtpbr_gltf_log_level level, const std::string& text) const {
    if (desc.logger.func) desc.logger.func(level, text.c_str(), desc.logger.user_data);
}

namespace {

// ---- file system confinement ----------------------------------------------
// tinygltf resolves an external URI u as ExpandFilePath(JoinPath(dir, u)) for
// dir in {base_dir, "."} and then FileExists/ReadWholeFile on the result.
// Debian's default ExpandFilePath runs wordexp(3); ours never expands: it
// accepts only relative paths below base_dir made of plain characters.

const char kShellCharacters[] = "$`~*?[]{}|;&<>\\\"'";

std::string expand_file_path(const std::string& joined, void* user_data) {
    Context& ctx = *static_cast<Context*>(user_data);
    if (ctx.base_dir.empty()) {
        ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED,
                 "external file '%s' rejected: loading from memory without base_dir",
                 joined.c_str());
        return std::string();
    }
    const std::string prefix = ctx.base_dir + "/";
    // The "." search path of tinygltf, or anything else not built from base_dir.
    if (joined.compare(0, prefix.size(), prefix) != 0) return std::string();
    const std::string rel = joined.substr(prefix.size());
    if (rel.empty()) return std::string();
    if (rel[0] == '/') {
        ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED, "uri '%s': absolute paths are not allowed",
                 rel.c_str());
        return std::string();
    }
    for (unsigned char c : rel) {
        if (c < 0x20 || c == 0x7f || std::strchr(kShellCharacters, c)) {
            ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED,
                     "uri '%s': character '%c' (0x%02x) is not allowed in file names",
                     rel.c_str(), c >= 0x20 && c < 0x7f ? c : '?', c);
            return std::string();
        }
    }
    size_t start = 0;
    bool first = true;
    while (start <= rel.size()) {
        size_t end = rel.find('/', start);
        if (end == std::string::npos) end = rel.size();
        const std::string part = rel.substr(start, end - start);
        if (part == "..") {
            ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED,
                     "uri '%s': '..' would escape the scene folder", rel.c_str());
            return std::string();
        }
        if (first && part.find(':') != std::string::npos) {
            ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED,
                     "uri '%s': only relative file paths and data: URIs are supported",
                     rel.c_str());
            return std::string();
        }
        first = false;
        start = end + 1;
    }
    // Symbolic links must not lead out of the folder either.
    char* real = realpath(joined.c_str(), nullptr);
    if (!real) {
        ctx.fail(RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "uri '%s': file not found in '%s'",
                 rel.c_str(), ctx.base_dir.c_str());
        return std::string();
    }
    std::string resolved(real);
    std::free(real);
    if (resolved.compare(0, prefix.size(), prefix) != 0) {
        ctx.fail(RTPBR_GLTF_ERROR_URI_REJECTED, "uri '%s': resolves outside the scene folder",
                 rel.c_str());
        return std::string();
    }
    return resolved;
}

bool file_exists(const std::string& path, void* user_data) {
    Context& ctx = *static_cast<Context*>(user_data);
    if (path.empty()) return false;
    struct stat st;
    if (stat(path.c_str(), &st) != 0) {
        ctx.fail(RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "file '%s' not found", path.c_str());
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        ctx.fail(RTPBR_GLTF_ERROR_IO, "'%s' is not a regular file", path.c_str());
        return false;
    }
    return true;
}

// Reads a whole regular file; the result code says why it failed.
rtpbr_gltf_result read_file(const std::string& path, std::vector<unsigned char>* out,
                             std::string* why) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) {
        *why = std::strerror(errno);
        return errno == ENOENT || errno == ENOTDIR ? RTPBR_GLTF_ERROR_FILE_NOT_FOUND
                                                   : RTPBR_GLTF_ERROR_IO;
    }
    if (S_ISDIR(st.st_mode)) {
        *why = "is a directory";
        return RTPBR_GLTF_ERROR_IO;
    }
    if (!S_ISREG(st.st_mode)) {
        *why = "is not a regular file";
        return RTPBR_GLTF_ERROR_IO;
    }
    if (static_cast<uint64_t>(st.st_size) > RTPBR_GLTF_MAX_FILE_SIZE) {
        *why = "larger than RTPBR_GLTF_MAX_FILE_SIZE (1 GiB)";
        return RTPBR_GLTF_ERROR_IO;
    }
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        *why = std::strerror(errno);
        return RTPBR_GLTF_ERROR_IO;
    }
    out->resize(static_cast<size_t>(st.st_size));
    size_t got = out->empty() ? 0 : std::fread(out->data(), 1, out->size(), f);
    bool error = std::ferror(f) != 0;
    std::fclose(f);
    if (error || got != out->size()) {
        *why = "short read";
        return RTPBR_GLTF_ERROR_IO;
    }
    return RTPBR_GLTF_SUCCESS;
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user_data) {
    Context& ctx = *static_cast<Context*>(user_data);
    std::string why;
    rtpbr_gltf_result r = read_file(path, out, &why);
    if (r != RTPBR_GLTF_SUCCESS) {
        ctx.fail(r, "cannot read '%s': %s", path.c_str(), why.c_str());
        if (err) *err = why;
        return false;
    }
    return true;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
    if (err) *err = "writing is disabled";
    return false;
}

// Keeps encoded bytes of URI images; bufferView images are sliced after the
// bufferView has been validated (tinygltf 2.7 passes an unchecked pointer).
bool capture_image(tinygltf::Image* image, const int image_index, std::string*, std::string*,
                   int, int, const unsigned char* bytes, int size, void* user_data) {
    Context& ctx = *static_cast<Context*>(user_data);
    if (image->bufferView >= 0) return true;
    if (!bytes || size <= 0) return true;
    ctx.encoded_images[image_index].assign(bytes, bytes + size);
    return true;
}

// ---- container checks ------------------------------------------------------

uint32_t read_u32le(const unsigned char* p) {
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
           static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

// Checks the GLB header and chunk table. *has_unknown_second_chunk: the chunk after the JSON
// exists and is not BIN (tinygltf 2.7 refuses that, so it is shown the JSON chunk only).
bool check_glb(Context& ctx, const unsigned char* data, size_t size, bool* has_unknown_second_chunk) {
    if (size < 12)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: %zu bytes, shorter than the 12-byte header",
                        size);
    if (std::memcmp(data, "glTF", 4) != 0)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB,
                        "GLB: bad magic 0x%08x (expected 0x46546c67 'glTF')", read_u32le(data));
    uint32_t version = read_u32le(data + 4), length = read_u32le(data + 8);
    if (version != 2)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: version %u, only 2 is supported",
                        version);
    if (length > size)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB,
                        "GLB: header length %u exceeds the %zu bytes available", length, size);
    if (length < 20)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: no JSON chunk (length %u)", length);
    uint32_t json_length = read_u32le(data + 12), json_type = read_u32le(data + 16);
    if (json_type != 0x4E4F534Au)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: first chunk type 0x%08x is not JSON",
                        json_type);
    if (json_length % 4 != 0)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: JSON chunk length %u is not a multiple of 4", json_length);
    if (json_length == 0 || json_length > length - 20)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB,
                        "GLB: JSON chunk length %u exceeds the file length %u", json_length,
                        length);
    // Chunks after the JSON: an optional BIN chunk second, then chunks of any other type,
    // which readers must ignore (glTF 2.0, "Binary glTF Layout"). Every chunk must fit.
    *has_unknown_second_chunk = false;
    uint64_t at = 20ull + json_length;
    for (unsigned chunk = 1; at < length; ++chunk) {
        if (at + 8 > length)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: truncated header of chunk %u", chunk);
        uint32_t chunk_length = read_u32le(data + at), chunk_type = read_u32le(data + at + 4);
        if (chunk_length % 4 != 0)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: chunk %u (type 0x%08x) length %u is not a multiple of 4",
                            chunk, chunk_type, chunk_length);
        if (at + 8 + chunk_length > length)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB,
                            "GLB: chunk %u (type 0x%08x) length %u exceeds the file length %u", chunk, chunk_type,
                            chunk_length, length);
        if (chunk_type == 0x004E4942u && chunk != 1)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: BIN chunk in position %u (only the second chunk may be BIN)",
                            chunk + 1);
        if (chunk_type == 0x4E4F534Au)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_GLB, "GLB: a second JSON chunk (chunk %u)", chunk);
        if (chunk == 1 && chunk_type != 0x004E4942u) *has_unknown_second_chunk = true;
        at += 8ull + chunk_length;
    }
    return true;
}

// Bounds the nesting of JSON arrays/objects: nlohmann builds and destroys
// values recursively, so a deep nest would exhaust the stack.
bool check_json_depth(Context& ctx, const char* json, size_t size) {
    const unsigned max_depth = RTPBR_GLTF_MAX_JSON_DEPTH;
    unsigned depth = 0;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < size; ++i) {
        char c = json[i];
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                                "JSON nested deeper than %u levels at byte %zu", max_depth, i);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return true;
}

// The checked GLB `data` with its JSON chunk replaced by `json` (empty: kept as it is) and,
// unless keep_rest, nothing after the JSON chunk.
bool rebuild_glb(Context& ctx, const unsigned char* data, uint32_t json_length, const std::string& json,
                 bool keep_rest, std::vector<unsigned char>* out) {
    const size_t length = read_u32le(data + 8);
    const size_t padded = json.empty() ? json_length : (json.size() + 3) / 4 * 4;
    const size_t rest = keep_rest ? length - 20 - json_length : 0;
    if (20 + padded + rest > RTPBR_GLTF_MAX_FILE_SIZE)
        return ctx.fail(RTPBR_GLTF_ERROR_IO, "GLB: the document with defaults filled in exceeds RTPBR_GLTF_MAX_FILE_SIZE");
    out->assign(data, data + 20);
    if (json.empty()) {
        out->insert(out->end(), data + 20, data + 20 + json_length);
    } else {
        out->insert(out->end(), json.begin(), json.end());
        out->resize(20 + padded, ' ');
    }
    out->insert(out->end(), data + 20 + json_length, data + 20 + json_length + rest);
    auto put_u32 = [&](size_t at, size_t v) {
        for (int k = 0; k < 4; ++k) (*out)[at + size_t(k)] = static_cast<unsigned char>(v >> (8 * k));
    };
    put_u32(8, out->size());
    put_u32(12, padded);
    return true;
}

void forward_lines(const Context& ctx, rtpbr_gltf_log_level level, const std::string& text) {
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        if (end > start) ctx.log(level, "tinygltf: " + text.substr(start, end - start));
        start = end + 1;
    }
}

std::string first_line(const std::string& text) {
    std::string s = text.substr(0, text.find('\n'));
    return s.empty() ? std::string("unknown tinygltf error") : s;
}

const char* const kSupportedRequiredExtensions[] = {
    "KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_materials_ior",
    "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_anisotropy",
    "KHR_texture_transform", "EXT_lights_area", "KHR_lights_punctual",
};

bool check_required_extensions(Context& ctx, const tinygltf::Model& model) {
    for (const std::string& name : model.extensionsRequired) {
        bool known = false;
        for (const char* s : kSupportedRequiredExtensions) known = known || name == s;
        if (!known)
            return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED,
                            "extension '%s' is required by the file but not supported", name.c_str());
    }
    return true;
}

// ---- output ----------------------------------------------------------------

struct Allocator {
    rtpbr_gltf_allocator a;
    void* alloc(size_t n) const {
        if (n == 0) n = 1;
        return a.alloc ? a.alloc(n, a.user_data) : std::malloc(n);
    }
    void release(void* p) const {
        if (!p) return;
        if (a.free) a.free(p, a.user_data);
        else std::free(p);
    }
};

template <typename T>
bool copy_array(const Allocator& al, const std::vector<T>& v, T** out) {
    *out = nullptr;
    if (v.empty()) return true;
    if (v.size() > std::numeric_limits<size_t>::max() / sizeof(T)) return false;
    *out = static_cast<T*>(al.alloc(v.size() * sizeof(T)));
    if (!*out) return false;
    std::memcpy(*out, v.data(), v.size() * sizeof(T));
    return true;
}

template <typename T>
T* alloc_zeroed(const Allocator& al, size_t count) {
    if (count == 0 || count > std::numeric_limits<size_t>::max() / sizeof(T)) return nullptr;
    T* p = static_cast<T*>(al.alloc(count * sizeof(T)));
    if (p) std::memset(static_cast<void*>(p), 0, count * sizeof(T));
    return p;
}

void grow_bounds(float* lo, float* hi, const float* p) {
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
    }
}

rtpbr_gltf_result build_output(Context& ctx, const Scene& in, rtpbr_gltf_scene** out) {
    Allocator al{ctx.desc.allocator};
    rtpbr_gltf_scene* s = alloc_zeroed<rtpbr_gltf_scene>(al, 1);
    if (!s) return RTPBR_GLTF_ERROR_OUT_OF_MEMORY;
    s->allocator = ctx.desc.allocator;
    bool ok = true;

    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    if (!in.primitives.empty()) {
        s->primitives = alloc_zeroed<rtpbr_gltf_primitive>(al, in.primitives.size());
        ok = s->primitives != nullptr;
        if (ok) s->primitive_count = static_cast<uint32_t>(in.primitives.size());
    }
    for (size_t i = 0; ok && i < in.primitives.size(); ++i) {
        const Primitive& p = in.primitives[i];
        rtpbr_gltf_primitive& o = s->primitives[i];
        o.vertex_count = static_cast<uint32_t>(p.positions.size() / 3);
        o.index_count = static_cast<uint32_t>(p.indices.size());
        ok = copy_array(al, p.positions, &o.positions) && copy_array(al, p.normals, &o.normals) &&
             copy_array(al, p.texcoords, &o.texcoords) && copy_array(al, p.texcoords1, &o.texcoords1) &&
             copy_array(al, p.tangents, &o.tangents) &&
             copy_array(al, p.indices, &o.indices);
        o.material = p.material;
        o.gltf_mesh = p.gltf_mesh;
        o.gltf_primitive = p.gltf_primitive;
        o.gltf_node = p.gltf_node;
        o.has_texcoords = p.has_texcoords;
        o.has_texcoords1 = p.has_texcoords1;
        o.normals_generated = p.normals_generated;
        o.tangents_generated = p.tangents_generated;
        o.has_tangents = p.has_tangents;
        float plo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, phi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        for (uint32_t idx : p.indices) grow_bounds(plo, phi, &p.positions[3 * size_t(idx)]);
        if (p.indices.empty())
            for (int k = 0; k < 3; ++k) plo[k] = phi[k] = 0.0f;
        else
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], plo[k]), hi[k] = std::max(hi[k], phi[k]);
        std::memcpy(o.bounds_min, plo, sizeof plo);
        std::memcpy(o.bounds_max, phi, sizeof phi);
    }
    if (ok) ok = copy_array(al, in.materials, &s->materials);
    if (ok) s->material_count = static_cast<uint32_t>(in.materials.size());
    if (ok && !in.textures.empty()) {
        s->textures = alloc_zeroed<rtpbr_gltf_texture>(al, in.textures.size());
        ok = s->textures != nullptr;
        if (ok) s->texture_count = static_cast<uint32_t>(in.textures.size());
    }
    for (size_t i = 0; ok && i < in.textures.size(); ++i) {
        s->textures[i] = in.textures[i].info;
        s->textures[i].pixels = nullptr;
        ok = copy_array(al, in.textures[i].pixels, &s->textures[i].pixels);
    }
    if (ok) ok = copy_array(al, in.lights, &s->lights);
    if (ok) s->light_count = static_cast<uint32_t>(in.lights.size());
    if (ok) ok = copy_array(al, in.punctual_lights, &s->punctual_lights);
    if (ok) s->punctual_light_count = static_cast<uint32_t>(in.punctual_lights.size());
    if (ok) ok = copy_array(al, in.cameras, &s->cameras);
    if (ok) s->camera_count = static_cast<uint32_t>(in.cameras.size());
    if (!ok) {
        rtpbr_gltf_destroy(s);
        return RTPBR_GLTF_ERROR_OUT_OF_MEMORY;
    }
    for (const rtpbr_gltf_light& l : in.lights) {
        for (uint32_t v = 0; v < l.vertex_count; ++v) grow_bounds(lo, hi, l.vertices[v]);
        if (l.shape == RTPBR_GLTF_LIGHT_DISK) {
            // The disk itself: centre ± r·sqrt(1 - n_k²) along each axis (an ellipse: r its larger
            // half-axis, radius, a bound).
            for (int k = 0; k < 3; ++k) {
                float e = l.radius * std::sqrt(std::max(0.0f, 1.0f - l.facts.normal[k] * l.facts.normal[k]));
                lo[k] = std::min(lo[k], l.facts.center[k] - e);
                hi[k] = std::max(hi[k], l.facts.center[k] + e);
            }
        }
    }
    if (lo[0] > hi[0])
        for (int k = 0; k < 3; ++k) lo[k] = hi[k] = 0.0f;
    std::memcpy(s->bounds_min, lo, sizeof lo);
    std::memcpy(s->bounds_max, hi, sizeof hi);
    s->total_vertex_count = static_cast<uint32_t>(in.total_vertices);
    s->total_index_count = static_cast<uint32_t>(in.total_indices);
    *out = s;
    return RTPBR_GLTF_SUCCESS;
}

bool setup_context(Context& ctx, const rtpbr_gltf_load_desc* desc) {
    if (desc) ctx.desc = *desc;
    if (ctx.desc.error_message && ctx.desc.error_message_size > 0) ctx.desc.error_message[0] = '\0';
    if ((ctx.desc.allocator.alloc == nullptr) != (ctx.desc.allocator.free == nullptr))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ARGUMENT,
                        "desc.allocator: alloc and free must both be set or both be NULL");
    if (ctx.desc.max_vertices) ctx.max_vertices = std::min(ctx.desc.max_vertices, ctx.max_vertices);
    if (ctx.desc.max_lights) ctx.max_lights = std::min(ctx.desc.max_lights, ctx.max_lights);
    if (ctx.desc.max_texture_dimension)
        ctx.max_texture_dimension = std::min(ctx.desc.max_texture_dimension, ctx.max_texture_dimension);
    float scale = ctx.desc.area_light_radiance_scale;
    if (!(std::isfinite(scale) && scale >= 0.0f))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ARGUMENT,
                        "desc.area_light_radiance_scale must be finite and >= 0");
    if (scale > 0.0f) ctx.area_light_radiance_scale = scale;
    if (ctx.desc.texture_memory_budget) ctx.texture_budget = ctx.desc.texture_memory_budget;
    return true;
}

bool set_base_dir(Context& ctx, const std::string& dir) {
    char* real = realpath(dir.c_str(), nullptr);
    if (!real)
        return ctx.fail(RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "base directory '%s': %s", dir.c_str(),
                        std::strerror(errno));
    ctx.base_dir = real;
    std::free(real);
    return true;
}

rtpbr_gltf_result finish(Context& ctx, rtpbr_gltf_result r) {
    if (r != RTPBR_GLTF_SUCCESS) {
        if (ctx.result == RTPBR_GLTF_SUCCESS) ctx.result = r;
        if (ctx.message.empty()) ctx.message = rtpbr_gltf_result_string(r);
        if (ctx.desc.error_message && ctx.desc.error_message_size > 0)
            std::snprintf(ctx.desc.error_message, ctx.desc.error_message_size, "%s",
                          ctx.message.c_str());
        ctx.log(RTPBR_GLTF_LOG_ERROR, ctx.message);
        return ctx.result;
    }
    return r;
}

rtpbr_gltf_result load_model(Context& ctx, const unsigned char* data, size_t size, bool want_glb,
                              rtpbr_gltf_scene** out) {
    if (size > RTPBR_GLTF_MAX_FILE_SIZE) {
        ctx.fail(RTPBR_GLTF_ERROR_IO, "input of %zu bytes exceeds RTPBR_GLTF_MAX_FILE_SIZE", size);
        return ctx.result;
    }
    bool is_glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    std::vector<unsigned char> rebuilt_glb;
    std::string rewritten;  // the JSON tinygltf reads instead, when check_schema fills it
    if (want_glb || is_glb) {
        bool unknown_second_chunk = false;
        if (!check_glb(ctx, data, size, &unknown_second_chunk)) return ctx.result;
        uint32_t json_length = read_u32le(data + 12);
        if (!check_json_depth(ctx, reinterpret_cast<const char*>(data) + 20, json_length) ||
            !check_schema(ctx, reinterpret_cast<const char*>(data) + 20, json_length, &rewritten))
            return ctx.result;
        if (unknown_second_chunk) ctx.warn("GLB: chunks of unknown type ignored");
        if (unknown_second_chunk || !rewritten.empty()) {
            if (!rebuild_glb(ctx, data, json_length, rewritten, !unknown_second_chunk, &rebuilt_glb))
                return ctx.result;
            data = rebuilt_glb.data();
            size = rebuilt_glb.size();
        }
        is_glb = true;
    } else {
        if (size < 2)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "JSON: %zu bytes, empty document", size),
                   ctx.result;
        if (!check_json_depth(ctx, reinterpret_cast<const char*>(data), size) ||
            !check_schema(ctx, reinterpret_cast<const char*>(data), size, &rewritten))
            return ctx.result;
        if (!rewritten.empty()) {
            if (rewritten.size() > RTPBR_GLTF_MAX_FILE_SIZE)
                return ctx.fail(RTPBR_GLTF_ERROR_IO, "JSON: the document with defaults filled in exceeds "
                                "RTPBR_GLTF_MAX_FILE_SIZE"), ctx.result;
            data = reinterpret_cast<const unsigned char*>(rewritten.data());
            size = rewritten.size();
        }
    }

    tinygltf::TinyGLTF loader;
    tinygltf::FsCallbacks fs{};
    fs.FileExists = &file_exists;
    fs.ExpandFilePath = &expand_file_path;
    fs.ReadWholeFile = &read_whole_file;
    fs.WriteWholeFile = &write_whole_file;
    fs.user_data = &ctx;
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(&capture_image, &ctx);

    tinygltf::Model model;
    std::string err, warn;
    // tinygltf's base_dir: our canonical folder, or one that cannot exist so
    // that every external URI is routed to the rejection in expand_file_path.
    const std::string base = ctx.base_dir.empty() ? std::string("\x01no-base-dir") : ctx.base_dir;
    bool ok;
    if (is_glb)
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(size),
                                         base);
    else
        ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data),
                                        static_cast<unsigned int>(size), base);
    forward_lines(ctx, RTPBR_GLTF_LOG_WARNING, warn);
    if (ctx.failed()) return ctx.result;  // our callbacks know best what went wrong
    // tinygltf reports some schema errors (e.g. a 3-element baseColorFactor)
    // in err while still returning true: those are errors here too.
    if (!ok || !err.empty()) {
        rtpbr_gltf_result r = RTPBR_GLTF_ERROR_INVALID_JSON;
        if (err.find("File not found") != std::string::npos) r = RTPBR_GLTF_ERROR_FILE_NOT_FOUND;
        else if (err.find("glTF binary") != std::string::npos || err.find("Chunk") != std::string::npos)
            r = RTPBR_GLTF_ERROR_INVALID_GLB;
        ctx.fail(r, "%s", first_line(err).c_str());
        return ctx.result;
    }

    if (!check_required_extensions(ctx, model)) return ctx.result;
    Scene scene;
    LightNodes light_nodes;
    if (!convert_materials(ctx, model, scene)) return ctx.result;
    if (!convert_nodes(ctx, model, scene, &light_nodes)) return ctx.result;
    if (!ctx.desc.no_emissive_lights) {
        for (uint32_t i = 0; i < scene.primitives.size(); ++i)
            if (!lights_from_primitive(ctx, scene, i)) return ctx.result;
    }
    if (!lights_from_ext_area(ctx, model, scene, light_nodes.area)) return ctx.result;
    if (!lights_from_khr_punctual(ctx, model, scene, light_nodes.punctual)) return ctx.result;
    if (scene.lights.empty() && scene.punctual_lights.empty())
        ctx.warn("the scene has no lights (no EXT_lights_area or KHR_lights_punctual light%s): only emission "
                 "and the background will show; add lights (docs/materials.md)",
                 ctx.desc.no_emissive_lights ? ", emissive lights turned off" : " and no emissive surface");
    ctx.info("loaded %zu primitives (%llu vertices, %llu indices), %zu materials, %zu textures, "
             "%zu area lights, %zu punctual lights, %zu cameras",
             scene.primitives.size(), static_cast<unsigned long long>(scene.total_vertices),
             static_cast<unsigned long long>(scene.total_indices), scene.materials.size(),
             scene.textures.size(), scene.lights.size(), scene.punctual_lights.size(), scene.cameras.size());
    rtpbr_gltf_result r = build_output(ctx, scene, out);
    if (r != RTPBR_GLTF_SUCCESS) ctx.fail(r, "out of memory while copying the scene");
    return r;
}

bool ends_with_glb(const std::string& path) {
    if (path.size() < 4) return false;
    std::string ext = path.substr(path.size() - 4);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".glb";
}

}  // namespace
}  // namespace rtpbr_gltf_detail

using namespace rtpbr_gltf_detail;

extern "C" const char* rtpbr_gltf_result_string(rtpbr_gltf_result result) {
    switch (result) {
    case RTPBR_GLTF_SUCCESS: return "RTPBR_GLTF_SUCCESS";
    case RTPBR_GLTF_ERROR_INVALID_ARGUMENT: return "RTPBR_GLTF_ERROR_INVALID_ARGUMENT";
    case RTPBR_GLTF_ERROR_FILE_NOT_FOUND: return "RTPBR_GLTF_ERROR_FILE_NOT_FOUND";
    case RTPBR_GLTF_ERROR_IO: return "RTPBR_GLTF_ERROR_IO";
    case RTPBR_GLTF_ERROR_INVALID_GLB: return "RTPBR_GLTF_ERROR_INVALID_GLB";
    case RTPBR_GLTF_ERROR_INVALID_JSON: return "RTPBR_GLTF_ERROR_INVALID_JSON";
    case RTPBR_GLTF_ERROR_URI_REJECTED: return "RTPBR_GLTF_ERROR_URI_REJECTED";
    case RTPBR_GLTF_ERROR_INVALID_REFERENCE: return "RTPBR_GLTF_ERROR_INVALID_REFERENCE";
    case RTPBR_GLTF_ERROR_INVALID_ACCESSOR: return "RTPBR_GLTF_ERROR_INVALID_ACCESSOR";
    case RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE: return "RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE";
    case RTPBR_GLTF_ERROR_NONFINITE: return "RTPBR_GLTF_ERROR_NONFINITE";
    case RTPBR_GLTF_ERROR_UNSUPPORTED: return "RTPBR_GLTF_ERROR_UNSUPPORTED";
    case RTPBR_GLTF_ERROR_IMAGE_DECODE: return "RTPBR_GLTF_ERROR_IMAGE_DECODE";
    case RTPBR_GLTF_ERROR_TOO_MANY_VERTICES: return "RTPBR_GLTF_ERROR_TOO_MANY_VERTICES";
    case RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS: return "RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS";
    case RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE: return "RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE";
    case RTPBR_GLTF_ERROR_OUT_OF_MEMORY: return "RTPBR_GLTF_ERROR_OUT_OF_MEMORY";
    case RTPBR_GLTF_RESULT_COUNT: break;
    }
    return "RTPBR_GLTF_RESULT_UNKNOWN";
}

namespace {

// The frame of both load entry points: the context from desc, *out cleared, the arguments
// checked (args_ok, else the error null_message), then load(ctx); what it throws becomes the
// result.
template <class Load>
rtpbr_gltf_result guarded_load(const rtpbr_gltf_load_desc* desc, rtpbr_gltf_scene** out, bool args_ok,
                               const char* null_message, Load load) {
    Context ctx;
    try {
        if (out) *out = nullptr;
        if (!setup_context(ctx, desc)) return finish(ctx, ctx.result);
        if (!args_ok) {
            ctx.fail(RTPBR_GLTF_ERROR_INVALID_ARGUMENT, "%s", null_message);
            return finish(ctx, ctx.result);
        }
        return finish(ctx, load(ctx));
    } catch (const std::bad_alloc&) {
        ctx.fail(RTPBR_GLTF_ERROR_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
        ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "%s", e.what());
    }
    return finish(ctx, ctx.result);
}

}  // namespace

extern "C" rtpbr_gltf_result rtpbr_gltf_load(const char* path, const rtpbr_gltf_load_desc* desc,
                                               rtpbr_gltf_scene** out) {
    return guarded_load(desc, out, path && out, "rtpbr_gltf_load: path and out must not be NULL", [&](Context& ctx) {
        std::vector<unsigned char> data;
        std::string why;
        rtpbr_gltf_result r = read_file(path, &data, &why);
        if (r != RTPBR_GLTF_SUCCESS) {
            ctx.fail(r, "cannot read scene '%s': %s", path, why.c_str());
            return r;
        }
        std::string dir;
        if (ctx.desc.base_dir) {
            dir = ctx.desc.base_dir;
        } else {
            std::string p(path);
            size_t slash = p.find_last_of('/');
            dir = slash == std::string::npos ? std::string(".") : slash == 0 ? std::string("/") : p.substr(0, slash);
        }
        if (!set_base_dir(ctx, dir)) return ctx.result;
        return load_model(ctx, data.data(), data.size(), ends_with_glb(path), out);
    });
}

extern "C" rtpbr_gltf_result rtpbr_gltf_load_memory(const void* data, size_t size,
                                                      const rtpbr_gltf_load_desc* desc,
                                                      rtpbr_gltf_scene** out) {
    return guarded_load(desc, out, data && out, "rtpbr_gltf_load_memory: data and out must not be NULL",
                        [&](Context& ctx) {
                            if (ctx.desc.base_dir && !set_base_dir(ctx, ctx.desc.base_dir)) return ctx.result;
                            return load_model(ctx, static_cast<const unsigned char*>(data), size, false, out);
                        });
}

extern "C" void rtpbr_gltf_texture_transform_apply(const rtpbr_gltf_texture_transform* t, float uv[2]) {
    if (!t || !uv || !t->has_transform) return;
    const float c = std::cos(t->rotation), s = std::sin(t->rotation);
    const float u = t->scale[0] * uv[0], v = t->scale[1] * uv[1];
    uv[0] = c * u + s * v + t->offset[0];
    uv[1] = -s * u + c * v + t->offset[1];
}

extern "C" void rtpbr_gltf_destroy(rtpbr_gltf_scene* scene) {
    if (!scene) return;
    Allocator al{scene->allocator};
    for (uint32_t i = 0; scene->primitives && i < scene->primitive_count; ++i) {
        rtpbr_gltf_primitive& p = scene->primitives[i];
        al.release(p.positions);
        al.release(p.normals);
        al.release(p.texcoords);
        al.release(p.texcoords1);
        al.release(p.tangents);
        al.release(p.indices);
    }
    for (uint32_t i = 0; scene->textures && i < scene->texture_count; ++i)
        al.release(scene->textures[i].pixels);
    al.release(scene->primitives);
    al.release(scene->materials);
    al.release(scene->textures);
    al.release(scene->lights);
    al.release(scene->punctual_lights);
    al.release(scene->cameras);
    al.release(scene);
}
