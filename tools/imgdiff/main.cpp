// rtpbr-diff: compares a test image with a reference image using LDR-FLIP or HDR-FLIP
// (rtpbr_common/flip.hpp), and reports RMSE, relative MSE and PSNR. See usage() for the exact definitions.
#include "rtpbr_common/flip.hpp"
#include "rtpbr_common/colormap.hpp"
#include "rtpbr_common/energy.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/image_read.hpp"
#include "rtpbr_common/memory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace {

enum ExitCode { kExitPass = 0, kExitThreshold = 1, kExitError = 2 };

const char* const kUsage =
    "usage: rtpbr-diff REFERENCE TEST [--hdr] [--heatmap OUT.png] [--json]\n"
    "                  [--max-mean X] [--max-p95 Y] [--ppd P] [--bound L [--max-ratio R]]\n"
    "                  [--memory-limit MIB]\n"
    "\n"
    "Compares TEST with REFERENCE (EXR, PNG, HDR, JPEG, TIFF, BMP, PNM/PFM or TGA).\n"
    "  Integer pixel formats (8/16-bit PNG, ...) are taken as sRGB-encoded and decoded to linear;\n"
    "  float formats (EXR, HDR) are taken as linear. Grey images are replicated to RGB, alpha\n"
    "  and extra channels are ignored.\n"
    "  default  LDR-FLIP (Andersson et al. 2020) on the linear values clamped to [0, 1]; float\n"
    "           inputs get no exposure or tone mapping, only the clamp.\n"
    "  --hdr    HDR-FLIP (Andersson et al. 2021): exposures from the reference, ACES tone map.\n"
    "  --ppd P  viewing condition in pixels per degree (default 67: a 0.7 m wide 3840-pixel\n"
    "           monitor seen from 0.7 m).\n"
    "  --heatmap OUT.png  writes the FLIP error map through the magma colour map.\n"
    "  --json   prints one JSON object instead of text.\n"
    "  --max-mean X, --max-p95 Y  exit 1 when the mean / 95th percentile FLIP error exceeds them.\n"
    "  --bound L  the energy bound of both images against L, the brightest emitter's radiance (no\n"
    "           pixel of a render may exceed it; rtpbr-render prints it): the largest pixel / L, the\n"
    "           mean of that ratio, the energy share of the brightest 0.01 % of pixels, non-finite\n"
    "           pixels (JSON: \"bound\": {\"reference\": {...}, \"test\": {...}}). A scene with punctual\n"
    "           lights (KHR_lights_punctual) has no such L (rtpbr-render's stats: \"bounded\": false).\n"
    "  --max-ratio R  with --bound: exit 1 when a TEST pixel exceeds R x L or is not finite.\n"
    "  --memory-limit MIB  refuse images whose comparison needs more memory than this (default:\n"
    "           what the system has available); the need is counted from the headers before any\n"
    "           pixel is read (docs/limits.md).\n"
    "Also reported: rmse = sqrt(mean (t - r)^2) and relmse = mean (t - r)^2 / (r^2 + 0.01) over all\n"
    "RGB values as read (linear, unclamped); psnr = 10 log10(1 / mse) on the linear values clamped\n"
    "to [0, 1] (what LDR-FLIP sees), infinite (JSON null) for identical images.\n"
    "Exit status: 0 thresholds hold (or none given), 1 a threshold is exceeded, 2 error.\n";

struct Options {
    std::string reference;
    std::string test;
    std::string heatmap;
    bool hdr = false;
    bool json = false;
    bool has_max_mean = false;
    bool has_max_p95 = false;
    double max_mean = 0.0;
    double max_p95 = 0.0;
    double bound = 0.0;     // 0: no energy bound
    double max_ratio = 0.0; // 0: report only
    float ppd = rtpbr::kFlipDefaultPpd;
    uint64_t memory_limit = 0;  // bytes; 0: what the system has available
};

