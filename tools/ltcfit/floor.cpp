// rtpbr-ltc-floor: LTC against a converged quadrature on floors lit by lights near their
// horizon and seen at low angles (issue 19). Per case (roughness, light elevation, NoV), a
// floor around the light is shaded twice: one patch of P x P points per light azimuth 0, 30,
// ..., 180 degrees from the viewer's side (the lobe is symmetric about the plane of incidence:
// 30..150 stand for their mirror images too and count twice), each shaded
//   - LTC: the tables (the compiled-in rtpbr_ltc_tables.h, or --tables FILE) fetched with
//     GPU-like bilinear filtering at LTC_LutCoord, LTC_PolygonToLocal + LTC_IntegrateLocal,
//     times norm (F = 1): what a renderer computes;
//   - reference: the integral of the true BRDF (the shaderlib's D x V, F = 1) x NoL over the
//     light, by composite Gauss-Legendre quadrature over the light's area (no noise; the light
//     is seen nearly edge-on, so the area parametrisation keeps the integrand smooth; across
//     the plane of incidence, where the grazing lobe is narrow, on nodes crowded toward it, see
//     quadrature()), checked against the same rule with half the points per axis (printed:
//     the largest difference).
// The light is a horizontal square of half-size 0.15 facing down (a ceiling panel), centred at
// distance 1 from the patch centre in direction (elevation e, azimuth phi from the viewer's
// side: 0 = the light between the eye and the floor, the "far floor" of a scene, 180 = the
// mirror side, the near floor); the patch spans +-0.2 around its centre (elevations within
// about +-20% of e); V is the same at every point (a distant camera) with NoV given.
// Floor error of a case = sum |LTC - ref| / sum ref over all its points (the relative L1 error
// of the floor image: dominated by the bright mirror side, as in a picture). Prints markdown
// tables (per NoV: roughness x elevation; with the signed error of the far floor, azimuth 0,
// and of the near floor, 180) and writes signed error maps.
//
//   rtpbr-ltc-floor [--lobe ggx|beckmann|diffuse] [--tables HEADER] [--png FILE] [--quick] [--per-azimuth] [--threads T]
//                   [--exact-cells] [--elevation-correction | --direction-correction | --residual-correction |
//                    --hybrid-correction] [--correction-bins E A] [--correction-samples N]
//                   [--second-lobe | --second-lobe-joint] [--no-point | --no-tail | --no-streak | --point-raw | --point-ff]
// The last four are the experiments of issue 19's second round (shaderlib/luts/ltc.md): the
// LTC fitted at each case's exact (roughness, NoV) instead of the table's interpolation, and
// the LTC corrected by the direction of the lit part of the light (ltc_floor.hpp).
// --second-lobe, --second-lobe-joint (third round): a second LTC lobe per (roughness, NoV)
// cell, fitted on other floors to the table LTC's residual, or together with a refitted first
// lobe, and the sweep's floors of nine grazing cells with it (ltc_floor_lobe2.hpp); prints its
// own table and nothing else.
// The LTC is evaluated as the engine does, with the point correction (ltc_corrections.h, LTC_PointFactor;
// fourth round) unless --no-point (the second round's corrections and --exact-cells measure
// the LTC alone); --point-raw: the uncorrected ratio at the lit part's centre (no clamp, no
// fade); --point-ff: no LTC, the true f NoL / NoL at that centre x pi x the form factor.
// The engine also takes the tail estimate (ltc_corrections.h, LTC_PointTail; fifth round) where the light
// lies in the LTC's tail, and so does this tool unless --no-tail (the fourth round's engine);
// and the streak estimate (ltc_corrections.h, LTC_StreakEnd; sixth round) on the mirror side near the
// horizon, unless --no-streak (the fifth round's engine).
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <thread>

#include "ltc_fit.hpp"
#include "ltc_floor.hpp"
#include "ltc_floor_lobe2.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/markdown.hpp"

using namespace ltcfloor;

