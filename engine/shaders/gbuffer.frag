#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass: writes the material parameters the lighting pass needs.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/material.h"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_GBUFFER_FRAME
#include "frame.glsl"

#include "draw.glsl"

#include "material.glsl"
layout(set = 0, binding = RTPBR_BINDING_GBUFFER_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};

#include "fragment_material.glsl"

layout(location = 0) out vec4 out_gbuffer0; // base colour rgb, metallic
layout(location = 1) out vec4 out_gbuffer1; // world normal xyz, perceptual roughness
layout(location = 2) out vec4 out_gbuffer2; // emitted radiance rgb, material index
layout(location = 3) out vec4 out_gbuffer3; // anisotropy direction (world, unit; zero: none)

void main()
{
    Material m = materials[draw.material];
    FragmentMaterial f = fragment_material(m); // samples every texture first
    // glTF alphaMode MASK: cut out where the coverage is below the cutoff. (BLEND materials are
    // not drawn here: the forward pass shades them.)
    if ((m.flags & RTPBR_MATERIAL_FLAG_ALPHA_MASK) != 0u && f.alpha < m.alpha_cutoff) discard;
    out_gbuffer0 = vec4(f.baseColor, f.metallic);
    out_gbuffer1 = vec4(f.normal, f.roughness);
    out_gbuffer2 = vec4(f.emission, float(draw.material)); // exact: RTPBR_MAX_MATERIALS < 2^24
    out_gbuffer3 = vec4(f.anisotropyDirection, 0.0);
}
