// lutgen-kc: computes the Kulla-Conty tables of every NDF / Smith variant of the shader
// library and writes them to shaderlib/luts/ (rtpbr_kc_tables.h, kc_*.exr) plus a CSV for
// the plots. Usage: lutgen-kc [--out DIR] [--csv FILE] [--strata N] [--replicas R]
//                             [--threads T] [--quick] [--no-check]
#include "kc_compute.hpp"

#include <rtpbr/kulla_conty.h>

#include "rtpbr_common/image.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

namespace {

bool write_exr(const std::string &path, const float *data, int w, int h, const std::string &desc) {
    rtpbr_tools::ImageWrite image;
    image.width = w, image.height = h, image.channels = 1, image.pixels = data;
    image.channel_names = {"R"};
    // No capture date: regenerating gives byte-identical files.
    image.attributes = {{"ImageDescription", desc}, {"compression", "zip"}, {"DateTime", ""}};
    std::string error;
    if (!rtpbr_tools::write_image(path, image, error)) {
        std::fprintf(stderr, "lutgen-kc: %s\n", error.c_str());
        return false;
    }
    return true;
}

// A float literal valid in C and C++ ("1.0f", not "1f").
std::string float_literal(float x) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g", static_cast<double>(x));
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos)
        s += ".0";
    return s + "f";
}

void print_array(FILE *f, const std::vector<float> &v, int perLine) {
    for (size_t i = 0; i < v.size(); i++)
        std::fprintf(f, "%s%s,", (i % perLine) ? " " : "\n    ", float_literal(v[i]).c_str());
    std::fprintf(f, "\n");
}

float max_of(const std::vector<float> &v) { return v.empty() ? 0.0f : *std::max_element(v.begin(), v.end()); }

float quantile_of(std::vector<float> v, double q) {
    if (v.empty())
        return 0.0f;
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(q * (v.size() - 1))];
}

// Trilinear lookup of E_F at (mu, r, eta), as the shader's KC_TableCoord3D addresses it.
float lookup3(const kc::Tables &t, float mu, float r, float eta) {
    const int nT = t.g.nMu * t.g.nR;
    float tz = rtpbr::KC_EtaAxis(eta) * (t.g.nEta - 1.0f);
    int iz = std::min(static_cast<int>(tz), t.g.nEta - 2);
    float fz = tz - iz;
    float a = kc::kc_lookup2(&t.EF[static_cast<size_t>(iz) * nT], t.g.nMu, t.g.nR, mu, r);
    float b = kc::kc_lookup2(&t.EF[static_cast<size_t>(iz + 1) * nT], t.g.nMu, t.g.nR, mu, r);
    return a + (b - a) * fz;
}

const char *const kUsage =
    "usage: lutgen-kc [--out DIR] [--csv FILE] [--strata N] [--replicas R] [--threads T] [--quick]\n"
    "                 [--no-check]\n"
    "Computes the Kulla-Conty tables of every NDF / Smith variant of the shader library and writes\n"
    "DIR/rtpbr_kc_tables.h and DIR/kc_*.exr.\n"
    "  --out DIR     output directory (default .)\n"
    "  --csv FILE    also write the plot data (tools/lutgen/plot_kc.py reads it)\n"
    "  --strata N    N x N stratified samples per replica and cell (default 32)\n"
    "  --replicas R  independent replicas per cell, >= 2 (default 8)\n"
    "  --threads T   worker threads (1..64; default 2)\n"
    "  --quick       8 strata, 4 replicas\n"
    "  --no-check    skip the interpolation error check against a finer reference\n"
    "  -h, --help    this text\n";

} // namespace

