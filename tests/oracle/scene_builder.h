// Hand-built rtpbr scenes for the oracle tests (the loader's structs are plain data).
#ifndef RTPBR_TESTS_ORACLE_SCENE_BUILDER_H
#define RTPBR_TESTS_ORACLE_SCENE_BUILDER_H

#include <rtpbr/rtpbr_gltf.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <vector>

struct SceneBuilder {
    std::deque<std::vector<float>> floatArrays;
    std::deque<std::vector<uint32_t>> indexArrays;
    std::vector<rtpbr_gltf_primitive> primitives;
    std::vector<rtpbr_gltf_material> materials;
    std::vector<rtpbr_gltf_light> lights;
    std::vector<rtpbr_gltf_punctual_light> punctualLights;
    std::vector<rtpbr_gltf_camera> cameras;
    rtpbr_gltf_scene scene{};

    uint32_t material(glm::vec3 base, float metallic, float roughness) {
        rtpbr_gltf_material m{};
        m.base_color[0] = base.x;
        m.base_color[1] = base.y;
        m.base_color[2] = base.z;
        m.base_color[3] = 1.0f;
        m.metallic = metallic;
        m.roughness = roughness;
        m.specular.specular_color_factor[0] = m.specular.specular_color_factor[1] =
            m.specular.specular_color_factor[2] = 1.0f;
        m.specular.specular_factor = 1.0f;
        m.ior.ior = 1.5f;
        m.emissive_strength.emissive_strength = 1.0f;
        m.disney.specular = 0.5f;
        m.disney.clearcoat_gloss = 1.0f;
        m.normal_scale = 1.0f;
        m.alpha_cutoff = 0.5f;
        m.base_color_texture = m.metallic_roughness_texture = m.normal_texture = m.emission_texture = -1;
        m.specular.specular_texture = m.specular.specular_color_texture = -1;
        m.clearcoat.clearcoat_texture = m.clearcoat.clearcoat_roughness_texture = m.clearcoat.clearcoat_normal_texture = -1;
        m.sheen.sheen_color_texture = m.sheen.sheen_roughness_texture = -1;
        m.gltf_material = -1;
        materials.push_back(m);
        return uint32_t(materials.size() - 1);
    }

    // A convex planar polygon as a triangle fan primitive, normal (v1 - v0) x (v2 - v0).
    void polygon(const std::vector<glm::vec3> &v, uint32_t mat) {
        glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
        std::vector<float> pos, nrm;
        for (glm::vec3 p : v) {
            pos.insert(pos.end(), {p.x, p.y, p.z});
            nrm.insert(nrm.end(), {n.x, n.y, n.z});
        }
        std::vector<uint32_t> idx;
        for (uint32_t k = 1; k + 1 < v.size(); k++)
            idx.insert(idx.end(), {0u, k, k + 1});
        rtpbr_gltf_primitive p{};
        p.vertex_count = uint32_t(v.size());
        p.index_count = uint32_t(idx.size());
        floatArrays.push_back(pos);
        p.positions = floatArrays.back().data();
        floatArrays.push_back(nrm);
        p.normals = floatArrays.back().data();
        floatArrays.push_back(std::vector<float>(2 * v.size(), 0.0f));
        p.texcoords = floatArrays.back().data();
        floatArrays.push_back(std::vector<float>(4 * v.size(), 0.0f));
        p.tangents = floatArrays.back().data();
        indexArrays.push_back(idx);
        p.indices = indexArrays.back().data();
        p.material = mat;
        p.gltf_mesh = p.gltf_primitive = p.gltf_node = -1;
        primitives.push_back(p);
    }

    // A light polygon without geometry of its own (like EXT_lights_area); material -1 = black.
    void light(const std::vector<glm::vec3> &v, glm::vec3 radiance, bool twoSided, int32_t mat = -1) {
        rtpbr_gltf_light L{};
        L.shape = RTPBR_GLTF_LIGHT_POLYGON;
        L.vertex_count = uint32_t(v.size());
        for (size_t k = 0; k < v.size(); k++)
            for (int i = 0; i < 3; i++)
                L.vertices[k][i] = v[k][i];
        for (int i = 0; i < 3; i++)
            L.radiance[i] = radiance[i];
        rtpbr_gltf_polygon_facts_of(L.vertices, L.vertex_count, &L.facts); // as the loader does
        L.two_sided = twoSided;
        L.primitive = -1;
        L.material = mat;
        L.gltf_node = -1;
        lights.push_back(L);
    }

