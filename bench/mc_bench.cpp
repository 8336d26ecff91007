// LTC against brute-force Monte Carlo lighting at equal error (issue 7, "Speed").
//   rtpbr-bench-mc SCENE.gltf REFERENCE.exr [--width 320 --height 240] [--repeat 5]
//                  [--samples 1,2,4,...,128] [--out DIR]
// Renders SCENE with the engine's LTC lighting pass and with its Monte Carlo pass
// (rtpbr_render_desc.mc_samples = N) and prints a Markdown table: per configuration the
// median, over --repeat interleaved rounds, of rtpbr_render's wall time and of the process
// CPU time (on lavapipe the "GPU" is the CPU; its worker threads count), the time above the
// base (the MC pass on the same scene without lights: G-buffer, per-pixel setup, tone mapping,
// readback), its cost per pixel and light (and per sample), and the mean HDR-FLIP of the image
// against REFERENCE (the oracle's unshadowed direct lighting: rtpbr-oracle SCENE --no-shadows
// --direct-only), the same computation as `rtpbr-diff REFERENCE TEST --hdr` (the same
// library, 67 pixels per degree). The MC images use seed 1 (timed frames other seeds). Then
// the N at which MC reaches the LTC pass's FLIP (interpolated linearly in log2 N) and the time
// ratios MC(N)/LTC there (times interpolated linearly in N). --out writes every image (linear
// EXR, tone-mapped PNG) for rtpbr-diff and for looking at.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "rtpbr_common/image.hpp"
#include "rtpbr_common/image_read.hpp"

#include "rtpbr_common/flip.hpp"
#include "rtpbr/rtpbr.h"

