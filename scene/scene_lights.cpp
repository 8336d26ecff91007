// Polygonal area lights: emissive primitives merged into convex polygons of
// at most 8 vertices, and EXT_lights_area rect/disk lights; KHR_lights_punctual
// point, spot and directional lights.
#include "scene_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace rtpbr_gltf_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr size_t kMaxVerts = RTPBR_GLTF_MAX_POLYGON_VERTICES;
// sin of the angle below which three vertices count as collinear, and
// 1 - cos of the angle below which two triangle normals count as parallel.
constexpr double kCollinearSin = 1e-6;
constexpr double kParallelCos = 1e-6;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

// Huge coordinates can make a finite polygon's area or centre overflow a float.
bool facts_finite(const rtpbr_gltf_polygon_facts& f) {
    bool finite = std::isfinite(f.area) && std::isfinite(f.bound_radius);
    for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(f.center[k]) && std::isfinite(f.normal[k]);
    return finite;
}

struct Triangle {
    uint32_t v[3];  // welded vertex ids, counter-clockwise about n
    Vec3 n;         // unit normal
    double area;
};

struct LightBuilder {
    Context& ctx;
    Scene& scene;
    uint32_t primitive_index;
    std::vector<Vec3> verts;  // welded positions
    std::vector<Triangle> tris;
    // Directed edges (a << 32 | b, triangle), sorted: all triangles with edge a→b.
    std::vector<std::pair<uint64_t, uint32_t>> edges;
    double eps_dist = 0.0;
    // BOUNDED mode: stop (over = true, no failure) past this many polygons.
    size_t exact_limit = SIZE_MAX;
    size_t first_light = 0;
    bool over = false;

    static uint64_t key(uint32_t a, uint32_t b) { return uint64_t(a) << 32 | b; }
    // Triangles having the directed edge a→b: [first, last) in `edges`.
    std::pair<const std::pair<uint64_t, uint32_t>*, const std::pair<uint64_t, uint32_t>*> with_edge(
        uint32_t a, uint32_t b) const {
        const uint64_t k = key(a, b);
        auto lo = std::lower_bound(edges.begin(), edges.end(), std::make_pair(k, uint32_t(0)));
        auto hi = lo;
        while (hi != edges.end() && hi->first == k) ++hi;
        return {edges.data() + (lo - edges.begin()), edges.data() + (hi - edges.begin())};
    }

    // Removes collinear vertices (passes until none is left); false if the
    // loop folds back on itself or collapses.
    bool simplify(const std::vector<uint32_t>& loop, std::vector<uint32_t>* out) const {
        std::vector<uint32_t> cur = loop, kept;
        for (;;) {
            const size_t m = cur.size();
            if (m < 3) return false;
            kept.clear();
            bool removed = false;
            for (size_t i = 0; i < m; ++i) {
                const Vec3& p = verts[kept.empty() ? cur[m - 1] : kept.back()];
                const Vec3& c = verts[cur[i]];
                const Vec3& q = verts[cur[(i + 1) % m]];
                const Vec3 e1 = sub(c, p), e2 = sub(q, c);
                if (length(cross(e1, e2)) <= kCollinearSin * length(e1) * length(e2)) {
                    if (dot(e1, e2) < 0.0) return false;  // spike
                    removed = true;
                    continue;
                }
                kept.push_back(cur[i]);
            }
            cur.swap(kept);
            if (!removed) break;
        }
        if (cur.size() < 3) return false;
        *out = std::move(cur);
        return true;
    }

    // Strictly convex and turning about n at every vertex.
    bool convex(const std::vector<uint32_t>& loop, const Vec3& n) const {
        const size_t m = loop.size();
        for (size_t i = 0; i < m; ++i) {
            const Vec3 e1 = sub(verts[loop[i]], verts[loop[(i + m - 1) % m]]);
            const Vec3 e2 = sub(verts[loop[(i + 1) % m]], verts[loop[i]]);
            if (!(dot(cross(e1, e2), n) > kCollinearSin * length(e1) * length(e2))) return false;
        }
        return true;
    }

    // Newell's method: twice the signed area along n.
    double area(const std::vector<uint32_t>& loop, const Vec3& n) const {
        Vec3 s{0, 0, 0};
        for (size_t i = 0; i < loop.size(); ++i) {
            const Vec3 c = cross(verts[loop[i]], verts[loop[(i + 1) % loop.size()]]);
            for (int k = 0; k < 3; ++k) s[size_t(k)] += c[size_t(k)];
        }
        return 0.5 * dot(s, n);
    }

