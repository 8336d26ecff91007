// rtpbr oracle: result strings and scene validation.
#include "oracle.h"

#include "internal.h"

#include "rtpbr_common/memory.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace rtpbr_oracle {

std::string fmt(const char *f, ...) {
    char buf[512];
    va_list ap;
    va_start(ap, f);
    vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}

const char *resultString(Result r) {
    switch (r) {
    case Result::Success: return "success";
    case Result::InvalidArgument: return "invalid argument";
    case Result::InvalidScene: return "invalid scene";
    case Result::NoCamera: return "no camera";
    case Result::NoLights: return "no lights";
    case Result::Embree: return "Embree error";
    case Result::Io: return "I/O error";
    case Result::Incompatible: return "incompatible accumulators";
    }
    return "unknown result";
}

// ---- memory ----------------------------------------------------------------------------------

bool checkMemory(uint64_t need, uint64_t limit, const std::string &what, std::string *error) {
    std::string shortfall = rtpbr_tools::memory_shortfall(need, limit, what);
    if (shortfall.empty())
        return true;
    *error = shortfall;
    return false;
}

// ---- validation ------------------------------------------------------------------------------

namespace {

bool withinExtent(const float *v) {
    for (int k = 0; k < 3; k++)
        if (!(std::fabs(v[k]) <= kMaxSceneCoordinate))
            return false;
    return true;
}

// A KHR_lights_punctual light as the renderer relies on it (rtpbr_gltf_punctual_light's
// contract); *emits when its intensity is above 0 in any channel.
Result validatePunctualLight(const rtpbr_gltf_punctual_light &P, uint32_t i, bool *emits, std::string *error) {
    // The type's bits as stored: a C caller (or a corrupted scene) may hold any int there, which
    // C++ may not read as the enum (UBSan: not a valid value for the type).
    int raw = 0;
    static_assert(sizeof raw == sizeof P.type, "rtpbr_gltf_punctual_type is an int");
    std::memcpy(&raw, &P.type, sizeof raw);
    const char *type = raw == RTPBR_GLTF_PUNCTUAL_POINT         ? "point"
                       : raw == RTPBR_GLTF_PUNCTUAL_SPOT        ? "spot"
                       : raw == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL ? "directional"
                                                                : nullptr;
    if (!type) {
        *error = fmt("punctual light %u: unknown type %d (point, spot or directional)", i, raw);
        return Result::InvalidScene;
    }
    if (!finite3(P.intensity) || P.intensity[0] < 0.0f || P.intensity[1] < 0.0f || P.intensity[2] < 0.0f) {
        *error = fmt("punctual light %u (%s): intensity (%g, %g, %g) is negative or not finite", i, type,
                     double(P.intensity[0]), double(P.intensity[1]), double(P.intensity[2]));
        return Result::InvalidScene;
    }
    if (P.type != RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) {
        if (!finite3(P.position) || !withinExtent(P.position)) {
            *error = fmt("punctual light %u (%s): position (%g, %g, %g) is not finite or lies beyond the oracle's "
                         "scene extent of +-%g", i, type, double(P.position[0]), double(P.position[1]),
                         double(P.position[2]), double(kMaxSceneCoordinate));
            return Result::InvalidScene;
        }
        if (!finite(P.range) || P.range < 0.0f) {
            *error = fmt("punctual light %u (%s): range %g is negative or not finite (0 = infinite)", i, type,
                         double(P.range));
            return Result::InvalidScene;
        }
    }
    if (P.type != RTPBR_GLTF_PUNCTUAL_POINT) {
        // The direction must be unit: the spot's cosines and the directional wi use it as is.
        double len = std::sqrt(double(P.direction[0]) * P.direction[0] + double(P.direction[1]) * P.direction[1] +
                               double(P.direction[2]) * P.direction[2]);
        if (!finite3(P.direction) || !(std::fabs(len - 1.0) <= 1e-3)) {
            *error = fmt("punctual light %u (%s): direction (%g, %g, %g) is not a finite unit vector (length %g)", i,
                         type, double(P.direction[0]), double(P.direction[1]), double(P.direction[2]), len);
            return Result::InvalidScene;
        }
    }
    if (P.type == RTPBR_GLTF_PUNCTUAL_SPOT) {
        // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi/2. Equal angles are
        // let through: the loader checks the file's doubles, which may round to the same float
        // (the falloff's max(1e-3, ...) keeps them finite).
        const float inner = P.inner_cone_angle, outer = P.outer_cone_angle;
        if (!finite(inner) || !finite(outer) || !(inner >= 0.0f) || !(inner <= outer) ||
            !(outer <= 1.5707964f)) {
            *error = fmt("punctual light %u (spot): cone angles inner %g, outer %g rad: need 0 <= inner <= outer <= "
                         "pi/2", i, double(inner), double(outer));
            return Result::InvalidScene;
        }
    }
    // A directional light's sun disk: 0 <= angular_diameter < pi/2 (the cap's half-angle below
    // pi/4); point and spot lights have no size.
    const float diameter = P.angular_diameter;
    if (P.type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) {
        if (!(diameter >= 0.0f) || !(double(diameter) < 1.57079632679489661923)) {
            *error = fmt("punctual light %u (directional): angular diameter %g rad: need 0 <= angular diameter < pi/2",
                         i, double(diameter));
            return Result::InvalidScene;
        }
    } else if (diameter != 0.0f) {
        *error = fmt("punctual light %u (%s): angular diameter %g rad: only a directional light has one (0 here)", i,
                     type, double(diameter));
        return Result::InvalidScene;
    }
    // A point light's sphere: radius >= 0 (0: a true point); spot and directional lights have
    // none (a spot with a radius, a sphere with a cone: not modelled).
    if (P.type == RTPBR_GLTF_PUNCTUAL_POINT) {
        if (!finite(P.radius) || !(P.radius >= 0.0f)) {
            *error = fmt("punctual light %u (point): radius %g is negative or not finite (0 = a true point)", i,
                         double(P.radius));
            return Result::InvalidScene;
        }
    } else if (P.radius != 0.0f) {
        *error = fmt("punctual light %u (%s): radius %g: only a point light has one (0 here)", i, type,
                     double(P.radius));
        return Result::InvalidScene;
    }
    // A point light's capsule: length >= 0 (0: the sphere or the point), only with a radius > 0,
    // along a unit axis, both ends within the scene extent.
    if (!finite(P.length) || !(P.length >= 0.0f)) {
        *error = fmt("punctual light %u (%s): length %g is negative or not finite (0 = no capsule)", i, type,
                     double(P.length));
        return Result::InvalidScene;
    }
    if (P.length > 0.0f) {
        if (P.type != RTPBR_GLTF_PUNCTUAL_POINT || !(P.radius > 0.0f)) {
            *error = fmt("punctual light %u (%s): length %g: only a point light with a radius > 0 has one (0 here)", i,
                         type, double(P.length));
            return Result::InvalidScene;
        }
        const double len = std::sqrt(double(P.axis[0]) * P.axis[0] + double(P.axis[1]) * P.axis[1] +
                                     double(P.axis[2]) * P.axis[2]);
        if (!finite3(P.axis) || !(std::fabs(len - 1.0) <= 1e-3)) {
            *error = fmt("punctual light %u (point): capsule axis (%g, %g, %g) is not a finite unit vector (length %g)",
                         i, double(P.axis[0]), double(P.axis[1]), double(P.axis[2]), len);
            return Result::InvalidScene;
        }
        for (double side : {-0.5, 0.5}) {
            float end[3];
            for (int k = 0; k < 3; ++k)
                end[k] = float(double(P.position[k]) + side * double(P.length) * double(P.axis[k]) / len);
            if (!finite3(end) || !withinExtent(end)) {
                *error = fmt("punctual light %u (point): capsule of length %g reaches beyond the oracle's scene extent "
                             "of +-%g", i, double(P.length), double(kMaxSceneCoordinate));
                return Result::InvalidScene;
            }
        }
    }
    if (P.intensity[0] > 0.0f || P.intensity[1] > 0.0f || P.intensity[2] > 0.0f)
        *emits = true;
    return Result::Success;
}

} // namespace

