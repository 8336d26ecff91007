// Node hierarchy, validated accessor reads, world-space primitives, cameras.
#include "scene_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace rtpbr_gltf_detail {

Mat4 mat_mul(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += a[size_t(k * 4 + row)] * b[size_t(c * 4 + k)];
            r[size_t(c * 4 + row)] = s;
        }
    return r;
}

Vec3 transform_point(const Mat4& m, const Vec3& p) {
    return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12],
            m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
            m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

Vec3 transform_dir(const Mat4& m, const Vec3& d) {
    return {m[0] * d[0] + m[4] * d[1] + m[8] * d[2], m[1] * d[0] + m[5] * d[1] + m[9] * d[2],
            m[2] * d[0] + m[6] * d[1] + m[10] * d[2]};
}

namespace {

const Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
bool normalize(Vec3* a) {
    double l = length(*a);
    if (!(l > 0.0) || !std::isfinite(l)) return false;
    for (double& x : *a) x /= l;
    return true;
}

// Cofactor matrix of the upper 3×3 (= det · inverse transpose), column-major 3×3.
std::array<double, 9> cofactor3(const Mat4& m, double* det) {
    const Vec3 c0 = {m[0], m[1], m[2]}, c1 = {m[4], m[5], m[6]}, c2 = {m[8], m[9], m[10]};
    const Vec3 a = cross(c1, c2), b = cross(c2, c0), c = cross(c0, c1);
    *det = dot(c0, a);
    return {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]};
}

const char* type_name(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "other";
    }
}

int component_count(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

int component_size(int component_type) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

// Validates accessor `index` (declared type, allowed component types, every
// byte it touches inside its bufferView and buffer, sparse substitution) and
// returns a pointer to its first element and its stride.
struct AccessorView {
    const unsigned char* data = nullptr;  // NULL: no bufferView, all zeros
    size_t count = 0, stride = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
    std::vector<unsigned char> dense;     // sparse accessors, materialised
};

// Locates `count` elements of `element` bytes starting `offset` bytes into
// bufferView `view` (its byteStride apart when use_stride, else packed) and
// checks that all of them lie inside the view and the view inside its buffer.
bool view_slice(Context& ctx, const tinygltf::Model& model, int accessor, const char* part, int view,
                size_t offset, size_t count, size_t element, bool use_stride, const unsigned char** data,
                size_t* stride) {
    if (view < 0 || size_t(view) >= model.bufferViews.size())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                        "accessor %d%s: bufferView %d does not exist (%zu bufferViews)", accessor, part, view,
                        model.bufferViews.size());
    const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "bufferView %d: buffer %d does not exist", view,
                        v.buffer);
    const size_t buffer_size = model.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset > buffer_size || v.byteLength > buffer_size - v.byteOffset)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                        "bufferView %d: byteOffset %zu + byteLength %zu exceeds buffer %d (%zu bytes)", view,
                        v.byteOffset, v.byteLength, v.buffer, buffer_size);
    *stride = use_stride && v.byteStride ? v.byteStride : element;
    if (use_stride && v.byteStride && (v.byteStride < element || v.byteStride > 252))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                        "accessor %d: bufferView %d byteStride %zu invalid for %zu-byte elements", accessor, view,
                        v.byteStride, element);
    // Last byte touched: offset + (count-1)·stride + element ≤ byteLength.
    const size_t room = offset <= v.byteLength ? v.byteLength - offset : 0;
    if (offset > v.byteLength || element > room || (count - 1) > (room - element) / *stride)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                        "accessor %d%s: byteOffset %zu + count %zu * stride %zu exceeds bufferView %d "
                        "(%zu bytes)",
                        accessor, part, offset, count, *stride, view, v.byteLength);
    *data = model.buffers[size_t(v.buffer)].data.data() + v.byteOffset + offset;
    return true;
}

