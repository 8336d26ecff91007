// Hand-built rtpbr scenes for the oracle tests (the loader's structs are plain data).
#ifndef RTPBR_TESTS_ORACLE_SCENE_BUILDER_H
#define RTPBR_TESTS_ORACLE_SCENE_BUILDER_H

#include <rtpbr/rtpbr_gltf.h>

#include <glm/glm.hpp>

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

#endif
