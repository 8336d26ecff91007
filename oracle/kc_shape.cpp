// rtpbr-kc-shape: where the multiple scattering of the Smith microsurface goes, against the
// separable Kulla-Conty lobe and the shaped lobe (kulla_conty.h, KC_LobeShaped; issue 19).
//
//   rtpbr-kc-shape [--samples N] [--threads T] [--f0 F] [--csv FILE] [--quick] [--check]
//
// For each cell (perceptual roughness r, view cosine mu_o) of a grid, N walks of the oracle's
// random walk (oracle/microsurface.h: Heitz et al. 2016, GGX, Schlick Fresnel f0 = F, f90 = 1;
// default F = 1, the uncoloured lobe the tables are made for) start along -wo; where each
// leaves is binned over the hemisphere (32 bins in mu^2 x 32 in |phi|: equal projected solid
// angle), once scattered and twice or more. The model lobes are integrated over the same
// bins: the separable lobe (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)), and the single-
// scattering lobe's shape with the same energy, (1 - E(mu_o)) f_ss / E(mu_o), taken from the
// walk's own once-scattered exits (E from the walk too, so that the two agree exactly in
// energy). For every beta in [0, 1] (steps of 0.01) two distances of the blend
// beta x shape + (1 - beta) x separable from the walk:
//   whole   the error of the whole BRDF a light in a bin would see: |model - walk ms| /
//           (walk ss + walk ms) averaged over the projected solid angle (denominator floored at
//           2% of the multiple scattering's uniform level);
//   ms      the L1 distance of the multiple scattering over its energy.
// Printed per cell: the best beta for each distance, and both distances at beta = 0 (the
// separable lobe), at KC_ShapeWeight(r, mu_o) (the shaderlib's closed form, fitted to these
// numbers) and at the per-cell best. --csv writes every cell's two curves.
// Takes about 20 s on 2 cores at the defaults (--quick: a 4 x 4 grid, 3x fewer walks, 1 s).
// --check: exit status 3 unless the closed form's mean of both distances is below the
// separable lobe's (the test suite runs --quick --check).
#include "microsurface.h"
#include "rng.h"

#include <rtpbr/kulla_conty.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kNU = 32, kNP = 32, kBetas = 101;

struct Cell {
    float r = 0.0f, mu = 0.0f;
    double walkMs = 0.0;
    std::vector<double> whole, ms; // per beta
};

// E(mu) of the walk: the fraction of walks that leave after one reflection (F = 1), on a
// grid of mu, linearly interpolated.
struct WalkE {
    std::vector<double> e;
    double at(double mu) const {
        double x = std::min(std::max(mu, 0.0), 1.0) * (e.size() - 1);
        size_t k = std::min(static_cast<size_t>(x), e.size() - 2);
        double t = x - k;
        return e[k] * (1.0 - t) + e[k + 1] * t;
    }
};

WalkE walk_E(const rtpbr_oracle::MicrosurfaceGGX &ms, long n, uint64_t seed) {
    rtpbr_oracle::ConductorFresnel white;
    rtpbr_oracle::Rng rng(seed, 17);
    WalkE w;
    const int NE = 33;
    for (int k = 0; k < NE; k++) {
        float mu = std::max(k / float(NE - 1), 2e-3f);
        glm::vec3 o(std::sqrt(1.0f - mu * mu), 0.0f, mu), wo, weight;
        long once = 0;
        for (long i = 0; i < n; i++) {
            int order = 0;
            if (rtpbr_oracle::conductorSample(ms, white, o, rng, &wo, &weight, &order) && order == 1)
                once++;
        }
        w.e.push_back(double(once) / n);
    }
    return w;
}

