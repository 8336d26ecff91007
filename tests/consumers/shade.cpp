// The shader library's C++ build from an installed rtpbr (tests/consumers, through the
// pkg-config file rtpbr-shaderlib and the CMake target rtpbr::shaderlib): GGX at the peak
// against its closed form 1 / (pi alpha^2) (Walter et al. 2007), Schlick's Fresnel at normal
// incidence against f0. Exit 0 when both hold to 1e-5 relative.
#include <cmath>
#include <cstdio>

#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ndf.h"

int main()
{
    const float alpha = 0.3f;
    const double peak = 1.0 / (3.14159265358979323846 * alpha * alpha);
    const float d = rtpbr::D_GGX(1.0f, alpha);
    const rtpbr::float3 f = rtpbr::F_Schlick(rtpbr::float3(0.04f, 0.5f, 0.9f), 1.0f, 1.0f);
    const bool ok = std::fabs(d - peak) <= 1e-5 * peak && std::fabs(f.x - 0.04f) <= 1e-7f &&
                    std::fabs(f.y - 0.5f) <= 1e-6f && std::fabs(f.z - 0.9f) <= 1e-6f;
    std::printf("shade: D_GGX(1, %.1f) = %.6f (closed form %.6f), F_Schlick(f0, 1) = (%.3f, %.3f, %.3f): %s\n",
                alpha, d, peak, f.x, f.y, f.z, ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
