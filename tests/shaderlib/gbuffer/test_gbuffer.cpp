// Precision of the G-buffer contract (shaderlib/rtpbr/gbuffer.h; suite 'unit'): every field of
// a GBufferSurface goes through GBuffer_Encode, the quantisation of its target's Vulkan format
// (UNORM8: round(x 255) / 255; sRGB8: the sRGB encoding rounded to 8 bits, decoded; FP16:
// round to nearest even half; FP32: as is), and GBuffer_Decode, on random and hostile inputs
// (0, 1, negative, > 1, NaN, infinities, denormals, unnormalised normals). Each decoded field
// must lie within the header's stated bound of the input (the input as Encode's range rules
// read it), and no input may give a NaN or an infinity. The quantisers propagate NaN, so a NaN
// that Encode let through would fail here (the formats' own NaN rules are not relied on).
// In range, Encode must write its input unchanged (the engine's images did not move when its
// G-buffer pass started calling it).
#include <cstdarg>
#include <cstddef>
#include <csetjmp>
#include <cstdint>

extern "C" {
#include "test_main.h"
}

#include <rtpbr/gbuffer.h>

#if defined(RTPBR_TEST_HAVE_VULKAN)
#include <vulkan/vulkan.h>
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G0 == VK_FORMAT_R8G8B8A8_UNORM, "g0 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G1 == VK_FORMAT_R16G16B16A16_SFLOAT, "g1 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G2 == VK_FORMAT_R32G32B32A32_SFLOAT, "g2 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G3 == VK_FORMAT_R16G16B16A16_SFLOAT, "g3 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G4 == VK_FORMAT_R8G8B8A8_SRGB, "g4 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G5 == VK_FORMAT_R8G8B8A8_SRGB, "g5 format");
static_assert(rtpbr::RTPBR_GBUFFER_FORMAT_G6 == VK_FORMAT_R8G8_UNORM, "g6 format");
#endif
static_assert(RTPBR_GBUFFER_VERSION == 1, "the layout this test states");

#include <cmath>
#include <limits>
#include <random>

using namespace rtpbr;

// Scales every stated bound (1: the header's). A value below 1 must make the test fail.
#ifndef RTPBR_TEST_GBUFFER_BOUND_SCALE
#define RTPBR_TEST_GBUFFER_BOUND_SCALE 1.0
#endif

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// --- the formats' quantisation ---------------------------------------------------------------

float q_unorm8(float x) {
    if (std::isnan(x)) return x;
    double c = std::fmin(std::fmax(double(x), 0.0), 1.0);
    return float(std::nearbyint(c * 255.0) / 255.0);
}