    // An EXT_lights_area disk as the loader fills it (scene_lights.cpp): shape DISK, the radius,
    // the equal-area octagon (diskOctagon) as its vertices and their facts (the octagon's
    // centre and normal are the disk's); material -1 = black.
    void disk(glm::vec3 centre, glm::vec3 normal, float radius, glm::vec3 radiance, bool twoSided, int32_t mat = -1) {
        light(diskOctagon(centre, normal, radius), radiance, twoSided, mat);
        lights.back().shape = RTPBR_GLTF_LIGHT_DISK;
        lights.back().radius = radius;
    }

    // An ellipse (issue 30): half-axes r1 along axis (unit, in the plane) and r2 across it, as the
    // loader gives an EXT_lights_area disk under an uneven scale (its octagon stretched alike).
    void ellipse(glm::vec3 centre, glm::vec3 normal, glm::vec3 axis, float r1, float r2, glm::vec3 radiance,
                 bool twoSided) {
        const double pi = 3.14159265358979323846;
        const glm::dvec3 n = glm::normalize(glm::dvec3(normal)), t = glm::dvec3(axis), b = glm::cross(n, t);
        const double R = std::sqrt(pi / (2.0 * std::sqrt(2.0)));
        std::vector<glm::vec3> v;
        for (int k = 0; k < 8; k++) {
            const double a = 2.0 * pi * k / 8.0;
            v.push_back(glm::vec3(glm::dvec3(centre) + R * (r1 * std::cos(a) * t + r2 * std::sin(a) * b)));
        }
        light(v, radiance, twoSided);
        lights.back().shape = RTPBR_GLTF_LIGHT_DISK;
        lights.back().radius = r1;
        lights.back().radius2 = r2;
        for (int k = 0; k < 3; k++) lights.back().axis[k] = axis[k];
    }

    // The regular octagon of the disk's area (2 sqrt(2) R^2 = pi r^2) the loader gives a disk,
    // counter-clockwise about normal (its emitting side), a vertex along diskTangent(normal).
    static std::vector<glm::vec3> diskOctagon(glm::vec3 centre, glm::vec3 normal, float radius) {
        const double pi = 3.14159265358979323846;
        const glm::dvec3 n = glm::normalize(glm::dvec3(normal)), t = diskTangent(normal), b = glm::cross(n, t);
        const double R = double(radius) * std::sqrt(pi / (2.0 * std::sqrt(2.0)));
        std::vector<glm::vec3> v;
        for (int k = 0; k < 8; k++) {
            const double a = 2.0 * pi * k / 8.0;
            v.push_back(glm::vec3(glm::dvec3(centre) + R * (std::cos(a) * t + std::sin(a) * b)));
        }
        return v;
    }
    // A unit vector orthogonal to normal: where diskOctagon puts its first vertex.
    static glm::dvec3 diskTangent(glm::vec3 normal) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
        const glm::dvec3 a = std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        return glm::normalize(glm::cross(a, n));
    }

    // A KHR_lights_punctual light as the loader fills it (rtpbr_gltf_punctual_light):
    // direction is normalised here; range 0 = infinite; cone angles for spots only.
    void punctual(rtpbr_gltf_punctual_type type, glm::vec3 position, glm::vec3 direction, glm::vec3 intensity,
                  float range = 0.0f, float inner = 0.0f, float outer = 0.7853982f) {
        rtpbr_gltf_punctual_light P{};
        P.type = type;
        glm::vec3 d = glm::normalize(direction);
        for (int i = 0; i < 3; i++) {
            P.position[i] = position[i];
            P.direction[i] = d[i];
            P.intensity[i] = intensity[i];
        }
        P.range = range;
        P.inner_cone_angle = inner;
        P.outer_cone_angle = outer;
        P.gltf_node = P.gltf_light = -1;
        punctualLights.push_back(P);
    }

    // A camera at pos looking at target (up hint +y unless parallel).
    void camera(glm::vec3 pos, glm::vec3 target, float yfov, glm::vec3 upHint = glm::vec3(0, 1, 0)) {
        rtpbr_gltf_camera c{};
        glm::vec3 f = glm::normalize(target - pos);
        glm::vec3 r = glm::normalize(glm::cross(f, upHint));
        glm::vec3 u = glm::cross(r, f);
        for (int i = 0; i < 3; i++) {
            c.position[i] = pos[i];
            c.forward[i] = f[i];
            c.up[i] = u[i];
            c.right[i] = r[i];
        }
        c.yfov = yfov;
        c.aspect = 0.0f;
        c.znear = 0.01f;
        c.gltf_node = c.gltf_camera = -1;
        cameras.push_back(c);
    }

    const rtpbr_gltf_scene &build() {
        scene = rtpbr_gltf_scene{};
        scene.primitives = primitives.data();
        scene.primitive_count = uint32_t(primitives.size());
        scene.materials = materials.data();
        scene.material_count = uint32_t(materials.size());
        scene.lights = lights.data();
        scene.light_count = uint32_t(lights.size());
        scene.punctual_lights = punctualLights.data();
        scene.punctual_light_count = uint32_t(punctualLights.size());
        scene.cameras = cameras.data();
        scene.camera_count = uint32_t(cameras.size());
        return scene;
    }
};

