// rtpbr-ltcfit: fitting Linearly Transformed Cosines to the shaderlib's microfacet BRDFs.
//
// Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines", sec. 4 and their fitting code's method:
//   - per table cell (perceptual roughness r, view cosine), the lobe to fit is f(V, L) NoL with
//     F = 1, normalised by its integral `norm` (the directional albedo);
//   - the LTC is M = [X Y Z] diag-ish(m11, m22, m13): Z is the lobe's average direction, X the
//     tangent in the plane of incidence, and (m11, m22, m13) shape the clamped cosine;
//   - the error is the L3 norm of f NoL - norm D_ltc, estimated with the samples of both
//     distributions (f by visible-normal sampling, the LTC by sampling the cosine and
//     transforming) weighted by 1 / (pdf_ltc + pdf_brdf), on a fixed grid of sample points;
//   - it is minimised by Nelder-Mead over (log m11, log m22, m13), starting from the
//     neighbouring cell's result (continuation).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "error_stats.hpp"

namespace ltcfit {

// DisneyDiffuse: Burley's diffuse lobe (BRDF_DisneyDiffuse: white base colour, metallic 0,
// subsurface 0, isotropic), the table's roughness axis being the material's perceptual
// roughness. Its fresnel and f82 columns are 0: the lobe has no separate Fresnel factor.
// Sheen: the KHR_materials_sheen lobe (rtpbr/sheen.h: D_Charlie x V_Charlie, sheenColor 1),
// the roughness axis being the sheen perceptual roughness; fresnel = f82 = 0 like the diffuse.
enum class Lobe { GGX, Beckmann, DisneyDiffuse, Sheen };

struct FitSettings {
    int size = 64;           // table cells per side
    int fitSamples = 24;     // per-strategy sample grid side for the fit error
    int momentSamples = 128; // sample grid side for norm / Fresnel / average direction
    int errorSamples = 64;   // sample grid side for the reported per-cell error
    int maxIterations = 200; // Nelder-Mead iterations per cell
    int threads = 2;
    int errorPower = 3;      // fit the L^p norm of the difference (Heitz et al.: 3)
    bool horizonNormalised = true; // fit above the horizon only, norm / LTC mass above it
    bool freeRotation = true; // fit the frame's angle too (4 parameters) instead of fixing
                              // Z at the lobe's average direction (Heitz et al.: fixed)
    // Second stage (microfacet lobes): refine the L3 fit on the error of the integrals over a
    // fixed set of square lights (see ltc.md, "Polygon refinement"). 0 = off (L3 fit only);
    // otherwise the side of the sample grid of the reference integrals.
    int polygonSamples = 256;
    double polygonFloor = 0.1;  // relative error denominator: integral + floor x albedo
    double peakWeight = 30.0;   // weight of the squares centred on the lobe (mirror / average)
    // --fast (issue 19, measured in ltc.md; not what the committed tables were fitted with):
    // the reference integrals from the moments' momentSamples^2 samples instead of their own,
    // and, where the refinement follows, an L3 fit from refinedL3Samples^2 samples and at most
    // refinedL3Iterations iterations (it only starts the refinement).
    bool fast = false;
    int refinedL3Samples = 16;
    int refinedL3Iterations = 100;
    double horizonWeight = 0.0;
    double horizonFloor = 0.1;
    bool horizonAlbedoFloor = false;
    // No polygon refinement below this perceptual roughness: the squares cannot resolve
    // lobes that narrow, and the refinement blew the smoothest columns up (engine spikes of
    // 1e6 on clear coats and roughness-0 spheres of disney_grid); the L3 fit stays there.
    double polygonMinRoughness = 0.1;
    int firstRow = 0;           // development: fit only rows >= firstRow (and the last column)
};

// One fitted cell.
struct Cell {
    double roughness = 1;      // perceptual roughness of the cell
    double m11 = 1, m22 = 1, m13 = 0;
    double rotation = 0;       // angle of the frame's Z from the lobe's average direction
    glm::dvec3 avgDir{0, 0, 1};
    glm::dmat3 invM{1.0};      // M^-1 normalised by its middle element
    double albedo = 0;         // integral of f NoL (F = 1), the directional albedo
    double norm = 0;           // albedo / (the LTC's mass above the horizon)
    double fresnel = 0;        // integral of f NoL (1 - VoH)^5
    double f82 = 0;            // integral of f NoL VoH (1 - VoH)^6
    double error = 0;          // integral of |f NoL - norm D_ltc| / norm  (relative L1)
    double polygonError = 0;   // RMS relative error over the refinement's square lights (0 if off)
};

struct Table {
    Lobe lobe;
    int size;
    std::vector<Cell> cells; // row-major: cells[row * size + col], row = view, col = roughness
    double seconds = 0;      // wall time from the start of the fit to this lobe's last row
    double cpuSeconds = 0;   // CPU time spent on this lobe's cells (all threads)
};

// The cell parameters: column i <-> perceptual roughness i / (size - 1), row j <->
// sqrt(1 - NoV) = j / (size - 1); NoV is clamped below at kMinNoV.
constexpr double kMinNoV = 1e-3;
double cell_roughness(int col, int size);
double cell_nov(int row, int size);

// The fit of one cell at exactly (perceptual roughness r, NoV), as the table's row
// continuation from r = 1 would reach it (for measuring the table's interpolation error).
Cell fit_exact(Lobe lobe, double r, double nov, const FitSettings &s);

// Fits one lobe. progress(done rows, total rows) is called from worker threads (serialised).
Table fit_table(Lobe lobe, const FitSettings &s, const std::function<void(int, int)> &progress);
// Fits several lobes at once on one pool of s.threads threads (each lobe's serial first column
// overlaps the other lobes' work); the same tables as fit_table one lobe at a time.
// progress(done rows, total rows of all lobes).
std::vector<Table> fit_tables(const std::vector<Lobe> &lobes, const FitSettings &s,
                              const std::function<void(int, int)> &progress);

// The horizon-clipped sphere form factor table (ltc2.w): column i <-> z = 2 i / (size-1) - 1
// (cosine of the elevation of the sphere's centre), row j <-> |F| = j / (size - 1) (= sin^2
// of its angular radius); value = clipped form factor / |F| (max(z, 0) at |F| = 0).
std::vector<float> sphere_table(int size);
// The clipped form factor of a sphere (cap) of angular radius sigma whose centre is at angle
// omega from the normal: (1/pi) * integral over the cap above the horizon of cos(theta).
double clipped_cap_form_factor(double omega, double sigma);

// The statistics (error_stats.hpp) of a table's per-cell errors.
ErrorStats error_stats(const Table &t);

// Writers (return false and fill err on failure).
// fopen(path, "w"); nullptr, and err set, when it fails.
FILE *open_for_writing(const std::string &path, std::string &err);
// The packed arrays (pack_ltc1 / pack_ltc2) of the three lobes, as written to the header.
struct PackedTables {
    std::vector<float> ggx1, ggx2, beckmann1, beckmann2, diffuse1, diffuse2;
};
PackedTables pack_tables(const Table &ggx, const Table &beckmann, const Table &diffuse,
                         const std::vector<float> &sphere);
bool write_header(const std::string &path, int size, const PackedTables &t, const std::string &quality,
                  std::string &err);
// Reads the arrays (and the quality line) of an existing rtpbr_ltc_tables.h written by
// write_header: floats printed with 9 significant digits read back to the same floats, so
// rewriting them gives the same bytes.
bool read_header(const std::string &path, int size, PackedTables &t, std::string &quality, std::string &err);
// One array `name` (size x size x 4 floats) of a generated header's text (read from path).
bool read_header_array(const std::string &text, const std::string &path, const char *name, int size,
                       std::vector<float> &out, std::string &err);
bool write_exr(const std::string &path, int size, const std::vector<float> &rgba, std::string &err);
// One panel per table, side by side.
bool write_error_png(const std::string &path, const std::vector<const Table *> &tables, std::string &err);

// Packs a table as the two RGBA float images of the contract (ltc1, ltc2).
std::vector<float> pack_ltc1(const Table &t);
std::vector<float> pack_ltc2(const Table &t, const std::vector<float> &sphere);

// The sheen lobe alone (rtpbr-ltcfit --sheen-only): fits it, writes DIR/rtpbr_ltc_sheen_tables.h
// (arrays rtpbr_ltc_sheen_1/_2), DIR/ltc_sheen_{1,2}.exr, DIR/ltc_fit_error_sheen.png and the
// generated section of DIR/sheen.md. Returns the process exit code.
int run_sheen(const std::string &outDir, const FitSettings &s, bool quick);
int run_sheen_undivide(const std::string &outDir, int size);

} // namespace ltcfit
