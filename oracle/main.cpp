// rtpbr-oracle: command-line front end of the path tracer (see README.md).
#include "oracle.h"

#include <rtpbr/rtpbr_gltf.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

const char *kUsage =
    "usage: rtpbr-oracle SCENE.gltf -o OUT.exr|OUT.acc [options]\n"
    "       rtpbr-oracle --merge A.acc B.acc ... -o OUT.exr|OUT.acc [--stderr-image SE.exr]\n"
    "options:\n"
    "  --width W --height H     image size (default 512 x width/camera aspect)\n"
    "  --camera I               glTF camera index (default 0)\n"
    "  --spp N                  samples per pixel of the full render (default 16)\n"
    "  --seed S                 random seed (default 0)\n"
    "  --threads T              render threads (default: all cores)\n"
    "  --max-depth D            scattering events per path (default 16; 1 = direct light)\n"
    "  --direct-only            direct lighting only (= --max-depth 1)\n"
    "  --no-shadows             direct lighting ignores occluders\n"
    "  --single-scatter         plain microfacet BRDF instead of the multiple-scattering walk\n"
    "  --light-sampling M       solid-angle (default) | area\n"
    "  --sample-range A:B       render samples [A, B) of the N (write an .acc to merge)\n"
    "  --region X0:Y0:X1:Y1     render pixels [X0, X1) x [Y0, Y1) only\n"
    "  --stderr-image SE.exr    per-pixel standard error of the mean radiance\n"
    "  --preview OUT.png        sRGB preview (clamped radiance x exposure)\n"
    "  --exposure E             preview exposure multiplier (default 1)\n"
    "  --quiet                  no progress bar or summary\n"
    "  --memory-limit MIB       refuse work that needs more memory than this (default: what\n"
    "                           the system has available; docs/limits.md)\n"
    "  --texture-memory MIB     decoded texture budget of the loader (default 256)\n";

bool parseU32(const char *s, uint32_t *out) {
    char *end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(s, &end, 10);
    if (errno || end == s || *end != '\0' || v > 0xffffffffull || s[0] == '-')
        return false;
    *out = uint32_t(v);
    return true;
}

bool parseList(const char *s, uint32_t *vals, int n) {
    std::string str(s);
    size_t pos = 0;
    for (int i = 0; i < n; i++) {
        size_t next = str.find(':', pos);
        if ((i < n - 1) != (next != std::string::npos))
            return false;
        std::string part = str.substr(pos, next == std::string::npos ? std::string::npos : next - pos);
        if (!parseU32(part.c_str(), &vals[i]))
            return false;
        pos = next + 1;
    }
    return true;
}