bool validate_accessor(Context& ctx, const tinygltf::Model& model, int index, const char* usage,
                       int expected_type, const int* allowed_components, size_t n_allowed,
                       AccessorView* out) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                        "%s: accessor %d does not exist (%zu accessors)", usage, index,
                        model.accessors.size());
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    if (a.type != expected_type)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor %d (%s): type %s, expected %s",
                        index, usage, type_name(a.type), type_name(expected_type));
    bool allowed = false;
    for (size_t i = 0; i < n_allowed; ++i) allowed = allowed || a.componentType == allowed_components[i];
    if (!allowed)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                        "accessor %d (%s): componentType %d not allowed here", index, usage,
                        a.componentType);
    if (a.count == 0)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor %d (%s): count is 0", index, usage);
    if (a.count > size_t(std::numeric_limits<uint32_t>::max()))
        return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_VERTICES, "accessor %d (%s): count %zu too large",
                        index, usage, a.count);
    out->count = a.count;
    out->component_type = a.componentType;
    out->components = component_count(a.type);
    out->normalized = a.normalized;
    const size_t element = size_t(component_size(a.componentType)) * size_t(out->components);
    out->data = nullptr;  // glTF: no bufferView → zeros
    out->stride = element;
    if (a.bufferView >= 0 && !view_slice(ctx, model, index, "", a.bufferView, a.byteOffset, a.count, element,
                                         true, &out->data, &out->stride))
        return false;
    if (!a.sparse.isSparse) return true;

    // Sparse (glTF 2.0 §3.6.2.3): dense copy of the base, then substitution.
    if (a.count > ctx.max_vertices)
        return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_VERTICES, "accessor %d (%s): sparse count %zu exceeds the limit %u",
                        index, usage, a.count, ctx.max_vertices);
    const int ictype = a.sparse.indices.componentType;
    if (a.sparse.count <= 0 || size_t(a.sparse.count) > a.count || a.sparse.indices.byteOffset < 0 ||
        a.sparse.values.byteOffset < 0 ||
        (ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         ictype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                        "accessor %d (%s): invalid sparse count %d, byteOffset or index componentType %d", index,
                        usage, a.sparse.count, ictype);
    const size_t n_sparse = size_t(a.sparse.count), isize = size_t(component_size(ictype));
    const unsigned char *indices = nullptr, *values = nullptr;
    size_t istride = 0, vstride = 0;
    if (!view_slice(ctx, model, index, " sparse indices", a.sparse.indices.bufferView,
                    size_t(a.sparse.indices.byteOffset), n_sparse, isize, false, &indices, &istride) ||
        !view_slice(ctx, model, index, " sparse values", a.sparse.values.bufferView,
                    size_t(a.sparse.values.byteOffset), n_sparse, element, false, &values, &vstride))
        return false;
    out->dense.assign(a.count * element, 0);
    if (out->data)
        for (size_t i = 0; i < a.count; ++i) std::memcpy(&out->dense[i * element], out->data + i * out->stride, element);
    for (size_t i = 0; i < n_sparse; ++i) {
        uint32_t target = 0;
        if (isize == 1) target = indices[i];
        else if (isize == 2) { uint16_t t; std::memcpy(&t, indices + 2 * i, 2); target = t; }
        else std::memcpy(&target, indices + 4 * i, 4);
        if (target >= a.count)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR, "accessor %d (%s): sparse index %u >= count %zu",
                            index, usage, target, a.count);
        std::memcpy(&out->dense[size_t(target) * element], values + i * element, element);
    }
    out->data = out->dense.data();
    out->stride = element;
    return true;
}

// Reads element i, component c as double (normalised integers mapped to
// [0,1] / [-1,1] per glTF 2.0 §3.11).
double read_component(const AccessorView& v, size_t i, int c) {
    if (!v.data) return 0.0;
    const unsigned char* p = v.data + i * v.stride + size_t(c) * size_t(component_size(v.component_type));
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); return u; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t u; std::memcpy(&u, p, 2);
        return v.normalized ? u / 65535.0 : double(u);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t s; std::memcpy(&s, p, 2);
        return v.normalized ? std::max(s / 32767.0, -1.0) : double(s);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[0] / 255.0 : double(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t s; std::memcpy(&s, p, 1);
        return v.normalized ? std::max(s / 127.0, -1.0) : double(s);
    }
    default: return 0.0;
    }
}

struct Builder {
    Context& ctx;
    const tinygltf::Model& model;
    Scene& scene;
    LightNodes* light_nodes;
    std::vector<char> on_path;
    size_t visits = 0;

    bool primitive(int node_index, const Mat4& world, int mesh_index, int prim_index);
    bool camera(int node_index, const Mat4& world);
    bool node(int index, const Mat4& parent, unsigned depth);
};

// One primitive's way into the scene, in the order a reader follows it: its attributes, its
// triangles, its world-space vertices, then the normals, texture coordinates and tangents
// every vertex carries. Each step that can end early says whether the primitive goes on,
// is skipped (a warning: valid glTF with nothing to draw) or the load fails.
enum class Step { Go, Skip, Fail };

