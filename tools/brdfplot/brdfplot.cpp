// rtpbr-brdfplot: renders the shaderlib's microfacet BRDFs on a grid of spheres (rows: GGX
// conductor, Beckmann conductor, GGX dielectric over a Lambertian base; columns: perceptual
// roughness 0.05 .. 1) lit by one directional light plus a dim uniform sky, and writes a PNG.
// A quick look at the shader library's C++ build; the engine and the oracle render scenes.
#include <rtpbr/microfacet.h>

#include "rtpbr_tools/image.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace rtpbr;

namespace {

enum class Row { GgxGold, BeckmannGold, GgxPlastic };

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

} // namespace

int main(int argc, char **argv) {
    std::string out = "brdf-spheres.png";
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-o") && i + 1 < argc) {
            out = argv[++i];
        } else {
            std::fprintf(stderr, "usage: %s [-o OUT.png]\n", argv[0]);
            return 2;
        }
    }
    const int cols = 8, rows = 3, cell = 96;
    const int W = cols * cell, H = rows * cell;
    std::vector<unsigned char> pixels(size_t(W) * H * 3, 0);
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
                pixels[(size_t(y) * W + x) * 3 + k] = (unsigned char)std::lround(255.0f * to_srgb(color[k]));
        }
    }
    std::string error;
    if (!rtpbr_tools::write_image_u8(out, W, H, 3, pixels.data(), error)) {
        std::fprintf(stderr, "rtpbr-brdfplot: %s\n", error.c_str());
        return 1;
    }
    return 0;
}
