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

// A disk light's Embree user geometry (one primitive): its shape, and whether a ray that meets
// its back passes through it (a single-sided emissive material, as a light polygon's filter
// does). A hit's u, v are the point's disk coordinates (DiskShape::point).
struct DiskGeometry {
    DiskShape shape;
    bool cullBackFaces = false;
};

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene full = nullptr;
    RTCScene lightsOnly = nullptr;
    std::vector<GeometryRecord> fullGeoms;  // by geomID in `full`
    std::vector<uint32_t> lightOnlyGeoms;   // light index by geomID in `lightsOnly`
    std::deque<SurfaceFilter> filters;      // user data of the filters (stable addresses)
    std::deque<DiskGeometry> disks;         // user data of the disk lights' geometries
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

// Builds `full` (surfaces + lights) and `lightsOnly` (lights, for --no-shadows); a light is its
// polygon's triangles, or a disk light (RTPBR_GLTF_LIGHT_DISK) the disk itself (DiskGeometry);
// the first device error, if any, becomes *error. In `full`, the surfaces of single-sided
// materials (and lights of single-sided emissive materials) drop back-face hits (a filter; a
// disk's own test), and the surfaces of MASK and BLEND materials carry filters that apply
// their alpha (SurfaceFilter), for camera, bounce and shadow rays alike. `textures` (the
// scene's, by loader index) must outlive *es.
Result buildEmbree(const rtpbr_gltf_scene &scene, const std::vector<Texture> &textures, EmbreeScene *es,
                   std::string *error);

} // namespace rtpbr_oracle

#endif