struct PrimitiveReader {
    Context& ctx;
    const tinygltf::Model& model;
    Scene& scene;
    const tinygltf::Primitive& src;
    int node_index;
    const Mat4& world;
    char usage[96];
    AccessorView pos, nrm, uv, uv1, tan;
    size_t n = 0;                // vertices
    std::vector<uint32_t> tris;  // triangle list of the file's indices (strips and fans unrolled)
    std::vector<Vec3> world_pos;
    std::array<double, 9> cof{};  // the world matrix's cofactors (normals)
    double det = 0.0, det_sign = 1.0;
    Primitive p;

    PrimitiveReader(Context& c, const tinygltf::Model& m, Scene& s, int mesh_index, int prim_index, int node,
                    const Mat4& w)
        : ctx(c), model(m), scene(s), src(m.meshes[size_t(mesh_index)].primitives[size_t(prim_index)]),
          node_index(node), world(w) {
        std::snprintf(usage, sizeof usage, "mesh %d primitive %d", mesh_index, prim_index);
    }

    static Step fail(bool) { return Step::Fail; }

    // The mode, POSITION and the other attributes, each validated and as long as POSITION.
    Step attributes() {
        if (src.mode >= 0 && src.mode < TINYGLTF_MODE_TRIANGLES) {
            ctx.warn("%s: points/lines (mode %d) ignored", usage, src.mode);
            return Step::Skip;
        }
        if (src.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            return fail(ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "%s: invalid mode %d", usage, src.mode));
        if (!src.targets.empty()) ctx.warn("%s: morph targets ignored", usage);
        auto pos_it = src.attributes.find("POSITION");
        if (pos_it == src.attributes.end()) {  // valid glTF (the validator warns): nothing to draw
            ctx.warn("%s: no POSITION attribute; primitive skipped", usage);
            return Step::Skip;
        }
        static const int kFloat[] = {TINYGLTF_COMPONENT_TYPE_FLOAT};
        static const int kTexcoord[] = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
        if (!validate_accessor(ctx, model, pos_it->second, "POSITION", TINYGLTF_TYPE_VEC3, kFloat, 1, &pos))
            return Step::Fail;
        if (!pos.data) {  // glTF: no bufferView = zeros; all triangles degenerate, nothing allocated
            ctx.warn("%s: POSITION accessor %d has no bufferView (all zeros); primitive skipped", usage,
                     pos_it->second);
            return Step::Skip;
        }
        n = pos.count;
        if (scene.total_vertices + n > ctx.max_vertices)
            return fail(ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_VERTICES,
                                 "%s (node %d): %llu + %zu vertices exceed the limit of %u", usage, node_index,
                                 static_cast<unsigned long long>(scene.total_vertices), n, ctx.max_vertices));
        auto attribute = [&](const char* name, int type, const int* comps, size_t n_comps, AccessorView* v) {
            auto it = src.attributes.find(name);
            if (it == src.attributes.end()) return true;
            if (!validate_accessor(ctx, model, it->second, name, type, comps, n_comps, v)) return false;
            if (v->count != n)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                                "%s: %s accessor %d has %zu elements, POSITION has %zu", usage, name,
                                it->second, v->count, n);
            return true;
        };
        if (!attribute("NORMAL", TINYGLTF_TYPE_VEC3, kFloat, 1, &nrm) ||
            !attribute("TEXCOORD_0", TINYGLTF_TYPE_VEC2, kTexcoord, 3, &uv) ||
            !attribute("TEXCOORD_1", TINYGLTF_TYPE_VEC2, kTexcoord, 3, &uv1) ||
            !attribute("TANGENT", TINYGLTF_TYPE_VEC4, kFloat, 1, &tan))
            return Step::Fail;
        return Step::Go;
    }

    Step material() {
        if (src.material < 0) {
            p.material = default_material(scene);
        } else if (size_t(src.material) >= model.materials.size()) {
            return fail(ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "%s: material %d does not exist (%zu materials)",
                                 usage, src.material, model.materials.size()));
        } else {
            p.material = uint32_t(src.material);
        }
        return Step::Go;
    }

    // Indices (or the implicit 0..n-1), then triangulation of strips/fans, into tris.
    Step triangles() {
        static const int kIndex[] = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};
        std::vector<uint32_t> raw;
        if (src.indices >= 0) {
            AccessorView idx;
            if (!validate_accessor(ctx, model, src.indices, "indices", TINYGLTF_TYPE_SCALAR, kIndex, 3, &idx))
                return Step::Fail;
            if (!idx.data) {  // all indices 0: every triangle degenerate
                ctx.warn("%s: index accessor %d has no bufferView (all zeros); primitive skipped", usage,
                         src.indices);
                return Step::Skip;
            }
            if (idx.count > RTPBR_GLTF_MAX_INDICES)
                return fail(ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_VERTICES, "%s: %zu indices exceed the limit", usage,
                                     idx.count));
            raw.resize(idx.count);
            for (size_t i = 0; i < idx.count; ++i) {
                double v = read_component(idx, i, 0);
                if (v >= double(n))
                    return fail(ctx.fail(RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE,
                                         "%s: index %.0f at position %zu (accessor %d) >= vertex count %zu", usage,
                                         v, i, src.indices, n));
                raw[i] = uint32_t(v);
            }
        } else {
            raw.resize(n);
            for (size_t i = 0; i < n; ++i) raw[i] = uint32_t(i);
        }
        const int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
        const uint64_t tri_indices = mode == TINYGLTF_MODE_TRIANGLES ? raw.size() / 3 * 3
                                     : raw.size() >= 3             ? 3 * uint64_t(raw.size() - 2)
                                                                   : 0;
        if (scene.total_indices + tri_indices > RTPBR_GLTF_MAX_INDICES)
            return fail(ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_VERTICES,
                                 "%s: index count exceeds RTPBR_GLTF_MAX_INDICES", usage));
        tris.reserve(size_t(tri_indices));
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (raw.size() % 3 != 0)
                ctx.warn("%s: %zu indices is not a multiple of 3; tail dropped", usage, raw.size());
            tris.assign(raw.begin(), raw.begin() + long(raw.size() / 3 * 3));
        } else if (raw.size() >= 3) {
            for (size_t i = 2; i < raw.size(); ++i) {
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // glTF §3.7.2.1 strip winding
                    bool even = (i % 2) == 0;
                    tris.insert(tris.end(), {raw[i - 2], even ? raw[i - 1] : raw[i], even ? raw[i] : raw[i - 1]});
                } else {
                    tris.insert(tris.end(), {raw[0], raw[i - 1], raw[i]});
                }
            }
        }
        return Step::Go;
    }

    // World-space positions (p.positions, and world_pos as the floats read back).
    Step positions() {
        cof = cofactor3(world, &det);
        det_sign = det < 0.0 ? -1.0 : 1.0;
        if (det == 0.0) ctx.warn("node %d: singular transform, %s collapses", node_index, usage);
        world_pos.resize(n);
        p.positions.resize(3 * n);
        for (size_t i = 0; i < n; ++i) {
            Vec3 local = {read_component(pos, i, 0), read_component(pos, i, 1), read_component(pos, i, 2)};
            if (!std::isfinite(local[0]) || !std::isfinite(local[1]) || !std::isfinite(local[2]))
                return fail(ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "%s: POSITION accessor %d element %zu is not finite",
                                     usage, src.attributes.at("POSITION"), i));
            Vec3 w = transform_point(world, local);
            for (int k = 0; k < 3; ++k) {
                if (!std::isfinite(float(w[size_t(k)])))
                    return fail(ctx.fail(RTPBR_GLTF_ERROR_NONFINITE,
                                         "%s (node %d): world position of vertex %zu overflows", usage, node_index, i));
                p.positions[3 * i + size_t(k)] = float(w[size_t(k)]);
            }
            world_pos[i] = {p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]};
        }
        return Step::Go;
    }

    // p.indices: winding follows the world determinant; degenerate triangles are dropped.
    Step kept_triangles() {
        size_t dropped = 0;
        p.indices.reserve(tris.size());
        for (size_t t = 0; t + 2 < tris.size(); t += 3) {
            uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
            if (det < 0.0) std::swap(b, c);
            const Vec3 e1 = sub(world_pos[b], world_pos[a]), e2 = sub(world_pos[c], world_pos[a]);
            const double area2 = length(cross(e1, e2));
            if (a == b || b == c || a == c || !(area2 > 1e-7 * length(e1) * length(e2))) {
                ++dropped;
                continue;
            }
            p.indices.insert(p.indices.end(), {a, b, c});
        }
        if (dropped) ctx.warn("%s (node %d): %zu degenerate triangles dropped", usage, node_index, dropped);
        // Nothing left (a node scaled by 0 is the usual way to hide an object): the primitive is
        // left out, so that neither renderer meets a mesh without triangles.
        if (p.indices.empty()) {
            ctx.warn("%s (node %d): no non-degenerate triangle; primitive skipped", usage, node_index);
            return Step::Skip;
        }
        return Step::Go;
    }

    // Area-weighted vertex normals of the kept triangles.
    std::vector<Vec3> smooth_normals() const {
        std::vector<Vec3> smooth(n, Vec3{0, 0, 0});
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            const uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
            const Vec3 f = cross(sub(world_pos[b], world_pos[a]), sub(world_pos[c], world_pos[a]));
            for (uint32_t v : {a, b, c})
                for (int k = 0; k < 3; ++k) smooth[v][size_t(k)] += f[size_t(k)];
        }
        for (Vec3& s : smooth)
            if (!normalize(&s)) s = {0, 0, 1};
        return smooth;
    }

    // Normals: file normals through the cofactor matrix, else area-weighted.
    void normals() {
        const bool has_normals = nrm.count != 0;
        std::vector<Vec3> smooth;
        p.normals.resize(3 * n);
        bool repaired = false;
        for (size_t i = 0; i < n; ++i) {
            Vec3 nw;
            bool ok = false;
            if (has_normals) {
                const Vec3 l = {read_component(nrm, i, 0), read_component(nrm, i, 1), read_component(nrm, i, 2)};
                if (std::isfinite(l[0]) && std::isfinite(l[1]) && std::isfinite(l[2])) {
                    nw = {cof[0] * l[0] + cof[3] * l[1] + cof[6] * l[2], cof[1] * l[0] + cof[4] * l[1] + cof[7] * l[2],
                          cof[2] * l[0] + cof[5] * l[1] + cof[8] * l[2]};
                    for (double& x : nw) x *= det_sign;
                    ok = normalize(&nw);
                }
                repaired = repaired || !ok;
            }
            if (!ok) {
                if (smooth.empty()) smooth = smooth_normals();
                nw = smooth[i];
            }
            for (int k = 0; k < 3; ++k) p.normals[3 * i + size_t(k)] = float(nw[size_t(k)]);
        }
        p.normals_generated = !has_normals;
        if (repaired) ctx.warn("%s: zero or non-finite normals replaced by generated ones", usage);
    }

    // One TEXCOORD_n set into out (zeros without the attribute).
    Step texcoords(const AccessorView& v, const char* name, std::vector<float>* out) {
        out->assign(2 * n, 0.0f);
        for (size_t i = 0; v.count != 0 && i < n; ++i)
            for (int k = 0; k < 2; ++k) {
                double x = read_component(v, i, k);
                if (!std::isfinite(x))
                    return fail(ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "%s: %s element %zu is not finite", usage, name, i));
                (*out)[2 * i + size_t(k)] = float(x);
            }
        return Step::Go;
    }

    // The file's tangents, to world space (w: the bitangent's sign, flipped by a mirroring node).
    void file_tangents() {
        for (size_t i = 0; i < n; ++i) {
            Vec3 t = {read_component(tan, i, 0), read_component(tan, i, 1), read_component(tan, i, 2)};
            double w = read_component(tan, i, 3);
            if (!std::isfinite(w)) w = 1.0;
            t = transform_dir(world, t);
            if (!normalize(&t)) continue;
            for (int k = 0; k < 3; ++k) p.tangents[4 * i + size_t(k)] = float(t[size_t(k)]);
            p.tangents[4 * i + 3] = float((w < 0.0 ? -1.0 : 1.0) * det_sign);
        }
    }

    // Per-triangle tangent frames from UV gradients (Lengyel 2001, "Computing Tangent Space
    // Basis Vectors"), accumulated per vertex, orthogonalised against the normal.
    void generated_tangents() {
        std::vector<Vec3> ts(n, Vec3{0, 0, 0}), bs(n, Vec3{0, 0, 0});
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            const uint32_t v[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
            const Vec3 e1 = sub(world_pos[v[1]], world_pos[v[0]]), e2 = sub(world_pos[v[2]], world_pos[v[0]]);
            const double du1 = p.texcoords[2 * v[1]] - p.texcoords[2 * v[0]];
            const double dv1 = p.texcoords[2 * v[1] + 1] - p.texcoords[2 * v[0] + 1];
            const double du2 = p.texcoords[2 * v[2]] - p.texcoords[2 * v[0]];
            const double dv2 = p.texcoords[2 * v[2] + 1] - p.texcoords[2 * v[0] + 1];
            const double d = du1 * dv2 - du2 * dv1;
            if (d == 0.0 || !std::isfinite(1.0 / d)) continue;
            const double r = 1.0 / d;
            for (int k = 0; k < 3; ++k) {
                const double tk = (e1[size_t(k)] * dv2 - e2[size_t(k)] * dv1) * r;
                const double bk = (e2[size_t(k)] * du1 - e1[size_t(k)] * du2) * r;
                for (uint32_t vi : v) ts[vi][size_t(k)] += tk, bs[vi][size_t(k)] += bk;
            }
        }
        for (size_t i = 0; i < n; ++i) {
            const Vec3 nn = {p.normals[3 * i], p.normals[3 * i + 1], p.normals[3 * i + 2]};
            Vec3 t = ts[i];
            const double tn = dot(t, nn);
            for (int k = 0; k < 3; ++k) t[size_t(k)] -= nn[size_t(k)] * tn;
            if (!normalize(&t)) {  // no UV gradient: any unit vector ⟂ n
                t = std::fabs(nn[0]) < 0.9 ? cross(nn, Vec3{1, 0, 0}) : cross(nn, Vec3{0, 1, 0});
                normalize(&t);
            }
            for (int k = 0; k < 3; ++k) p.tangents[4 * i + size_t(k)] = float(t[size_t(k)]);
            p.tangents[4 * i + 3] = dot(cross(nn, t), bs[i]) < 0.0 ? -1.0f : 1.0f;
        }
    }

    // Tangents: from the file, else generated when a normal map or an anisotropic lobe needs
    // them (KHR_materials_anisotropy: "when tangents are not specified, client implementations
    // should calculate tangents"; Disney's anisotropy follows the tangent too).
    void tangents() {
        p.tangents.assign(4 * n, 0.0f);
        const rtpbr_gltf_material& mat = scene.materials[p.material];
        const bool wants_tangents = mat.normal_texture >= 0 || mat.anisotropy.anisotropy_strength > 0.0f ||
                                    (mat.has_disney && mat.disney.anisotropic > 0.0f);
        if (tan.count != 0) {
            file_tangents();
            p.has_tangents = true;
        } else if (wants_tangents && uv.count != 0) {
            generated_tangents();
            p.has_tangents = true;
            p.tangents_generated = true;
        } else if (wants_tangents) {
            ctx.warn("%s: normal texture without TEXCOORD_0; tangents left zero", usage);
        }
    }
};