    bool emit(const std::vector<uint32_t>& loop) {
        if (scene.lights.size() - first_light >= exact_limit) {
            over = true;
            return false;
        }
        if (scene.lights.size() >= ctx.max_lights)
            return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS,
                            "primitive %u (mesh %d): more than %u area lights", primitive_index,
                            scene.primitives[primitive_index].gltf_mesh, ctx.max_lights);
        const Primitive& p = scene.primitives[primitive_index];
        const rtpbr_gltf_material& m = scene.materials[p.material];
        rtpbr_gltf_light l;
        std::memset(&l, 0, sizeof l);
        l.shape = RTPBR_GLTF_LIGHT_POLYGON;
        l.vertex_count = uint32_t(loop.size());
        for (size_t i = 0; i < loop.size(); ++i)
            for (int k = 0; k < 3; ++k) l.vertices[i][k] = float(verts[loop[i]][size_t(k)]);
        for (int k = 0; k < 3; ++k) l.radiance[k] = m.emission[k];
        rtpbr_gltf_polygon_facts_of(l.vertices, l.vertex_count, &l.facts);
        // Huge coordinates can make a finite polygon's area overflow a float.
        if (!facts_finite(l.facts))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "primitive %u (mesh %d): light polygon area overflows",
                            primitive_index, p.gltf_mesh);
        if (!(l.facts.area > 0.0f)) {  // underflows to 0: emits nothing
            ctx.warn("primitive %u (mesh %d): light of zero area (as a float) dropped", primitive_index, p.gltf_mesh);
            return true;
        }
        l.two_sided = m.double_sided;
        l.primitive = int32_t(primitive_index);
        l.material = int32_t(p.material);
        l.gltf_node = p.gltf_node;
        l.triangle = -1;
        scene.lights.push_back(l);
        return true;
    }

    bool coplanar(const Triangle& seed, const Triangle& t) const {
        if (dot(seed.n, t.n) < 1.0 - kParallelCos) return false;
        const double d = dot(seed.n, verts[seed.v[0]]);
        for (uint32_t v : t.v)
            if (std::fabs(dot(seed.n, verts[v]) - d) > eps_dist) return false;
        return true;
    }

    // The whole component as one polygon: exactly one boundary loop, convex
    // after removing collinear vertices, ≤ 8 vertices, same area.
    bool single_loop(const std::vector<uint32_t>& comp, const Vec3& n, std::vector<uint32_t>* out) const {
        std::vector<uint64_t> own;  // directed edges of the component, sorted
        own.reserve(3 * comp.size());
        double tri_area = 0.0;
        for (uint32_t t : comp) {
            tri_area += tris[t].area;
            for (int e = 0; e < 3; ++e) own.push_back(key(tris[t].v[e], tris[t].v[(e + 1) % 3]));
        }
        std::sort(own.begin(), own.end());
        if (std::adjacent_find(own.begin(), own.end()) != own.end()) return false;  // non-manifold
        std::vector<std::pair<uint32_t, uint32_t>> next;  // boundary edges a→b, sorted by a
        for (uint64_t e : own) {
            const uint32_t a = uint32_t(e >> 32), b = uint32_t(e);
            if (!std::binary_search(own.begin(), own.end(), key(b, a))) next.push_back({a, b});
        }
        const size_t boundary = next.size();
        if (boundary < 3) return false;
        for (size_t i = 1; i < boundary; ++i)
            if (next[i].first == next[i - 1].first) return false;  // pinched boundary
        std::vector<uint32_t> loop;
        loop.reserve(boundary);
        uint32_t v = next[0].first;
        for (size_t i = 0; i < boundary; ++i) {
            loop.push_back(v);
            auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(v, uint32_t(0)));
            if (it == next.end() || it->first != v) return false;
            v = it->second;
        }
        if (v != loop[0]) return false;  // more than one loop (holes, islands)
        std::vector<uint32_t> simple;
        if (!simplify(loop, &simple) || simple.size() > kMaxVerts || !convex(simple, n)) return false;
        if (std::fabs(area(simple, n) - tri_area) > 1e-4 * tri_area) return false;
        *out = simple;
        return true;
    }

    // Greedy growth of convex pieces across shared edges.
    bool greedy(const std::vector<uint32_t>& comp, const Vec3& n) {
        std::vector<char> remaining(tris.size(), 0);
        for (uint32_t t : comp) remaining[t] = 1;
        for (uint32_t seed : comp) {
            if (!remaining[seed]) continue;
            remaining[seed] = 0;
            std::vector<uint32_t> loop(tris[seed].v, tris[seed].v + 3);
            bool grown = true;
            while (grown) {
                grown = false;
                for (size_t i = 0; i < loop.size() && !grown; ++i) {
                    const uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
                    const auto range = with_edge(b, a);
                    for (auto it = range.first; it != range.second; ++it) {
                        const uint32_t u = it->second;
                        if (!remaining[u]) continue;
                        const Triangle& t = tris[u];
                        uint32_t c = t.v[0] + t.v[1] + t.v[2] - a - b;
                        const size_t m = loop.size();
                        const uint32_t prev = loop[(i + m - 1) % m], after = loop[(i + 2) % m];
                        std::vector<uint32_t> cand = loop;
                        if (c == prev && m > 3) {
                            cand.erase(cand.begin() + long(i));                 // a becomes interior
                        } else if (c == after && m > 3) {
                            cand.erase(cand.begin() + long((i + 1) % m));       // b becomes interior
                        } else if (std::find(loop.begin(), loop.end(), c) == loop.end()) {
                            cand.insert(cand.begin() + long(i + 1), c);
                        } else {
                            continue;
                        }
                        std::vector<uint32_t> simple;
                        if (!simplify(cand, &simple) || simple.size() > kMaxVerts || !convex(simple, n))
                            continue;
                        loop = cand;
                        remaining[u] = 0;
                        grown = true;
                        break;
                    }
                }
            }
            std::vector<uint32_t> simple;
            if (!simplify(loop, &simple)) simple = loop;
            if (!emit(simple)) return false;
        }
        return true;
    }

    bool run() {
        const Primitive& p = scene.primitives[primitive_index];
        std::map<std::array<float, 3>, uint32_t> weld;  // exact positions (+0 == -0)
        std::vector<uint32_t> id(p.positions.size() / 3);
        Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
        for (size_t i = 0; i < id.size(); ++i) {
            std::array<float, 3> pk = {p.positions[3 * i] + 0.0f, p.positions[3 * i + 1] + 0.0f,
                                       p.positions[3 * i + 2] + 0.0f};
            auto ins = weld.insert({pk, uint32_t(verts.size())});
            if (ins.second) {
                verts.push_back({pk[0], pk[1], pk[2]});
                for (int k = 0; k < 3; ++k) {
                    lo[size_t(k)] = std::min(lo[size_t(k)], double(pk[size_t(k)]));
                    hi[size_t(k)] = std::max(hi[size_t(k)], double(pk[size_t(k)]));
                }
            }
            id[i] = ins.first->second;
        }
        eps_dist = 1e-5 * std::max(length(sub(hi, lo)), 1e-30);
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            Triangle tri;
            for (int k = 0; k < 3; ++k) tri.v[k] = id[p.indices[t + size_t(k)]];
            if (tri.v[0] == tri.v[1] || tri.v[1] == tri.v[2] || tri.v[0] == tri.v[2]) continue;
            const Vec3 c = cross(sub(verts[tri.v[1]], verts[tri.v[0]]), sub(verts[tri.v[2]], verts[tri.v[0]]));
            const double l = length(c);
            if (!(l > 0.0)) continue;
            tri.n = scaled(c, 1.0 / l);
            tri.area = 0.5 * l;
            for (int e = 0; e < 3; ++e) edges.push_back({key(tri.v[e], tri.v[(e + 1) % 3]), uint32_t(tris.size())});
            tris.push_back(tri);
        }
        std::sort(edges.begin(), edges.end());
        // Connected components of coplanar, consistently wound triangles.
        std::vector<int> comp_of(tris.size(), -1);
        for (uint32_t s = 0; s < tris.size(); ++s) {
            if (comp_of[s] >= 0) continue;
            std::vector<uint32_t> comp{s}, stack{s};
            comp_of[s] = int(s);
            while (!stack.empty()) {
                const uint32_t t = stack.back();
                stack.pop_back();
                for (int e = 0; e < 3; ++e) {
                    const auto range = with_edge(tris[t].v[(e + 1) % 3], tris[t].v[e]);
                    for (auto it = range.first; it != range.second; ++it) {
                        const uint32_t u = it->second;
                        if (comp_of[u] >= 0 || !coplanar(tris[s], tris[u])) continue;
                        comp_of[u] = int(s);
                        comp.push_back(u);
                        stack.push_back(u);
                    }
                }
            }
            std::sort(comp.begin(), comp.end());
            // Plane normal: area-weighted mean of the member normals.
            Vec3 n{0, 0, 0};
            for (uint32_t t : comp)
                for (int k = 0; k < 3; ++k) n[size_t(k)] += tris[t].n[size_t(k)] * tris[t].area;
            n = scaled(n, 1.0 / length(n));
            std::vector<uint32_t> loop;
            if (comp.size() > 1 && single_loop(comp, n, &loop)) {
                if (!emit(loop)) return false;
            } else if (!greedy(comp, n)) {
                return false;
            }
        }
        return true;
    }
};