int main(int argc, char **argv) {
    std::string outDir = ".", csvPath;
    kc::SampleSpec spec;
    spec.strata = 32;
    spec.replicas = 8;
    int threads = 2;
    bool check = true;
    kc::Geometry g;
    for (int i = 1; i < argc; i++) {
        auto need = [&](const char *name) -> const char * {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "lutgen-kc: %s needs a value\n", name);
                std::exit(2);
            }
            return argv[++i];
        };
        if (!std::strcmp(argv[i], "--out"))
            outDir = need("--out");
        else if (!std::strcmp(argv[i], "--csv"))
            csvPath = need("--csv");
        else if (!std::strcmp(argv[i], "--strata"))
            spec.strata = std::atoi(need("--strata"));
        else if (!std::strcmp(argv[i], "--replicas"))
            spec.replicas = std::atoi(need("--replicas"));
        else if (!std::strcmp(argv[i], "--threads"))
            threads = std::atoi(need("--threads"));
        else if (!std::strcmp(argv[i], "--quick")) {
            spec.strata = 8;
            spec.replicas = 4;
        } else if (!std::strcmp(argv[i], "--no-check"))
            check = false;
        else if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help"))
            return std::fputs(kUsage, stdout), 0;
        else {
            std::fprintf(stderr, "lutgen-kc: unknown argument %s\n%s", argv[i], kUsage);
            return 2;
        }
    }
    if (spec.strata < 1 || spec.replicas < 2 || threads < 1 || threads > 64) {
        std::fprintf(stderr, "lutgen-kc: need --strata >= 1, --replicas >= 2, 1 <= --threads <= 64\n");
        return 2;
    }
    std::error_code ec;
    if (!std::filesystem::is_directory(outDir, ec)) {
        std::fprintf(stderr, "lutgen-kc: output directory %s does not exist\n", outDir.c_str());
        return 1;
    }
    if (g.nMu != static_cast<int>(rtpbr::KC_LUT_SIZE) || g.nEta != static_cast<int>(rtpbr::KC_LUT_SIZE_ETA) ||
        g.etaAxisMax != rtpbr::KC_ETA_AXIS_MAX) {
        std::fprintf(stderr, "lutgen-kc: table geometry disagrees with kulla_conty.h\n");
        return 1;
    }

    const auto &variants = kc::kc_variants();
    std::vector<kc::Tables> tables(variants.size());
    auto t0 = std::chrono::steady_clock::now();
    for (size_t v = 0; v < variants.size(); v++) {
        auto tv = std::chrono::steady_clock::now();
        kc::kc_build(variants[v], g, spec, threads, &tables[v]);
        double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - tv).count();
        std::printf("%-14s %6.1f s  stderr E: median %.1e 99%% %.1e | max stderr: E %.2e  E_avg %.2e  E_F %.2e  "
                    "E_F_avg %.2e\n",
                    variants[v].name, sec, static_cast<double>(quantile_of(tables[v].E_err, 0.5)),
                    static_cast<double>(quantile_of(tables[v].E_err, 0.99)), static_cast<double>(max_of(tables[v].E_err)),
                    static_cast<double>(max_of(tables[v].Eavg_err)), static_cast<double>(max_of(tables[v].EF_err)),
                    static_cast<double>(max_of(tables[v].EFavg_err)));
        std::fflush(stdout);
    }
    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("generation: %.1f s with %d thread(s), %d samples per cell\n", total, threads,
                spec.strata * spec.strata * spec.replicas);

    // ---- C header -----------------------------------------------------------------------
    float maxErr = 0.0f;
    for (const auto &t : tables)
        maxErr = std::max({maxErr, max_of(t.E_err), max_of(t.Eavg_err), max_of(t.EF_err), max_of(t.EFavg_err)});
    std::string hpath = outDir + "/rtpbr_kc_tables.h";
    FILE *f = std::fopen(hpath.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "lutgen-kc: cannot write %s\n", hpath.c_str());
        return 1;
    }
    const int nV = static_cast<int>(variants.size());
    std::fprintf(f,
                 "// Kulla-Conty energy-compensation tables. GENERATED by tools/lutgen (lutgen-kc,\n"
                 "// `ninja -C build lutgen-kc`); do not edit. See kulla_conty.md and rtpbr/kulla_conty.h.\n"
                 "// Plain C / C++. Every axis holds its values at texel centres, node i at axis value\n"
                 "// i / (N - 1): mu axis x = sqrt(mu) (node 0 evaluated at mu = 1e-4), roughness axis =\n"
                 "// perceptual roughness r (alpha = max(r^2, 1e-3)), IOR axis s = (eta - 1) / (eta + 1)\n"
                 "// on [0, %g] (eta in [1, %g]).\n"
                 "// Layouts (row-major, last index fastest):\n"
                 "//   rtpbr_kc_E      [variant][r][mu]        E(mu, r), F = 1\n"
                 "//   rtpbr_kc_Eavg   [variant][r]            E_avg(r) = 2 int E mu dmu\n"
                 "//   rtpbr_kc_EF     [variant][eta][r][mu]   albedo with the exact dielectric Fresnel\n"
                 "//   rtpbr_kc_EFavg  [variant][eta][r]\n"
                 "// Monte Carlo: %d samples per cell (%d replicas of %dx%d stratified VNDF samples);\n"
                 "// largest standard error of any entry: RTPBR_KC_MAX_STDERR.\n"
                 "#ifndef RTPBR_KC_TABLES_H\n#define RTPBR_KC_TABLES_H\n\n",
                 static_cast<double>(g.etaAxisMax),
                 static_cast<double>((1.0f + g.etaAxisMax) / (1.0f - g.etaAxisMax)),
                 spec.strata * spec.strata * spec.replicas, spec.replicas, spec.strata, spec.strata);
    std::fprintf(f, "#define RTPBR_KC_SIZE %d\n#define RTPBR_KC_SIZE_ETA %d\n#define RTPBR_KC_VARIANTS %d\n",
                 g.nMu, g.nEta, nV);
    std::fprintf(f, "#define RTPBR_KC_MAX_STDERR %s\n\n", float_literal(maxErr).c_str());
    std::fprintf(f, "// Variant order:");
    for (int v = 0; v < nV; v++)
        std::fprintf(f, " %d %s (%s)%s", v, variants[v].name, variants[v].description, v + 1 < nV ? ";" : ".");
    std::fprintf(f, "\n");
    for (int v = 0; v < nV; v++)
        std::fprintf(f, "#define RTPBR_KC_VARIANT_%s %d\n", variants[v].name, v);
    std::fprintf(f, "\nstatic const char *const rtpbr_kc_variant_names[%d] = {", nV);
    for (int v = 0; v < nV; v++)
        std::fprintf(f, "\"%s\"%s", variants[v].name, v + 1 < nV ? ", " : "");
    std::fprintf(f, "};\n");
    // Fully braced nested initialisers (C's -Wmissing-braces), innermost rows 8 values a line.
    auto emit = [&](const char *name, std::vector<int> dims, std::vector<float> kc::Tables::*member) {
        std::string d;
        for (int n : dims)
            d += "[" + std::to_string(n) + "]";
        std::fprintf(f, "\nstatic const float %s[%d]%s = {", name, nV, d.c_str());
        for (int v = 0; v < nV; v++) {
            const std::vector<float> &a = tables[v].*member;
            const int inner = dims.back();
            const int rows = static_cast<int>(a.size()) / inner;
            std::fprintf(f, "\n  {");
            for (int row = 0; row < rows; row++) {
                // Open / close the braces of every dimension this row starts / ends.
                int open = 0, close = 0;
                for (size_t k = 0; k + 1 < dims.size(); k++) {
                    int block = 1;
                    for (size_t j = k + 1; j + 1 < dims.size(); j++)
                        block *= dims[j];
                    if (row % block == 0)
                        open++;
                    if ((row + 1) % block == 0)
                        close++;
                }
                if (open > 0)
                    std::fprintf(f, "\n    %s", std::string(static_cast<size_t>(open), '{').c_str());
                std::vector<float> slice(a.begin() + static_cast<std::ptrdiff_t>(row) * inner,
                                         a.begin() + static_cast<std::ptrdiff_t>(row + 1) * inner);
                print_array(f, slice, 8);
                if (close > 0)
                    std::fprintf(f, "    %s,", std::string(static_cast<size_t>(close), '}').c_str());
            }
            std::fprintf(f, "  },");
        }
        std::fprintf(f, "\n};\n");
    };
    emit("rtpbr_kc_E", {g.nR, g.nMu}, &kc::Tables::E);
    emit("rtpbr_kc_Eavg", {g.nR}, &kc::Tables::Eavg);
    emit("rtpbr_kc_EF", {g.nEta, g.nR, g.nMu}, &kc::Tables::EF);
    emit("rtpbr_kc_EFavg", {g.nEta, g.nR}, &kc::Tables::EFavg);
    std::fprintf(f, "\n#endif // RTPBR_KC_TABLES_H\n");
    std::fclose(f);

    // ---- EXR ---------------------------------------------------------------------------------
    for (int v = 0; v < nV; v++) {
        const kc::Tables &t = tables[v];
        std::string base = outDir + "/kc_";
        std::string n = variants[v].name;
        if (!write_exr(base + "E_" + n + ".exr", t.E.data(), g.nMu, g.nR,
                       "E(mu, r) " + n + ": x = sqrt(mu), y = perceptual roughness") ||
            !write_exr(base + "Eavg_" + n + ".exr", t.Eavg.data(), g.nR, 1, "E_avg(r) " + n) ||
            !write_exr(base + "EF_" + n + ".exr", t.EF.data(), g.nMu, g.nR * g.nEta,
                       "E_F(mu, r, eta) " + n + ": x = sqrt(mu), y = r, slices of nR rows along eta") ||
            !write_exr(base + "EFavg_" + n + ".exr", t.EFavg.data(), g.nR, g.nEta,
                       "E_F_avg(r, eta) " + n + ": x = r, y = eta axis"))
            return 1;
    }

    // ---- interpolation error and plot data -------------------------------------------------------
    if (check) {
        kc::SampleSpec ref;
        ref.strata = 64;
        ref.replicas = 4;
        ref.seed = 777;
        std::mt19937 rng(12345);
        std::uniform_real_distribution<float> U(0.0f, 1.0f);
        for (int v = 0; v < nV; v++) {
            double maxE = 0.0, sumE = 0.0, maxE1 = 0.0, maxF = 0.0, maxRef = 0.0;
            const int N = 100;
            for (int s = 0; s < N; s++) {
                float mu = U(rng), r = U(rng);
                float eta = 1.0f + 2.0f * U(rng);
                kc::CellResult c;
                variants[v].cell(mu, r, &eta, 1, ref, &c);
                double e = std::fabs(kc::kc_lookup2(tables[v].E.data(), g.nMu, g.nR, mu, r) - c.E);
                maxE = std::max(maxE, e);
                if (mu >= 0.1f)
                    maxE1 = std::max(maxE1, e);
                sumE += e;
                maxF = std::max(maxF, std::fabs(static_cast<double>(lookup3(tables[v], mu, r, eta)) - c.EF[0]));
                maxRef = std::max({maxRef, c.E_err, c.EF_err[0]});
            }
            std::printf("%-14s interpolation |lerp - direct| over %d random points: E max %.2e (mu >= 0.1: %.2e) "
                        "mean %.2e; E_F max %.2e; reference stderr <= %.1e\n",
                        variants[v].name, N, maxE, maxE1, sumE / N, maxF, maxRef);
            std::fflush(stdout);
        }
    }
    if (!csvPath.empty()) {
        FILE *c = std::fopen(csvPath.c_str(), "w");
        if (!c) {
            std::fprintf(stderr, "lutgen-kc: cannot write %s\n", csvPath.c_str());
            return 1;
        }
        std::vector<double> gx, gw;
        kc::gauss_legendre01(64, gx, gw);
        kc::SampleSpec ps;
        ps.strata = 32;
        ps.replicas = 2;
        ps.seed = 99;
        std::fprintf(c, "variant,r,mu,E_ss,E_total\n");
        for (int v = 0; v < nV; v++) {
            const kc::Tables &t = tables[v];
            for (float r : {0.1f, 0.25f, 0.4f, 0.55f, 0.7f, 0.85f, 1.0f}) {
                // Albedo of f_ms at mu_o: (1 - E(mu_o)) / (1 - E_avg) * 2 int (1 - E(mu_i)) mu_i dmu_i.
                double I = 0.0;
                for (int q = 0; q < 64; q++)
                    I += 2.0 * gx[q] * gw[q] * (1.0 - kc::kc_lookup2(t.E.data(), g.nMu, g.nR, static_cast<float>(gx[q]), r));
                float Eavg = kc::kc_lookup1(t.Eavg.data(), g.nR, r);
                for (int m = 0; m < 48; m++) {
                    float mu = (m + 0.5f) / 48.0f;
                    kc::CellResult cr;
                    variants[v].cell(mu, r, nullptr, 0, ps, &cr);
                    float Eo = kc::kc_lookup2(t.E.data(), g.nMu, g.nR, mu, r);
                    double ms = Eavg < 1.0f ? (1.0 - Eo) * I / (1.0 - Eavg) : 0.0;
                    std::fprintf(c, "%s,%g,%g,%.6g,%.6g\n", variants[v].name, static_cast<double>(r),
                                 static_cast<double>(mu), cr.E, cr.E + ms);
                }
            }
        }
        std::fclose(c);
    }
    return 0;
}
