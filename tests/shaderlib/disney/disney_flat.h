// A Disney material as the 13 floats it crosses the boundary of the separately compiled
// variants with (disney_variants.cpp) and is stored as in the tests' tables:
// {r, g, b, metallic, subsurface, specular, specularTint, roughness, anisotropic, sheen,
// sheenTint, clearcoat, clearcoatGloss}. Include after <rtpbr/disney.h>: each file's own
// (variant) DisneyMaterial is the one meant.
#pragma once

namespace {

[[maybe_unused]] void flatten(const rtpbr::DisneyMaterial &m, float *p) {
    p[0] = m.baseColor.x;
    p[1] = m.baseColor.y;
    p[2] = m.baseColor.z;
    p[3] = m.metallic;
    p[4] = m.subsurface;
    p[5] = m.specular;
    p[6] = m.specularTint;
    p[7] = m.roughness;
    p[8] = m.anisotropic;
    p[9] = m.sheen;
    p[10] = m.sheenTint;
    p[11] = m.clearcoat;
    p[12] = m.clearcoatGloss;
}

[[maybe_unused]] rtpbr::DisneyMaterial unflatten(const float *p) {
    rtpbr::DisneyMaterial m;
    m.baseColor = rtpbr::float3(p[0], p[1], p[2]);
    m.metallic = p[3];
    m.subsurface = p[4];
    m.specular = p[5];
    m.specularTint = p[6];
    m.roughness = p[7];
    m.anisotropic = p[8];
    m.sheen = p[9];
    m.sheenTint = p[10];
    m.clearcoat = p[11];
    m.clearcoatGloss = p[12];
    return m;
}

} // namespace