// ---- emissive surfaces as bounded light sets (issue 28) ------------------------------------

// The emission texture of a material as the loader decoded it (nullptr: none, or images
// skipped), with the slot's texture coordinate set and transform.
struct EmissionTexture {
    const Texture* texture = nullptr;
    const rtpbr_gltf_texture_transform* transform = nullptr;
};

EmissionTexture emission_texture(const Scene& scene, const rtpbr_gltf_material& m) {
    EmissionTexture e;
    if (m.emission_texture >= 0 && size_t(m.emission_texture) < scene.textures.size()) {
        const Texture& t = scene.textures[size_t(m.emission_texture)];
        if (t.width > 0 && t.height > 0 && t.pixels.size() >= size_t(t.width) * t.height * 4) {
            e.texture = &t;
            e.transform = &m.emission_texture_transform;
        }
    }
    return e;
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double wrap_coord(double x, rtpbr_gltf_wrap mode) {
    if (mode == RTPBR_GLTF_WRAP_CLAMP_TO_EDGE) return std::min(std::max(x, 0.0), 1.0);
    if (mode == RTPBR_GLTF_WRAP_MIRRORED_REPEAT) {
        double f = x - 2.0 * std::floor(x * 0.5);  // [0, 2)
        return f > 1.0 ? 2.0 - f : f;
    }
    return x - std::floor(x);
}

// The texel nearest to uv (linear RGB; the colour space the loader flagged).
Vec3 texel(const Texture& t, double u, double v) {
    if (!std::isfinite(u) || !std::isfinite(v)) return {0, 0, 0};
    u = wrap_coord(u, t.info.wrap_s);
    v = wrap_coord(v, t.info.wrap_t);
    const uint32_t x = std::min(uint32_t(u * t.width), t.width - 1), y = std::min(uint32_t(v * t.height), t.height - 1);
    const uint8_t* px = &t.pixels[(size_t(y) * t.width + x) * 4];
    Vec3 c;
    for (int k = 0; k < 3; ++k) c[size_t(k)] = t.info.srgb ? srgb_to_linear(px[k] / 255.0) : px[k] / 255.0;
    return c;
}

struct EmissiveTriangle {
    Vec3 centroid, normal;  // normal unit
    double area;
    Vec3 radiance;          // emission x the texture's mean over the triangle
    double power;           // area x luminance of radiance
    uint32_t index;         // the primitive's triangle (indices[3 index ..])
};

// The primitive's triangles with their emission: the emissive factor times the texture's mean
// over the triangle, sampled at the 10 points of a 4 x 4 barycentric grid's cells (centres
// and corners' insets); zero-area triangles are left out.
std::vector<EmissiveTriangle> emissive_triangles(const Scene& scene, uint32_t primitive_index, const EmissionTexture& tex) {
    const Primitive& p = scene.primitives[primitive_index];
    const rtpbr_gltf_material& m = scene.materials[p.material];
    const std::vector<float>& uvs = tex.transform && tex.transform->texcoord == 1 ? p.texcoords1 : p.texcoords;
    std::vector<EmissiveTriangle> out;
    out.reserve(p.indices.size() / 3);
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        Vec3 v[3];
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) v[k][size_t(c)] = p.positions[3 * size_t(p.indices[t + size_t(k)]) + size_t(c)];
        const Vec3 c = cross(sub(v[1], v[0]), sub(v[2], v[0]));
        const double l = length(c);
        if (!(l > 0.0) || !std::isfinite(l)) continue;
        EmissiveTriangle e;
        e.normal = scaled(c, 1.0 / l);
        e.area = 0.5 * l;
        for (int k = 0; k < 3; ++k) e.centroid[size_t(k)] = (v[0][size_t(k)] + v[1][size_t(k)] + v[2][size_t(k)]) / 3.0;
        Vec3 mean{1, 1, 1};
        if (tex.texture && uvs.size() >= 2 * (p.positions.size() / 3)) {
            mean = {0, 0, 0};
            int samples = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; i + j < 4; ++j) {
                    const double b1 = (i + 1.0 / 3.0) / 4.0, b2 = (j + 1.0 / 3.0) / 4.0, b0 = 1.0 - b1 - b2;
                    float uv[2] = {0.0f, 0.0f};
                    for (int q = 0; q < 2; ++q) {
                        const double w[3] = {b0, b1, b2};
                        double x = 0.0;
                        for (int k = 0; k < 3; ++k) x += w[k] * uvs[2 * size_t(p.indices[t + size_t(k)]) + size_t(q)];
                        uv[q] = float(x);
                    }
                    rtpbr_gltf_texture_transform_apply(tex.transform, uv);
                    const Vec3 c3 = texel(*tex.texture, uv[0], uv[1]);
                    for (int k = 0; k < 3; ++k) mean[size_t(k)] += c3[size_t(k)];
                    ++samples;
                }
            mean = scaled(mean, 1.0 / samples);
        }
        for (int k = 0; k < 3; ++k) e.radiance[size_t(k)] = double(m.emission[k]) * mean[size_t(k)];
        e.power = e.area * (0.2126 * e.radiance[0] + 0.7152 * e.radiance[1] + 0.0722 * e.radiance[2]);
        e.index = uint32_t(t / 3);
        out.push_back(e);
    }
    return out;
}

