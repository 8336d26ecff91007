// rtpbr oracle: the Embree scenes of a render (one device, errors through its callback).
#ifndef RTPBR_ORACLE_EMBREE_SCENE_H
#define RTPBR_ORACLE_EMBREE_SCENE_H

#include "oracle.h"

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

// What the back-face filter of a single-sided surface needs (glTF doubleSided false: a ray
// that meets the back of the surface passes through it).
struct SingleSided {
    const float *positions = nullptr; // a primitive's world positions and indices, or
    const uint32_t *indices = nullptr;
    float lightNormal[3] = {0.0f, 0.0f, 0.0f}; // a light polygon's front normal
};

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene full = nullptr;
    RTCScene lightsOnly = nullptr;
    std::vector<GeometryRecord> fullGeoms;  // by geomID in `full`
    std::vector<uint32_t> lightOnlyGeoms;   // light index by geomID in `lightsOnly`
    std::deque<SingleSided> singleSided;    // user data of the back-face filters (stable addresses)
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
// intersection and occlusion filters that drop back-face hits, for camera, bounce and shadow
// rays alike.
Result buildEmbree(const rtpbr_gltf_scene &scene, EmbreeScene *es, std::string *error);

} // namespace rtpbr_oracle

#endif
