// rtpbr oracle: deterministic random numbers.
//
// Every pixel sample owns its own generator, seeded from (pixel x, pixel y, sample index,
// user seed) by a hash, so the image does not depend on tiling, thread count, or on which
// sample range / image region a run renders.
#ifndef RTPBR_ORACLE_RNG_H
#define RTPBR_ORACLE_RNG_H

#include <cstdint>

#include "rtpbr_common/rng.h"

namespace rtpbr_oracle {

// SplitMix64's finaliser (common/), the hash of the seeds.
inline uint64_t mix64(uint64_t z) { return rtpbr_tools_mix64(z); }

// PCG32 (common/) with the seeding of one pixel sample.
class Rng : public rtpbr_tools::Pcg32 {
public:
    using Pcg32::Pcg32;

    // The generator of one pixel sample.
    static Rng forSample(uint32_t px, uint32_t py, uint64_t sample, uint64_t seed) {
        uint64_t a = mix64(seed ^ 0x9e3779b97f4a7c15ull);
        uint64_t b = mix64(a ^ ((uint64_t(px) << 32) | py));
        uint64_t c = mix64(b + sample * 0xd1b54a32d192ed03ull);
        return Rng(c, mix64(c ^ b));
    }

    // Uniform in [0, 1): 24 random bits, so 1 is never returned in float.
    float uniform() { return uniform_float(); }
};

} // namespace rtpbr_oracle

#endif