rtpbr_gltf_light base_light(const Scene& scene, uint32_t primitive_index) {
    const Primitive& p = scene.primitives[primitive_index];
    rtpbr_gltf_light l;
    std::memset(&l, 0, sizeof l);
    l.shape = RTPBR_GLTF_LIGHT_POLYGON;
    l.two_sided = scene.materials[p.material].double_sided;
    l.primitive = int32_t(primitive_index);
    l.material = int32_t(p.material);
    l.gltf_node = p.gltf_node;
    l.triangle = -1;
    return l;
}

bool push_light(Context& ctx, Scene& scene, uint32_t primitive_index, const rtpbr_gltf_light& l) {
    if (scene.lights.size() >= ctx.max_lights)
        return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS, "primitive %u (mesh %d): more than %u area lights",
                        primitive_index, scene.primitives[primitive_index].gltf_mesh, ctx.max_lights);
    scene.lights.push_back(l);
    return true;
}

// EXACT mode with an emission texture: each triangle its own light (rtpbr_gltf_light.triangle),
// at the factor's radiance: the path tracer applies the texture at each point.
bool triangle_lights(Context& ctx, Scene& scene, uint32_t primitive_index) {
    const Primitive& p = scene.primitives[primitive_index];
    const rtpbr_gltf_material& m = scene.materials[p.material];
    for (const EmissiveTriangle& t : emissive_triangles(scene, primitive_index, EmissionTexture{})) {
        rtpbr_gltf_light l = base_light(scene, primitive_index);
        l.vertex_count = 3;
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c)
                l.vertices[k][c] = p.positions[3 * size_t(p.indices[3 * size_t(t.index) + size_t(k)]) + size_t(c)];
        for (int c = 0; c < 3; ++c) l.radiance[c] = m.emission[c];
        rtpbr_gltf_polygon_facts_of(l.vertices, l.vertex_count, &l.facts);
        l.triangle = int32_t(t.index);
        if (!(l.facts.area > 0.0f) || !facts_finite(l.facts)) continue;
        if (!push_light(ctx, scene, primitive_index, l)) return false;
    }
    return true;
}