bool endsWith(const std::string &s, const char *suffix) {
    size_t n = std::strlen(suffix);
    return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

struct ProgressBar {
    bool enabled;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    double lastPrint = -1.0;
    void operator()(uint64_t done, uint64_t total) {
        if (!enabled)
            return;
        double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (done < total && t - lastPrint < 0.2)
            return;
        lastPrint = t;
        double f = total ? double(done) / double(total) : 1.0;
        int bars = int(f * 30.0);
        char bar[31];
        for (int i = 0; i < 30; i++)
            bar[i] = i < bars ? '#' : '.';
        bar[30] = '\0';
        double left = f > 0.0 ? t * (1.0 - f) / f : 0.0;
        std::fprintf(stderr, "\r[%s] %5.1f%%  %6.1fs elapsed  %6.1fs left ", bar, 100.0 * f, t, left);
        if (done >= total)
            std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }
};

void logToStderr(rtpbr_gltf_log_level level, const char *message, void *user) {
    bool quiet = *static_cast<bool *>(user);
    if (level == RTPBR_GLTF_LOG_WARNING && !quiet)
        std::fprintf(stderr, "rtpbr-oracle: scene warning: %s\n", message);
}

int fail(const std::string &msg) {
    std::fprintf(stderr, "rtpbr-oracle: %s\n", msg.c_str());
    return 1;
}

int writeOutputs(const rtpbr_oracle::Accumulator &acc, const std::string &out, const std::string &stderrPath,
                 const std::string &preview, float exposure) {
    std::string error;
    if (endsWith(out, ".acc")) {
        if (rtpbr_oracle::writeAccumulator(out, acc, &error) != rtpbr_oracle::Result::Success)
            return fail(error);
    }
    std::vector<float> rgb, se;
    rtpbr_oracle::resolve(acc, &rgb, stderrPath.empty() ? nullptr : &se);
    if (!endsWith(out, ".acc") && rtpbr_oracle::writeImage(out, acc.width, acc.height, rgb, 1.0f, &error) !=
                                      rtpbr_oracle::Result::Success)
        return fail(error);
    if (!stderrPath.empty() &&
        rtpbr_oracle::writeImage(stderrPath, acc.width, acc.height, se, 1.0f, &error) != rtpbr_oracle::Result::Success)
        return fail(error);
    if (!preview.empty() &&
        rtpbr_oracle::writeImage(preview, acc.width, acc.height, rgb, exposure, &error) != rtpbr_oracle::Result::Success)
        return fail(error);
    return 0;
}

// The command line, parsed.
struct Options {
    rtpbr_oracle::RenderSettings s;
    std::string scenePath, outPath, stderrPath, previewPath;
    std::vector<std::string> mergeInputs;
    bool merging = false, quiet = false;
    uint64_t textureBudget = 0; // 0: the loader's default
    float exposure = 1.0f;
};

// What an option parser returns besides an exit status: go on, or not an option of its own.
constexpr int kGo = -1, kNotMine = -2;

// The arguments, read one after the other; an option's value is the next argument.
struct Args {
    int argc;
    char **argv;
    int i = 1;

    const char *value(const char *name) {
        if (i + 1 >= argc) {
            std::fprintf(stderr, "rtpbr-oracle: %s needs a value\n", name);
            return nullptr;
        }
        return argv[++i];
    }
    bool u32(const char *name, uint32_t *dst) {
        const char *v = value(name);
        if (!v || !parseU32(v, dst)) {
            std::fprintf(stderr, "rtpbr-oracle: %s: expected a non-negative integer\n", name);
            return false;
        }
        return true;
    }
};

// The options of the render itself (rtpbr_oracle::RenderSettings).
int settingOption(const std::string &a, Args &args, rtpbr_oracle::RenderSettings &s) {
    using rtpbr_oracle::RenderSettings;
    // The options that set one whole-number field.
    static const struct {
        const char *name;
        uint32_t RenderSettings::*field;
    } counts[] = {
        {"--width", &RenderSettings::width},     {"--height", &RenderSettings::height},
        {"--camera", &RenderSettings::camera},   {"--spp", &RenderSettings::spp},
        {"--threads", &RenderSettings::threads}, {"--max-depth", &RenderSettings::maxDepth},
    };
    for (const auto &c : counts)
        if (a == c.name)
            return args.u32(c.name, &(s.*c.field)) ? kGo : 2;
    const char *v = nullptr;
    if (a == "--seed") {
        uint32_t seed;
        if (!args.u32("--seed", &seed))
            return 2;
        s.seed = seed;
    } else if (a == "--direct-only") {
        s.directOnly = true;
    } else if (a == "--no-shadows") {
        s.noShadows = true;
    } else if (a == "--single-scatter") {
        s.singleScatter = true;
    } else if (a == "--light-sampling") {
        if (!(v = args.value("--light-sampling")))
            return 2;
        if (std::strcmp(v, "solid-angle") == 0)
            s.lightSampling = rtpbr_oracle::LightSampling::SolidAngle;
        else if (std::strcmp(v, "area") == 0)
            s.lightSampling = rtpbr_oracle::LightSampling::Area;
        else
            return fail("--light-sampling: expected solid-angle or area");
    } else if (a == "--sample-range") {
        uint32_t r[2];
        if (!(v = args.value("--sample-range")) || !parseList(v, r, 2))
            return fail("--sample-range: expected A:B");
        s.sampleBegin = r[0];
        s.sampleEnd = r[1];
        if (s.sampleEnd == 0)
            return fail("--sample-range: B must be > A");
    } else if (a == "--region") {
        uint32_t r[4];
        if (!(v = args.value("--region")) || !parseList(v, r, 4))
            return fail("--region: expected X0:Y0:X1:Y1");
        s.region = {r[0], r[1], r[2], r[3]};
        if (r[0] >= r[2] || r[1] >= r[3])
            return fail("--region: empty region");
    } else {
        return kNotMine;
    }
    return kGo;
}

// The other options and the positional arguments (scene, or accumulators after --merge).
int otherOption(const std::string &a, Args &args, Options *o) {
    // The options that name a file to write.
    static const struct {
        const char *name;
        std::string Options::*path;
    } paths[] = {{"-o", &Options::outPath}, {"--stderr-image", &Options::stderrPath}, {"--preview", &Options::previewPath}};
    const char *v = nullptr;
    for (const auto &p : paths)
        if (a == p.name) {
            if (!(v = args.value(p.name)))
                return 2;
            o->*p.path = v;
            return kGo;
        }
    if (a == "-h" || a == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
    } else if (a == "--exposure") {
        if (!(v = args.value("--exposure")))
            return 2;
        char *end = nullptr;
        o->exposure = std::strtof(v, &end);
        if (end == v || *end || !(o->exposure > 0.0f))
            return fail("--exposure: expected a positive number");
    } else if (a == "--quiet") {
        o->quiet = true;
    } else if (a == "--memory-limit" || a == "--texture-memory") {
        uint32_t mib = 0;
        if (!args.u32(a.c_str(), &mib) || mib == 0)
            return 2;
        (a == "--memory-limit" ? o->s.memoryLimit : o->textureBudget) = uint64_t(mib) << 20;
    } else if (a == "--merge") {
        o->merging = true;
    } else if (!a.empty() && a[0] == '-') {
        std::fprintf(stderr, "rtpbr-oracle: unknown option %s\n%s", a.c_str(), kUsage);
        return 2;
    } else if (o->merging) {
        o->mergeInputs.push_back(a);
    } else if (o->scenePath.empty()) {
        o->scenePath = a;
    } else {
        return fail("more than one scene given");
    }
    return kGo;
}

// kGo, or the exit status (0 after --help).
int parseOptions(int argc, char **argv, Options *o) {
    for (Args args{argc, argv}; args.i < argc; args.i++) {
        const std::string a = argv[args.i];
        int r = settingOption(a, args, o->s);
        if (r == kNotMine)
            r = otherOption(a, args, o);
        if (r != kGo)
            return r;
    }
    if (o->outPath.empty()) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    return kGo;
}

// --merge: the accumulators summed, then written as a render's would be.
int mergeAccumulators(const Options &o) {
    if (o.mergeInputs.empty() || !o.scenePath.empty())
        return fail("--merge takes accumulator files only");
    std::string error;
    rtpbr_oracle::Accumulator acc;
    for (size_t i = 0; i < o.mergeInputs.size(); i++) {
        rtpbr_oracle::Accumulator part;
        if (rtpbr_oracle::readAccumulator(o.mergeInputs[i], &part, &error, o.s.memoryLimit) !=
            rtpbr_oracle::Result::Success)
            return fail(error);
        if (i == 0)
            acc = std::move(part);
        else if (rtpbr_oracle::merge(&acc, part, &error) != rtpbr_oracle::Result::Success)
            return fail(o.mergeInputs[i] + ": " + error);
    }
    return writeOutputs(acc, o.outPath, o.stderrPath, o.previewPath, o.exposure);
}

// The scene loaded, rendered (with a progress bar on a terminal) and written.
int renderScene(Options &o) {
    if (o.scenePath.empty()) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    char loadError[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
    rtpbr_gltf_load_desc desc = {};
    desc.error_message = loadError;
    desc.error_message_size = sizeof loadError;
    desc.texture_memory_budget = o.textureBudget;
    // every emissive triangle an emitter, textured ones each alone (emittedAt applies the texture)
    desc.emissive_mode = RTPBR_GLTF_EMISSIVE_EXACT;
    desc.logger.func = logToStderr;
    desc.logger.user_data = &o.quiet;
    rtpbr_gltf_scene *scene = nullptr;
    rtpbr_gltf_result lr = rtpbr_gltf_load(o.scenePath.c_str(), &desc, &scene);
    if (lr != RTPBR_GLTF_SUCCESS)
        return fail(o.scenePath + ": " + rtpbr_gltf_result_string(lr) + ": " + loadError);

    std::string error;
    rtpbr_oracle::Accumulator acc;
    ProgressBar bar{!o.quiet && isatty(STDERR_FILENO)};
    rtpbr_oracle::RenderStats stats;
    rtpbr_oracle::Result r =
        rtpbr_oracle::render(*scene, o.s, &acc, &error, [&bar](uint64_t d, uint64_t t) { bar(d, t); }, &stats);
    rtpbr_gltf_destroy(scene);
    if (r != rtpbr_oracle::Result::Success)
        return fail(o.scenePath + ": " + rtpbr_oracle::resultString(r) + ": " + error);
    if (!o.quiet)
        std::fprintf(stderr,
                     "rtpbr-oracle: %ux%u, %" PRIu64 " samples in %.2fs (%.0f samples/s, %.2f Mrays/s)%s\n",
                     acc.width, acc.height, stats.samples, stats.seconds, double(stats.samples) / stats.seconds,
                     double(stats.rays) / stats.seconds * 1e-6,
                     acc.nonFinite ? ", non-finite samples were zeroed" : "");
    return writeOutputs(acc, o.outPath, o.stderrPath, o.previewPath, o.exposure);
}

} // namespace

static int run(int argc, char **argv) {
    Options o;
    const int status = parseOptions(argc, argv, &o);
    if (status != kGo)
        return status;
    return o.merging ? mergeAccumulators(o) : renderScene(o);
}

// Memory needs are checked before the large allocations (rtpbr_oracle::checkMemory); what the
// estimates do not cover (OpenImageIO's and Embree's own buffers) ends here with a message.
int main(int argc, char **argv) {
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc &) {
        return fail("out of memory (see docs/limits.md for the oracle's memory needs)");
    } catch (const std::exception &e) {
        return fail(std::string("unexpected error: ") + e.what());
    }
}
