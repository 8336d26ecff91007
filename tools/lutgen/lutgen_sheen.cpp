// lutgen-sheen: the directional albedo E_sheen(mu, r) of the KHR_materials_sheen lobe
// (shaderlib/rtpbr/sheen.h, sheenColor = 1) for the albedo-scaling layering, written to
// shaderlib/luts/rtpbr_sheen_tables.h and the generated section of shaderlib/luts/sheen.md.
//   lutgen-sheen [--out DIR] [--strata N] [--replicas R] [--threads T]
// Per cell: R independent replicas of an N x N jittered-stratified grid of Sample_SheenLobe
// directions (half D_Charlie reflection, half uniform hemisphere), estimator f cos / pdf;
// the standard error is the spread of the replica means / sqrt(R). Seeds depend only on the
// cell: a rerun gives the same bytes.
#include <rtpbr/sheen.h>

#include "rtpbr_common/markdown.hpp"
#include "rtpbr_common/rng.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kSize = 32;
constexpr int kVariants = 2; // 0 charlie (V_Charlie, the default), 1 neubelt (V_Neubelt)
const char *const kVariantNames[kVariants] = {"charlie", "neubelt"};

double node_mu(int i) {
    double x = double(i) / (kSize - 1);
    return i == 0 ? 1e-4 : x * x;
}

struct CellResult {
    double mean, stderr_;
};

CellResult cell(int variant, int ir, int imu, int strata, int replicas) {
    const float r = float(ir) / float(kSize - 1);
    const float alpha = rtpbr::Sheen_Alpha(r);
    const float mu = float(node_mu(imu));
    const glm::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    rtpbr_tools::SplitMix64 rng(0x7368656e00000000ull ^ (uint64_t(variant) << 24) ^ (uint64_t(ir) << 12) ^ uint64_t(imu));
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < replicas; k++) {
        double acc = 0.0;
        for (int j = 0; j < strata * strata; j++) {
            glm::vec2 u((float(j % strata) + rng.uniform_float()) / float(strata),
                        (float(j / strata) + rng.uniform_float()) / float(strata));
            glm::vec3 wi = rtpbr::Sample_SheenLobe(wo, u, alpha);
            if (!(wi.z > 0.0f))
                continue;
            float pdf = rtpbr::PDF_SheenLobe(wo, wi, alpha);
            glm::vec3 h = glm::normalize(wo + wi);
            float V = variant == 0 ? rtpbr::V_Charlie(wo.z, wi.z, alpha) : rtpbr::V_Neubelt(wo.z, wi.z);
            double f = double(rtpbr::D_Charlie(h.z, alpha)) * double(V);
            if (pdf > 0.0f)
                acc += f * double(wi.z) / double(pdf);
        }
        acc /= double(strata * strata);
        sum += acc;
        sum2 += acc * acc;
    }
    double mean = sum / replicas;
    double var = std::max(0.0, sum2 / replicas - mean * mean) * replicas / std::max(1, replicas - 1);
    return {mean, std::sqrt(var / replicas)};
}

std::string float_literal(float x) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", double(x));
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos)
        s += ".0";
    return s + "f";
}

const char *const kUsage =
    "usage: lutgen-sheen [--out DIR] [--strata N] [--replicas R] [--threads T]\n"
    "The directional albedo of the KHR_materials_sheen lobe: writes DIR/rtpbr_sheen_tables.h and\n"
    "the generated section of DIR/sheen.md. Deterministic.\n"
    "  --out DIR     output directory (default .)\n"
    "  --strata N    N x N jittered-stratified samples per replica and cell (4..512; default 64)\n"
    "  --replicas R  independent replicas per cell (2..64; default 8)\n"
    "  --threads T   worker threads (1..64; default 2)\n"
    "  -h, --help    this text\n";

int usage() {
    std::fputs(kUsage, stderr);
    return 2;
}

} // namespace

