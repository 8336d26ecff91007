// rtpbr oracle: an Embree path tracer over rtpbr scenes, the ground truth the real-time
// engine is measured against (see README.md).
//
//   rtpbr_oracle::RenderSettings settings;          // defaults documented below
//   settings.spp = 64;
//   rtpbr_oracle::Accumulator acc;
//   std::string error;
//   if (rtpbr_oracle::render(*scene, settings, &acc, &error, nullptr) != rtpbr_oracle::Result::Success)
//       fprintf(stderr, "%s\n", error.c_str());
//   std::vector<float> rgb, stderrRgb;
//   rtpbr_oracle::resolve(acc, &rgb, &stderrRgb);   // linear radiance, RGB, rows top down
//
// Determinism: every pixel sample has its own random sequence, a hash of (pixel, sample
// index, seed). Sample values are summed per pixel in 128-bit fixed point (value x 2^64),
// which is associative: the image does not depend on the thread count, and accumulators
// of disjoint sample ranges or image regions merge into exactly the full render.
#ifndef RTPBR_ORACLE_ORACLE_H
#define RTPBR_ORACLE_ORACLE_H

#include "lights.h"

#include <rtpbr/rtpbr_gltf.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace rtpbr_oracle {

enum class Result {
    Success = 0,
    InvalidArgument, // bad settings (zero size, empty sample range, region outside image)
    InvalidScene,    // NaN/Inf vertex, index out of range, bad material reference, ...
    NoCamera,        // the scene has no camera (or the camera index is out of range)
    NoLights,        // nothing emits
    Embree,          // the Embree device reported an error
    Io,              // a file could not be read or written
    Incompatible,    // accumulators that cannot be merged
};
const char *resultString(Result r);

struct Region {
    uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0; // [x0, x1) x [y0, y1); all zero = whole image
};

struct RenderSettings {
    uint32_t width = 0;        // 0: 512
    uint32_t height = 0;       // 0: width / camera aspect (width * 3 / 4 without aspect)
    uint32_t camera = 0;       // index into scene.cameras
    uint32_t spp = 16;         // samples per pixel of the full render (>= 1)
    uint64_t seed = 0;
    uint32_t threads = 0;      // 0: std::thread::hardware_concurrency()
    uint32_t maxDepth = 16;    // scattering events along a path (1 = direct lighting)
    bool directOnly = false;   // maxDepth = 1
    bool noShadows = false;    // direct lighting ignores occluders (what LTC computes)
    bool singleScatter = false;// plain microfacet BRDF instead of the random walk
    LightSampling lightSampling = LightSampling::SolidAngle;
    uint32_t sampleBegin = 0;  // sample range [sampleBegin, sampleEnd) of this run;
    uint32_t sampleEnd = 0;    // sampleEnd 0 = spp
    Region region;             // pixels this run renders
    uint64_t memoryLimit = 0;  // bytes the render may need at most; 0: what the system has
};

// Per-pixel sums of one render (or of merged renders). Pixels outside the region are 0.
struct Accumulator {
    uint32_t width = 0, height = 0;
    uint64_t seed = 0;
    uint64_t settingsHash = 0;      // everything but the sample range and region
    std::vector<uint32_t> samples;  // per pixel: samples accumulated
    std::vector<__int128> sum;      // 3 per pixel: sum of x * 2^64, truncated
    std::vector<double> sumSquares; // 3 per pixel
    uint64_t nonFinite = 0;         // samples discarded because NaN/Inf
    uint64_t clamped = 0;           // samples clamped to kMaxSampleValue
};
// Host memory per pixel: the accumulator (4 + 48 + 24 bytes) and the resolved image with its
// standard error (2 x 12 bytes).
constexpr uint64_t kBytesPerPixel = 100;
constexpr double kMaxSampleValue = 1099511627776.0; // 2^40: keeps every int128 sum exact

struct RenderStats {
    uint64_t samples = 0;
    uint64_t rays = 0; // closest-hit and occlusion queries
    double seconds = 0.0;
};

// Called from the render threads, serialised, after each finished tile.
using ProgressCallback = std::function<void(uint64_t pixelsDone, uint64_t pixelsTotal)>;

// Checks the scene data the renderer relies on (finite vertices, indices in range, material
// references, a camera, an emitting light, the punctual lights' parameters); error describes
// the first problem.
Result validateScene(const rtpbr_gltf_scene &scene, const RenderSettings &settings, std::string *error);

Result render(const rtpbr_gltf_scene &scene, const RenderSettings &settings, Accumulator *out, std::string *error,
              const ProgressCallback &progress, RenderStats *stats = nullptr);

// Adds b into a. Both must come from the same image size, seed and settings (checked);
// that they cover disjoint sample ranges or regions is the caller's promise (overlaps would
// be counted twice).
Result merge(Accumulator *a, const Accumulator &b, std::string *error);

// Mean radiance per pixel (RGB, rows top down) and, if stderrRgb, the standard error of the
// mean (0 where fewer than 2 samples).
void resolve(const Accumulator &acc, std::vector<float> *rgb, std::vector<float> *stderrRgb);

// The accumulator file (".acc"): a small binary format, see README.md.
Result writeAccumulator(const std::string &path, const Accumulator &acc, std::string *error);
Result readAccumulator(const std::string &path, Accumulator *acc, std::string *error, uint64_t memoryLimit = 0);

// OpenImageIO output: EXR (float RGB, linear) or, for .png/.jpg, an sRGB preview of the
// clamped radiance times exposure.
Result writeImage(const std::string &path, uint32_t width, uint32_t height, const std::vector<float> &rgb,
                  float exposure, std::string *error);

} // namespace rtpbr_oracle

#endif