void run_cell(Cell &c, long n, float f0, uint64_t seed) {
    const float alpha = rtpbr::Alpha_FromPerceptual(c.r);
    rtpbr_oracle::MicrosurfaceGGX ms(alpha, alpha);
    const WalkE E = walk_E(ms, std::max(n / 8, 1000L), seed * 7 + 1);
    double Eavg = 0.0;
    for (int k = 0; k < 1000; k++) {
        double mu = (k + 0.5) / 1000.0;
        Eavg += 2.0 * E.at(mu) * mu / 1000.0;
    }
    rtpbr_oracle::ConductorFresnel F;
    F.f0 = glm::vec3(f0);
    F.f90 = 1.0f;
    rtpbr_oracle::Rng rng(seed, 29);
    const glm::vec3 o(std::sqrt(1.0f - c.mu * c.mu), 0.0f, c.mu);
    std::vector<double> ss(kNU * kNP, 0.0), msw(kNU * kNP, 0.0);
    for (long i = 0; i < n; i++) {
        glm::vec3 wo, weight;
        int order = 0;
        if (!rtpbr_oracle::conductorSample(ms, F, o, rng, &wo, &weight, &order) || order < 1)
            continue;
        float u = std::min(wo.z * wo.z, 0.999999f);
        int a = std::min(static_cast<int>(u * kNU), kNU - 1);
        int p = std::min(static_cast<int>(std::fabs(std::atan2(wo.y, wo.x)) / kPi * kNP), kNP - 1);
        (order == 1 ? ss : msw)[a * kNP + p] += double(weight.y) / n;
    }
    double ssTotal = 0.0, msTotal = 0.0;
    for (int q = 0; q < kNU * kNP; q++)
        ssTotal += ss[q], msTotal += msw[q];
    c.walkMs = msTotal;
    // The model's multiple-scattering energy: KC_FmsColor x (1 - E(mu_o)) (F = 1: 1 - E).
    const float Favg = f0 + (1.0f - f0) / 21.0f; // F_Avg_Schlick with f90 = 1
    const double energy = rtpbr::KC_FmsColor(rtpbr::float3(Favg), float(Eavg)).y * (1.0 - E.at(c.mu));
    std::vector<double> sep(kNU * kNP), shape(kNU * kNP);
    const int SUB = 4;
    const double area = (1.0 / kNU) * (kPi / kNP) / (SUB * SUB); // projected solid angle, both signs of phi
    for (int a = 0; a < kNU; a++)
        for (int p = 0; p < kNP; p++) {
            double k = 0.0;
            for (int sa = 0; sa < SUB; sa++) {
                double m = std::sqrt((a + (sa + 0.5) / SUB) / kNU);
                k += SUB * (1.0 - E.at(m)) / (kPi * (1.0 - Eavg)) * area;
            }
            int q = a * kNP + p;
            sep[q] = energy * k;
            shape[q] = ssTotal > 0.0 ? energy * ss[q] / ssTotal : 0.0;
        }
    c.whole.assign(kBetas, 0.0);
    c.ms.assign(kBetas, 0.0);
    const double w = 1.0 / (kNU * kNP), floor = 0.02 * msTotal * w;
    for (int b = 0; b < kBetas; b++) {
        double beta = b / double(kBetas - 1), whole = 0.0, l1 = 0.0;
        for (int q = 0; q < kNU * kNP; q++) {
            double d = std::fabs(beta * shape[q] + (1.0 - beta) * sep[q] - msw[q]);
            whole += w * d / (ss[q] + msw[q] + floor);
            l1 += d;
        }
        c.whole[b] = whole;
        c.ms[b] = msTotal > 0.0 ? l1 / msTotal : 0.0;
    }
}

double curve_at(const std::vector<double> &c, double beta) {
    double x = std::min(std::max(beta, 0.0), 1.0) * (kBetas - 1);
    int k = std::min(static_cast<int>(x), kBetas - 2);
    double t = x - k;
    return c[k] * (1.0 - t) + c[k + 1] * t;
}

const char *const kUsage =
    "usage: rtpbr-kc-shape [--samples N] [--threads T] [--f0 F] [--csv FILE] [--quick] [--check]\n"
    "Where the Smith microsurface's multiple scattering goes, against the separable Kulla-Conty\n"
    "lobe and the shaped lobe: per cell (roughness, view cosine) the best blend weight and the\n"
    "distances of both lobes from the oracle's random walk.\n"
    "  --samples N  random walks per grid cell (>= 1000; default 300000)\n"
    "  --threads T  worker threads (1..256; default 2)\n"
    "  --f0 F       Schlick Fresnel f0 of the walk, in (0, 1] (default 1: the tables' lobe)\n"
    "  --csv FILE   also write every cell's two distance curves over the blend weight\n"
    "  --quick      a 4 x 4 grid and 3x fewer walks (about 1 s instead of 20 s on 2 cores)\n"
    "  --check      exit 3 unless the closed form KC_ShapeWeight beats the separable lobe\n"
    "  -h, --help   this text\n";

int best_index(const std::vector<double> &c) { return static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin()); }

} // namespace