int main(int argc, char **argv) {
    std::string out = ".";
    int strata = 64, replicas = 8, threads = 2;
    for (int i = 1; i < argc; i++) {
        auto intArg = [&](int lo, int hi, int &dst) {
            if (i + 1 >= argc)
                return false;
            char *end = nullptr;
            long v = std::strtol(argv[++i], &end, 10);
            if (!end || *end || v < lo || v > hi)
                return false;
            dst = int(v);
            return true;
        };
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help"))
            return std::fputs(kUsage, stdout), 0;
        if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!std::strcmp(argv[i], "--strata")) {
            if (!intArg(4, 512, strata))
                return usage();
        } else if (!std::strcmp(argv[i], "--replicas")) {
            if (!intArg(2, 64, replicas))
                return usage();
        } else if (!std::strcmp(argv[i], "--threads")) {
            if (!intArg(1, 64, threads))
                return usage();
        } else
            return usage();
    }
    std::vector<double> E(size_t(kVariants) * kSize * kSize), SE(E.size());
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; t++)
        pool.emplace_back([&, t]() {
            for (int row = t; row < kVariants * kSize; row += threads) {
                int v = row / kSize, ir = row % kSize;
                for (int imu = 0; imu < kSize; imu++) {
                    CellResult c = cell(v, ir, imu, strata, replicas);
                    size_t k = (size_t(v) * kSize + size_t(ir)) * kSize + size_t(imu);
                    E[k] = c.mean;
                    SE[k] = c.stderr_;
                }
            }
        });
    for (std::thread &th : pool)
        th.join();

    double maxSE[kVariants] = {0, 0}, maxE[kVariants] = {0, 0}, maxRelSE[kVariants] = {0, 0};
    std::vector<double> ses[kVariants];
    for (int v = 0; v < kVariants; v++)
        for (int k = 0; k < kSize * kSize; k++) {
            size_t i = size_t(v) * kSize * kSize + size_t(k);
            maxSE[v] = std::max(maxSE[v], SE[i]);
            maxE[v] = std::max(maxE[v], E[i]);
            if (E[i] >= 0.01) // relative error where the lobe carries light
                maxRelSE[v] = std::max(maxRelSE[v], SE[i] / E[i]);
            ses[v].push_back(SE[i]);
        }
    const std::string header = out + "/rtpbr_sheen_tables.h";
    FILE *f = std::fopen(header.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "lutgen-sheen: cannot write %s\n", header.c_str());
        return 1;
    }
    std::fprintf(f,
                 "// KHR_materials_sheen directional albedo E_sheen(mu, r). GENERATED by tools/lutgen\n"
                 "// (lutgen-sheen, `ninja -C build lutgen-sheen`); do not edit. See sheen.md and rtpbr/sheen.h.\n"
                 "// Plain C / C++. E = int D_Charlie V cos dw_i with sheenColor = 1 (no Fresnel), the\n"
                 "// Kulla-Conty axis conventions: node i of 32 at i / 31 on texel centres; mu axis x = sqrt(mu)\n"
                 "// (node 0 evaluated at mu = 1e-4), roughness axis = sheen perceptual roughness r\n"
                 "// (alpha = max(r^2, 1e-3)). Fetch bilinearly at Sheen_TableCoord(NoV, sheenRoughness).\n"
                 "// Layout (row-major, last index fastest): rtpbr_sheen_E[variant][r][mu];\n"
                 "// variant 0 charlie (V_Charlie, the default), 1 neubelt (V_Neubelt).\n"
                 "// Monte Carlo: %d samples per cell (%d replicas of %dx%d stratified Sample_SheenLobe\n"
                 "// directions); largest standard error of any entry: RTPBR_SHEEN_MAX_STDERR.\n"
                 "#ifndef RTPBR_SHEEN_TABLES_H\n#define RTPBR_SHEEN_TABLES_H\n\n"
                 "#define RTPBR_SHEEN_SIZE %d\n#define RTPBR_SHEEN_VARIANTS %d\n"
                 "#define RTPBR_SHEEN_VARIANT_charlie 0\n#define RTPBR_SHEEN_VARIANT_neubelt 1\n"
                 "#define RTPBR_SHEEN_MAX_STDERR %s\n\n"
                 "static const float rtpbr_sheen_E[%d][%d][%d] = {\n",
                 replicas * strata * strata, replicas, strata, strata, kSize, kVariants,
                 float_literal(float(std::max(maxSE[0], maxSE[1]))).c_str(), kVariants, kSize, kSize);
    for (int v = 0; v < kVariants; v++) {
        std::fprintf(f, "  { // %s\n", kVariantNames[v]);
        for (int ir = 0; ir < kSize; ir++) {
            std::fprintf(f, "    {");
            for (int imu = 0; imu < kSize; imu++)
                std::fprintf(f, "%s%s,", imu % 8 ? " " : "\n      ",
                             float_literal(float(E[(size_t(v) * kSize + size_t(ir)) * kSize + size_t(imu)])).c_str());
            std::fprintf(f, "\n    },\n");
        }
        std::fprintf(f, "  },\n");
    }
    std::fprintf(f, "};\n\n#endif // RTPBR_SHEEN_TABLES_H\n");
    if (std::fclose(f) != 0) {
        std::fprintf(stderr, "lutgen-sheen: error writing %s\n", header.c_str());
        return 1;
    }
    std::ostringstream md;
    md << "<!-- lutgen-sheen:begin (generated by tools/lutgen; do not edit by hand) -->\n"
       << "### E_sheen table report (generated)\n\n"
       << replicas * strata * strata << " samples per cell (" << replicas << " replicas of " << strata << "x" << strata
       << " stratified samples).\n\n| variant | max E | median SE | 99th pct SE | max SE | max SE / E (E >= 0.01) |\n"
       << "|---|---|---|---|---|---|\n";
    for (int v = 0; v < kVariants; v++) {
        std::sort(ses[v].begin(), ses[v].end());
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %.4f | %.2e | %.2e | %.2e | %.2e |\n", kVariantNames[v], maxE[v],
                      ses[v][ses[v].size() / 2], ses[v][size_t(0.99 * double(ses[v].size() - 1))], maxSE[v],
                      maxRelSE[v]);
        md << line;
    }
    md << "<!-- lutgen-sheen:end -->\n";
    std::string error;
    if (!rtpbr_tools::replace_markdown_section(out + "/sheen.md", "lutgen-sheen", md.str(), error)) {
        std::fprintf(stderr, "lutgen-sheen: %s\n", error.c_str());
        return 1;
    }
    std::fprintf(stderr, "lutgen-sheen: wrote %s; max stderr charlie %.2e neubelt %.2e; max E %.4f / %.4f\n",
                 header.c_str(), maxSE[0], maxSE[1], maxE[0], maxE[1]);
    return 0;
}