// BOUNDED mode, a primitive that does not merge into a few polygons: its triangles in at most
// RTPBR_GLTF_MAX_EMITTER_CLUSTERS clusters (Lloyd's k-means on position over the primitive's
// extent and unit normal, weighted by power, seeded by farthest points from the most powerful
// triangle; deterministic), each an equal-area regular octagon at the cluster's power-weighted
// centroid, facing its power-weighted mean normal, at its area-weighted mean radiance.
bool cluster_lights(Context& ctx, Scene& scene, uint32_t primitive_index, const EmissionTexture& tex) {
    std::vector<EmissiveTriangle> tris = emissive_triangles(scene, primitive_index, tex);
    tris.erase(std::remove_if(tris.begin(), tris.end(), [](const EmissiveTriangle& t) { return !(t.power > 0.0); }),
               tris.end());
    if (tris.empty()) return true;
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const EmissiveTriangle& t : tris)
        for (int k = 0; k < 3; ++k) {
            lo[size_t(k)] = std::min(lo[size_t(k)], t.centroid[size_t(k)]);
            hi[size_t(k)] = std::max(hi[size_t(k)], t.centroid[size_t(k)]);
        }
    const double extent = std::max(length(sub(hi, lo)), 1e-30);
    auto distance2 = [extent](const EmissiveTriangle& t, const Vec3& c, const Vec3& n) {
        const Vec3 d = scaled(sub(t.centroid, c), 1.0 / extent), dn = sub(t.normal, n);
        return dot(d, d) + dot(dn, dn);
    };
    const size_t k = std::min<size_t>(RTPBR_GLTF_MAX_EMITTER_CLUSTERS, tris.size());
    std::vector<Vec3> centres, normals;
    size_t seed = 0;
    for (size_t i = 1; i < tris.size(); ++i)
        if (tris[i].power > tris[seed].power) seed = i;
    centres.push_back(tris[seed].centroid);
    normals.push_back(tris[seed].normal);
    std::vector<double> nearest(tris.size(), 1e300);
    while (centres.size() < k) {
        size_t far = 0;
        for (size_t i = 0; i < tris.size(); ++i) {
            nearest[i] = std::min(nearest[i], distance2(tris[i], centres.back(), normals.back()));
            if (nearest[i] > nearest[far]) far = i;
        }
        if (!(nearest[far] > 0.0)) break;  // fewer distinct triangles than clusters
        centres.push_back(tris[far].centroid);
        normals.push_back(tris[far].normal);
    }
    std::vector<size_t> cluster(tris.size(), 0);
    for (int iteration = 0; iteration < 12; ++iteration) {
        for (size_t i = 0; i < tris.size(); ++i) {
            double best = 1e300;
            for (size_t c = 0; c < centres.size(); ++c) {
                const double d = distance2(tris[i], centres[c], normals[c]);
                if (d < best) best = d, cluster[i] = c;
            }
        }
        for (size_t c = 0; c < centres.size(); ++c) {
            Vec3 sc{0, 0, 0}, sn{0, 0, 0};
            double w = 0.0;
            for (size_t i = 0; i < tris.size(); ++i)
                if (cluster[i] == c) {
                    for (int q = 0; q < 3; ++q) {
                        sc[size_t(q)] += tris[i].power * tris[i].centroid[size_t(q)];
                        sn[size_t(q)] += tris[i].power * tris[i].normal[size_t(q)];
                    }
                    w += tris[i].power;
                }
            if (!(w > 0.0)) continue;
            centres[c] = scaled(sc, 1.0 / w);
            const double ln = length(sn);
            if (ln > 0.0) normals[c] = scaled(sn, 1.0 / ln);
        }
    }
    for (size_t c = 0; c < centres.size(); ++c) {
        double area = 0.0;
        Vec3 power{0, 0, 0};
        for (size_t i = 0; i < tris.size(); ++i)
            if (cluster[i] == c) {
                area += tris[i].area;
                for (int q = 0; q < 3; ++q) power[size_t(q)] += tris[i].area * tris[i].radiance[size_t(q)];
            }
        if (!(area > 0.0)) continue;
        const Vec3 n = normals[c];
        // tangent frame of the octagon: t1 perpendicular to n, t2 = n x t1 (counter-clockwise about n)
        const Vec3 axis = std::fabs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        Vec3 t1 = cross(axis, n);
        t1 = scaled(t1, 1.0 / length(t1));
        const Vec3 t2 = cross(n, t1);
        const double r = std::sqrt(area / (2.0 * std::sqrt(2.0)));  // regular octagon: area 2 sqrt(2) r^2
        rtpbr_gltf_light l = base_light(scene, primitive_index);
        l.vertex_count = 8;
        for (int v = 0; v < 8; ++v) {
            const double a = kPi * 0.25 * v, ca = std::cos(a), sa = std::sin(a);
            for (int q = 0; q < 3; ++q)
                l.vertices[v][q] = float(centres[c][size_t(q)] + r * (ca * t1[size_t(q)] + sa * t2[size_t(q)]));
        }
        for (int q = 0; q < 3; ++q) l.radiance[q] = float(power[size_t(q)] / area);
        rtpbr_gltf_polygon_facts_of(l.vertices, l.vertex_count, &l.facts);
        l.proxy = true;
        if (!(l.facts.area > 0.0f) || !facts_finite(l.facts)) continue;
        if (!push_light(ctx, scene, primitive_index, l)) return false;
    }
    return true;
}

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

double number_or(const tinygltf::Value& obj, const char* key, double def, bool* bad) {
    if (!obj.IsObject() || !obj.Has(key)) return def;
    const tinygltf::Value& v = obj.Get(key);
    if (!v.IsNumber()) {
        *bad = true;
        return def;
    }
    return v.GetNumberAsDouble();
}

// The index of the light a node's `extension` ({"light": n}) references: an integer below
// count, else the load fails (false).
bool node_light(Context& ctx, const tinygltf::Model& model, int node, const char* extension, size_t count,
                int* index) {
    const tinygltf::Value& ref = model.nodes[size_t(node)].extensions.at(extension);
    bool bad = false;
    const double li = number_or(ref, "light", -1.0, &bad);
    if (bad || !ref.IsObject() || !ref.Has("light") || li != std::floor(li))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "node %d: %s.light must be an integer", node, extension);
    if (li < 0.0 || li >= double(count))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "node %d: %s light %.0f does not exist (%zu lights)", node,
                        extension, li, count);
    *index = int(li);
    return true;
}

}  // namespace

