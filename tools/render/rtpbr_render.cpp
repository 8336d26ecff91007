// rtpbr-render: headless render of a glTF scene with librtpbr.
//   rtpbr-render SCENE.gltf -o OUT.exr|OUT.png [--width W] [--height H] [--camera I]
//                [--exposure EV] [--tonemap aces|reinhard|linear] [--ndf ggx|beckmann]
//                [--no-multiscatter] [--supersample S] [--mc-samples N] [--validation]
//                [--shadows] [--shadow-samples N] [--no-shadow-denoiser] [--no-shadow-cull]
//                [--ray-query auto|on|off]
//                [--max-ratio R] [--stats-json FILE] [--memory-limit MIB]
// OUT.exr holds linear scene radiance (RGB float; no exposure, no tone mapping: the quantity
// the oracle writes); OUT.png the tone-mapped 8-bit sRGB image.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "rtpbr_common/energy.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/memory.hpp"

#include "rtpbr/rtpbr.h"
#include "rtpbr/rtpbr_gltf.h"

namespace {

void usage(FILE *out = stderr)
{
    std::fprintf(out,
                 "usage: rtpbr-render SCENE.gltf -o OUT.exr|OUT.png [--width W] [--height H] [--camera I]\n"
                 "                    [--exposure EV] [--tonemap aces|reinhard|linear] [--ndf ggx|beckmann]\n"
                 "                    [--no-multiscatter] [--supersample S] [--mc-samples N] [--validation]\n"
                 "                    [--shadows] [--shadow-samples N] [--no-shadow-denoiser] [--no-shadow-cull]\n"
                 "                    [--ray-query auto|on|off] [--max-ratio R] [--stats-json FILE] [--memory-limit MIB]\n"
                 "  --shadows        area-light shadows (ratio estimator; in each 16x16 tile the 8 lights that may light it most cast)\n"
                 "  --shadow-samples N  shadow rays per pixel and shadowed light (default 4; implies --shadows)\n"
                 "  --no-shadow-denoiser  each pixel's own shadow ratio, unfiltered\n"
                 "  --no-shadow-cull  trace every shadow ray, also where no triangle can block one (the same image)\n"
                 "  --ray-query M    how shadow rays are traced: auto (VK_KHR_ray_query on a GPU that has it, the\n"
                 "                   compute BVH walk otherwise; default), on (ray queries, also on a CPU device;\n"
                 "                   an error without them), off (the compute walk)\n"
                 "  --supersample S  anti-aliasing: shade S x S samples per pixel, box-filtered (1..4; default 1)\n"
                 "  --mc-samples N   brute-force Monte Carlo lighting pass, N samples per pixel and light\n"
                 "                   (the reference the LTC pass is benchmarked against; default 0: LTC)\n"
                 "  --max-ratio R    exit 1 when a pixel exceeds R x the brightest emitter's radiance (lights,\n"
                 "                   emissive materials): no surface reflects more than reaches it. The\n"
                 "                   figures are printed on every render (energy bound, docs/limits.md).\n"
                 "                   A scene with KHR_lights_punctual lights has no such bound: the figures\n"
                 "                   say so, and --max-ratio is refused\n"
                 "  --stats-json FILE  writes those figures as JSON (rtpbr-validate reads them)\n"
                 "  --memory-limit MIB  refuse a render that needs more memory than this (default: what the\n"
                 "                   system has available; the need is counted before anything is allocated:\n"
                 "                   docs/limits.md)\n");
}

void on_log(rtpbr_log_level level, const char *message, void *)
{
    if (level <= RTPBR_LOG_WARNING)
        std::fprintf(stderr, "rtpbr-render: %s: %s\n", level == RTPBR_LOG_ERROR ? "error" : "warning", message);
}

bool ends_with(const std::string &s, const char *suffix)
{
    size_t n = std::strlen(suffix);
    if (s.size() < n) return false;
    for (size_t i = 0; i < n; ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i]) return false;
    return true;
}