bool Builder::primitive(int node_index, const Mat4& world, int mesh_index, int prim_index) {
    PrimitiveReader r(ctx, model, scene, mesh_index, prim_index, node_index, world);
    for (Step (PrimitiveReader::*step)() : {&PrimitiveReader::attributes, &PrimitiveReader::material,
                                            &PrimitiveReader::triangles, &PrimitiveReader::positions,
                                            &PrimitiveReader::kept_triangles}) {
        const Step s = (r.*step)();
        if (s != Step::Go) return s == Step::Skip;
    }
    r.p.gltf_mesh = mesh_index;
    r.p.gltf_primitive = prim_index;
    r.p.gltf_node = node_index;
    r.p.has_texcoords = r.uv.count != 0;
    r.p.has_texcoords1 = r.uv1.count != 0;
    r.normals();
    if (r.texcoords(r.uv, "TEXCOORD_0", &r.p.texcoords) != Step::Go ||
        r.texcoords(r.uv1, "TEXCOORD_1", &r.p.texcoords1) != Step::Go)
        return false;
    r.tangents();
    scene.total_vertices += r.n;
    scene.total_indices += r.p.indices.size();
    scene.primitives.push_back(std::move(r.p));
    return true;
}

bool Builder::camera(int node_index, const Mat4& world) {
    const int index = model.nodes[size_t(node_index)].camera;
    if (size_t(index) >= model.cameras.size())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "node %d: camera %d does not exist (%zu cameras)",
                        node_index, index, model.cameras.size());
    const tinygltf::Camera& cam = model.cameras[size_t(index)];
    if (cam.type != "perspective") {
        ctx.warn("camera %d: type '%s' ignored (only perspective)", index, cam.type.c_str());
        return true;
    }
    const tinygltf::PerspectiveCamera& pc = cam.perspective;
    if (!fits_float(pc.yfov) || !fits_float(pc.znear) || !fits_float(pc.zfar) || !fits_float(pc.aspectRatio))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "camera %d: non-finite parameter", index);
    if (!(pc.yfov > 0.0 && pc.yfov < 3.14159265358979323846) || pc.znear <= 0.0 || pc.aspectRatio < 0.0 ||
        (pc.zfar != 0.0 && pc.zfar <= pc.znear))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                        "camera %d: needs 0 < yfov < pi, znear > 0, zfar > znear (yfov %g znear %g zfar %g)",
                        index, pc.yfov, pc.znear, pc.zfar);
    rtpbr_gltf_camera c;
    std::memset(&c, 0, sizeof c);
    const Vec3 pos = transform_point(world, {0, 0, 0});
    Vec3 fwd = transform_dir(world, {0, 0, -1}), up = transform_dir(world, {0, 1, 0});
    if (!normalize(&fwd))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: degenerate camera transform", node_index);
    const double uf = dot(up, fwd);
    for (int k = 0; k < 3; ++k) up[size_t(k)] -= uf * fwd[size_t(k)];
    if (!normalize(&up))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: degenerate camera transform", node_index);
    const Vec3 right = cross(fwd, up);
    for (int k = 0; k < 3; ++k) {
        c.position[k] = float(pos[size_t(k)]);
        c.forward[k] = float(fwd[size_t(k)]);
        c.up[k] = float(up[size_t(k)]);
        c.right[k] = float(right[size_t(k)]);
    }
    c.yfov = float(pc.yfov);
    c.aspect = float(pc.aspectRatio);
    c.znear = float(pc.znear);
    c.zfar = float(pc.zfar);
    // Finite doubles can still overflow the floats they are stored in (znear 1e39).
    bool finite = std::isfinite(c.aspect) && std::isfinite(c.znear) && std::isfinite(c.zfar);
    for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(c.position[k]);
    if (!finite)
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "camera %d (node %d): a parameter overflows a float", index,
                        node_index);
    c.gltf_node = node_index;
    c.gltf_camera = index;
    scene.cameras.push_back(c);
    return true;
}