double srgb_to_linear(double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double l) { return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

float q_srgb8(float x) {
    if (std::isnan(x)) return x;
    double c = std::fmin(std::fmax(double(x), 0.0), 1.0);
    return float(srgb_to_linear(std::nearbyint(linear_to_srgb(c) * 255.0) / 255.0));
}

// Round to the nearest binary16 (ties to even), overflow to infinity.
float q_half(float x) {
    if (std::isnan(x) || std::isinf(x)) return x;
    double a = std::fabs(double(x));
    double q;
    if (a >= 65520.0) {
        q = double(kInf);
    } else if (a < std::ldexp(1.0, -14)) {
        q = std::nearbyint(a / std::ldexp(1.0, -24)) * std::ldexp(1.0, -24);
    } else {
        int e;
        std::frexp(a, &e); // a in [2^(e-1), 2^e): ulp 2^(e-11)
        double ulp = std::ldexp(1.0, e - 11);
        q = std::nearbyint(a / ulp) * ulp;
    }
    return float(std::signbit(x) ? -q : q);
}

float4 q_unorm8(float4 v) { return float4(q_unorm8(v.x), q_unorm8(v.y), q_unorm8(v.z), q_unorm8(v.w)); }
float4 q_srgb8_alpha(float4 v) { return float4(q_srgb8(v.x), q_srgb8(v.y), q_srgb8(v.z), q_unorm8(v.w)); }
float4 q_half(float4 v) { return float4(q_half(v.x), q_half(v.y), q_half(v.z), q_half(v.w)); }

GBufferTargets quantise(GBufferTargets t) {
    GBufferTargets q;
    q.g0 = q_unorm8(t.g0);
    q.g1 = q_half(t.g1);
    q.g2 = t.g2;
    q.g3 = q_half(t.g3);
    q.g4 = q_srgb8_alpha(t.g4);
    q.g5 = q_srgb8_alpha(t.g5);
    q.g6 = float2(q_unorm8(t.g6.x), q_unorm8(t.g6.y));
    return q;
}

// --- the inputs as Encode's range rules read them ----------------------------------------------

double unit(float x) { return x > 0.0f ? std::fmin(double(x), 1.0) : 0.0; }

// The expected direction (double), or the fallback.
void direction(float3 v, double lo2, bool normalise_in_range, const double fallback[3], double out[3]) {
    double x = v.x, y = v.y, z = v.z;
    double d = x * x + y * y + z * z;
    float df = v.x * v.x + v.y * v.y + v.z * v.z; // what the float encoder sees
    bool finite = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
    if (finite && df > float(lo2) && df <= 4.0f) {
        double s = normalise_in_range ? 1.0 / std::sqrt(d) : 1.0;
        out[0] = x * s, out[1] = y * s, out[2] = z * s;
    } else if (finite && df > 1e-30f && df <= std::numeric_limits<float>::max()) {
        double s = 1.0 / std::sqrt(d);
        out[0] = x * s, out[1] = y * s, out[2] = z * s;
    } else {
        out[0] = fallback[0], out[1] = fallback[1], out[2] = fallback[2];
    }
}

struct Worst {
    double err[16] = {};
};

enum Field { BASE, METALLIC, NORMAL, ROUGHNESS, EMISSION, INDEX, ANISO, SPEC_RGB, SPEC_A, SHEEN_RGB, SHEEN_A, COAT, FIELDS };
const char *const kFieldNames[FIELDS] = {"baseColor", "metallic", "normal", "roughness", "emission", "materialIndex",
                                         "anisotropyDirection", "specular rgb", "specular a", "sheen rgb", "sheen a", "coat"};
double bound(Field f) {
    double b = 0.0;
    switch (f) {
    case BASE: case METALLIC: case SPEC_A: case SHEEN_A: case COAT: b = RTPBR_GBUFFER_UNORM8_ERROR; break;
    case SPEC_RGB: case SHEEN_RGB: b = RTPBR_GBUFFER_SRGB8_ERROR; break;
    case ROUGHNESS: b = RTPBR_GBUFFER_ROUGHNESS_ERROR; break;
    case NORMAL: b = RTPBR_GBUFFER_NORMAL_ERROR; break;
    case ANISO: b = RTPBR_GBUFFER_ANISOTROPY_ERROR; break;
    case EMISSION: case INDEX: b = 0.0; break; // exact
    default: break;
    }
    // float rounding of the decoded value on top of the format's (relative 2^-24 of values <= 2)
    return b * RTPBR_TEST_GBUFFER_BOUND_SCALE + (b > 0.0 ? 2.5e-7 : 0.0);
}

void expect(Field f, double got, double want, Worst &w, const char *what, int i) {
    double e = std::fabs(got - want);
    if (!std::isfinite(got)) fail_msg("%s (%s, case %d): decoded %g is not finite", kFieldNames[f], what, i, got);
    if (!(e <= bound(f)))
        fail_msg("%s (%s, case %d): decoded %.9g, input %.9g: error %.3g over the bound %.3g", kFieldNames[f], what,
                 i, got, want, e, bound(f));
    if (e > w.err[f]) w.err[f] = e;
}

// One round trip, every field checked.
void round_trip(const GBufferSurface &in, Worst &w, const char *what, int i) {
    GBufferSurface out = GBuffer_Decode(quantise(GBuffer_Encode(in)));
    for (int c = 0; c < 3; ++c) expect(BASE, out.baseColor[c], unit(in.baseColor[c]), w, what, i);
    expect(METALLIC, out.metallic, unit(in.metallic), w, what, i);
    expect(ROUGHNESS, out.roughness, unit(in.roughness), w, what, i);
    for (int c = 0; c < 3; ++c) {
        float e = in.emission[c];
        expect(EMISSION, out.emission[c], e > 0.0f ? std::fmin(double(e), double(std::numeric_limits<float>::max())) : 0.0,
               w, what, i);
    }
    if (in.materialIndex < RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT)
        expect(INDEX, double(out.materialIndex), double(in.materialIndex), w, what, i);
    const double up[3] = {0.0, 0.0, 1.0}, zero[3] = {0.0, 0.0, 0.0};
    double n[3], a[3];
    direction(in.normal, 0.25, true, up, n);
    double nerr = 0.0;
    for (int c = 0; c < 3; ++c) nerr += (out.normal[c] - n[c]) * (out.normal[c] - n[c]);
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(out.normal[c])) fail_msg("normal (%s, case %d): not finite", what, i);
    expect(NORMAL, n[0] + std::sqrt(nerr), n[0], w, what, i);
    direction(in.anisotropyDirection, -1.0, false, zero, a);
    for (int c = 0; c < 3; ++c) expect(ANISO, out.anisotropyDirection[c], a[c], w, what, i);
    for (int c = 0; c < 3; ++c) expect(SPEC_RGB, out.specular[c], unit(in.specular[c]), w, what, i);
    expect(SPEC_A, out.specular.w, unit(in.specular.w), w, what, i);
    for (int c = 0; c < 3; ++c) expect(SHEEN_RGB, out.sheen[c], unit(in.sheen[c]), w, what, i);
    expect(SHEEN_A, out.sheen.w, unit(in.sheen.w), w, what, i);
    for (int c = 0; c < 2; ++c) expect(COAT, out.coat[c], unit(in.coat[c]), w, what, i);
}

