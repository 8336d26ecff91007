// Oracle benchmark: samples/s and rays/s on a small scene, single-scatter vs multi-bounce
// microfacets, 1 and 2 threads, and solid-angle vs area light sampling (efficiency =
// 1 / (relative variance x time)). Prints a Markdown table; all ratios come from one run.
//   oracle_bench SCENE.gltf... [--width W] [--spp N]
#include "oracle.h"

#include <rtpbr/rtpbr_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/resource.h>
#include <vector>

using namespace rtpbr_oracle;

namespace {

// Process CPU time (user + system) in seconds: samples per CPU-second do not depend on how
// busy the machine is, wall-clock rates do.
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Run {
    const char *name;
    bool single;
    uint32_t threads;
    LightSampling lights;
    uint32_t maxDepth;
};

// Mean over pixels of the relative standard error of the luminance-like channel mean.
double meanRelativeStderr(const Accumulator &acc) {
    std::vector<float> rgb, se;
    resolve(acc, &rgb, &se);
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < rgb.size(); i += 3) {
        double v = (rgb[i] + rgb[i + 1] + rgb[i + 2]) / 3.0;
        double e = (se[i] + se[i + 1] + se[i + 2]) / 3.0;
        if (v > 1e-3) {
            sum += e / v;
            n++;
        }
    }
    return n ? sum / double(n) : 0.0;
}

int benchScene(const char *path, uint32_t width, uint32_t spp) {
    char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_load_desc desc = {};
    desc.emissive_mode = RTPBR_GLTF_EMISSIVE_EXACT; // as rtpbr-oracle loads
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene *scene = nullptr;
    if (rtpbr_gltf_load(path, &desc, &scene) != RTPBR_GLTF_SUCCESS) {
        std::fprintf(stderr, "oracle_bench: %s: %s\n", path, err);
        return 1;
    }
    const Run runs[] = {
        {"multi-bounce walk, 1 thread", false, 1, LightSampling::SolidAngle, 16},
        {"multi-bounce walk, 2 threads", false, 2, LightSampling::SolidAngle, 16},
        {"single-scatter, 1 thread", true, 1, LightSampling::SolidAngle, 16},
        {"single-scatter, 2 threads", true, 2, LightSampling::SolidAngle, 16},
        {"direct only, solid-angle lights, 2 threads", false, 2, LightSampling::SolidAngle, 1},
        {"direct only, area lights, 2 threads", false, 2, LightSampling::Area, 1},
    };
    std::printf("Scene %s, %u px wide, %u spp.\n\n", path, width, spp);
    std::printf("| configuration | samples/s | Mrays/s | samples/CPU-s | rays/sample | mean rel. std. error | "
                "efficiency 1/(se^2 t) |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    int status = 0;
    for (const Run &r : runs) {
        RenderSettings s;
        s.width = width;
        s.spp = spp;
        s.threads = r.threads;
        s.singleScatter = r.single;
        s.lightSampling = r.lights;
        s.maxDepth = r.maxDepth;
        Accumulator acc;
        RenderStats stats;
        std::string error;
        double cpu0 = cpuSeconds();
        Result res = render(*scene, s, &acc, &error, nullptr, &stats);
        double cpu = cpuSeconds() - cpu0;
        if (res != Result::Success) {
            std::fprintf(stderr, "oracle_bench: %s: %s\n", path, error.c_str());
            status = 1;
            break;
        }
        double se = meanRelativeStderr(acc);
        std::printf("| %s | %.0f | %.2f | %.0f | %.2f | %.4f | %.0f |\n", r.name, double(stats.samples) / stats.seconds,
                    double(stats.rays) / stats.seconds * 1e-6, double(stats.samples) / cpu,
                    double(stats.rays) / double(stats.samples), se, 1.0 / (se * se * stats.seconds));
        std::fflush(stdout);
    }
    std::printf("\n");
    rtpbr_gltf_destroy(scene);
    return status;
}

const char *const kUsage =
    "usage: oracle_bench SCENE.gltf... [--width W] [--spp N]\n"
    "The oracle's samples/s and rays/s: single-scatter against multi-bounce microfacets, 1 and 2\n"
    "threads, solid-angle against area light sampling; prints a Markdown table.\n"
    "  --width W   image width (default 128)\n"
    "  --spp N     samples per pixel (default 16)\n"
    "  -h, --help  this text\n";

} // namespace

int main(int argc, char **argv) {
    uint32_t width = 128, spp = 16;
    std::vector<const char *> scenes;
    for (int i = 1; i < argc; i++) {
        if (std::strcmp(argv[i], "--width") == 0 && i + 1 < argc)
            width = uint32_t(std::atoi(argv[++i]));
        else if (std::strcmp(argv[i], "--spp") == 0 && i + 1 < argc)
            spp = uint32_t(std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help"))
            return std::fputs(kUsage, stdout), 0;
        else if (argv[i][0] == '-')
            return std::fputs(kUsage, stderr), 2;
        else
            scenes.push_back(argv[i]);
    }
    if (scenes.empty() || width == 0 || spp == 0)
        return std::fputs(kUsage, stderr), 2;
    int status = 0;
    for (const char *path : scenes)
        status |= benchScene(path, width, spp);
    return status;
}