bool Builder::node(int index, const Mat4& parent, unsigned depth) {
    if (index < 0 || size_t(index) >= model.nodes.size())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "node %d does not exist (%zu nodes)", index,
                        model.nodes.size());
    // depth counts from 0 at a root: RTPBR_GLTF_MAX_NODE_DEPTH levels are depths 0 .. MAX-1.
    if (depth >= RTPBR_GLTF_MAX_NODE_DEPTH)
        return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "node %d: hierarchy deeper than %u levels", index,
                        RTPBR_GLTF_MAX_NODE_DEPTH);
    if (on_path[size_t(index)])
        return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "node %d: the node hierarchy has a cycle", index);
    if (++visits > 4 * model.nodes.size() + 1024)
        return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "node %d: nodes are shared by many parents (not a tree)",
                        index);
    const tinygltf::Node& n = model.nodes[size_t(index)];
    Mat4 local;
    if (!node_local_matrix(ctx, n, index, &local)) return false;
    const Mat4 world = mat_mul(parent, local);
    if (n.skin >= 0) ctx.warn("node %d: skin ignored (bind pose used)", index);
    if (n.mesh >= 0) {
        if (size_t(n.mesh) >= model.meshes.size())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "node %d: mesh %d does not exist (%zu meshes)",
                            index, n.mesh, model.meshes.size());
        const size_t count = model.meshes[size_t(n.mesh)].primitives.size();
        for (size_t p = 0; p < count; ++p)
            if (!primitive(index, world, n.mesh, int(p))) return false;
    }
    if (n.camera >= 0 && !camera(index, world)) return false;
    if (n.extensions.count("EXT_lights_area")) light_nodes->area.push_back({index, world});
    if (n.extensions.count("KHR_lights_punctual")) light_nodes->punctual.push_back({index, world});
    on_path[size_t(index)] = 1;
    for (int child : n.children)
        if (!node(child, world, depth + 1)) return false;
    on_path[size_t(index)] = 0;
    return true;
}

}  // namespace