void on_loader_log(rtpbr_gltf_log_level level, const char *message, void *)
{
    if (level <= RTPBR_GLTF_LOG_WARNING)
        std::fprintf(stderr, "rtpbr-render: %s: %s\n", level == RTPBR_GLTF_LOG_ERROR ? "error" : "warning", message);
}

// Is punctual light l a sphere (a point light with a radius): an emitter of radiance
// intensity / (pi r^2) (times its range window, at most 1), not a delta light?
bool is_sphere(const rtpbr_gltf_punctual_light &l)
{
    return l.type == RTPBR_GLTF_PUNCTUAL_POINT && l.radius > 0.0f;
}

// The KHR_lights_punctual lights of the scene that shine (intensity > 0) and have no size
// (spheres apart): with any, the scene has no energy bound (a delta light's irradiance I / d^2
// has no upper limit; rtpbr_common/energy.hpp).
uint32_t shining_punctual_lights(const rtpbr_gltf_scene *scene)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < scene->punctual_light_count; ++i) {
        const float *c = scene->punctual_lights[i].intensity;
        n += !is_sphere(scene->punctual_lights[i]) && (c[0] > 0.0f || c[1] > 0.0f || c[2] > 0.0f) ? 1u : 0u;
    }
    return n;
}

// The brightest radiance any emitter of the scene has: its lights (a sphere's intensity /
// (pi r^2); a capsule's, length L, 2 intensity / (pi r (2 r + L)), with a range or not: the engine's
// tube, rtpbr_gpu_scene_from_loaded) and its emissive materials (an emission texture only
// scales the factor down). The background is black here. Not a bound for a scene with punctual
// lights (shining_punctual_lights).
double brightest_emitter(const rtpbr_gltf_scene *scene)
{
    double b = 0.0;
    for (uint32_t i = 0; i < scene->light_count; ++i)
        for (int c = 0; c < 3; ++c) b = std::max(b, double(scene->lights[i].radiance[c]));
    for (uint32_t i = 0; i < scene->punctual_light_count; ++i) {
        const rtpbr_gltf_punctual_light &l = scene->punctual_lights[i];
        const double r = l.radius, pi = 3.14159265358979323846;
        const double area = l.length > 0.0f ? pi * r * (2.0 * r + l.length) / 2.0 : pi * r * r;
        if (is_sphere(l))
            for (int c = 0; c < 3; ++c) b = std::max(b, double(l.intensity[c]) / area);
    }
    for (uint32_t i = 0; i < scene->material_count; ++i)
        for (int c = 0; c < 3; ++c) b = std::max(b, double(scene->materials[i].emission[c]));
    return b;
}

// Memory of a render, counted before anything is allocated (measured on lavapipe, where device
// memory is host memory, as peak RSS over the program's own at 1024² and 2048²: 113-116 bytes
// a pixel without supersampling, 298 with 2x2): the device's per-sample images (G-buffer,
// lighting) and, per pixel, the resolved and tone-mapped images, the host's readback and output
// buffers and the writer's copy. Rounded up.
constexpr uint64_t kBytesPerSample = 64;
constexpr uint64_t kBytesPerPixel = 64;

uint64_t render_memory_need(const rtpbr_renderer_desc &size)
{
    const uint64_t pixels = uint64_t(size.width) * size.height;
    const uint64_t ss = size.supersample ? size.supersample : 1;
    return pixels * (ss * ss * kBytesPerSample + kBytesPerPixel);
}

bool parse_uint(const char *text, uint32_t &out)
{
    char *end = nullptr;
    unsigned long v = std::strtoul(text, &end, 10);
    if (!end || *end || end == text || v > 1u << 20) return false;
    out = static_cast<uint32_t>(v);
    return true;
}

} // namespace