int main(int argc, char **argv) {
    long samples = 300000;
    int threads = 2;
    float f0 = 1.0f;
    const char *csv = nullptr;
    bool quick = false, check = false;
    for (int i = 1; i < argc; i++) {
        bool more = i + 1 < argc;
        if (!strcmp(argv[i], "--samples") && more)
            samples = atol(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && more)
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--f0") && more)
            f0 = static_cast<float>(atof(argv[++i]));
        else if (!strcmp(argv[i], "--csv") && more)
            csv = argv[++i];
        else if (!strcmp(argv[i], "--quick"))
            quick = true;
        else if (!strcmp(argv[i], "--check"))
            check = true;
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help"))
            return fputs(kUsage, stdout), 0;
        else
            return fputs(kUsage, stderr), 2;
    }
    if (samples < 1000 || threads < 1 || threads > 256 || !(f0 > 0.0f && f0 <= 1.0f)) {
        fprintf(stderr, "rtpbr-kc-shape: --samples must be >= 1000, --threads 1-256, --f0 in (0, 1]\n");
        return 2;
    }
    FILE *out = nullptr;
    if (csv && !(out = fopen(csv, "w"))) {
        fprintf(stderr, "rtpbr-kc-shape: cannot write %s\n", csv);
        return 1;
    }
    std::vector<float> rs = {0.1f, 0.15f, 0.2f, 0.25f, 0.3f, 0.35f, 0.4f, 0.45f, 0.5f, 0.55f, 0.6f, 0.65f, 0.7f, 0.8f, 0.9f, 1.0f};
    std::vector<float> mus = {0.05f, 0.1f, 0.15f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 0.95f, 1.0f};
    if (quick) {
        rs = {0.2f, 0.35f, 0.5f, 0.8f};
        mus = {0.1f, 0.3f, 0.6f, 0.9f};
        samples = std::max(samples / 3, 1000L);
    }
    std::vector<Cell> cells;
    for (float r : rs)
        for (float mu : mus) {
            Cell c;
            c.r = r;
            c.mu = mu;
            cells.push_back(c);
        }
    const auto start = std::chrono::steady_clock::now();
    std::atomic<size_t> next(0), done(0);
    std::mutex printMutex;
    auto work = [&]() {
        for (size_t k; (k = next++) < cells.size();) {
            run_cell(cells[k], samples, f0, 1000 + k); // seeds by cell: independent of the thread count
            std::lock_guard<std::mutex> lock(printMutex);
            fprintf(stderr, "\rrtpbr-kc-shape: %zu/%zu cells", size_t(++done), cells.size());
        }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; t++)
        pool.emplace_back(work);
    for (auto &t : pool)
        t.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fprintf(stderr, "\rrtpbr-kc-shape: %zu cells, %ld walks each, %.1f s\n", cells.size(), samples, seconds);

    printf("| r | mu_o | walk ms | best beta (whole / ms) | KC_ShapeWeight | whole: separable / closed form / best | "
           "ms L1: separable / closed form / best |\n|---|---|---|---|---|---|---|\n");
    double sum[2][3] = {}, n = 0;
    for (const Cell &c : cells) {
        double beta = rtpbr::KC_ShapeWeight(c.r, c.mu);
        int bw = best_index(c.whole), bm = best_index(c.ms);
        printf("| %.2f | %.2f | %.4f | %.2f / %.2f | %.2f | %.3f / %.3f / %.3f | %.3f / %.3f / %.3f |\n", c.r, c.mu, c.walkMs,
               bw / double(kBetas - 1), bm / double(kBetas - 1), beta, c.whole[0], curve_at(c.whole, beta), c.whole[bw],
               c.ms[0], curve_at(c.ms, beta), c.ms[bm]);
        if (c.r >= 0.2f) {
            sum[0][0] += c.whole[0], sum[0][1] += curve_at(c.whole, beta), sum[0][2] += c.whole[bw];
            sum[1][0] += c.ms[0], sum[1][1] += curve_at(c.ms, beta), sum[1][2] += c.ms[bm];
            n++;
        }
        if (out) {
            fprintf(out, "%.3f,%.3f", c.r, c.mu);
            for (double v : c.whole)
                fprintf(out, ",%.6f", v);
            for (double v : c.ms)
                fprintf(out, ",%.6f", v);
            fprintf(out, "\n");
        }
    }
    if (n > 0)
        printf("\nMeans over the cells with r >= 0.2 (%d): whole BRDF's error separable %.4f, closed form %.4f, per-cell best "
               "%.4f; multiple scattering's L1 separable %.4f, closed form %.4f, per-cell best %.4f\n",
               int(n), sum[0][0] / n, sum[0][1] / n, sum[0][2] / n, sum[1][0] / n, sum[1][1] / n, sum[1][2] / n);
    if (out && fclose(out) != 0) {
        fprintf(stderr, "rtpbr-kc-shape: error writing %s\n", csv);
        return 1;
    }
    if (check && !(n > 0 && sum[0][1] < sum[0][0] && sum[1][1] < sum[1][0])) {
        fprintf(stderr, "rtpbr-kc-shape: the closed form is not closer to the walk than the separable lobe\n");
        return 3;
    }
    return 0;
}
