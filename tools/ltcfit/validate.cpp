// rtpbr-ltc-validate: LTC (committed tables) against Monte Carlo on the full grid of
// ltc_mc.hpp; prints the markdown error table for shaderlib/luts/ltc.md and writes the error
// plot. Deterministic (fixed seeds); 2 threads.
//
//   rtpbr-ltc-validate [--reduced] [--verbose] [--png FILE] [--diffuse] [--sheen] [--back]
//
// --back: only lights at the "back" position (elevation 25 degrees on the viewer's side),
// which the default grid does not hold; no plot, no breakdown by position.
// --diffuse: the Disney diffuse table instead of GGX and Beckmann (the plot has one lobe row).
// --sheen: the KHR_materials_sheen table (rtpbr_ltc_sheen_tables.h), likewise.
#include <atomic>
#include <cstring>
#include <mutex>
#include <thread>

#include "ltc_mc.hpp"
#include "rtpbr_common/colormap.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/markdown.hpp"

using namespace ltcmc;

namespace {

int index_of(const std::vector<Lobe> &lobes, Lobe l) {
    return int(std::find(lobes.begin(), lobes.end(), l) - lobes.begin());
}

// Error plot: one panel per (lobe, method): GGX top, Beckmann bottom; exact clipping,
// clipless with the analytic sphere, clipless with the sphere table from left to right. In a
// panel, column groups = roughness (smooth to rough), columns in a group = view angle (0 to
// 80 degrees); row groups = position (mirror, normal, side, low), rows in a group = light
// size (small to large). 8x8-pixel cells, 2-pixel white gaps between groups; colour = log10
// relative error from 0.1% (dark) to 100% (bright); grey = far-tail light (< 1% of the
// lobe's energy) or the mirror direction at normal view (same as "normal").
bool write_plot(const std::string &path, const std::vector<Lobe> &lobes, const std::vector<Outcome> &out,
                const std::vector<float> &rough,
                const std::vector<float> &views, const std::vector<float> &halves, std::string &err) {
    const int cell = 8, group = 2, gap = 12;
    const int nr = int(rough.size()), nv = int(views.size()), nh = int(halves.size());
    const int pw = nr * nv * cell + (nr - 1) * group, ph = 4 * nh * cell + 3 * group;
    const int nl = int(lobes.size());
    const int w = 3 * pw + 2 * gap, h = nl * ph + (nl - 1) * gap + gap + 12;
    std::vector<unsigned char> img(size_t(w) * h * 3, 255);
    auto index = [](const std::vector<float> &v, float x) {
        return int(std::find(v.begin(), v.end(), x) - v.begin());
    };
    // grey background for every cell, so missing configurations show as grey
    for (int lobe = 0; lobe < nl; lobe++)
        for (int m = 0; m < 3; m++)
            for (int ri = 0; ri < nr; ri++)
                for (int vi = 0; vi < nv; vi++)
                    for (int pi = 0; pi < 4; pi++)
                        for (int hi = 0; hi < nh; hi++) {
                            int x0 = m * (pw + gap) + ri * (nv * cell + group) + vi * cell;
                            int y0 = lobe * (ph + gap) + pi * (nh * cell + group) + hi * cell;
                            for (int y = 0; y < cell; y++)
                                for (int x = 0; x < cell; x++)
                                    for (int k = 0; k < 3; k++)
                                        img[(size_t(y0 + y) * w + size_t(x0 + x)) * 3 + k] = 160;
                        }
    for (const Outcome &o : out) {
        int ri = index(rough, o.cfg.roughness), vi = index(views, o.cfg.viewDeg), hi = index(halves, o.cfg.half);
        int lobe = index_of(lobes, o.cfg.lobe);
        double errs[3] = {o.relExact, o.relClipless, o.relClipTable};
        for (int m = 0; m < 3; m++) {
            unsigned char rgb[3] = {160, 160, 160};
            if (o.significant)
                rtpbr_tools::magma_coarse((std::log10(std::max(errs[m], 1e-3)) + 3.0) / 3.0, rgb);
            int x0 = m * (pw + gap) + ri * (nv * cell + group) + vi * cell;
            int y0 = lobe * (ph + gap) + o.cfg.position * (nh * cell + group) + hi * cell;
            for (int y = 0; y < cell; y++)
                for (int x = 0; x < cell; x++)
                    for (int k = 0; k < 3; k++)
                        img[(size_t(y0 + y) * w + size_t(x0 + x)) * 3 + k] = rgb[k];
        }
    }
    for (int y = nl * ph + nl * gap; y < h; y++)
        for (int x = 0; x < w; x++)
            rtpbr_tools::magma_coarse(double(x) / (w - 1), &img[(size_t(y) * w + x) * 3]);
    return rtpbr_tools::write_image_u8(path, w, h, 3, img.data(), err);
}

const char *const kUsage =
    "usage: rtpbr-ltc-validate [--reduced] [--verbose] [--png FILE] [--diffuse] [--sheen] [--back]\n"
    "The LTC (committed tables) against Monte Carlo on the grid of ltc_mc.hpp: prints the markdown\n"
    "error table of shaderlib/luts/ltc.md. Deterministic (fixed seeds); 2 threads.\n"
    "  --reduced    the reduced grid the test suite uses (3 roughnesses, 3 views, 2 light sizes)\n"
    "  --verbose    also print every case\n"
    "  --png FILE   write the error plot\n"
    "  --diffuse    the Disney diffuse table instead of GGX and Beckmann\n"
    "  --sheen      the KHR_materials_sheen table instead\n"
    "  --back       only lights at the back position (elevation 25 degrees on the viewer's side);\n"
    "               no plot, no breakdown by position\n"
    "  -h, --help   this text\n";

} // namespace

