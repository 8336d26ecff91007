// rtpbr-brdfplot: renders the shaderlib's microfacet BRDFs on a grid of spheres (rows: GGX
// conductor, Beckmann conductor, GGX dielectric over a Lambertian base; columns: perceptual
// roughness 0.05 .. 1) lit by one directional light plus a dim uniform sky, and writes a PNG
// with the rows, columns and lighting written in its margins (stb_easy_font's glyphs).
// A quick look at the shader library's C++ build; the engine and the oracle render scenes.
#include <rtpbr/microfacet.h>

#include "rtpbr_common/image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <stb_easy_font.h>

using namespace rtpbr;

namespace {

enum class Row { GgxGold, BeckmannGold, GgxPlastic };
const char *const kRowNames[] = {"GGX\ngold conductor", "Beckmann\ngold conductor", "GGX dielectric\nIOR 1.5 over\nred Lambert"};

float3 shade(Row row, float roughness, float3 n, float3 v, float3 l) {
    float NoV = dot(n, v), NoL = dot(n, l);
    if (NoV <= 0.0f || NoL <= 0.0f)
        return float3(0.0f);
    float3 h = normalize(v + l);
    float NoH = dot(n, h), VoH = dot(v, h);
    float alpha = Alpha_FromPerceptual(roughness);
    // Gold, complex IOR at (650, 550, 450) nm (Johnson & Christy 1972).
    FresnelParams gold = Fresnel_FromConductor(float3(0.143f, 0.374f, 1.442f), float3(3.983f, 2.385f, 1.603f));
    switch (row) {
    case Row::GgxGold:
        return D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha) * F_Conductor(VoH, gold.eta, gold.k) * NoL;
    case Row::BeckmannGold:
        return D_Beckmann(NoH, alpha) * V_SmithBeckmann(NoV, NoL, alpha) * F_Conductor(VoH, gold.eta, gold.k) * NoL;
    case Row::GgxPlastic: {
        float F = F_Dielectric(VoH, 1.5f);
        float3 spec = float3(D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha) * F);
        float3 diffuse = float3(0.8f, 0.1f, 0.1f) * RTPBR_INV_PI * (1.0f - F);
        return (spec + diffuse) * NoL;
    }
    }
    return float3(0.0f);
}

float to_srgb(float x) {
    x = x / (1.0f + x); // Reinhard, to fit highlights
    x = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
    return std::fmin(std::fmax(x, 0.0f), 1.0f);
}

// An RGB8 image that text is written into.
struct Canvas {
    int width, height;
    std::vector<unsigned char> pixels;
    // Draws text (lines split at '\n') with its top left corner at (x, y), each glyph pixel
    // scale x scale image pixels: stb_easy_font's quads filled as rectangles.
    void text(int x, int y, int scale, const std::string &s, unsigned char grey) {
        std::vector<char> str(s.begin(), s.end());
        str.push_back('\0');
        std::vector<float> quads(s.size() * 300); // ~270 bytes per character, 16 per vertex
        int n = stb_easy_font_print(0.0f, 0.0f, str.data(), nullptr, quads.data(), int(quads.size() * sizeof(float)));
        for (int q = 0; q < n; q++) {
            const float *v = &quads[size_t(q) * 16]; // 4 vertices of x, y, z, colour
            int x0 = x + int(std::lround(v[0] * scale)), y0 = y + int(std::lround(v[1] * scale));
            int x1 = x + int(std::lround(v[8] * scale)), y1 = y + int(std::lround(v[9] * scale));
            for (int py = std::max(y0, 0); py < std::min(y1, height); py++)
                for (int px = std::max(x0, 0); px < std::min(x1, width); px++)
                    for (int k = 0; k < 3; k++)
                        pixels[(size_t(py) * width + px) * 3 + k] = grey;
        }
    }
    int text_width(const std::string &s, int scale) {
        std::vector<char> str(s.begin(), s.end());
        str.push_back('\0');
        return stb_easy_font_width(str.data()) * scale;
    }
};