namespace {

// Diverging colour: blue (LTC too dark) - white (exact) - red (too bright), saturating at +-50%.
void diverging(float e, unsigned char rgb[3]) {
    float t = std::clamp(e / 0.5f, -1.0f, 1.0f);
    float a = std::fabs(t);
    unsigned char lo = (unsigned char)std::lround(255.0f * (1.0f - a));
    if (t >= 0) {
        rgb[0] = 255, rgb[1] = lo, rgb[2] = lo;
    } else {
        rgb[0] = lo, rgb[1] = lo, rgb[2] = 255;
    }
}

const char *const kUsage =
    "usage: rtpbr-ltc-floor [--lobe ggx|beckmann|diffuse] [--tables HEADER] [--png FILE] [--quick]\n"
    "                       [--per-azimuth] [--threads T] [--exact-cells]\n"
    "                       [--elevation-correction | --direction-correction | --residual-correction |\n"
    "                        --hybrid-correction] [--correction-bins E A] [--correction-samples N]\n"
    "                       [--second-lobe | --second-lobe-joint]\n"
    "                       [--no-point | --no-tail | --no-streak | --point-raw | --point-ff]\n"
    "The LTC against a converged quadrature on floors lit by lights near their horizon and seen\n"
    "at low angles; prints markdown tables of the relative L1 floor error (see floor.cpp).\n"
    "  --lobe L               ggx (default), beckmann or diffuse (Disney diffuse)\n"
    "  --tables HEADER        LTC tables from this header instead of the compiled-in ones\n"
    "  --png FILE             also write the signed error maps\n"
    "  --quick                fewer cases and points\n"
    "  --per-azimuth          also a table per light azimuth of the grazing floors\n"
    "  --threads T            worker threads (1..64; default 2)\n"
    "  --exact-cells          no table interpolation: each case's own fit (experiment)\n"
    "  --elevation-correction, --direction-correction, --residual-correction,\n"
    "  --hybrid-correction    the LTC corrected by the lit part's direction (experiments,\n"
    "                         ltc_floor.hpp)\n"
    "  --correction-bins E A  elevation and azimuth bins of those corrections\n"
    "  --correction-samples N samples per side of the correction fit (16..4096; default 512)\n"
    "  --second-lobe          a second LTC lobe per cell fitted to the residual (experiment)\n"
    "  --second-lobe-joint    the same, both lobes refitted together\n"
    "  --no-point             the LTC without the point correction (LTC_PointFactor)\n"
    "  --no-tail              the point correction without the tail estimate\n"
    "  --no-streak            without the streak estimate\n"
    "  --point-raw            the uncorrected point ratio (experiment)\n"
    "  --point-ff             the true BRDF at the lit part's centre x the form factor (experiment)\n"
    "  -h, --help             this text\n";

} // namespace