const float kHostile[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, 1.0f - 1e-7f, 1e-40f, -1e-40f, 1e-8f, 0.5f,
                          65504.0f, 1e5f, 1e30f, -1e30f, std::numeric_limits<float>::max(), kInf, -kInf, kNaN};

float pick(std::mt19937 &rng, float lo, float hi, double hostile_share) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (u(rng) < hostile_share)
        return kHostile[std::uniform_int_distribution<int>(0, int(sizeof kHostile / sizeof kHostile[0]) - 1)(rng)];
    return float(lo + (hi - lo) * u(rng));
}

float3 random_direction(std::mt19937 &rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    double x = g(rng), y = g(rng), z = g(rng), l = std::sqrt(x * x + y * y + z * z);
    return float3(float(x / l), float(y / l), float(z / l));
}

GBufferSurface random_surface(std::mt19937 &rng, double hostile) {
    GBufferSurface s;
    s.baseColor = float3(pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile));
    s.metallic = pick(rng, 0, 1, hostile);
    s.roughness = pick(rng, 0, 1, hostile);
    s.emission = float3(pick(rng, 0, 100, hostile), pick(rng, 0, 1e6f, hostile), pick(rng, 0, 1, hostile));
    s.materialIndex = std::uniform_int_distribution<uint32_t>(0u, RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT - 1u)(rng);
    // unit directions, scaled (unnormalised), or hostile components
    static const float kScales[] = {1.0f, 1.0f, 1.0f, 0.6f, 1.9f, 2.1f, 0.4f, 1e-3f, 1e-12f, 1e3f, 1e15f, 0.0f};
    float3 n = random_direction(rng) * kScales[std::uniform_int_distribution<int>(0, 11)(rng)];
    if (std::uniform_real_distribution<double>(0, 1)(rng) < hostile) n.y = pick(rng, -1, 1, 1.0);
    s.normal = n;
    float3 a = random_direction(rng) * kScales[std::uniform_int_distribution<int>(0, 11)(rng)];
    if (std::uniform_real_distribution<double>(0, 1)(rng) < hostile) a.x = pick(rng, -1, 1, 1.0);
    s.anisotropyDirection = a;
    s.specular = float4(pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile),
                        pick(rng, 0, 1, hostile));
    s.sheen = float4(pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile),
                     pick(rng, 0, 1, hostile));
    s.coat = float2(pick(rng, 0, 1, hostile), pick(rng, 0, 1, hostile));
    return s;
}