bool lights_from_primitive(Context& ctx, Scene& scene, uint32_t primitive_index) {
    const Primitive& p = scene.primitives[primitive_index];
    const rtpbr_gltf_material& m = scene.materials[p.material];
    if (!(std::max(m.emission[0], std::max(m.emission[1], m.emission[2])) > 0.0f)) return true;
    const EmissionTexture tex = emission_texture(scene, m);
    if (ctx.desc.emissive_mode == RTPBR_GLTF_EMISSIVE_EXACT) {
        if (tex.texture) return triangle_lights(ctx, scene, primitive_index);
        LightBuilder b{ctx, scene, primitive_index, {}, {}, {}, 0.0};
        return b.run();
    }
    // BOUNDED: exact polygons where the primitive merges into a few, else clusters.
    LightBuilder b{ctx, scene, primitive_index, {}, {}, {}, 0.0};
    b.exact_limit = RTPBR_GLTF_MAX_EXACT_EMITTER_POLYGONS;
    b.first_light = scene.lights.size();
    if (!b.run() && !b.over) return false;
    if (!b.over) {
        if (tex.texture) {  // the texture's mean over the primitive, on every polygon
            const std::vector<EmissiveTriangle> tris = emissive_triangles(scene, primitive_index, tex);
            double area = 0.0;
            Vec3 power{0, 0, 0};
            for (const EmissiveTriangle& t : tris) {
                area += t.area;
                for (int k = 0; k < 3; ++k) power[size_t(k)] += t.area * t.radiance[size_t(k)];
            }
            for (size_t i = b.first_light; i < scene.lights.size(); ++i)
                for (int k = 0; k < 3; ++k)
                    scene.lights[i].radiance[k] = area > 0.0 ? float(power[size_t(k)] / area) : 0.0f;
        }
        return true;
    }
    scene.lights.resize(b.first_light);
    return cluster_lights(ctx, scene, primitive_index, tex);
}

bool lights_from_ext_area(Context& ctx, const tinygltf::Model& model, Scene& scene,
                          const std::vector<std::pair<int, Mat4>>& light_nodes) {
    if (light_nodes.empty()) return true;
    const tinygltf::Value* lights = nullptr;
    auto root = model.extensions.find("EXT_lights_area");
    if (root != model.extensions.end() && root->second.IsObject() && root->second.Has("lights") &&
        root->second.Get("lights").IsArray())
        lights = &root->second.Get("lights");
    for (const auto& ln : light_nodes) {
        const int node = ln.first;
        const Mat4& world = ln.second;
        int index = -1;
        if (!node_light(ctx, model, node, "EXT_lights_area", lights ? lights->ArrayLen() : 0, &index)) return false;
        bool bad = false;
        const tinygltf::Value& L = lights->Get(index);
        if (!L.IsObject())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "EXT_lights_area light %d is not an object", index);
        // Current draft: "type" + "size" (+ "rect.aspect") + "intensity";
        // the earlier draft of the same pull request: "shape", "width",
        // "height", "radius", "luminance". Both are read.
        std::string type;
        for (const char* key : {"type", "shape"})
            if (type.empty() && L.Has(key) && L.Get(key).IsString()) type = L.Get(key).Get<std::string>();
        if (type != "rect" && type != "disk")
            return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "EXT_lights_area light %d: type '%s' not supported",
                            index, type.c_str());
        float color[3] = {1, 1, 1};
        if (L.Has("color")) {
            const tinygltf::Value& c = L.Get("color");
            if (!c.IsArray() || c.ArrayLen() != 3)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "EXT_lights_area light %d: color must be 3 numbers",
                                index);
            for (int k = 0; k < 3; ++k) {
                if (!c.Get(k).IsNumber()) bad = true;
                color[k] = float(c.Get(k).GetNumberAsDouble());
            }
        }
        const double intensity = number_or(L, "intensity", number_or(L, "luminance", 1000.0, &bad), &bad);
        const bool has_size = L.Has("size");
        const double size = number_or(L, "size", 1.0, &bad);
        const double aspect = L.Has("rect") ? number_or(L.Get("rect"), "aspect", 1.0, &bad) : 1.0;
        double width = number_or(L, "width", 1.0, &bad), height = number_or(L, "height", 1.0, &bad);
        double radius = number_or(L, "radius", 0.5, &bad);
        if (has_size || (!L.Has("width") && !L.Has("height") && !L.Has("radius"))) {
            height = size;
            width = size * aspect;
            radius = 0.5 * size;
        }
        if (bad)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "EXT_lights_area light %d: a property is not a number",
                            index);
        const double values[] = {color[0], color[1], color[2], intensity, width, height, radius};
        for (double v : values)
            if (!fits_float(v))
                return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "EXT_lights_area light %d: non-finite property", index);
        if (color[0] < 0 || color[1] < 0 || color[2] < 0 || intensity < 0.0 || width <= 0.0 ||
            height <= 0.0 || radius <= 0.0)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                            "EXT_lights_area light %d: color/intensity must be >= 0 and sizes > 0", index);

        // Node frame: centre, rotation by Gram-Schmidt; the world columns of local X and Y.
        const Vec3 center = transform_point(world, {0, 0, 0});
        Vec3 x = {world[0], world[1], world[2]}, y = {world[4], world[5], world[6]};
        const Vec3 column_x = x, column_y = y;
        const double lx = length(x);
        if (!(lx > 0.0))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: degenerate transform for an area light", node);
        x = scaled(x, 1.0 / lx);
        const double shear = dot(x, y); // the y column's part along x
        y = sub(y, scaled(x, shear));
        const double ly = length(y);
        if (!(ly > 0.0))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: degenerate transform for an area light", node);
        y = scaled(y, 1.0 / ly);

        if (scene.lights.size() >= ctx.max_lights)
            return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS, "node %d: more than %u area lights", node,
                            ctx.max_lights);
        rtpbr_gltf_light l;
        std::memset(&l, 0, sizeof l);
        // (x, y) in the light plane, clockwise about +Z: the light emits towards local -Z
        std::vector<std::array<double, 2>> local;
        if (type == "rect") {
            // The rect's image under the node's transform: its corners through the world columns of
            // local X and Y (a parallelogram under an uneven scale with a turn between scales; the
            // draft's uniform scale scales it alike). (x, y) becomes those columns for the corners.
            const double hw = 0.5 * width, hh = 0.5 * height;
            l.shape = RTPBR_GLTF_LIGHT_POLYGON;
            local = {{-hw, -hh}, {-hw, hh}, {hw, hh}, {hw, -hh}};
            x = column_x;
            y = column_y;
        } else {
            // The disk's image under the node's transform, an ellipse: in the orthonormal (x, y)
            // the map is A = [lx shear; 0 ly], whose singular values are the half-axes (per unit
            // radius) along the eigenvectors of A A^T (angle t: tan 2t = 2 b / (a - d)).
            const double a = lx * lx + shear * shear, b = shear * ly, d = ly * ly;
            const double mid = 0.5 * (a + d), half = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
            const double s1 = std::sqrt(mid + half), s2 = std::sqrt(std::max(mid - half, 0.0));
            const double t = 0.5 * std::atan2(2.0 * b, a - d);
            const Vec3 e1 = add(scaled(x, std::cos(t)), scaled(y, std::sin(t)));
            const Vec3 e2 = add(scaled(x, -std::sin(t)), scaled(y, std::cos(t)));
            x = e1; // (x, y) stays a right-handed frame of the plane: e2 is e1 turned by +90 degrees
            y = e2;
            const double r1 = radius * s1, r2 = radius * s2;
            // Octagon with the ellipse's area: 2·sqrt(2)·R1·R2 = π r1 r2 (a regular one for a disk).
            const double k = std::sqrt(kPi / (2.0 * std::sqrt(2.0)));
            l.shape = RTPBR_GLTF_LIGHT_DISK;
            for (int v = 0; v < 8; ++v) {
                const double ang = -2.0 * kPi * v / 8.0;
                local.push_back({k * r1 * std::cos(ang), k * r2 * std::sin(ang)});
            }
            l.radius = float(r1);
            l.radius2 = float(r2);
            for (int c = 0; c < 3; ++c) l.axis[c] = float(e1[size_t(c)]);
            if (!(r2 > 0.0))
                return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: degenerate transform for an area light", node);
        }
        l.vertex_count = uint32_t(local.size());
        for (size_t i = 0; i < local.size(); ++i)
            for (int k = 0; k < 3; ++k)
                l.vertices[i][k] = float(center[size_t(k)] + x[size_t(k)] * local[i][0] + y[size_t(k)] * local[i][1]);
        for (int k = 0; k < 3; ++k) l.radiance[k] = float(color[k] * intensity * ctx.area_light_radiance_scale);
        bool finite = std::isfinite(l.radius) && std::isfinite(l.radius2);
        for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(l.radiance[k]);
        for (const auto& v : l.vertices)
            for (float f : v) finite = finite && std::isfinite(f);
        rtpbr_gltf_polygon_facts_of(l.vertices, l.vertex_count, &l.facts);
        finite = finite && facts_finite(l.facts);
        finite = finite && l.facts.area > 0.0f;  // finite doubles can underflow the float area
        if (!finite)
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: area light %d: radiance or area not representable as a float",
                            node, index);
        l.two_sided = false;
        l.primitive = -1;
        l.material = -1;
        l.gltf_node = node;
        l.triangle = -1;
        scene.lights.push_back(l);
    }
    return true;
}