int run(int argc, char **argv)
{
    std::string scene_path, out_path;
    rtpbr_renderer_desc size{};
    size.width = 640;
    size.height = 480;
    size.timings = 1; // the frame's GPU times, printed
    rtpbr_render_desc render{};
    int validation = 0;
    int ray_query = RTPBR_SHADOW_RAY_QUERY_AUTO;
    double max_ratio = 0.0; // 0: report only
    std::string stats_path;
    uint64_t memory_limit = 0; // 0: what the system has available
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        bool has_value = i + 1 < argc;
        if (a == "-o" && has_value) out_path = argv[++i];
        else if (a == "--width" && has_value) {
            if (!parse_uint(argv[++i], size.width)) return usage(), 2;
        } else if (a == "--height" && has_value) {
            if (!parse_uint(argv[++i], size.height)) return usage(), 2;
        } else if (a == "--camera" && has_value) {
            if (!parse_uint(argv[++i], render.camera_index)) return usage(), 2;
        } else if (a == "--exposure" && has_value) {
            render.exposure = std::strtof(argv[++i], nullptr);
        } else if (a == "--tonemap" && has_value) {
            std::string t = argv[++i];
            if (t == "aces") render.tonemap = RTPBR_TONEMAP_ACES;
            else if (t == "reinhard") render.tonemap = RTPBR_TONEMAP_REINHARD;
            else if (t == "linear") render.tonemap = RTPBR_TONEMAP_LINEAR;
            else return usage(), 2;
        } else if (a == "--ndf" && has_value) {
            std::string t = argv[++i];
            if (t == "ggx") render.ndf = RTPBR_NDF_GGX_MODEL;
            else if (t == "beckmann") render.ndf = RTPBR_NDF_BECKMANN_MODEL;
            else return usage(), 2;
        } else if (a == "--supersample" && has_value) {
            if (!parse_uint(argv[++i], size.supersample)) return usage(), 2;
        } else if (a == "--mc-samples" && has_value) {
            if (!parse_uint(argv[++i], render.mc_samples)) return usage(), 2;
        } else if (a == "--shadow-samples" && has_value) {
            if (!parse_uint(argv[++i], render.shadow_samples)) return usage(), 2;
            render.shadows = RTPBR_SHADOWS_ON;
        } else if (a == "--shadows") render.shadows = RTPBR_SHADOWS_ON;
        else if (a == "--no-shadow-denoiser") render.shadow_denoiser = RTPBR_SHADOW_DENOISER_OFF;
        else if (a == "--no-shadow-cull") render.shadow_cull = RTPBR_SHADOW_CULL_OFF;
        else if (a == "--no-multiscatter") render.multiscatter = RTPBR_MULTISCATTER_OFF;
        else if (a == "--validation") validation = 1;
        else if (a == "--ray-query" && has_value) {
            std::string t = argv[++i];
            if (t == "auto") ray_query = RTPBR_SHADOW_RAY_QUERY_AUTO;
            else if (t == "on") ray_query = RTPBR_SHADOW_RAY_QUERY_ON;
            else if (t == "off") ray_query = RTPBR_SHADOW_RAY_QUERY_OFF;
            else return usage(), 2;
        }
        else if (a == "--max-ratio" && has_value) {
            char *end = nullptr;
            max_ratio = std::strtod(argv[++i], &end);
            if (!end || *end || !(max_ratio > 0.0)) return usage(), 2;
        } else if (a == "--stats-json" && has_value) stats_path = argv[++i];
        else if (a == "--memory-limit" && has_value) {
            uint32_t mib = 0;
            if (!parse_uint(argv[++i], mib) || mib == 0) return usage(), 2;
            memory_limit = uint64_t(mib) << 20;
        }
        else if (a == "-h" || a == "--help") return usage(stdout), 0;
        else if (a[0] != '-' && scene_path.empty()) scene_path = a;
        else return usage(), 2;
    }
    bool exr = ends_with(out_path, ".exr"), png = ends_with(out_path, ".png");
    if (scene_path.empty() || (!exr && !png)) return usage(), 2;
    char what[96];
    std::snprintf(what, sizeof what, "rendering %ux%u with %ux%u supersampling", size.width, size.height,
                  size.supersample ? size.supersample : 1, size.supersample ? size.supersample : 1);
    const std::string shortfall = rtpbr_tools::memory_shortfall(render_memory_need(size), memory_limit, what);
    if (!shortfall.empty()) {
        std::fprintf(stderr, "rtpbr-render: %s (--memory-limit; docs/limits.md)\n", shortfall.c_str());
        return 1;
    }

    rtpbr_context_desc cd{};
    cd.logger.func = on_log;
    cd.validation = validation;
    cd.shadow_ray_query = ray_query;
    rtpbr_context *ctx = nullptr;
    rtpbr_gpu_scene *scene = nullptr;
    rtpbr_renderer *renderer = nullptr;
    int status = 1;
    // Loaded here rather than by rtpbr_gpu_scene_load_gltf: the energy bound needs the scene's
    // emitters.
    char load_error[RTPBR_GLTF_ERROR_MESSAGE_SIZE] = "";
    rtpbr_gltf_load_desc ld{};
    ld.logger.func = on_loader_log;
    ld.error_message = load_error;
    ld.error_message_size = sizeof load_error;
    ld.max_lights = RTPBR_MAX_LIGHTS;
    rtpbr_gltf_scene *loaded = nullptr;
    rtpbr_gltf_result lr = rtpbr_gltf_load(scene_path.c_str(), &ld, &loaded);
    if (lr != RTPBR_GLTF_SUCCESS) {
        std::fprintf(stderr, "rtpbr-render: cannot load %s: %s: %s\n", scene_path.c_str(), rtpbr_gltf_result_string(lr),
                     load_error);
        return 1;
    }
    const double bound = brightest_emitter(loaded);
    const uint32_t punctual = shining_punctual_lights(loaded);
    if (punctual && max_ratio > 0.0) {
        std::fprintf(stderr, "rtpbr-render: --max-ratio: %s has %u KHR_lights_punctual light(s), and a scene with "
                             "punctual (delta) lights has no energy bound to hold pixels to (docs/limits.md)\n",
                     scene_path.c_str(), punctual);
        rtpbr_gltf_destroy(loaded);
        return 1;
    }
    uint32_t proxies = 0;
    for (uint32_t i = 0; i < loaded->light_count; ++i) proxies += loaded->lights[i].proxy ? 1u : 0u;
    std::printf("rtpbr-render: %s: %u %slights", scene_path.c_str(), loaded->light_count,
                loaded->punctual_light_count ? "area " : "");
    if (proxies)
        std::printf(" (%u of them standing in for emissive meshes: docs/materials.md, \"Lights from materials\")", proxies);
    if (loaded->punctual_light_count)
        std::printf(" and %u punctual lights (KHR_lights_punctual)", loaded->punctual_light_count);
    std::printf("\n");
    if (loaded->camera_count == 0)
        std::fprintf(stderr, "rtpbr-render: warning: %s has no camera: rendering from a default one at (0, 0, 5) "
                             "looking at the origin, which rarely frames a scene (add a camera to the file)\n",
                     scene_path.c_str());
    rtpbr_result r = rtpbr_context_create(&cd, &ctx);
    if (r == RTPBR_SUCCESS) r = rtpbr_gpu_scene_from_loaded(ctx, loaded, &scene);
    rtpbr_gltf_destroy(loaded);
    if (r == RTPBR_SUCCESS) r = rtpbr_renderer_create(ctx, &size, &renderer);
    if (r == RTPBR_ERROR_MISSING_FEATURE && size.timings) { // a queue without timestamps: no times
        size.timings = 0;
        r = rtpbr_renderer_create(ctx, &size, &renderer);
    }
    if (r == RTPBR_SUCCESS) r = rtpbr_render(renderer, scene, &render);
    std::string error;
    auto write_out = [&error](bool written) {
        if (!written) std::fprintf(stderr, "rtpbr-render: %s\n", error.c_str());
        return written;
    };
    bool bound_held = true;
    rtpbr_timings times{};
    if (r == RTPBR_SUCCESS && size.timings && rtpbr_renderer_timings(renderer, &times) == RTPBR_SUCCESS && times.valid)
        std::printf("rtpbr-render: frame %.1f ms on the device (G-buffer %.1f, lighting %.1f, tone map %.1f)\n",
                    times.total_ms, times.gbuffer_ms, times.lighting_ms, times.tonemap_ms);
    if (r == RTPBR_SUCCESS) {
        int w = static_cast<int>(size.width), h = static_cast<int>(size.height);
        std::vector<float> rgba(size_t(w) * h * 4), rgb(size_t(w) * h * 3);
        r = rtpbr_read_radiance(renderer, rgba.data(), rgba.size() * sizeof(float));
        for (size_t p = 0; p < size_t(w) * h; ++p)
            for (int c = 0; c < 3; ++c) rgb[3 * p + c] = rgba[4 * p + c];
        if (r == RTPBR_SUCCESS) {
            rtpbr_tools::EnergyStats es = punctual ? rtpbr_tools::energy_stats_unbounded(rgb.data(), w, h, 3)
                                                   : rtpbr_tools::energy_stats(rgb.data(), w, h, 3, bound);
            std::printf("rtpbr-render: %s%s\n", es.bounded ? "energy bound: " : "",
                        rtpbr_tools::energy_summary(es).c_str());
            bound_held = es.non_finite == 0 && (max_ratio <= 0.0 || es.max_ratio <= max_ratio);
            if (!bound_held)
                std::fprintf(stderr, "rtpbr-render: energy bound exceeded: largest pixel %.6g x the brightest emitter "
                             "(limit %.6g), %zu pixels not finite\n", es.max_ratio, max_ratio, es.non_finite);
            if (!stats_path.empty()) {
                FILE *f = std::fopen(stats_path.c_str(), "w");
                if (!f || std::fprintf(f, "%s\n", rtpbr_tools::energy_json(es).c_str()) < 0) {
                    std::fprintf(stderr, "rtpbr-render: cannot write %s\n", stats_path.c_str());
                    bound_held = false;
                }
                if (f) std::fclose(f);
            }
        }
        if (r == RTPBR_SUCCESS && exr) {
            if (write_out(rtpbr_tools::write_image_float(out_path, w, h, 3, rgb.data(), error))) status = 0;
        } else if (r == RTPBR_SUCCESS) {
            std::vector<uint8_t> display(size_t(w) * h * 4), display_rgb(size_t(w) * h * 3);
            r = rtpbr_read_display(renderer, display.data(), display.size());
            for (size_t p = 0; p < size_t(w) * h; ++p)
                for (int c = 0; c < 3; ++c) display_rgb[3 * p + c] = display[4 * p + c];
            if (r == RTPBR_SUCCESS && write_out(rtpbr_tools::write_image_u8(out_path, w, h, 3, display_rgb.data(), error)))
                status = 0;
        }
    }
    if (r != RTPBR_SUCCESS) std::fprintf(stderr, "rtpbr-render: failed: %s\n", rtpbr_result_string(r));
    else if (validation && rtpbr_context_validation_message_count(ctx)) {
        std::fprintf(stderr, "rtpbr-render: %u validation message(s)\n", rtpbr_context_validation_message_count(ctx));
        status = 1;
    }
    if (!bound_held) status = 1;
    if (status == 0) std::printf("rtpbr-render: wrote %s (%ux%u) on %s\n", out_path.c_str(), size.width, size.height,
                                 rtpbr_context_device_name(ctx));
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    return status;
}

// The need of the render is checked before its allocations (render_memory_need); what the
// estimate misses (the loader's, Vulkan's and OpenImageIO's own buffers) ends here with a
// message.
int main(int argc, char **argv)
{
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "rtpbr-render: out of memory (docs/limits.md: rtpbr-render's memory needs)\n");
    } catch (const std::exception &e) {
        std::fprintf(stderr, "rtpbr-render: unexpected error: %s\n", e.what());
    }
    return 1;
}
