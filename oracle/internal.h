// rtpbr oracle: small helpers shared by the library's source files (not installed).
#ifndef RTPBR_ORACLE_INTERNAL_H
#define RTPBR_ORACLE_INTERNAL_H

#include <cmath>
#include <cstdint>
#include <string>

namespace rtpbr_oracle {

// printf-style formatting into a std::string (error messages; truncated at 511 bytes).
std::string fmt(const char *f, ...) __attribute__((format(printf, 1, 2)));

// Embree asserts (ray.valid()) on ray origins beyond FLT_LARGE = 1.844e18 and builds
// degenerate bounds near FLT_MAX: every scene coordinate must stay within this, which leaves
// room for the spans between points and for ray offsets.
constexpr float kMaxSceneCoordinate = 1e15f;

// Checks that `need` bytes (for `what`) fit in the memory available and in `limit` (0: no
// limit of its own); the error says both (rtpbr_common/memory.hpp).
bool checkMemory(uint64_t need, uint64_t limit, const std::string &what, std::string *error);

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite3(const float *v) { return finite(v[0]) && finite(v[1]) && finite(v[2]); }

} // namespace rtpbr_oracle

#endif