int main(int argc, char **argv) {
    Lobe lobe = Lobe::GGX;
    std::string tablesPath, png;
    bool quick = false, exactCells = false, secondLobe = false, secondLobeJoint = false;
    int correctionAzimuths = 0, point = 1;
    bool tail = true, streak = true, perAzimuth = false;
    bool residual = false, hybrid = false;
    int correctionElevations = 16, correctionSamples = 512;
    int threads = 2;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--lobe") && i + 1 < argc) {
            std::string l = argv[++i];
            if (l == "ggx")
                lobe = Lobe::GGX;
            else if (l == "beckmann")
                lobe = Lobe::Beckmann;
            else if (l == "diffuse")
                lobe = Lobe::DisneyDiffuse;
            else {
                fprintf(stderr, "rtpbr-ltc-floor: unknown lobe '%s' (ggx, beckmann, diffuse)\n", l.c_str());
                return 2;
            }
        } else if (!strcmp(argv[i], "--tables") && i + 1 < argc)
            tablesPath = argv[++i];
        else if (!strcmp(argv[i], "--png") && i + 1 < argc)
            png = argv[++i];
        else if (!strcmp(argv[i], "--quick"))
            quick = true;
        else if (!strcmp(argv[i], "--per-azimuth")) // also a table per azimuth of the grazing floors
            perAzimuth = true;
        else if (!strcmp(argv[i], "--second-lobe")) // experiment, see ltc_floor_lobe2.hpp
            secondLobe = true;
        else if (!strcmp(argv[i], "--second-lobe-joint")) // the same, both lobes refitted together
            secondLobe = secondLobeJoint = true;
        else if (!strcmp(argv[i], "--no-point")) // the LTC without the point correction (ltc_floor.hpp)
            point = 0;
        else if (!strcmp(argv[i], "--no-tail")) // the point correction without the tail estimate (round 4's engine)
            tail = false;
        else if (!strcmp(argv[i], "--no-streak")) // without the streak estimate (round 5's engine)
            streak = false;
        else if (!strcmp(argv[i], "--point-raw")) // experiment (round 4), see ltc_floor.hpp
            point = 2;
        else if (!strcmp(argv[i], "--point-ff")) // experiment (round 4), see ltc_floor.hpp
            point = 3;
        else if (!strcmp(argv[i], "--exact-cells")) // no table interpolation: each case's own fit
            exactCells = true;
        else if (!strcmp(argv[i], "--elevation-correction")) // experiment, see ltc_floor.hpp
            correctionAzimuths = 1;
        else if (!strcmp(argv[i], "--direction-correction")) // experiment, see ltc_floor.hpp
            correctionAzimuths = 12;
        else if (!strcmp(argv[i], "--residual-correction")) { // experiment, see ltc_floor.hpp
            correctionAzimuths = 12;
            residual = true;
        } else if (!strcmp(argv[i], "--hybrid-correction")) { // experiment, see ltc_floor.hpp
            if (!correctionAzimuths)
                correctionAzimuths = 12;
            hybrid = true;
        } else if (!strcmp(argv[i], "--correction-bins") && i + 2 < argc) { // elevation, azimuth bins
            correctionElevations = atoi(argv[++i]);
            correctionAzimuths = atoi(argv[++i]);
            if (correctionElevations < 2 || correctionElevations > DirectionCorrection::kElev ||
                correctionAzimuths < 1 || correctionAzimuths > DirectionCorrection::kMaxAz) {
                fprintf(stderr, "rtpbr-ltc-floor: --correction-bins: 2..%d elevation, 1..%d azimuth bins\n",
                        DirectionCorrection::kElev, DirectionCorrection::kMaxAz);
                return 2;
            }
        } else if (!strcmp(argv[i], "--correction-samples") && i + 1 < argc) { // per side
            correctionSamples = atoi(argv[++i]);
            if (correctionSamples < 16 || correctionSamples > 4096) {
                fprintf(stderr, "rtpbr-ltc-floor: --correction-samples must be 16..4096\n");
                return 2;
            }
        }
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
            threads = atoi(argv[++i]);
            if (threads < 1 || threads > 64) {
                fprintf(stderr, "rtpbr-ltc-floor: --threads must be 1..64\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            fputs(kUsage, stdout);
            return 0;
        } else {
            fputs(kUsage, stderr);
            return 2;
        }
    }
    ltcfit::PackedTables packed;
    Tables tab{lobe == Lobe::GGX ? rtpbr_ltc_ggx_1 : lobe == Lobe::Beckmann ? rtpbr_ltc_beckmann_1 : rtpbr_ltc_disney_diffuse_1,
               lobe == Lobe::GGX ? rtpbr_ltc_ggx_2 : lobe == Lobe::Beckmann ? rtpbr_ltc_beckmann_2 : rtpbr_ltc_disney_diffuse_2};
    if (!tablesPath.empty()) {
        std::string quality, err;
        if (!ltcfit::read_header(tablesPath, RTPBR_LTC_SIZE, packed, quality, err)) {
            fprintf(stderr, "rtpbr-ltc-floor: error: %s\n", err.c_str());
            return 1;
        }
        tab = lobe == Lobe::GGX        ? Tables{packed.ggx1.data(), packed.ggx2.data()}
              : lobe == Lobe::Beckmann ? Tables{packed.beckmann1.data(), packed.beckmann2.data()}
                                       : Tables{packed.diffuse1.data(), packed.diffuse2.data()};
    }
    if (secondLobe) { // issue 19, round 3: a second lobe fitted to the residual (ltc_floor_lobe2.hpp)
        std::vector<std::pair<float, float>> keys;
        for (float v : {0.1f, 0.2f, 0.3f})
            for (float r : quick ? std::vector<float>{0.5f} : std::vector<float>{0.3f, 0.5f, 0.8f})
                keys.push_back({r, v});
        std::vector<Lobe2Result> res(keys.size());
        std::atomic<size_t> nextKey{0}, doneKeys{0};
        std::mutex pm;
        std::vector<std::thread> fitters;
        for (int t = 0; t < threads; t++)
            fitters.emplace_back([&]() {
                for (size_t k = nextKey++; k < keys.size(); k = nextKey++) {
                    const float r = keys[k].first, v = keys[k].second;
                    res[k] = lobe2_cell(lobe, r, v, ltcmc::fetch(tab.t1, rtpbr::LTC_LutCoord(v, r)),
                                        ltcmc::fetch(tab.t2, rtpbr::LTC_LutCoord(v, r)), quick ? 100 : 400, secondLobeJoint);
                    std::lock_guard<std::mutex> lock(pm);
                    fprintf(stderr, "\rrtpbr-ltc-floor: second lobe %zu/%zu", size_t(++doneKeys), keys.size());
                }
            });
        for (std::thread &t : fitters)
            t.join();
        fprintf(stderr, "\n");
        printf("%s floor error, table LTC -> %s fitted per cell on other floors (training: mean floor error "
               "before -> after; lobe: m00 m02 m20 m22 a):\n\n",
               ltcmc::lobe_name(lobe), secondLobeJoint ? "two lobes (the first refitted with the second)"
                                                       : "table LTC + a second lobe fitted to the residual");
        printf("| NoV | r | 2 deg | 5 deg | 10 deg | 20 deg | 40 deg | training | lobe |\n|---|---|---|---|---|---|---|---|---|\n");
        for (const Lobe2Result &x : res) {
            printf("| %.1f | %.1f |", double(x.nov), double(x.roughness));
            for (size_t e = 0; e < x.elevs.size(); e++)
                printf(" %.1f -> **%.1f** |", 100 * x.before[e], 100 * x.after[e]);
            printf(" %.1f -> %.1f | %.3g %.3g %.3g %.3g %.3g |\n", 100 * x.trainBefore, 100 * x.trainAfter, x.m[0], x.m[1],
                   x.m[2], x.m[3], x.m[4]);
        }
        return 0;
    }
    const std::vector<float> rough = quick ? std::vector<float>{0.3f, 0.5f, 0.8f}
                                           : std::vector<float>{0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.8f};
    const std::vector<float> elevs = quick ? std::vector<float>{2.0f, 10.0f, 30.0f}
                                           : std::vector<float>{2.0f, 5.0f, 10.0f, 20.0f, 40.0f};
    const std::vector<float> novs = quick ? std::vector<float>{0.1f, 0.3f} : std::vector<float>{0.1f, 0.2f, 0.3f, 0.5f};
    const std::vector<float> azims{0.0f, 30.0f, 60.0f, 90.0f, 120.0f, 150.0f, 180.0f};
    const int P = quick ? 6 : 8, sub = quick ? 6 : 8;
    // --exact-cells: the LTC fitted at exactly each case's (roughness, NoV) with the table's
    // settings, instead of the table's bilinear interpolation: how far any denser table
    // parametrisation could go.
    std::map<std::pair<float, float>, std::pair<float4, float4>> exact;
    if (exactCells) {
        if (lobe == Lobe::Sheen) {
            fprintf(stderr, "rtpbr-ltc-floor: --exact-cells: no sheen\n");
            return 2;
        }
        ltcfit::FitSettings fs;
        fs.size = RTPBR_LTC_SIZE;
        const ltcfit::Lobe fl = lobe == Lobe::GGX ? ltcfit::Lobe::GGX : lobe == Lobe::Beckmann ? ltcfit::Lobe::Beckmann
                                                                                                : ltcfit::Lobe::DisneyDiffuse;
        std::vector<std::pair<float, float>> keys;
        for (float v : novs)
            for (float r : rough)
                keys.push_back({r, v});
        std::vector<ltcfit::Cell> cells(keys.size());
        std::atomic<size_t> nextKey{0};
        std::vector<std::thread> fitters;
        for (int t = 0; t < threads; t++)
            fitters.emplace_back([&]() {
                for (size_t k = nextKey++; k < keys.size(); k = nextKey++)
                    cells[k] = ltcfit::fit_exact(fl, keys[k].first, keys[k].second, fs);
            });
        for (std::thread &t : fitters)
            t.join();
        for (size_t k = 0; k < keys.size(); k++) {
            const glm::dmat3 &m = cells[k].invM;
            exact[keys[k]] = {float4(float(m[0][0]), float(m[2][0]), float(m[0][2]), float(m[2][2])),
                              float4(float(cells[k].norm), float(cells[k].fresnel), float(cells[k].f82), 0.0f)};
        }
        tab.exact = [&exact](const Case &c, float4 &l1, float4 &l2) {
            const auto &e = exact.at({c.roughness, c.nov});
            l1 = e.first;
            l2 = e.second;
        };
    }
    tab.correctionAzimuths = correctionAzimuths;
    tab.residual = residual;
    tab.hybrid = hybrid;
    tab.point = correctionAzimuths > 0 || exactCells ? 0 : point; // the older experiments: on the LTC alone
    tab.tail = tail;
    tab.streak = streak;
    tab.correctionElevations = correctionElevations;
    tab.correctionSamples = correctionSamples;
    std::vector<Case> cases;
    for (float v : novs)
        for (float r : rough)
            for (float e : elevs)
                for (float a : azims)
                    cases.push_back({r, e, v, a});
    std::vector<CaseResult> out(cases.size());
    std::atomic<size_t> next{0};
    std::atomic<size_t> done{0};
    std::mutex m;
    auto worker = [&]() {
        for (size_t i = next++; i < cases.size(); i = next++) {
            out[i] = run_case(cases[i], lobe, tab, P, sub);
            size_t d = ++done;
            std::lock_guard<std::mutex> lock(m);
            fprintf(stderr, "\rrtpbr-ltc-floor: %zu/%zu", d, cases.size());
        }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; t++)
        pool.emplace_back(worker);
    for (std::thread &t : pool)
        t.join();
    fprintf(stderr, "\n");

    auto find = [&](float r, float e, float v, float a) -> const CaseResult & {
        for (const CaseResult &c : out)
            if (c.c.roughness == r && c.c.elevDeg == e && c.c.nov == v && c.c.azimDeg == a)
                return c;
        return out[0];
    };
    struct Floor {
        double err, farSigned, nearSigned;
    };
    auto floor_of = [&](float r, float e, float v) {
        std::vector<CaseResult> az;
        for (float a : azims)
            az.push_back(find(r, e, v, a));
        return Floor{ltcfloor::floor_error(az), find(r, e, v, 0.0f).signedErr, find(r, e, v, 180.0f).signedErr};
    };
    double quadWorst = 0, grazingWorst = 0, sumAll = 0, sumGrazing = 0;
    int nAll = 0, nGrazing = 0;
    const CaseResult *quadCase = &out[0];
    for (const CaseResult &c : out)
        if (c.quadDiff > quadWorst) {
            quadWorst = c.quadDiff;
            quadCase = &c;
        }
    printf("%s floor error (sum |LTC - ref| / sum ref over the floor), %s tables; [signed error of the far floor "
           "(light azimuth 0, on the viewer's side) / of the near floor (azimuth 180, the mirror side)]:\n",
           ltcmc::lobe_name(lobe), tablesPath.empty() ? "compiled-in" : tablesPath.c_str());
    for (float v : novs) {
        printf("\nNoV = %.1f\n\n| r |", double(v));
        rtpbr_tools::print_markdown_head(elevs, " %g deg |", 1);
        for (float r : rough) {
            printf("| %.1f |", double(r));
            for (float e : elevs) {
                Floor f = floor_of(r, e, v);
                printf(" **%.1f%%** [%+.0f%% / %+.0f%%] |", 100 * f.err, 100 * f.farSigned, 100 * f.nearSigned);
                sumAll += f.err;
                nAll++;
                if (e <= 10.0f && v <= 0.3f && r >= 0.3f && r <= 0.8f) {
                    grazingWorst = std::max(grazingWorst, f.err);
                    sumGrazing += f.err;
                    nGrazing++;
                }
            }
            printf("\n");
        }
    }
    if (perAzimuth) {
        // Where a floor's error sits: per light azimuth, that patch's share of the floor's
        // |error| (azimuths 30..150 counted twice, as in the floor error) and its signed error.
        printf("\nGrazing floors per light azimuth (0 = far floor, 180 = near floor): share of the floor's "
               "sum |LTC - ref| / its sum ref, and the patch's signed error:\n\n| NoV | r | elev |");
        rtpbr_tools::print_markdown_head(azims, " %g |", 3);
        for (float v : novs)
            for (float r : rough)
                for (float e : elevs) {
                    if (!(e <= 10.0f && v <= 0.3f && r >= 0.3f && r <= 0.8f))
                        continue;
                    double ref = 0.0;
                    for (float a : azims) {
                        const CaseResult &c = find(r, e, v, a);
                        ref += (a == 0.0f || a == 180.0f ? 1.0 : 2.0) * c.sumRef;
                    }
                    printf("| %.1f | %.1f | %g |", double(v), double(r), double(e));
                    for (float a : azims) {
                        const CaseResult &c = find(r, e, v, a);
                        const double w = a == 0.0f || a == 180.0f ? 1.0 : 2.0;
                        printf(" %.1f%% (%+.0f%%) |", ref > 0 ? 100 * w * c.sumAbs / ref : 0.0, 100 * c.signedErr);
                    }
                    printf("\n");
                }
    }
    printf("\nAll %d floors: mean floor error %.2f%%; grazing (elevation <= 10, NoV <= 0.3, r 0.3-0.8, %d floors): "
           "mean %.2f%%, worst %.2f%%. Quadrature: largest difference between %d x %d points and half as many per axis, relative to the "
           "patch's largest value: %.1e (r %.1f, elevation %g, NoV %.1f, azimuth %g).\n",
           nAll, 100 * sumAll / nAll, nGrazing, 100 * sumGrazing / std::max(nGrazing, 1), 100 * grazingWorst, 8 * sub,
           16 * sub, quadWorst, double(quadCase->c.roughness), double(quadCase->c.elevDeg), double(quadCase->c.nov),
           double(quadCase->c.azimDeg));

    if (!png.empty()) {
        // Rows: NoV (top = 0.1) x roughness; columns: elevation x azimuth. One P x P tile per
        // case (scaled 4x), 2-pixel gaps, 6-pixel gaps between NoV blocks and elevation groups.
        const int s = 4, tile = P * s, gap = 2, big = 8;
        const int nc = int(elevs.size() * azims.size()), nr = int(novs.size() * rough.size());
        const int w = nc * (tile + gap) + int(elevs.size()) * big, h = nr * (tile + gap) + int(novs.size()) * big;
        std::vector<unsigned char> img(size_t(w) * h * 3, 96);
        for (size_t vi = 0; vi < novs.size(); vi++)
            for (size_t ri = 0; ri < rough.size(); ri++)
                for (size_t ei = 0; ei < elevs.size(); ei++)
                    for (size_t ai = 0; ai < azims.size(); ai++) {
                        const CaseResult &c = find(rough[ri], elevs[ei], novs[vi], azims[ai]);
                        int x0 = int(ei * azims.size() + ai) * (tile + gap) + int(ei) * big;
                        int y0 = int(vi * rough.size() + ri) * (tile + gap) + int(vi) * big;
                        for (int y = 0; y < tile; y++)
                            for (int x = 0; x < tile; x++)
                                diverging(c.map[size_t(y / s) * P + size_t(x / s)],
                                          &img[(size_t(y0 + y) * w + size_t(x0 + x)) * 3]);
                    }
        std::string err;
        if (!rtpbr_tools::write_image_u8(png, w, h, 3, img.data(), err)) {
            fprintf(stderr, "rtpbr-ltc-floor: error: %s\n", err.c_str());
            return 1;
        }
    }
    return 0;
}