Result validateScene(const rtpbr_gltf_scene &scene, const RenderSettings &s, std::string *error) {
    if (scene.camera_count == 0) {
        *error = "the scene has no camera (the oracle renders from a glTF perspective camera)";
        return Result::NoCamera;
    }
    if (s.camera >= scene.camera_count) {
        *error = fmt("camera %u requested, the scene has %u", s.camera, scene.camera_count);
        return Result::NoCamera;
    }
    const rtpbr_gltf_camera &cam = scene.cameras[s.camera];
    if (!finite3(cam.position) || !finite3(cam.forward) || !finite3(cam.up) || !finite3(cam.right) ||
        !(cam.yfov > 0.0f && cam.yfov < 3.14159f)) {
        *error = fmt("camera %u: non-finite position/orientation or yfov outside (0, pi)", s.camera);
        return Result::InvalidScene;
    }
    if (!withinExtent(cam.position)) {
        *error = fmt("camera %u: position (%g, %g, %g) beyond the oracle's scene extent of +-%g", s.camera,
                     double(cam.position[0]), double(cam.position[1]), double(cam.position[2]),
                     double(kMaxSceneCoordinate));
        return Result::InvalidScene;
    }
    for (uint32_t m = 0; m < scene.material_count; m++) {
        const rtpbr_gltf_material &mat = scene.materials[m];
        const rtpbr_gltf_disney &dn = mat.disney;
        const float vals[] = {mat.base_color[0], mat.base_color[1], mat.base_color[2], mat.metallic, mat.roughness,
                              mat.ior.ior, mat.specular.specular_factor, mat.specular.specular_color_factor[0],
                              mat.specular.specular_color_factor[1], mat.specular.specular_color_factor[2],
                              mat.anisotropy.anisotropy_strength, mat.anisotropy.anisotropy_rotation,
                              mat.clearcoat.clearcoat_factor, mat.clearcoat.clearcoat_roughness_factor,
                              mat.sheen.sheen_color_factor[0], mat.sheen.sheen_color_factor[1],
                              mat.sheen.sheen_color_factor[2], mat.sheen.sheen_roughness_factor, mat.normal_scale,
                              dn.subsurface, dn.specular, dn.specular_tint, dn.anisotropic, dn.sheen, dn.sheen_tint,
                              dn.clearcoat, dn.clearcoat_gloss};
        for (float v : vals)
            if (!finite(v)) {
                *error = fmt("material %u: non-finite parameter", m);
                return Result::InvalidScene;
            }
        const int32_t tex[] = {mat.base_color_texture, mat.metallic_roughness_texture, mat.normal_texture};
        for (int32_t t : tex)
            if (t >= 0 && uint32_t(t) >= scene.texture_count) {
                *error = fmt("material %u: texture %d out of range (%u textures)", m, t, scene.texture_count);
                return Result::InvalidScene;
            }
    }
    for (uint32_t p = 0; p < scene.primitive_count; p++) {
        const rtpbr_gltf_primitive &prim = scene.primitives[p];
        if (prim.index_count % 3 != 0) {
            *error = fmt("primitive %u: index count %u is not a multiple of 3", p, prim.index_count);
            return Result::InvalidScene;
        }
        if ((prim.vertex_count > 0 && (!prim.positions || !prim.normals)) || (prim.index_count > 0 && !prim.indices) ||
            (prim.has_texcoords && !prim.texcoords) || (prim.has_tangents && !prim.tangents)) {
            *error = fmt("primitive %u: missing vertex or index arrays", p);
            return Result::InvalidScene;
        }
        if (prim.material >= scene.material_count) {
            *error = fmt("primitive %u: material %u out of range (%u materials)", p, prim.material,
                         scene.material_count);
            return Result::InvalidScene;
        }
        for (uint32_t v = 0; v < prim.vertex_count; v++)
            if (!finite3(prim.positions + 3 * v)) {
                *error = fmt("primitive %u: vertex %u has a non-finite position", p, v);
                return Result::InvalidScene;
            } else if (!withinExtent(prim.positions + 3 * v)) {
                *error = fmt("primitive %u: vertex %u lies beyond the oracle's scene extent of +-%g", p, v,
                             double(kMaxSceneCoordinate));
                return Result::InvalidScene;
            }
        for (uint32_t i = 0; i < prim.index_count; i++)
            if (prim.indices[i] >= prim.vertex_count) {
                *error = fmt("primitive %u: index %u = %u out of range (%u vertices)", p, i, prim.indices[i],
                             prim.vertex_count);
                return Result::InvalidScene;
            }
    }
    bool emits = false;
    for (uint32_t l = 0; l < scene.light_count; l++) {
        const rtpbr_gltf_light &L = scene.lights[l];
        if (L.vertex_count < 3 || L.vertex_count > RTPBR_GLTF_MAX_POLYGON_VERTICES) {
            *error = fmt("light %u: %u vertices (3..%u allowed)", l, L.vertex_count, RTPBR_GLTF_MAX_POLYGON_VERTICES);
            return Result::InvalidScene;
        }
        for (uint32_t k = 0; k < L.vertex_count; k++)
            if (!finite3(L.vertices[k])) {
                *error = fmt("light %u: vertex %u is not finite", l, k);
                return Result::InvalidScene;
            } else if (!withinExtent(L.vertices[k])) {
                *error = fmt("light %u: vertex %u lies beyond the oracle's scene extent of +-%g", l, k,
                             double(kMaxSceneCoordinate));
                return Result::InvalidScene;
            }
        if (!finite3(L.facts.normal) || !finite3(L.radiance) || L.radiance[0] < 0.0f || L.radiance[1] < 0.0f ||
            L.radiance[2] < 0.0f) {
            *error = fmt("light %u: non-finite normal or negative/non-finite radiance", l);
            return Result::InvalidScene;
        }
        if (L.material >= 0 && uint32_t(L.material) >= scene.material_count) {
            *error = fmt("light %u: material %d out of range", l, L.material);
            return Result::InvalidScene;
        }
        // The shape's bits as stored (as a punctual light's type, which C++ may not read as the
        // enum when they are no enumerator). A disk is rendered as itself (its centre, normal
        // and radius), not as its octagon.
        int shape = 0;
        static_assert(sizeof shape == sizeof L.shape, "rtpbr_gltf_light_shape is an int");
        std::memcpy(&shape, &L.shape, sizeof shape);
        if (shape == RTPBR_GLTF_LIGHT_DISK) {
            const float *n = L.facts.normal, *c = L.facts.center;
            const double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
            bool inside = true; // the disk within the extent: each coordinate of its centre +- r
            for (int k = 0; k < 3; k++)
                inside = inside && std::fabs(double(c[k])) + double(L.radius) <= double(kMaxSceneCoordinate);
            if (!(L.radius > 0.0f) || !finite(L.radius) || !finite3(c) || !inside || !(std::fabs(len - 1.0) < 1e-3)) {
                *error = fmt("light %u (disk): radius %g, centre (%g, %g, %g) and normal (%g, %g, %g): need a finite "
                             "radius > 0, the disk within the oracle's scene extent of +-%g and a unit normal",
                             l, double(L.radius), double(L.facts.center[0]), double(L.facts.center[1]),
                             double(L.facts.center[2]), double(n[0]), double(n[1]), double(n[2]),
                             double(kMaxSceneCoordinate));
                return Result::InvalidScene;
            }
        } else if (shape != RTPBR_GLTF_LIGHT_POLYGON) {
            *error = fmt("light %u: unknown shape %d (polygon or disk)", l, shape);
            return Result::InvalidScene;
        }
        if (L.radiance[0] > 0.0f || L.radiance[1] > 0.0f || L.radiance[2] > 0.0f)
            emits = true;
    }
    if (scene.punctual_light_count > 0 && !scene.punctual_lights) {
        *error = fmt("%u punctual lights but no punctual light array", scene.punctual_light_count);
        return Result::InvalidScene;
    }
    for (uint32_t i = 0; i < scene.punctual_light_count; i++) {
        Result r = validatePunctualLight(scene.punctual_lights[i], i, &emits, error);
        if (r != Result::Success)
            return r;
    }
    if (!emits) {
        *error = "the scene has no lights (no emissive primitive, EXT_lights_area light with radiance > 0 or "
                 "KHR_lights_punctual light with intensity > 0)";
        return Result::NoLights;
    }
    return Result::Success;
}

} // namespace rtpbr_oracle