const char *const kUsage =
    "usage: rtpbr-brdfplot [-o OUT.png]\n"
    "Renders the shader library's microfacet BRDFs on a labelled grid of spheres (rows: GGX and\n"
    "Beckmann gold conductors, a GGX dielectric over a red Lambertian base; columns: perceptual\n"
    "roughness 0.05 .. 1) under one directional light and a dim sky, and writes a PNG.\n"
    "  -o OUT.png  the image (default brdf-spheres.png)\n"
    "  -h, --help  this text\n";

} // namespace

int main(int argc, char **argv) {
    std::string out = "brdf-spheres.png";
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-o") && i + 1 < argc) {
            out = argv[++i];
        } else if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
            std::fputs(kUsage, stdout);
            return 0;
        } else {
            std::fputs(kUsage, stderr);
            return 2;
        }
    }
    const int cols = 8, rows = 3, cell = 96;
    // The spheres' grid, with margins for the labels: row names on the left, the title and the
    // roughness of each column above, the lighting below.
    const int left = 176, top = 64, bottom = 40;
    const int W = cols * cell, H = rows * cell;
    Canvas canvas{left + W + 8, top + H + bottom, {}};
    const unsigned char background = (unsigned char)std::lround(255.0f * to_srgb(0.02f));
    canvas.pixels.assign(size_t(canvas.width) * canvas.height * 3, background);
    const float3 v(0.0f, 0.0f, 1.0f);
    const float3 l = normalize(float3(-0.5f, 0.6f, 0.6f));
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            int r = y / cell, c = x / cell;
            float px = ((x % cell) + 0.5f) / cell * 2.0f - 1.0f;
            float py = 1.0f - ((y % cell) + 0.5f) / cell * 2.0f;
            float rr = (px * px + py * py) / 0.81f;
            float3 color(0.02f);
            if (rr < 1.0f) {
                float3 n = normalize(float3(px, py, 0.9f * std::sqrt(1.0f - rr)));
                float roughness = 0.05f + 0.95f * c / (cols - 1);
                color = 3.0f * shade(Row(r), roughness, n, v, l) +
                        0.15f * shade(Row(r), roughness, n, v, normalize(float3(0.0f, 1.0f, 0.3f)));
            }
            for (int k = 0; k < 3; k++)
                canvas.pixels[(size_t(top + y) * canvas.width + left + x) * 3 + k] =
                    (unsigned char)std::lround(255.0f * to_srgb(color[k]));
        }
    }
    const unsigned char ink = 230, dim = 170;
    canvas.text(8, 6, 2, "rtpbr shader library: microfacet BRDFs", ink);
    canvas.text(8, 40, 2, "roughness", dim);
    for (int c = 0; c < cols; c++) {
        char label[16];
        std::snprintf(label, sizeof label, "%.2f", 0.05f + 0.95f * c / (cols - 1));
        canvas.text(left + c * cell + (cell - canvas.text_width(label, 2)) / 2, 40, 2, label, ink);
    }
    for (int r = 0; r < rows; r++) {
        int lines = int(std::count(kRowNames[r], kRowNames[r] + std::strlen(kRowNames[r]), '\n')) + 1;
        canvas.text(8, top + r * cell + (cell - 24 * lines) / 2, 2, kRowNames[r], ink);
    }
    canvas.text(8, top + H + 8, 1, "Perceptual roughness (alpha = r^2). Gold: complex IOR at 650/550/450 nm "
                                   "(Johnson & Christy 1972).", dim);
    canvas.text(8, top + H + 22, 1, "Lit by one directional light from the upper left and a dim light from above; "
                                    "Reinhard tone mapping, sRGB.", dim);
    std::string error;
    if (!rtpbr_tools::write_image_u8(out, canvas.width, canvas.height, 3, canvas.pixels.data(), error)) {
        std::fprintf(stderr, "rtpbr-brdfplot: %s\n", error.c_str());
        return 1;
    }
    return 0;
}
