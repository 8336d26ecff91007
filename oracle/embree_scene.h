// rtpbr oracle: the Embree scenes of a render (one device, errors through its callback).
#ifndef RTPBR_ORACLE_EMBREE_SCENE_H
#define RTPBR_ORACLE_EMBREE_SCENE_H

#include "oracle.h"
#include "texture.h"

#include <embree3/rtcore.h>

#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace rtpbr_oracle {

struct DeviceErrors {
    std::mutex mutex;
    std::string first;
};

struct GeometryRecord {
    bool isLight;
    uint32_t index; // primitive or light
};

// What the filter of a surface needs. Single-sided (glTF doubleSided false): a ray that meets
// the back of the surface passes through it. glTF alphaMode MASK: a hit where the coverage
// (baseColorFactor alpha x base colour texture alpha) is below alphaCutoff is dropped; BLEND:
// stochastic opacity, a hit of coverage a is kept with probability a (a hash of the ray and the
// triangle decides, so the same ray always decides the same way and the image is
// deterministic per seed).
struct SurfaceFilter {
    bool cullBackFaces = false;
    const float *positions = nullptr; // a primitive's world positions and indices, or
    const uint32_t *indices = nullptr;
    float lightNormal[3] = {0.0f, 0.0f, 0.0f}; // a light polygon's front normal
    const rtpbr_gltf_primitive *alphaPrimitive = nullptr; // set for MASK and BLEND materials
    const rtpbr_gltf_material *alphaMaterial = nullptr;
    const Texture *alphaTexture = nullptr; // the base colour texture; null: none
};

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene full = nullptr;
    RTCScene lightsOnly = nullptr;
    std::vector<GeometryRecord> fullGeoms;  // by geomID in `full`
    std::vector<uint32_t> lightOnlyGeoms;   // light index by geomID in `lightsOnly`
    std::deque<SurfaceFilter> filters;      // user data of the filters (stable addresses)
    DeviceErrors errors;

    ~EmbreeScene() {
        if (full)
            rtcReleaseScene(full);
        if (lightsOnly)
            rtcReleaseScene(lightsOnly);
        if (device)
            rtcReleaseDevice(device);
    }
};

// Builds `full` (surfaces + light polygons) and `lightsOnly` (light polygons, for
// --no-shadows); the first device error, if any, becomes *error. In `full`, the surfaces of
// single-sided materials (and light polygons of single-sided emissive materials) carry
// intersection and occlusion filters that drop back-face hits, and the surfaces of MASK and
// BLEND materials filters that apply their alpha (SurfaceFilter), for camera, bounce and
// shadow rays alike. `textures` (the scene's, by loader index) must outlive *es.
Result buildEmbree(const rtpbr_gltf_scene &scene, const std::vector<Texture> &textures, EmbreeScene *es,
                   std::string *error);

} // namespace rtpbr_oracle

#endif