bool node_local_matrix(Context& ctx, const tinygltf::Node& n, int index, Mat4* out) {
    auto finite = [](const std::vector<double>& v) {
        for (double x : v)
            if (!std::isfinite(x)) return false;
        return true;
    };
    if (!finite(n.matrix) || !finite(n.translation) || !finite(n.rotation) || !finite(n.scale))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: non-finite transform", index);
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "node %d: matrix has %zu elements", index, n.matrix.size());
        std::copy(n.matrix.begin(), n.matrix.end(), out->begin());
        return true;
    }
    if ((!n.translation.empty() && n.translation.size() != 3) || (!n.rotation.empty() && n.rotation.size() != 4) ||
        (!n.scale.empty() && n.scale.size() != 3))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "node %d: translation/rotation/scale of wrong length", index);
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (!n.translation.empty()) std::copy(n.translation.begin(), n.translation.end(), t);
    if (!n.rotation.empty()) std::copy(n.rotation.begin(), n.rotation.end(), q);
    if (!n.scale.empty()) std::copy(n.scale.begin(), n.scale.end(), s);
    const double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(ql > 0.0)) return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "node %d: zero rotation quaternion", index);
    if (std::fabs(ql - 1.0) > 1e-3) ctx.warn("node %d: rotation quaternion normalised", index);
    const double x = q[0] / ql, y = q[1] / ql, z = q[2] / ql, w = q[3] / ql;
    // M = T · R · S, R from the unit quaternion (x, y, z, w).
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                         2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                         2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    *out = kIdentity;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) (*out)[size_t(c * 4 + row)] = r[c * 3 + row] * s[c];
    for (int k = 0; k < 3; ++k) (*out)[size_t(12 + k)] = t[k];
    return true;
}

