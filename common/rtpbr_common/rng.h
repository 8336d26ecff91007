/* rtpbr tools: the deterministic random number generators of the tools, the tests and the
 * oracle: SplitMix64 and PCG32. Header-only, for C11 and C++17. A stream is fixed by its
 * seed, so tables generated from it are reproducible byte for byte.
 */
#ifndef RTPBR_TOOLS_RNG_H
#define RTPBR_TOOLS_RNG_H

#include <stdint.h>

/* ---- SplitMix64 (Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom Number Generators") */

/* The SplitMix64 finaliser: a bijective 64-bit mixer (also a good hash of a seed). */
static inline uint64_t rtpbr_tools_mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* The next output of the stream whose state is *state (advanced by the golden gamma). */
static inline uint64_t rtpbr_tools_splitmix64_next(uint64_t *state) {
    return rtpbr_tools_mix64(*state += 0x9e3779b97f4a7c15ull);
}

/* Uniform in [0, 1) from the top 24 bits: every value exact in float, 1 never returned. */
static inline float rtpbr_tools_splitmix64_float(uint64_t *state) {
    return (float)(rtpbr_tools_splitmix64_next(state) >> 40) * (1.0f / 16777216.0f);
}

/* Uniform in [0, 1) from the top 53 bits. */
static inline double rtpbr_tools_splitmix64_double(uint64_t *state) {
    return (double)(rtpbr_tools_splitmix64_next(state) >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
 * Algorithms for Random Number Generation"), XSH-RR output: 32 bits from 64 bits of state. */

typedef struct rtpbr_tools_pcg32 {
    uint64_t state, inc;
} rtpbr_tools_pcg32;

static inline uint32_t rtpbr_tools_pcg32_next(rtpbr_tools_pcg32 *r) {
    const uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    const uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* pcg32_srandom_r of the reference implementation: the initial state and the stream. */
static inline rtpbr_tools_pcg32 rtpbr_tools_pcg32_make(uint64_t initstate, uint64_t stream) {
    rtpbr_tools_pcg32 r = {0u, (stream << 1u) | 1u};
    rtpbr_tools_pcg32_next(&r);
    r.state += initstate;
    rtpbr_tools_pcg32_next(&r);
    return r;
}

/* Uniform in [0, 1) from the top 24 bits: every value exact in float, 1 never returned. */
static inline float rtpbr_tools_pcg32_float(rtpbr_tools_pcg32 *r) {
    return (float)(rtpbr_tools_pcg32_next(r) >> 8) * (1.0f / 16777216.0f);
}

#ifdef __cplusplus
namespace rtpbr_tools {

// The same stream as an object: SplitMix64 rng(seed); rng.uniform_float().
struct SplitMix64 {
    uint64_t state;
    explicit SplitMix64(uint64_t seed) : state(seed) {}
    uint64_t next() { return rtpbr_tools_splitmix64_next(&state); }
    float uniform_float() { return rtpbr_tools_splitmix64_float(&state); }
    double uniform_double() { return rtpbr_tools_splitmix64_double(&state); }
};

// The same generator as an object: Pcg32 rng(seed, stream); rng.uniform_float().
struct Pcg32 {
    rtpbr_tools_pcg32 r;
    Pcg32(uint64_t initstate, uint64_t stream) : r(rtpbr_tools_pcg32_make(initstate, stream)) {}
    uint32_t next() { return rtpbr_tools_pcg32_next(&r); }
    float uniform_float() { return rtpbr_tools_pcg32_float(&r); }
};

} // namespace rtpbr_tools
#endif

#endif /* RTPBR_TOOLS_RNG_H */