// Memory of a comparison per pixel, both images together: the two images as read (linear RGB
// floats and the decoder's buffer) and FLIP's colour and feature maps. Measured as peak RSS
// over the program's own on 1024² and 2048² EXRs: 72 bytes a pixel for LDR-FLIP, 104 for
// HDR-FLIP; rounded up.
constexpr uint64_t kBytesPerPixel = 128;


// Errors are reported as exactly one line: library messages may hold newlines.
void fail_message(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    std::fprintf(stderr, "rtpbr-diff: %s\n", message.c_str());
}


bool parse_number(const char* text, double& value) {
    char* end = nullptr;
    value = std::strtod(text, &end);
    return end != text && *end == '\0' && std::isfinite(value);
}

// Returns false with a message on bad arguments; sets show_help for -h/--help.
bool parse_args(int argc, char** argv, Options& opt, bool& show_help, std::string& error) {
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](const char*& out) {
            if (i + 1 >= argc) {
                error = "option " + arg + " needs a value";
                return false;
            }
            out = argv[++i];
            return true;
        };
        const char* v = nullptr;
        double number = 0.0;
        if (arg == "-h" || arg == "--help") {
            show_help = true;
            return true;
        } else if (arg == "--hdr") {
            opt.hdr = true;
        } else if (arg == "--json") {
            opt.json = true;
        } else if (arg == "--heatmap") {
            if (!value(v)) return false;
            opt.heatmap = v;
        } else if (arg == "--bound" || arg == "--max-ratio") {
            if (!value(v)) return false;
            if (!parse_number(v, number) || !(number > 0.0)) {
                error = "option " + arg + " needs a finite positive number, got '" + v + "'";
                return false;
            }
            (arg == "--bound" ? opt.bound : opt.max_ratio) = number;
        } else if (arg == "--max-mean" || arg == "--max-p95" || arg == "--ppd") {
            if (!value(v)) return false;
            if (!parse_number(v, number) || number < 0.0) {
                error = "option " + arg + " needs a finite non-negative number, got '" + v + "'";
                return false;
            }
            if (arg == "--max-mean") {
                opt.has_max_mean = true;
                opt.max_mean = number;
            } else if (arg == "--max-p95") {
                opt.has_max_p95 = true;
                opt.max_p95 = number;
            } else {
                if (number <= 0.0 || number > rtpbr::kFlipMaxPpd) {
                    error = "--ppd must be in (0, 1000], got '" + std::string(v) + "'";
                    return false;
                }
                opt.ppd = static_cast<float>(number);
            }
        } else if (arg == "--memory-limit") {
            if (!value(v)) return false;
            if (!parse_number(v, number) || number < 1.0 || number > 1e9 || number != std::floor(number)) {
                error = "option --memory-limit needs a whole number of MiB (1 or more), got '" + std::string(v) + "'";
                return false;
            }
            opt.memory_limit = static_cast<uint64_t>(number) << 20;
        } else if (arg.size() > 1 && arg[0] == '-') {
            error = "unknown option '" + arg + "' (see --help)";
            return false;
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 2) {
        error = "expected REFERENCE and TEST image paths, got " + std::to_string(positional.size()) +
                " (see --help)";
        return false;
    }
    if (opt.max_ratio > 0.0 && !(opt.bound > 0.0)) {
        error = "--max-ratio needs --bound";
        return false;
    }
    opt.reference = positional[0];
    opt.test = positional[1];
    return true;
}


bool write_heatmap(const std::string& path, const std::vector<float>& error_map, int w, int h,
                   std::string& error) {
    std::vector<uint8_t> rgb(error_map.size() * 3);
    for (std::size_t i = 0; i < error_map.size(); ++i)
        rtpbr_tools::magma(error_map[i], &rgb[i * 3]);
    if (!rtpbr_tools::write_image_u8(path, w, h, 3, rgb.data(), error)) {
        error = "heat map: " + error;
        return false;
    }
    return true;
}

struct PixelMetrics {
    double rmse = 0.0;
    double relmse = 0.0;
    double psnr = 0.0;  // +inf when identical
};