bool lights_from_khr_punctual(Context& ctx, const tinygltf::Model& model, Scene& scene,
                              const std::vector<std::pair<int, Mat4>>& light_nodes) {
    // check_schema has checked the extension's JSON (types, ranges, the cones, every node's
    // index), which tinygltf's model.lights then holds as written; what is left to check here
    // is what the node and desc add: the world frame and the float range of the results.
    for (const auto& ln : light_nodes) {
        const int node = ln.first;
        const Mat4& world = ln.second;
        int index = -1;
        if (!node_light(ctx, model, node, "KHR_lights_punctual", model.lights.size(), &index)) return false;
        const tinygltf::Light& L = model.lights[size_t(index)];
        rtpbr_gltf_punctual_light p;
        std::memset(&p, 0, sizeof p);
        if (L.type == "point") p.type = RTPBR_GLTF_PUNCTUAL_POINT;
        else if (L.type == "spot") p.type = RTPBR_GLTF_PUNCTUAL_SPOT;
        else if (L.type == "directional") p.type = RTPBR_GLTF_PUNCTUAL_DIRECTIONAL;
        else
            return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED, "node %d: KHR_lights_punctual light %d: type '%s' not supported",
                            node, index, L.type.size() > 40 ? "..." : L.type.c_str());
        if (!L.color.empty() && L.color.size() != 3)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "KHR_lights_punctual light %d: color must be 3 numbers", index);

        // The node's origin, and its -Z axis (the matrix's third column negated); scale is
        // left out by normalising.
        const Vec3 position = transform_point(world, {0, 0, 0});
        Vec3 direction = {-world[8], -world[9], -world[10]};
        const double len = length(direction);
        if (std::isfinite(len) && len > 0.0) {
            direction = scaled(direction, 1.0 / len);
        } else if (p.type == RTPBR_GLTF_PUNCTUAL_POINT) {
            direction = {0, 0, -1};  // unused by a point light: any unit vector
        } else {
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE,
                            "node %d: KHR_lights_punctual light %d: degenerate transform (the node's -Z axis has no direction)",
                            node, index);
        }
        for (int k = 0; k < 3; ++k) {
            p.position[k] = float(position[size_t(k)]);
            p.direction[k] = float(direction[size_t(k)]);
            const double color = L.color.empty() ? 1.0 : L.color[size_t(k)];
            p.intensity[k] = float(color * L.intensity * ctx.area_light_radiance_scale);
        }
        if (p.type != RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) {
            p.range = float(L.range);
        } else if (L.range > 0.0) {
            ctx.warn("node %d: KHR_lights_punctual light %d: range ignored on a directional light", node, index);
        }
        if (p.type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) p.angular_diameter = RTPBR_GLTF_SUN_ANGULAR_DIAMETER;
        // A point light's sphere (check_schema read it; 0 on the other types); the node's scale
        // does not change it, as it changes no range.
        const double radius = size_t(index) < ctx.punctual_radii.size() ? ctx.punctual_radii[size_t(index)] : 0.0;
        p.radius = float(radius);
        // Its capsule's length (0 without a radius: check_schema warned), unscaled like the
        // radius, along the node's +X axis (the matrix's first column, normalised).
        const double length_m = size_t(index) < ctx.punctual_lengths.size() ? ctx.punctual_lengths[size_t(index)] : 0.0;
        p.length = float(length_m);
        Vec3 axis = {world[0], world[1], world[2]};
        const double axis_len = length(axis);
        axis = std::isfinite(axis_len) && axis_len > 0.0 ? scaled(axis, 1.0 / axis_len) : Vec3{1, 0, 0};
        for (int k = 0; k < 3; ++k) p.axis[k] = float(axis[size_t(k)]);
        if (p.type == RTPBR_GLTF_PUNCTUAL_SPOT) {
            p.inner_cone_angle = float(L.spot.innerConeAngle);
            p.outer_cone_angle = float(L.spot.outerConeAngle);
        }
        if (!finite3(p.position) || !finite3(p.intensity))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE,
                            "node %d: KHR_lights_punctual light %d: position or intensity (color x intensity x "
                            "area_light_radiance_scale) not representable as a float",
                            node, index);
        if (p.type != RTPBR_GLTF_PUNCTUAL_DIRECTIONAL && L.range > 0.0 && !(p.range > 0.0f))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "node %d: KHR_lights_punctual light %d: range %g underflows a float",
                            node, index, L.range);
        if (radius > 0.0 && length_m > 0.0) {
            // The capsule's area 2 pi r (2 r + L) and radiance 2 intensity / (pi r (2 r + L))
            // (its total power stays the point light's 4 pi intensity) must be floats too.
            const double r = double(p.radius), L = double(p.length);
            const double area = 2.0 * kPi * r * (2.0 * r + L);
            bool fits = p.radius > 0.0f && p.length > 0.0f && fits_float(area);
            for (int k = 0; k < 3 && fits; ++k) fits = fits_float(4.0 * double(p.intensity[k]) / area);
            if (!fits)
                return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE,
                                "node %d: KHR_lights_punctual light %d: radius %g, length %g: the capsule's area "
                                "(2 pi radius (2 radius + length)) or radiance (4 intensity / area) not representable "
                                "as a float",
                                node, index, radius, length_m);
        } else if (radius > 0.0) {
            // The sphere's area and radiance, intensity / (pi radius^2), must be floats too.
            const double area = kPi * double(p.radius) * double(p.radius);
            bool fits = p.radius > 0.0f && fits_float(area);
            for (int k = 0; k < 3 && fits; ++k) fits = fits_float(double(p.intensity[k]) / area);
            if (!fits)
                return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE,
                                "node %d: KHR_lights_punctual light %d: radius %g: the sphere's area (pi radius^2) or "
                                "radiance (intensity / area) not representable as a float",
                                node, index, radius);
        }
        if (scene.lights.size() + scene.punctual_lights.size() >= ctx.max_lights)
            return ctx.fail(RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS,
                            "node %d: more than %u lights (area lights and KHR_lights_punctual lights together)", node,
                            ctx.max_lights);
        p.gltf_node = node;
        p.gltf_light = index;
        scene.punctual_lights.push_back(p);
    }
    return true;
}

}  // namespace rtpbr_gltf_detail