namespace {

// glTF 2.0 requires the nodes to form disjoint strict trees: a node has at most one parent,
// no cycles, and a scene's root nodes are nobody's children. Checked on every node, reached
// or not, so that the answer does not depend on which scene is shown.
bool check_forest(Context& ctx, const tinygltf::Model& model) {
    const size_t count = model.nodes.size();
    std::vector<int> parent(count, -1);
    for (size_t i = 0; i < count; ++i)
        for (int c : model.nodes[i].children) {
            if (c < 0 || size_t(c) >= count)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "node %zu: child %d does not exist (%zu nodes)",
                                i, c, count);
            if (parent[size_t(c)] >= 0)
                return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED,
                                "node %d is a child of both node %d and node %zu (nodes must form a tree)", c,
                                parent[size_t(c)], i);
            parent[size_t(c)] = int(i);
        }
    // With one parent each, a cycle is a parent chain that returns to a node of the same walk.
    std::vector<size_t> walk(count, SIZE_MAX);  // the walk that first visited a node
    for (size_t start = 0; start < count; ++start) {
        for (size_t i = start; walk[i] == SIZE_MAX;) {
            walk[i] = start;
            if (parent[i] < 0) break;
            i = size_t(parent[i]);
            if (walk[i] == start)
                return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "node %zu: the node hierarchy has a cycle", i);
        }
    }
    for (size_t s = 0; s < model.scenes.size(); ++s)
        for (int r : model.scenes[s].nodes) {
            if (r < 0 || size_t(r) >= count)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "scene %zu: node %d does not exist (%zu nodes)",
                                s, r, count);
            if (parent[size_t(r)] >= 0)
                return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED,
                                "scene %zu: root node %d is also a child of node %d (nodes must form a tree)", s, r,
                                parent[size_t(r)]);
        }
    return true;
}

}  // namespace

bool convert_nodes(Context& ctx, const tinygltf::Model& model, Scene& scene, LightNodes* light_nodes) {
    if (!check_forest(ctx, model)) return false;
    Builder b{ctx, model, scene, light_nodes, std::vector<char>(model.nodes.size(), 0), 0};
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int s = model.defaultScene;
        if (s >= 0 && size_t(s) >= model.scenes.size())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "scene %d does not exist (%zu scenes)", s,
                            model.scenes.size());
        roots = model.scenes[size_t(s < 0 ? 0 : s)].nodes;
    } else {  // no scenes: every node that is nobody's child
        std::vector<char> is_child(model.nodes.size(), 0);
        for (const tinygltf::Node& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < model.nodes.size()) is_child[size_t(c)] = 1;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!is_child[i]) roots.push_back(int(i));
    }
    for (int r : roots)
        if (!b.node(r, kIdentity, 0)) return false;
    return true;
}

}  // namespace rtpbr_gltf_detail