int main(int argc, char **argv) {
    bool reduced = false, verbose = false, back = false;
    std::vector<Lobe> lobes{Lobe::GGX, Lobe::Beckmann};
    std::string png;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--reduced"))
            reduced = true;
        else if (!strcmp(argv[i], "--diffuse"))
            lobes = {Lobe::DisneyDiffuse};
        else if (!strcmp(argv[i], "--sheen"))
            lobes = {Lobe::Sheen};
        else if (!strcmp(argv[i], "--back"))
            back = true;
        else if (!strcmp(argv[i], "--verbose"))
            verbose = true;
        else if (!strcmp(argv[i], "--png") && i + 1 < argc)
            png = argv[++i];
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help"))
            return fputs(kUsage, stdout), 0;
        else
            return fputs(kUsage, stderr), 2;
    }
    if (back && !png.empty()) {
        fprintf(stderr, "rtpbr-ltc-validate: --back has no plot\n");
        return 2;
    }
    std::vector<Config> g = back ? grid(reduced, lobes, {4}) : grid(reduced, lobes);
    std::vector<Outcome> out(g.size());
    std::atomic<size_t> next{0};
    std::mutex m;
    size_t done = 0;
    auto worker = [&]() {
        for (size_t i = next++; i < g.size(); i = next++) {
            out[i] = run_config(g[i], FresnelChoice{}, 7e-4, 1l << 22, 1 + i);
            std::lock_guard<std::mutex> lock(m);
            ++done;
            if (verbose) {
                const Outcome &o = out[i];
                fprintf(stderr, "%-8s r=%.2f view=%2.0f half=%.2f %-6s ref=%.5f (+-%.2e, %ld) ltc=%.5f cl=%.5f ct=%.5f err=%.2f%% engine=%.5f err=%.2f%%\n",
                        lobe_name(o.cfg.lobe), o.cfg.roughness, o.cfg.viewDeg, o.cfg.half, position_name(o.cfg.position),
                        o.ref.mean, o.ref.relStdErr, o.ref.samples, o.ltc.exact, o.ltc.clipless, o.ltc.clipless_table,
                        100 * o.relExact, o.ltc.point, 100 * o.relPoint);
            } else {
                fprintf(stderr, "\rrtpbr-ltc-validate: %zu/%zu", done, g.size());
            }
        }
    };
    std::thread t1(worker), t2(worker);
    t1.join();
    t2.join();
    fprintf(stderr, "\n");

    printf("| lobe | method | lights | mean | 95th pct | max | tail lights | tail mean | tail max |\n"
           "|---|---|---|---|---|---|---|---|---|\n");
    double worstRef = 0;
    long maxSamples = 0;
    for (Lobe l : lobes) {
        std::vector<double> e[4], tail[4];
        for (const Outcome &o : out) {
            if (o.cfg.lobe != l)
                continue;
            double v[4] = {o.relExact, o.relClipless, o.relClipTable, o.relPoint};
            for (int k = 0; k < 4; k++)
                (o.significant ? e[k] : tail[k]).push_back(v[k]);
            if (o.significant)
                worstRef = std::max(worstRef, o.ref.relStdErr);
            maxSamples = std::max(maxSamples, o.ref.samples);
        }
        const char *names[4] = {"exact clipping", "clipless, analytic sphere", "clipless, sphere table",
                                "exact clipping + point correction"};
        for (int k = 0; k < 4; k++) {
            Summary s = summarize(e[k]), t = summarize(tail[k]);
            printf("| %s | %s | %d | %.2f%% | %.2f%% | %.2f%% | %d | %.3f%% | %.3f%% |\n", lobe_name(l), names[k],
                   s.count, 100 * s.mean, 100 * s.p95, 100 * s.max, t.count, 100 * t.mean, 100 * t.max);
        }
    }
    printf("\nReference: largest relative standard error %.3f%% where the light matters (at most %ld sample pairs).\n", 100 * worstRef,
           maxSamples);
    // The exact method's errors over the significant cases that `keep` selects.
    auto point_errors = [&](auto keep) {
        std::vector<double> e;
        for (const Outcome &o : out)
            if (o.significant && keep(o.cfg))
                e.push_back(o.relPoint);
        return summarize(e);
    };
    // Breakdown of the exact method by roughness and view angle.
    for (Lobe l : lobes) {
        printf("\n%s, exact clipping + point correction (the engine), mean relative error by roughness (rows) and view angle (columns):\n\n| r |",
               lobe_name(l));
        std::vector<float> rough = grid_roughness(reduced), views = grid_views(reduced);
        rtpbr_tools::print_markdown_head(views, " %g deg |", 1);
        for (float r : rough) {
            printf("| %.2f |", double(r));
            for (float v : views) {
                Summary s = point_errors([&](const Config &c) { return c.lobe == l && c.roughness == r && c.viewDeg == v; });
                printf(" %.1f%% |", 100 * s.mean);
            }
            printf("\n");
        }
    }
    // Breakdown by light position and size.
    for (Lobe l : back ? std::vector<Lobe>{} : lobes) {
        printf("\n%s, exact clipping + point correction (the engine), mean relative error by position (rows) and light half-size (columns):\n\n| position |",
               lobe_name(l));
        std::vector<float> halves = grid_halves(reduced);
        rtpbr_tools::print_markdown_head(halves, " %g |", 1);
        for (int p = 0; p < 4; p++) {
            printf("| %s |", position_name(p));
            for (float h : halves) {
                Summary s = point_errors([&](const Config &c) { return c.lobe == l && c.position == p && c.half == h; });
                printf(" %.1f%% (%d) |", 100 * s.mean, s.count);
            }
            printf("\n");
        }
    }
    if (!png.empty()) {
        std::vector<float> rough = grid_roughness(reduced), views = grid_views(reduced), halves = grid_halves(reduced);
        std::string err;
        if (!write_plot(png, lobes, out, rough, views, halves, err)) {
            fprintf(stderr, "rtpbr-ltc-validate: error: %s\n", err.c_str());
            return 1;
        }
    }
    return 0;
}