void test_random_in_range(void **) {
    std::mt19937 rng(33);
    Worst w;
    for (int i = 0; i < 200000; ++i) round_trip(random_surface(rng, 0.0), w, "in range", i);
    for (int f = 0; f < FIELDS; ++f)
        print_message("%-20s worst %.3g, bound %.3g\n", kFieldNames[f], w.err[f], bound(Field(f)));
}

void test_random_hostile(void **) {
    std::mt19937 rng(34);
    Worst w;
    for (int i = 0; i < 200000; ++i) round_trip(random_surface(rng, 0.3), w, "hostile", i);
}

// Every code of each 8-bit channel and every value of the hostile list in every field.
void test_edges(void **) {
    Worst w;
    int i = 0;
    for (int code = 0; code <= 255; ++code)
        for (float d : {-0.49f, 0.0f, 0.49f}) {
            float x = (float(code) + d) / 255.0f;
            GBufferSurface s = GBuffer_DefaultSurface();
            s.baseColor = float3(x);
            s.metallic = s.roughness = x;
            s.specular = s.sheen = float4(x);
            s.coat = float2(x);
            round_trip(s, w, "codes", i++);
        }
    for (float h : kHostile) {
        GBufferSurface s = GBuffer_DefaultSurface();
        s.baseColor = s.emission = s.normal = s.anisotropyDirection = float3(h);
        s.metallic = s.roughness = h;
        s.specular = s.sheen = float4(h);
        s.coat = float2(h);
        round_trip(s, w, "hostile list", i++);
        s.normal = float3(h, 1.0f, 0.0f);
        s.anisotropyDirection = float3(0.0f, h, 0.0f);
        round_trip(s, w, "hostile list, one component", i++);
    }
    GBufferSurface s = GBuffer_DefaultSurface();
    for (uint32_t index : {0u, 1u, 65535u, RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT - 1u}) {
        s.materialIndex = index;
        round_trip(s, w, "material index", i++);
    }
}

// In range, Encode writes its input unchanged (the engine's G-buffer pass wrote these before
// it called Encode), and Decode of unquantised targets gives it back.
void test_in_range_identity(void **) {
    std::mt19937 rng(35);
    for (int i = 0; i < 10000; ++i) {
        GBufferSurface s = random_surface(rng, 0.0);
        s.normal = random_direction(rng);
        s.anisotropyDirection = i % 4 == 0 ? float3(0.0f) : random_direction(rng);
        GBufferTargets t = GBuffer_Encode(s);
        if (!(t.g0 == float4(s.baseColor, s.metallic) && t.g1 == float4(s.normal, s.roughness) &&
              t.g2 == float4(s.emission, float(s.materialIndex)) && t.g3 == float4(s.anisotropyDirection, 0.0f) &&
              t.g4 == s.specular && t.g5 == s.sheen && t.g6 == s.coat))
            fail_msg("case %d: Encode changed an in-range input", i);
        GBufferSurface d = GBuffer_Decode(t);
        if (!(d.baseColor == s.baseColor && d.metallic == s.metallic && d.roughness == s.roughness &&
              d.emission == s.emission && d.materialIndex == s.materialIndex &&
              d.anisotropyDirection == s.anisotropyDirection && d.specular == s.specular && d.sheen == s.sheen &&
              d.coat == s.coat && glm::length(d.normal - s.normal) < 1e-6f))
            fail_msg("case %d: Decode(Encode(x)) is not x", i);
    }
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_random_in_range),
                cmocka_unit_test(test_random_hostile),
                cmocka_unit_test(test_edges),
                cmocka_unit_test(test_in_range_identity))
