// rtpbr oracle: the Embree scenes of a render (one device, errors through its callback).
#ifndef RTPBR_ORACLE_EMBREE_SCENE_H
#define RTPBR_ORACLE_EMBREE_SCENE_H

#include "oracle.h"

#include <embree3/rtcore.h>

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

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene full = nullptr;
    RTCScene lightsOnly = nullptr;
    std::vector<GeometryRecord> fullGeoms;  // by geomID in `full`
    std::vector<uint32_t> lightOnlyGeoms;   // light index by geomID in `lightsOnly`
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
// --no-shadows); the first device error, if any, becomes *error.
Result buildEmbree(const rtpbr_gltf_scene &scene, EmbreeScene *es, std::string *error);

} // namespace rtpbr_oracle

#endif
