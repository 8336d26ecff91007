// Internal declarations of the scene loader (C++17). Not installed.
#pragma once

#include <rtpbr/rtpbr_gltf.h>

#include <tiny_gltf.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rtpbr_gltf_detail {

#if defined(__GNUC__)
#define RTPBR_GLTF_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define RTPBR_GLTF_PRINTF(a, b)
#endif

// Per-call state: options with defaults applied, the first failure, the
// logger. Passed to tinygltf callbacks as user_data; nothing is global.
struct Context {
    rtpbr_gltf_load_desc desc{};
    uint32_t max_vertices = RTPBR_GLTF_MAX_VERTICES;
    uint32_t max_lights = RTPBR_GLTF_MAX_LIGHTS;
    uint32_t max_texture_dimension = RTPBR_GLTF_MAX_TEXTURE_DIMENSION;
    float area_light_radiance_scale = 1.0f;
    uint64_t texture_budget = RTPBR_GLTF_DEFAULT_TEXTURE_BUDGET;
    uint64_t texture_bytes = 0;  // decoded texels held so far (decoded images and their copies)

    // Canonical absolute folder external URIs must stay in; empty = reject all.
    std::string base_dir;

    rtpbr_gltf_result result = RTPBR_GLTF_SUCCESS;
    std::string message;

    // Encoded bytes of images given by URI (captured by the image callback,
    // decoded after validation). Images in bufferViews are sliced later.
    std::map<int, std::vector<unsigned char>> encoded_images;

    // The radius of each KHR_lights_punctual light (index in the extension's lights), from its
    // "extras": {"radius": r} as written (a double: tinygltf casts integer literals in extras
    // to int), checked by check_schema: > 0 only for a point light; 0 when absent, not a
    // number or on a spot or directional light (those warned). Read by lights_from_khr_punctual.
    std::vector<double> punctual_radii;
    // Each light's "extras": {"length": L} alike: > 0 only for a point light with a radius > 0
    // (a capsule); a length without a radius is warned and left 0.
    std::vector<double> punctual_lengths;

    // Records the first failure; later ones are ignored. Always returns false.
    bool fail(rtpbr_gltf_result r, const char* fmt, ...) RTPBR_GLTF_PRINTF(3, 4);
    void warn(const char* fmt, ...) RTPBR_GLTF_PRINTF(2, 3);
    void info(const char* fmt, ...) RTPBR_GLTF_PRINTF(2, 3);
    bool failed() const { return result != RTPBR_GLTF_SUCCESS; }
    void log(rtpbr_gltf_log_level level, const std::string& text) const;
};

// Finite and representable as a float (outputs are float).
inline bool fits_float(double d) { return std::isfinite(d) && std::fabs(d) <= double(FLT_MAX); }

using Mat4 = std::array<double, 16>;  // column-major, like glTF
using Vec3 = std::array<double, 3>;

// A primitive being built (world space).
struct Primitive {
    std::vector<float> positions, normals, texcoords, texcoords1, tangents;
    std::vector<uint32_t> indices;
    uint32_t material = 0;
    int32_t gltf_mesh = -1, gltf_primitive = -1, gltf_node = -1;
    bool has_texcoords = false, has_texcoords1 = false, normals_generated = false;
    bool tangents_generated = false, has_tangents = false;
};

struct Texture {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> pixels;
    rtpbr_gltf_texture info{};
};

struct Scene {
    std::vector<Primitive> primitives;
    std::vector<rtpbr_gltf_material> materials;
    std::vector<Texture> textures;
    std::vector<rtpbr_gltf_light> lights;
    std::vector<rtpbr_gltf_punctual_light> punctual_lights;
    std::vector<rtpbr_gltf_camera> cameras;
    uint64_t total_vertices = 0;
    uint64_t total_indices = 0;
};

// scene_schema.cpp: the glTF 2.0 schema's types, ranges and required properties of the
// core objects and of KHR_lights_punctual, on the JSON text (syntax errors are left to
// tinygltf). *rewritten: left empty, or the document to give tinygltf instead, with the
// defaults it would refuse to supply (a spot light's "spot" object). Fills
// ctx.punctual_radii and ctx.punctual_lengths.
bool check_schema(Context& ctx, const char* json_text, size_t size, std::string* rewritten);

// scene_materials.cpp: fills scene.materials (one per glTF material, plus a
// default one appended on demand by default_material()) and scene.textures.
bool convert_materials(Context& ctx, const tinygltf::Model& model, Scene& scene);
uint32_t default_material(Scene& scene);
rtpbr_gltf_material make_default_material();

// Nodes carrying a light, in traversal order, with their world matrices.
struct LightNodes {
    std::vector<std::pair<int, Mat4>> area;      // extensions.EXT_lights_area
    std::vector<std::pair<int, Mat4>> punctual;  // extensions.KHR_lights_punctual
};

// scene_geometry.cpp: walks the node tree, fills primitives and cameras.
bool convert_nodes(Context& ctx, const tinygltf::Model& model, Scene& scene, LightNodes* light_nodes);
bool node_local_matrix(Context& ctx, const tinygltf::Node& node, int index, Mat4* out);
Mat4 mat_mul(const Mat4& a, const Mat4& b);
Vec3 transform_point(const Mat4& m, const Vec3& p);
Vec3 transform_dir(const Mat4& m, const Vec3& d);

// scene_lights.cpp
bool lights_from_primitive(Context& ctx, Scene& scene, uint32_t primitive_index);
bool lights_from_ext_area(Context& ctx, const tinygltf::Model& model, Scene& scene,
                          const std::vector<std::pair<int, Mat4>>& light_nodes);
// After the area lights: they and the punctual lights share ctx.max_lights.
bool lights_from_khr_punctual(Context& ctx, const tinygltf::Model& model, Scene& scene,
                              const std::vector<std::pair<int, Mat4>>& light_nodes);

}  // namespace rtpbr_gltf_detail