extern "C" void rtpbr_gltf_polygon_facts_of(const float (*v)[3], uint32_t count, rtpbr_gltf_polygon_facts* out) {
    if (!out) return;
    std::memset(out, 0, sizeof *out);
    if (!v || count < 3 || count > RTPBR_GLTF_MAX_POLYGON_VERTICES) return;
    // Newell's method: a normal whose length is twice the polygon's area.
    double n[3] = {0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < count; ++i) {
        const float *a = v[i], *b = v[(i + 1) % count];
        n[0] += (double(a[1]) - b[1]) * (double(a[2]) + b[2]);
        n[1] += (double(a[2]) - b[2]) * (double(a[0]) + b[0]);
        n[2] += (double(a[0]) - b[0]) * (double(a[1]) + b[1]);
    }
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0)
        for (int k = 0; k < 3; ++k) out->normal[k] = float(n[k] / len);
    out->area = float(0.5 * len);
    // Bounding sphere: centred on the vertex mean (not minimal, but bounding).
    double c[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
    for (uint32_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) c[k] += v[i][k] / double(count);
    for (uint32_t i = 0; i < count; ++i) {
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) d2 += (v[i][k] - c[k]) * (v[i][k] - c[k]);
        if (d2 > r2) r2 = d2;
    }
    for (int k = 0; k < 3; ++k) out->center[k] = float(c[k]);
    out->bound_radius = float(std::sqrt(r2) * (1.0 + 1e-6)) + 1e-6f;  // rounding must not shrink it
    // The fan (v0, v[k+1], v[k+2]).
    for (uint32_t k = 0; k + 2 < count; ++k) {
        double e1[3], e2[3];
        for (int q = 0; q < 3; ++q) {
            e1[q] = double(v[k + 1][q]) - v[0][q];
            e2[q] = double(v[k + 2][q]) - v[0][q];
        }
        using namespace rtpbr_gltf_detail;
        out->fan_area[k] = float(0.5 * length(cross({e1[0], e1[1], e1[2]}, {e2[0], e2[1], e2[2]})));
    }
}

