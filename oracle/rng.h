// rtpbr oracle: deterministic random numbers.
//
// Every pixel sample owns its own generator, seeded from (pixel x, pixel y, sample index,
// user seed) by a hash, so the image does not depend on tiling, thread count, or on which
// sample range / image region a run renders.
#ifndef RTPBR_ORACLE_RNG_H
#define RTPBR_ORACLE_RNG_H

#include <cstdint>

namespace rtpbr_oracle {

// SplitMix64 finaliser (Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom Number
// Generators"): a bijective 64-bit mixer.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation"), XSH-RR output.
class Rng {
public:
    Rng(uint64_t seed, uint64_t stream) {
        inc_ = (stream << 1u) | 1u;
        state_ = 0;
        next();
        state_ += seed;
        next();
    }

    // The generator of one pixel sample.
    static Rng forSample(uint32_t px, uint32_t py, uint64_t sample, uint64_t seed) {
        uint64_t a = mix64(seed ^ 0x9e3779b97f4a7c15ull);
        uint64_t b = mix64(a ^ ((uint64_t(px) << 32) | py));
        uint64_t c = mix64(b + sample * 0xd1b54a32d192ed03ull);
        return Rng(c, mix64(c ^ b));
    }

    uint32_t next() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    // Uniform in [0, 1): 24 random bits, so 1 is never returned in float.
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }

private:
    uint64_t state_;
    uint64_t inc_;
};

} // namespace rtpbr_oracle

#endif
