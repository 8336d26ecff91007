// rtpbr shader library: the G-buffer contract (version RTPBR_GBUFFER_VERSION) between a
// geometry pass and rtpbr's lighting passes. A fragment shader (the engine's gbuffer.frag, or a
// host's own GLSL or HLSL one) fills a GBufferSurface with what it knows at the point and
// writes GBuffer_Encode's targets; the lighting passes read the targets back through
// GBuffer_Decode (or its per-target parts), then combine the point's values with the
// material's record (the non-texture KHR and Disney factors, indexed by materialIndex) exactly
// as for rtpbr's own scenes. Every material the engine shades goes through it: glTF
// metallic-roughness with KHR_materials_ior/_specular/_clearcoat/_sheen/_anisotropy, and Disney
// (whose parameters other than base colour, metallic and roughness are per material).
//
// The layout (docs/gbuffer.md has the same table and the test, tests/shaderlib/gbuffer):
//   target  Vulkan format               channels                                  bound |decoded - input|
//   g0      R8G8B8A8_UNORM              base colour rgb (linear), metallic a      0.5/255 (UNORM8)
//   g1      R16G16B16A16_SFLOAT         world normal xyz, perceptual roughness a  normal: 1e-3 (after
//                                                                                 normalising both);
//                                                                                 roughness 2^-12 (FP16)
//   g2      R32G32B32A32_SFLOAT         emitted radiance rgb, material index a    exact (FP32; the index
//                                                                                 exact below 2^24)
//   g3      R16G16B16A16_SFLOAT         anisotropy direction xyz (world), 0       2^-11 per component
//   g4      R8G8B8A8_SRGB               KHR_materials_specular texels:            rgb 4.5e-3 (sRGB8),
//                                       specular colour rgb, specular a           a 0.5/255
//   g5      R8G8B8A8_SRGB               KHR_materials_sheen texels:               rgb 4.5e-3 (sRGB8),
//                                       sheen colour rgb, sheen roughness a       a 0.5/255
//   g6      R8G8_UNORM                  KHR_materials_clearcoat texels:           0.5/255
//                                       clearcoat r, clearcoat roughness g
// plus a depth buffer (the lighting passes reconstruct the position from it).
// The bounds hold for inputs in each field's range, after Encode's sanitising (below), with
// round-to-nearest conversions (FP16, UNORM, and sRGB encoding of the linear value); an
// implementation's own conversion tolerance comes on top (Vulkan leaves the sRGB one open).
//
// The field ranges and what Encode does outside them (so that no input gives a NaN or an
// infinity to the lighting pass; in range, Encode writes its input unchanged):
//   baseColor, metallic, roughness, the extension texels: [0, 1]; NaN and negatives -> 0,
//       above 1 -> 1 (the material resolve, material.h, reads roughness 0 as its floor)
//   normal: any length in (1e-15, 1e19) (the lighting pass normalises): lengths in (0.5, 2]
//       are stored as given, others normalised; NaN, infinite, zero or outside -> (0, 0, 1)
//   emission: [0, FLT_MAX]; NaN and negatives -> 0, +infinity -> FLT_MAX
//   materialIndex: [0, 2^24) (stored as an FP32 integer); the record the lighting pass reads
//       is the host's (an index past its material count is the host's error)
//   anisotropyDirection: unit, or 0 for none (the lighting pass treats lengths below 0.5 as
//       none, surface.h); lengths up to 2 stored as given, longer ones normalised; NaN or
//       infinite -> 0
//   specular, sheen, coat: the extension textures' values, multipliers of the material
//       record's KHR factors; 1 where the material has no such texture. g4 is read only in
//       frames whose scene has specular textures, g5 and g6 only with sheen or clear-coat
//       textures (the engine's RTPBR_EXTENSION_TEXTURES_* flags); otherwise they may be unbound.
//
// Version history: 1 — the layout above (the engine's layout before it became a contract).
#ifndef RTPBR_GBUFFER_H
#define RTPBR_GBUFFER_H

#include "lang.h"

// The layout's version: a host that writes the targets itself checks it at compile time.
#define RTPBR_GBUFFER_VERSION 1
// RTPBR_GBUFFER_TRUSTED 1: the caller guarantees every field in its range (above), and Encode
// writes the fields as given, without the clean-up (about 100 instructions per fragment on
// RDNA2). The engine's G-buffer pass sets it: its values come from validated materials and
// fragment_material.glsl. Default 0: a host's own shader gets the clean-up.
#ifndef RTPBR_GBUFFER_TRUSTED
#define RTPBR_GBUFFER_TRUSTED 0
#endif

RTPBR_NAMESPACE_BEGIN

