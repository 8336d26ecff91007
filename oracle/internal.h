// rtpbr oracle: small helpers shared by the library's source files (not installed).
#ifndef RTPBR_ORACLE_INTERNAL_H
#define RTPBR_ORACLE_INTERNAL_H

#include <cmath>
#include <string>

namespace rtpbr_oracle {

// printf-style formatting into a std::string (error messages; truncated at 511 bytes).
std::string fmt(const char *f, ...) __attribute__((format(printf, 1, 2)));

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite3(const float *v) { return finite(v[0]) && finite(v[1]) && finite(v[2]); }

} // namespace rtpbr_oracle

#endif