PixelMetrics pixel_metrics(const rtpbr::Image& ref, const rtpbr::Image& test) {
    double se = 0.0, rel = 0.0, se_clamped = 0.0;
    for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
        const double r = ref.rgb[i], t = test.rgb[i];
        const double d = t - r;
        se += d * d;
        rel += d * d / (r * r + 0.01);
        const double dc = std::min(1.0, std::max(0.0, t)) - std::min(1.0, std::max(0.0, r));
        se_clamped += dc * dc;
    }
    const double n = static_cast<double>(ref.rgb.size());
    PixelMetrics m;
    m.rmse = std::sqrt(se / n);
    m.relmse = rel / n;
    const double mse = se_clamped / n;
    m.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
    return m;
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (unsigned char ch : s) {
        if (ch == '"' || ch == '\\') {
            out += '\\';
            out += static_cast<char>(ch);
        } else if (ch < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", ch);
            out += buf;
        } else {
            out += static_cast<char>(ch);
        }
    }
    return out + "\"";
}

int run(int argc, char** argv) {
    Options opt;
    bool show_help = false;
    std::string error;
    if (!parse_args(argc, argv, opt, show_help, error)) {
        fail_message(error);
        return kExitError;
    }
    if (show_help) {
        std::fputs(kUsage, stdout);
        return kExitPass;
    }
    // Sizes and the memory need from the headers, before any pixel is read.
    int ref_w = 0, ref_h = 0, test_w = 0, test_h = 0;
    if (!rtpbr::read_image_size(opt.reference, ref_w, ref_h, error) ||
        !rtpbr::read_image_size(opt.test, test_w, test_h, error)) {
        fail_message(error);
        return kExitError;
    }
    if (ref_w != test_w || ref_h != test_h) {
        fail_message("size mismatch: reference '" + opt.reference + "' is " + std::to_string(ref_w) + "x" +
                     std::to_string(ref_h) + ", test '" + opt.test + "' is " + std::to_string(test_w) + "x" +
                     std::to_string(test_h));
        return kExitError;
    }
    const std::string shortfall = rtpbr_tools::memory_shortfall(
        uint64_t(ref_w) * uint64_t(ref_h) * kBytesPerPixel, opt.memory_limit,
        "comparing two " + std::to_string(ref_w) + "x" + std::to_string(ref_h) + " images");
    if (!shortfall.empty()) {
        fail_message(shortfall + " (--memory-limit; docs/limits.md)");
        return kExitError;
    }
    rtpbr::Image ref, test;
    if (!rtpbr::read_image(opt.reference, ref, error) || !rtpbr::read_image(opt.test, test, error)) {
        fail_message(error);
        return kExitError;
    }
    if (ref.width != test.width || ref.height != test.height) {  // the files changed meanwhile
        fail_message("'" + opt.reference + "' or '" + opt.test + "' changed while being read");
        return kExitError;
    }
    std::vector<float> error_map;
    rtpbr::FlipExposures exposures;
    const rtpbr::FlipResult result =
        opt.hdr ? rtpbr::flip_hdr(ref.rgb.data(), test.rgb.data(), ref.width, ref.height, opt.ppd, error_map, &exposures)
                : rtpbr::flip_ldr(ref.rgb.data(), test.rgb.data(), ref.width, ref.height, opt.ppd, error_map);
    if (result != rtpbr::FlipResult::ok) {
        fail_message(std::string("FLIP failed: ") + rtpbr::flip_result_string(result));
        return kExitError;
    }
    const rtpbr::FlipStats stats = rtpbr::flip_stats(error_map);
    const PixelMetrics pm = pixel_metrics(ref, test);
    if (!opt.heatmap.empty() && !write_heatmap(opt.heatmap, error_map, ref.width, ref.height, error)) {
        fail_message(error);
        return kExitError;
    }

    rtpbr_tools::EnergyStats ref_energy, test_energy;
    if (opt.bound > 0.0) {
        ref_energy = rtpbr_tools::energy_stats(ref.rgb.data(), ref.width, ref.height, 3, opt.bound);
        test_energy = rtpbr_tools::energy_stats(test.rgb.data(), test.width, test.height, 3, opt.bound);
    }
    if (opt.json) {
        std::string j = "{";
        j += "\"reference\": " + json_string(opt.reference);
        j += ", \"test\": " + json_string(opt.test);
        j += ", \"mode\": " + json_string(opt.hdr ? "hdr-flip" : "ldr-flip");
        j += ", \"ppd\": " + json_number(opt.ppd);
        j += ", \"width\": " + std::to_string(ref.width);
        j += ", \"height\": " + std::to_string(ref.height);
        j += ", \"mean\": " + json_number(stats.mean);
        j += ", \"median\": " + json_number(stats.median);
        j += ", \"p95\": " + json_number(stats.p95);
        j += ", \"p99\": " + json_number(stats.p99);
        j += ", \"max\": " + json_number(stats.max);
        j += ", \"rmse\": " + json_number(pm.rmse);
        j += ", \"relmse\": " + json_number(pm.relmse);
        j += ", \"psnr\": " + json_number(pm.psnr);
        if (opt.hdr) {
            j += ", \"exposure_start\": " + json_number(exposures.start);
            j += ", \"exposure_stop\": " + json_number(exposures.stop);
            j += ", \"exposure_count\": " + std::to_string(exposures.count);
        }
        if (opt.bound > 0.0)
            j += ", \"bound\": {\"reference\": " + rtpbr_tools::energy_json(ref_energy) +
                 ", \"test\": " + rtpbr_tools::energy_json(test_energy) + "}";
        j += "}\n";
        std::fputs(j.c_str(), stdout);
    } else {
        std::printf("mode      %s, %.3g pixels per degree\n", opt.hdr ? "HDR-FLIP" : "LDR-FLIP", opt.ppd);
        if (opt.hdr)
            std::printf("exposures %d from %.4f to %.4f stops\n", exposures.count, exposures.start, exposures.stop);
        std::printf("size      %dx%d\n", ref.width, ref.height);
        std::printf("FLIP mean %.6f\n", stats.mean);
        std::printf("   median %.6f\n", stats.median);
        std::printf("      p95 %.6f\n", stats.p95);
        std::printf("      p99 %.6f\n", stats.p99);
        std::printf("      max %.6f\n", stats.max);
        std::printf("rmse      %.6g\n", pm.rmse);
        std::printf("relmse    %.6g\n", pm.relmse);
        std::printf("psnr      %.4f dB (linear, clamped to [0, 1])\n", pm.psnr);
        if (opt.bound > 0.0) {
            std::printf("bound     reference: %s\n", rtpbr_tools::energy_summary(ref_energy).c_str());
            std::printf("          test: %s\n", rtpbr_tools::energy_summary(test_energy).c_str());
        }
    }

    std::string exceeded;
    if (opt.has_max_mean && stats.mean > opt.max_mean)
        exceeded += "mean FLIP " + json_number(stats.mean) + " exceeds --max-mean " + json_number(opt.max_mean);
    if (opt.has_max_p95 && stats.p95 > opt.max_p95)
        exceeded += std::string(exceeded.empty() ? "" : "; ") + "95th percentile FLIP " + json_number(stats.p95) +
                    " exceeds --max-p95 " + json_number(opt.max_p95);
    if (opt.max_ratio > 0.0 && (test_energy.max_ratio > opt.max_ratio || test_energy.non_finite > 0))
        exceeded += std::string(exceeded.empty() ? "" : "; ") + "largest test pixel " +
                    json_number(test_energy.max_ratio) + " x the bound exceeds --max-ratio " + json_number(opt.max_ratio) +
                    (test_energy.non_finite ? " (or pixels not finite)" : "");
    if (exceeded.empty()) return kExitPass;
    fail_message(exceeded);
    return kExitThreshold;
}

} // namespace

// The need is checked from the headers before the pixels are read; what the estimate misses
// (OpenImageIO's own buffers) ends here with a message.
int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        fail_message("out of memory (docs/limits.md: rtpbr-diff's memory needs)");
    } catch (const std::exception& e) {
        fail_message(std::string("error: ") + e.what());
    } catch (...) {
        fail_message("unknown error");
    }
    return kExitError;
}