namespace {

struct Options {
    const char *scene = nullptr;
    const char *reference = nullptr;
    uint32_t width = 320, height = 240;
    int repeat = 5;
    std::vector<uint32_t> samples = {1, 2, 4, 8, 16, 32, 64, 128};
    std::string out;
};

bool parse_list(const char *text, std::vector<uint32_t> &out)
{
    out.clear();
    std::string s(text);
    size_t pos = 0;
    while (pos <= s.size()) {
        size_t end = s.find(',', pos);
        if (end == std::string::npos) end = s.size();
        long v = std::strtol(s.substr(pos, end - pos).c_str(), nullptr, 10);
        if (v < 1 || v > (long)RTPBR_MAX_MC_SAMPLES) return false;
        out.push_back((uint32_t)v);
        pos = end + 1;
    }
    return !out.empty();
}

struct Measure {
    const rtpbr_gpu_scene *scene = nullptr;
    rtpbr_render_desc desc{};
    bool flip = true;
    double frame_ms = 0.0;   // median wall time of rtpbr_render
    double cpu_ms = 0.0;     // median process CPU time of rtpbr_render (lavapipe's threads included)
    double flip_mean = 0.0;
    std::vector<float> rgb;  // linear radiance of the FLIP image
    std::vector<uint8_t> display;
    std::vector<double> wall, cpu;
};

double cpu_now_ms()
{
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The image of seed 1 (also the warm-up) and its FLIP against the reference.
rtpbr_result first_frame(rtpbr_renderer *r, const Options &o, const rtpbr::Image &ref, Measure &m)
{
    size_t px = (size_t)o.width * o.height;
    std::vector<float> rgba(px * 4);
    m.desc.mc_seed = 1;
    rtpbr_result res = rtpbr_render(r, m.scene, &m.desc);
    if (res != RTPBR_SUCCESS) return res;
    res = rtpbr_read_radiance(r, rgba.data(), rgba.size() * sizeof(float));
    if (res != RTPBR_SUCCESS) return res;
    m.display.resize(px * 4);
    res = rtpbr_read_display(r, m.display.data(), m.display.size());
    if (res != RTPBR_SUCCESS) return res;
    m.rgb.resize(px * 3);
    for (size_t i = 0; i < px; ++i)
        for (int c = 0; c < 3; ++c) m.rgb[3 * i + c] = rgba[4 * i + c];
    if (m.flip) {
        std::vector<float> map;
        rtpbr::FlipResult fr = rtpbr::flip_hdr(ref.rgb.data(), m.rgb.data(), (int)o.width, (int)o.height,
                                               rtpbr::kFlipDefaultPpd, map);
        if (fr != rtpbr::FlipResult::ok) {
            std::fprintf(stderr, "rtpbr-bench-mc: FLIP: %s\n", rtpbr::flip_result_string(fr));
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
        m.flip_mean = rtpbr::flip_stats(map).mean;
    }
    return RTPBR_SUCCESS;
}

// One timed frame of a configuration (seed `seed`).
rtpbr_result timed_frame(rtpbr_renderer *r, Measure &m, uint32_t seed)
{
    m.desc.mc_seed = seed;
    double c0 = cpu_now_ms();
    auto t0 = std::chrono::steady_clock::now();
    rtpbr_result res = rtpbr_render(r, m.scene, &m.desc);
    m.wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    m.cpu.push_back(cpu_now_ms() - c0);
    return res;
}

const char *const kUsage =
    "usage: rtpbr-bench-mc SCENE.gltf REFERENCE.exr [--width W] [--height H] [--repeat N]\n"
    "                      [--samples 1,2,4] [--out DIR]\n"
    "The engine's LTC lighting pass against its brute-force Monte Carlo pass at equal HDR-FLIP\n"
    "error against REFERENCE (rtpbr-oracle SCENE --no-shadows --direct-only); prints a Markdown\n"
    "table of times and errors.\n"
    "  --width W       image width (default 320)\n"
    "  --height H      image height (default 240)\n"
    "  --repeat N      interleaved rounds (1..1000; default 5)\n"
    "  --samples LIST  Monte Carlo samples per pixel and light (default 1,2,4,...,128)\n"
    "  --out DIR       write every image (linear EXR, tone-mapped PNG) to DIR\n"
    "  -h, --help      this text\n";

int usage()
{
    std::fputs(kUsage, stderr);
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    Options o;
    int positional = 0;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        bool has = i + 1 < argc;
        if (a == "--width" && has) o.width = (uint32_t)std::atoi(argv[++i]);
        else if (a == "--height" && has) o.height = (uint32_t)std::atoi(argv[++i]);
        else if (a == "--repeat" && has) o.repeat = std::atoi(argv[++i]);
        else if (a == "--samples" && has) {
            if (!parse_list(argv[++i], o.samples)) return usage();
        } else if (a == "--out" && has) o.out = argv[++i];
        else if (a == "-h" || a == "--help") return std::fputs(kUsage, stdout), 0;
        else if (a[0] != '-' && positional == 0) o.scene = argv[i], ++positional;
        else if (a[0] != '-' && positional == 1) o.reference = argv[i], ++positional;
        else return usage();
    }
    if (!o.scene || !o.reference || o.width < 1 || o.height < 1 || o.repeat < 1 || o.repeat > 1000)
        return usage();

    rtpbr::Image ref;
    std::string err;
    if (!rtpbr::read_image(o.reference, ref, err)) {
        std::fprintf(stderr, "rtpbr-bench-mc: %s: %s\n", o.reference, err.c_str());
        return 1;
    }
    if ((uint32_t)ref.width != o.width || (uint32_t)ref.height != o.height) {
        std::fprintf(stderr, "rtpbr-bench-mc: reference is %dx%d, rendering %ux%u\n", ref.width, ref.height, o.width,
                     o.height);
        return 1;
    }

    rtpbr_context *ctx = nullptr;
    rtpbr_gpu_scene *scene = nullptr, *dark = nullptr;
    rtpbr_renderer *r = nullptr;
    rtpbr_context_desc cd{};
    rtpbr_result res = rtpbr_context_create(&cd, &ctx);
    if (res == RTPBR_SUCCESS) res = rtpbr_gpu_scene_load_gltf(ctx, o.scene, &scene);
    if (res == RTPBR_SUCCESS) res = rtpbr_gpu_scene_load_gltf(ctx, o.scene, &dark);
    if (res == RTPBR_SUCCESS) res = rtpbr_gpu_scene_set_lights(dark, nullptr, 0);
    rtpbr_renderer_desc rd{};
    rd.width = o.width;
    rd.height = o.height;
    if (res == RTPBR_SUCCESS) res = rtpbr_renderer_create(ctx, &rd, &r);
    uint32_t lights = scene ? rtpbr_gpu_scene_light_count(scene) : 0;

    // Configurations: 0 the scene without lights (the frame's fixed cost), 1 LTC, then MC at
    // each N. First every image once (warm-up, FLIP), then --repeat rounds of one timed frame
    // per configuration, interleaved so that changes of the machine's load hit all alike.
    // Configuration 0, the base, is the MC pass (1 sample) on the scene without lights: its
    // lighting pass reads the G-buffer and sets up each pixel's material, with no light to
    // loop over. Configuration 1 is the LTC pass on that scene: its fixed cost (tile bounding
    // box, culling, three barriers, each pixel's material and table fetches).
    std::vector<Measure> all(3 + o.samples.size());
    all[0].scene = dark;
    all[0].flip = false;
    all[0].desc.mc_samples = 1;
    all[1].scene = dark;
    all[1].flip = false;
    all[2].scene = scene;
    for (size_t i = 0; i < o.samples.size(); ++i) {
        all[3 + i].scene = scene;
        all[3 + i].desc.mc_samples = o.samples[i];
    }
    for (size_t i = 0; i < all.size() && res == RTPBR_SUCCESS; ++i) res = first_frame(r, o, ref, all[i]);
    for (int k = 0; k < o.repeat && res == RTPBR_SUCCESS; ++k)
        for (size_t i = 0; i < all.size() && res == RTPBR_SUCCESS; ++i) res = timed_frame(r, all[i], (uint32_t)k + 2);
    for (Measure &m : all)
        if (res == RTPBR_SUCCESS) {
            m.frame_ms = median(m.wall);
            m.cpu_ms = median(m.cpu);
        }
    const Measure &base = all[0], &ltc0 = all[1], &ltc = all[2];
    std::vector<Measure> mc(all.begin() + 3, all.end());
    if (res != RTPBR_SUCCESS) {
        std::fprintf(stderr, "rtpbr-bench-mc: %s\n", rtpbr_result_string(res));
    } else {
        double pl = (double)o.width * o.height * (lights ? lights : 1);
        std::printf("Scene %s, %ux%u, %u light(s), device %s; median of %d interleaved frames. Frame without "
                    "lights, MC pass (the base: G-buffer, the MC pass's per-pixel setup with no light to loop over, tone "
                    "mapping, readback): %.1f ms wall, %.1f ms CPU. Per pixel·light: CPU time above the base / (%ux%u "
                    "pixels x lights). CPU = process CPU time, lavapipe's threads included.\n\n",
                    o.scene, o.width, o.height, lights, rtpbr_context_device_name(ctx), o.repeat, base.frame_ms,
                    base.cpu_ms, o.width, o.height);
        std::printf("| pass | frame wall ms | frame CPU ms | wall ms above base | CPU ms above base | CPU ns / "
                    "pixel·light | CPU ns / pixel·light·sample | mean HDR-FLIP |\n");
        std::printf("|---|---|---|---|---|---|---|---|\n");
        auto row = [&](const char *name, uint32_t n, const Measure &m) {
            double lw = m.frame_ms - base.frame_ms, lc = m.cpu_ms - base.cpu_ms;
            char per_sample[32] = "–";
            if (n) std::snprintf(per_sample, sizeof per_sample, "%.1f", 1e6 * lc / (pl * n));
            std::printf("| %s%s | %.1f | %.1f | %.1f | %.1f | %.1f | %s | %.4f |\n", name,
                        n ? (" N=" + std::to_string(n)).c_str() : "", m.frame_ms, m.cpu_ms, lw, lc, 1e6 * lc / pl,
                        per_sample, m.flip_mean);
        };
        std::printf("| LTC, scene without lights (tile culling + per-pixel setup) | %.1f | %.1f | %.1f | %.1f | – | – "
                    "| – |\n",
                    ltc0.frame_ms, ltc0.cpu_ms, ltc0.frame_ms - base.frame_ms, ltc0.cpu_ms - base.cpu_ms);
        row("LTC", 0, ltc);
        for (size_t i = 0; i < mc.size(); ++i) row("MC", o.samples[i], mc[i]);
        std::printf("\nLTC per pixel·light above its own no-light frame: %.1f ns CPU.\n",
                    1e6 * (ltc.cpu_ms - ltc0.cpu_ms) / pl);
        // Equal error: the first bracket where MC's FLIP falls to the LTC pass's; N interpolated
        // linearly in log2 N against FLIP, times linearly in N.
        bool found = false;
        for (size_t i = 0; i < mc.size() && !found; ++i) {
            if (mc[i].flip_mean > ltc.flip_mean) continue;
            found = true;
            double n_eq = o.samples[i], s = 1.0;
            size_t lo = i > 0 ? i - 1 : i;
            if (i > 0) {
                double f0 = mc[lo].flip_mean, f1 = mc[i].flip_mean;
                double x = (f0 - ltc.flip_mean) / (f0 - f1);
                double la = std::log2((double)o.samples[lo]), lb = std::log2((double)o.samples[i]);
                n_eq = std::exp2(la + x * (lb - la));
                s = (n_eq - o.samples[lo]) / (double)(o.samples[i] - o.samples[lo]);
            }
            auto at = [&](double a, double b) { return a + s * (b - a); };
            double fw = at(mc[lo].frame_ms, mc[i].frame_ms), fc = at(mc[lo].cpu_ms, mc[i].cpu_ms);
            std::printf("\nEqual error: MC reaches the LTC pass's mean HDR-FLIP %.4f at N ≈ %.1f samples per pixel "
                        "per light. There MC/LTC: frame %.2fx (wall) %.2fx (CPU); light loop (each pass's frame "
                        "minus its own no-light frame) %.2fx (wall) %.2fx (CPU).\n",
                        ltc.flip_mean, n_eq, fw / ltc.frame_ms, fc / ltc.cpu_ms,
                        (fw - base.frame_ms) / (ltc.frame_ms - ltc0.frame_ms),
                        (fc - base.cpu_ms) / (ltc.cpu_ms - ltc0.cpu_ms));
        }
        if (!found)
            std::printf("\nEqual error: MC does not reach the LTC pass's mean HDR-FLIP %.4f by N = %u (its FLIP "
                        "there %.4f).\n",
                        ltc.flip_mean, o.samples.back(), mc.back().flip_mean);
        if (!o.out.empty()) {
            auto save = [&](const std::string &name, const Measure &m) {
                std::string error;
                bool ok = rtpbr_tools::write_image_float(o.out + "/" + name + ".exr", (int)o.width, (int)o.height, 3,
                                                         m.rgb.data(), error) &&
                          rtpbr_tools::write_image_u8(o.out + "/" + name + ".png", (int)o.width, (int)o.height, 4,
                                                      m.display.data(), error);
                if (!ok) std::fprintf(stderr, "rtpbr-bench-mc: %s\n", error.c_str());
            };
            save("ltc", ltc);
            for (size_t i = 0; i < mc.size(); ++i) save("mc" + std::to_string(o.samples[i]), mc[i]);
        }
    }
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(dark);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    return res == RTPBR_SUCCESS ? 0 : 1;
}
