// Kulla-Conty tables: the variant registry, the table layout and the threaded build.
#include "kc_compute.hpp"

#include <rtpbr/kulla_conty.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace kc {

#define KC_DECLARE(sfx)                                                                         \
    void kc_cell_##sfx(float, float, const float *, int, const SampleSpec &, CellResult *);     \
    float kc_brdf_##sfx(float, float, float, float, float);
KC_DECLARE(ggx_hc)
KC_DECLARE(ggx_sep)
KC_DECLARE(ggx_fast)
KC_DECLARE(beckmann_hc)
KC_DECLARE(beckmann_sep)
KC_DECLARE(beckmann_fast)
#undef KC_DECLARE

const std::vector<Variant> &kc_variants() {
    static const std::vector<Variant> variants = {
        {"ggx_hc", "GGX, height-correlated Smith", false, kc_cell_ggx_hc, kc_brdf_ggx_hc},
        {"ggx_sep", "GGX, separable Smith", false, kc_cell_ggx_sep, kc_brdf_ggx_sep},
        {"ggx_fast", "GGX, Hammon 2017 approximate height-correlated visibility", false,
         kc_cell_ggx_fast, kc_brdf_ggx_fast},
        {"beckmann_hc", "Beckmann, height-correlated Smith", true, kc_cell_beckmann_hc,
         kc_brdf_beckmann_hc},
        {"beckmann_sep", "Beckmann, separable Smith", true, kc_cell_beckmann_sep,
         kc_brdf_beckmann_sep},
        {"beckmann_fast", "Beckmann, Walter 2007 rational G1 (separable)", true,
         kc_cell_beckmann_fast, kc_brdf_beckmann_fast},
    };
    return variants;
}

float kc_mu_of_node(int i, int n) {
    float x = static_cast<float>(i) / static_cast<float>(n - 1);
    return std::max(x * x, 1e-4f); // inverse of KC_MuAxis (sqrt); grazing limit at 1e-4
}

float kc_r_of_node(int i, int n) { return static_cast<float>(i) / static_cast<float>(n - 1); }

float kc_eta_of_node(int i, int n, float etaAxisMax) {
    float s = etaAxisMax * static_cast<float>(i) / static_cast<float>(n - 1);
    return (1.0f + s) / (1.0f - s);
}

void gauss_legendre01(int n, std::vector<double> &x, std::vector<double> &w) {
    // Newton iteration on the Legendre polynomial P_n from the Chebyshev-like first guess.
    x.assign(n, 0.0);
    w.assign(n, 0.0);
    for (int i = 0; i < n; i++) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = 0.0;
            for (int j = 1; j <= n; j++) {
                double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            double dz = p0 / dp;
            z -= dz;
            if (std::fabs(dz) < 1e-15)
                break;
        }
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[n - 1 - i] = 1.0 / ((1.0 - z * z) * dp * dp); // 2 / ((1 - z^2) P'^2), halved for [0, 1]
    }
}

void kc_build(const Variant &v, const Geometry &g, const SampleSpec &spec, int nThreads, Tables *out) {
    out->g = g;
    std::vector<float> etas(g.nEta);
    for (int k = 0; k < g.nEta; k++)
        etas[k] = kc_eta_of_node(k, g.nEta, g.etaAxisMax);
    std::vector<double> gx, gw;
    gauss_legendre01(kAvgNodes, gx, gw);

    // Jobs: first the nR x nMu table cells, then nR x kAvgNodes cells for the averages.
    const int nTable = g.nR * g.nMu;
    const int nJobs = nTable + g.nR * kAvgNodes;
    std::vector<CellResult> res(nJobs);
    std::atomic<int> next{0};
    auto worker = [&]() {
        for (int j = next++; j < nJobs; j = next++) {
            float mu, r;
            if (j < nTable) {
                mu = kc_mu_of_node(j % g.nMu, g.nMu);
                r = kc_r_of_node(j / g.nMu, g.nR);
            } else {
                int q = j - nTable;
                mu = static_cast<float>(gx[q % kAvgNodes]);
                r = kc_r_of_node(q / kAvgNodes, g.nR);
            }
            v.cell(mu, r, etas.data(), g.nEta, spec, &res[j]);
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < nThreads; t++)
        pool.emplace_back(worker);
    worker();
    for (auto &t : pool)
        t.join();

    out->E.assign(nTable, 0.0f);
    out->E_err.assign(nTable, 0.0f);
    out->EF.assign(static_cast<size_t>(g.nEta) * nTable, 0.0f);
    out->EF_err.assign(static_cast<size_t>(g.nEta) * nTable, 0.0f);
    out->Eavg.assign(g.nR, 0.0f);
    out->Eavg_err.assign(g.nR, 0.0f);
    out->EFavg.assign(static_cast<size_t>(g.nEta) * g.nR, 0.0f);
    out->EFavg_err.assign(static_cast<size_t>(g.nEta) * g.nR, 0.0f);
    for (int c = 0; c < nTable; c++) {
        out->E[c] = static_cast<float>(res[c].E);
        out->E_err[c] = static_cast<float>(res[c].E_err);
        for (int k = 0; k < g.nEta; k++) {
            out->EF[static_cast<size_t>(k) * nTable + c] = static_cast<float>(res[c].EF[k]);
            out->EF_err[static_cast<size_t>(k) * nTable + c] = static_cast<float>(res[c].EF_err[k]);
        }
    }
    for (int ir = 0; ir < g.nR; ir++) {
        double s = 0.0, e2 = 0.0;
        std::vector<double> sF(g.nEta, 0.0), eF2(g.nEta, 0.0);
        for (int q = 0; q < kAvgNodes; q++) {
            const CellResult &c = res[nTable + ir * kAvgNodes + q];
            double wq = 2.0 * gx[q] * gw[q];
            s += wq * c.E;
            e2 += wq * wq * c.E_err * c.E_err;
            for (int k = 0; k < g.nEta; k++) {
                sF[k] += wq * c.EF[k];
                eF2[k] += wq * wq * c.EF_err[k] * c.EF_err[k];
            }
        }
        out->Eavg[ir] = static_cast<float>(s);
        out->Eavg_err[ir] = static_cast<float>(std::sqrt(e2));
        for (int k = 0; k < g.nEta; k++) {
            out->EFavg[static_cast<size_t>(k) * g.nR + ir] = static_cast<float>(sF[k]);
            out->EFavg_err[static_cast<size_t>(k) * g.nR + ir] = static_cast<float>(std::sqrt(eF2[k]));
        }
    }
}

float kc_lookup1(const float *table, int n, float x) {
    float t = std::min(std::max(x, 0.0f), 1.0f) * (n - 1);
    int i = std::min(static_cast<int>(t), n - 2);
    float f = t - i;
    return table[i] + (table[i + 1] - table[i]) * f;
}

float kc_lookup2(const float *table, int nMu, int nR, float mu, float r) {
    // The shader's axes (KC_TableCoord with any table size): fractional node indices.
    float tx = rtpbr::KC_MuAxis(mu) * (nMu - 1.0f);
    float ty = rtpbr::saturate(r) * (nR - 1.0f);
    int ix = std::min(static_cast<int>(tx), nMu - 2);
    int iy = std::min(static_cast<int>(ty), nR - 2);
    float fx = tx - ix, fy = ty - iy;
    const float *r0 = table + iy * nMu;
    const float *r1 = r0 + nMu;
    float a = r0[ix] + (r0[ix + 1] - r0[ix]) * fx;
    float b = r1[ix] + (r1[ix + 1] - r1[ix]) * fx;
    return a + (b - a) * fy;
}

} // namespace kc