// The irradiance at x (surface normal n) from a polygon of radiance L, by Lambert 1760's
// polygon form factor (e.g. Arvo 1995, "Applications of Irradiance Tensors", eq. 1):
// E(x) = L/2 sum_i angle(v_i, v_{i+1}) n . normalize(v_i x v_{i+1}), v_i the directions from x
// to the vertices; the absolute value takes care of orientation. The polygon wholly above the
// horizon.
inline double polygonIrradiance(glm::dvec3 x, glm::dvec3 n, const std::vector<glm::vec3> &poly, double L) {
    double s = 0.0;
    for (size_t i = 0; i < poly.size(); i++) {
        glm::dvec3 a = glm::normalize(glm::dvec3(poly[i]) - x);
        glm::dvec3 b = glm::normalize(glm::dvec3(poly[(i + 1) % poly.size()]) - x);
        double angle = std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0));
        s += angle * glm::dot(n, glm::normalize(glm::cross(a, b)));
    }
    return 0.5 * L * std::fabs(s);
}

// Camera ray direction through pixel coordinates (x, y) in [0, W] x [0, H] as the oracle
// computes it (pinhole, yfov vertical, image aspect W / H); used by tests to integrate
// closed-form references over pixel footprints.
inline glm::vec3 cameraRay(const rtpbr_gltf_camera &c, float x, float y, uint32_t W, uint32_t H) {
    float t = std::tan(0.5f * c.yfov);
    float a = float(W) / float(H);
    glm::vec3 f(c.forward[0], c.forward[1], c.forward[2]);
    glm::vec3 r(c.right[0], c.right[1], c.right[2]);
    glm::vec3 u(c.up[0], c.up[1], c.up[2]);
    return glm::normalize(f + (2.0f * x / float(W) - 1.0f) * t * a * r + (1.0f - 2.0f * y / float(H)) * t * u);
}

// ---- floors for the light tests ------------------------------------------------------------

// A pure Lambert material of the given albedo (no specular layer).
inline uint32_t lambertMaterial(SceneBuilder &b, float albedo) {
    uint32_t m = b.material(glm::vec3(albedo), 0.0f, 1.0f);
    b.materials[m].specular.specular_factor = 0.0f;
    return m;
}

// A floor y = 0 from (x0, z0) to (x1, z1), facing +y, of material mat.
inline void floorPlane(SceneBuilder &b, uint32_t mat, float x0 = -40, float x1 = 40, float z0 = -40, float z1 = 40) {
    b.polygon({{x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, {x0, 0, z0}}, mat);
}

// Where the oracle's rays leave a floor point p (normal +y) from: 1e-4 (1 + |p|_inf) above it
// (oracle/README.md, shadow rays).
inline glm::dvec3 leaving(glm::dvec3 p) {
    return p + glm::dvec3(0.0, 1e-4 * (1.0 + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)))), 0.0);
}

#endif
