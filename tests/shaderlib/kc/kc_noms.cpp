// kulla_conty.h compiled with RTPBR_MULTISCATTER=0 (its own C++ variant namespace): the
// compensated entry points reduce to single scattering, and the translation unit compiles
// warning-free with every parameter unused by that setting.
#include <rtpbr/kulla_conty.h>

#include <cmath>

bool kc_noms_reduces_to_single_scattering() {
    using namespace rtpbr;
    FresnelParams fp = Fresnel_FromF0(float3(0.9f, 0.6f, 0.3f));
    float3 favg = F_Avg_Microfacet(fp);
    float3 a = BRDF_SpecularMS(0.5f, 0.6f, 0.95f, 0.8f, 0.3f, fp, 0.7f, 0.7f, 0.6f, favg);
    float3 b = BRDF_Specular(0.5f, 0.6f, 0.95f, 0.8f, 0.3f, fp);
    // Layered: the specular is f_ss alone and E_s = E_F (white base: 1 - E_F scaled lobe).
    float3 l = BRDF_DielectricOverDiffuse(0.5f, 0.6f, 0.0f, 1.0f, 0.3f, 1.5f, float3(1.0f), 0.1f, 0.2f, 0.15f,
                                          0.7f, 0.7f, 0.6f);
    float expect = (1.0f - 0.1f) * (1.0f - 0.2f) / (RTPBR_PI * (1.0f - 0.15f));
    return a == b && std::fabs(l.x - expect) < 1e-6f;
}