// The targets' Vulkan formats (VkFormat values) and their count.
RTPBR_CONST uint RTPBR_GBUFFER_TARGET_COUNT = 7u;
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G0 = 37u;  // VK_FORMAT_R8G8B8A8_UNORM
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G1 = 97u;  // VK_FORMAT_R16G16B16A16_SFLOAT
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G2 = 109u; // VK_FORMAT_R32G32B32A32_SFLOAT
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G3 = 97u;  // VK_FORMAT_R16G16B16A16_SFLOAT
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G4 = 43u;  // VK_FORMAT_R8G8B8A8_SRGB
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G5 = 43u;  // VK_FORMAT_R8G8B8A8_SRGB
RTPBR_CONST uint RTPBR_GBUFFER_FORMAT_G6 = 16u;  // VK_FORMAT_R8G8_UNORM

// The stated bounds of |decoded - input| (the table above), for tests and hosts.
RTPBR_CONST float RTPBR_GBUFFER_UNORM8_ERROR = 0.5f / 255.0f; // base colour, metallic, texels
RTPBR_CONST float RTPBR_GBUFFER_SRGB8_ERROR = 4.5e-3f;        // sRGB colours (largest near 1)
RTPBR_CONST float RTPBR_GBUFFER_ROUGHNESS_ERROR = 1.0f / 4096.0f;  // FP16 on [0, 1]
RTPBR_CONST float RTPBR_GBUFFER_NORMAL_ERROR = 1e-3f;              // unit vectors, Euclidean
RTPBR_CONST float RTPBR_GBUFFER_ANISOTROPY_ERROR = 1.0f / 2048.0f; // FP16, per component
// The material index is stored exactly below this.
RTPBR_CONST uint RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT = 16777216u;

// What a fragment shader knows at a point, and what the lighting pass reads back.
struct GBufferSurface {
    rtpbr_float3 baseColor;           // linear RGB, textures applied
    float metallic;
    rtpbr_float3 normal;              // shading normal (world), facing the camera
    float roughness;                  // perceptual
    rtpbr_float3 emission;            // emitted radiance, textures and strength applied
    uint materialIndex;               // the material record the lighting pass reads
    rtpbr_float3 anisotropyDirection; // world, unit, or 0 for none
    rtpbr_float4 specular;            // KHR_materials_specular texels: colour rgb, specular a
    rtpbr_float4 sheen;               // KHR_materials_sheen texels: colour rgb, roughness a
    rtpbr_float2 coat;                // KHR_materials_clearcoat texels: clearcoat, roughness
};

// The values of the targets g0 to g6 (the fragment shader's outputs 0 to 6).
struct GBufferTargets {
    rtpbr_float4 g0;
    rtpbr_float4 g1;
    rtpbr_float4 g2;
    rtpbr_float4 g3;
    rtpbr_float4 g4;
    rtpbr_float4 g5;
    rtpbr_float2 g6;
};

// A surface without extension textures or anisotropy (the defaults of those fields).
RTPBR_FN GBufferSurface GBuffer_DefaultSurface() {
    GBufferSurface s;
    s.baseColor = RTPBR_F3(1.0f);
    s.metallic = 1.0f;
    s.normal = rtpbr_float3(0.0f, 0.0f, 1.0f);
    s.roughness = 1.0f;
    s.emission = RTPBR_F3(0.0f);
    s.materialIndex = 0u;
    s.anisotropyDirection = RTPBR_F3(0.0f);
    s.specular = RTPBR_F4(1.0f);
    s.sheen = RTPBR_F4(1.0f);
    s.coat = RTPBR_F2(1.0f);
    return s;
}

// NaN-safe clamps: NaN and negatives give 0 (the identity with RTPBR_GBUFFER_TRUSTED).
#if RTPBR_GBUFFER_TRUSTED
RTPBR_FN float GBuffer_Unit(float x) { return x; }
#else
RTPBR_FN float GBuffer_Unit(float x) { return x > 0.0f ? min(x, 1.0f) : 0.0f; }
#endif
RTPBR_FN rtpbr_float3 GBuffer_Unit3(rtpbr_float3 v) {
    return rtpbr_float3(GBuffer_Unit(v.x), GBuffer_Unit(v.y), GBuffer_Unit(v.z));
}
RTPBR_FN rtpbr_float4 GBuffer_Unit4(rtpbr_float4 v) {
    return rtpbr_float4(GBuffer_Unit(v.x), GBuffer_Unit(v.y), GBuffer_Unit(v.z), GBuffer_Unit(v.w));
}
#if RTPBR_GBUFFER_TRUSTED
RTPBR_FN float GBuffer_Finite(float x) { return x; }
#else
RTPBR_FN float GBuffer_Finite(float x) { return x > 0.0f ? min(x, RTPBR_FLT_MAX) : 0.0f; }
#endif

