// Kulla-Conty table computation, shared by the generator (lutgen_kc) and tests/shaderlib/kc.
//
// Each NDF / Smith variant of the shader library is compiled in its own translation unit
// (kc_variant.cpp with RTPBR_* flags and RTPBR_CPP_VARIANT); kc_variants() lists them.
// A "cell" is the directional albedo at one (mu, perceptual roughness) of the single-scattering
// BRDF with F = 1 (E) and with the exact dielectric Fresnel at each requested eta (E_F),
// estimated by importance sampling the library's visible-normal sampler: the estimator
// f cos / pdf is bounded, the samples are stratified on an n x n jittered grid, and the
// whole estimate is repeated over independent replicas whose spread gives the standard error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kc {

constexpr int kMaxEta = 32;

struct CellResult {
    double E = 0.0, E_err = 0.0;            // mean and standard error over replicas
    double EF[kMaxEta] = {}, EF_err[kMaxEta] = {};
};

struct SampleSpec {
    int strata = 16;    // n: n x n jittered samples per replica
    int replicas = 8;   // independent replicas (>= 2, for the error estimate)
    std::uint64_t seed = 1;
};

using CellFn = void (*)(float mu, float perceptualRoughness, const float *etas, int nEta,
                        const SampleSpec &spec, CellResult *out);
using BrdfFn = float (*)(float NoV, float NoL, float NoH, float VoH, float alpha);

struct Variant {
    const char *name;        // e.g. "ggx_hc"
    const char *description; // e.g. "GGX, height-correlated Smith"
    bool beckmann;           // NDF (for independent quadratures in tests)
    CellFn cell;
    BrdfFn brdf;             // the variant's BRDF_Specular with F = 1 (D V)
};

// The variants in table order (the order of rtpbr_kc_tables.h).
const std::vector<Variant> &kc_variants();

// Table geometry (matches shaderlib/rtpbr/kulla_conty.h).
struct Geometry {
    int nMu = 32, nR = 32, nEta = 16;
    float etaAxisMax = 0.5f;
};
float kc_mu_of_node(int i, int n);       // axis x = i / (n - 1), mu = x^2, floored at 1e-4
float kc_r_of_node(int i, int n);        // i / (n - 1)
float kc_eta_of_node(int i, int n, float etaAxisMax); // s = max * i / (n - 1), eta = (1+s)/(1-s)

struct Tables {
    Geometry g;
    // [r][mu], [r], [eta][r][mu], [eta][r]
    std::vector<float> E, Eavg, EF, EFavg;
    std::vector<float> E_err, Eavg_err, EF_err, EFavg_err; // standard errors
};

// Cosine-weighted averages use this many Gauss-Legendre nodes in mu.
constexpr int kAvgNodes = 32;
void gauss_legendre01(int n, std::vector<double> &x, std::vector<double> &w);

// Computes all tables of one variant. nThreads >= 1.
void kc_build(const Variant &v, const Geometry &g, const SampleSpec &spec, int nThreads, Tables *out);

// Bilinear lookup of a [r][mu] table at (mu, r) with the shader's texel-centre convention.
float kc_lookup2(const float *table, int nMu, int nR, float mu, float r);
float kc_lookup1(const float *table, int n, float x);

} // namespace kc