// A direction kept as given when its squared length lies in (lo, 4], else normalised when
// finite and not tiny, else fallback (the comparisons are false for NaN).
#if RTPBR_GBUFFER_TRUSTED
RTPBR_FN rtpbr_float3 GBuffer_Direction(rtpbr_float3 v, float lo, rtpbr_float3 fallback) {
    RTPBR_UNUSED(lo);
    RTPBR_UNUSED(fallback);
    return v;
}
#else
RTPBR_FN rtpbr_float3 GBuffer_Direction(rtpbr_float3 v, float lo, rtpbr_float3 fallback) {
    float d = dot(v, v);
    if (d > lo && d <= 4.0f) return v;
    return (d > 1e-30f && d <= RTPBR_FLT_MAX) ? v * rtpbr_rsqrt(d) : fallback;
}
#endif

// The per-target encoders (a fragment shader that writes some targets under conditions of its
// own calls these; GBuffer_Encode writes all).
RTPBR_FN rtpbr_float4 GBuffer_EncodeG0(GBufferSurface s) {
    return rtpbr_float4(GBuffer_Unit3(s.baseColor), GBuffer_Unit(s.metallic));
}
RTPBR_FN rtpbr_float4 GBuffer_EncodeG1(GBufferSurface s) {
    return rtpbr_float4(GBuffer_Direction(s.normal, 0.25f, rtpbr_float3(0.0f, 0.0f, 1.0f)),
                        GBuffer_Unit(s.roughness));
}
RTPBR_FN rtpbr_float4 GBuffer_EncodeG2(GBufferSurface s) {
    // exact: materialIndex < RTPBR_GBUFFER_MATERIAL_INDEX_LIMIT
    return rtpbr_float4(GBuffer_Finite(s.emission.x), GBuffer_Finite(s.emission.y),
                        GBuffer_Finite(s.emission.z), float(s.materialIndex));
}
RTPBR_FN rtpbr_float4 GBuffer_EncodeG3(GBufferSurface s) {
    return rtpbr_float4(GBuffer_Direction(s.anisotropyDirection, -1.0f, RTPBR_F3(0.0f)), 0.0f);
}
RTPBR_FN rtpbr_float4 GBuffer_EncodeG4(GBufferSurface s) { return GBuffer_Unit4(s.specular); }
RTPBR_FN rtpbr_float4 GBuffer_EncodeG5(GBufferSurface s) { return GBuffer_Unit4(s.sheen); }
RTPBR_FN rtpbr_float2 GBuffer_EncodeG6(GBufferSurface s) {
    return rtpbr_float2(GBuffer_Unit(s.coat.x), GBuffer_Unit(s.coat.y));
}

RTPBR_FN GBufferTargets GBuffer_Encode(GBufferSurface s) {
    GBufferTargets t;
    t.g0 = GBuffer_EncodeG0(s);
    t.g1 = GBuffer_EncodeG1(s);
    t.g2 = GBuffer_EncodeG2(s);
    t.g3 = GBuffer_EncodeG3(s);
    t.g4 = GBuffer_EncodeG4(s);
    t.g5 = GBuffer_EncodeG5(s);
    t.g6 = GBuffer_EncodeG6(s);
    return t;
}

// The per-target decoders (a lighting pass that reads some targets only under conditions of
// its own calls these; GBuffer_Decode reads all).
RTPBR_FN rtpbr_float3 GBuffer_DecodeEmission(rtpbr_float4 g2) { return rtpbr_float3(g2.x, g2.y, g2.z); }
RTPBR_FN uint GBuffer_DecodeMaterialIndex(rtpbr_float4 g2) { return uint(g2.w); }
RTPBR_FN rtpbr_float3 GBuffer_DecodeNormal(rtpbr_float4 g1) { return normalize(rtpbr_float3(g1.x, g1.y, g1.z)); }
RTPBR_FN rtpbr_float3 GBuffer_DecodeAnisotropy(rtpbr_float4 g3) { return rtpbr_float3(g3.x, g3.y, g3.z); }

// g0 to g2: everything but the anisotropy direction and the extension texels, which are left
// at their defaults (none, 1).
RTPBR_FN GBufferSurface GBuffer_DecodeBase(rtpbr_float4 g0, rtpbr_float4 g1, rtpbr_float4 g2) {
    GBufferSurface s = GBuffer_DefaultSurface();
    s.baseColor = rtpbr_float3(g0.x, g0.y, g0.z);
    s.metallic = g0.w;
    s.normal = GBuffer_DecodeNormal(g1);
    s.roughness = g1.w;
    s.emission = GBuffer_DecodeEmission(g2);
    s.materialIndex = GBuffer_DecodeMaterialIndex(g2);
    return s;
}

RTPBR_FN GBufferSurface GBuffer_Decode(GBufferTargets t) {
    GBufferSurface s = GBuffer_DecodeBase(t.g0, t.g1, t.g2);
    s.anisotropyDirection = GBuffer_DecodeAnisotropy(t.g3);
    s.specular = t.g4;
    s.sheen = t.g5;
    s.coat = t.g6;
    return s;
}

RTPBR_NAMESPACE_END

#endif
