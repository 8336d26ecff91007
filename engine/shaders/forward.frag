#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Forward pass of glTF alphaMode BLEND surfaces (engine/src/passes/forward.c): drawn after the
// lighting pass, back to front, over the lit radiance image, depth-tested against the
// G-buffer's depth without writing it. A fragment is shaded as the lighting pass shades a
// G-buffer pixel, by the same code (fragment_material.glsl for the material, shading.glsl's
// surface_terms and shade_lights.glsl's per-light loop), over every light of the frame (the
// tile masks were culled against the opaque surfaces) and without shadows, and written
// premultiplied: (radiance x alpha, alpha), blended as src + dst (1 - src alpha).
// One variant per RTPBR_NDF x RTPBR_MULTISCATTER (engine/shaders/meson.build), all materials.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "material.glsl"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"
#include "draw.glsl"

#define RTPBR_LIGHTING_FULL 1
#define RTPBR_SHADE_ALL_LIGHTS 1
#ifndef RTPBR_LIGHTING_SPHERES
#define RTPBR_LIGHTING_SPHERES 0 // 1: the variant that shades sphere lights
#endif
#include "shading.glsl"
#include "fragment_material.glsl"

// BLEND surfaces are not shadowed (the shadow ratios are per G-buffer pixel).
float shadow_factor(uint light, ivec2 pixel)
{
    return 1.0f;
}
#include "shade_lights.glsl"

layout(location = 0) out vec4 out_radiance;

void main()
{
    Material m = materials[draw.material];
    FragmentMaterial f = fragment_material(m); // samples every texture first
    // the extension textures' own values, in the same uniform control flow (the G-buffer pass
    // writes the same into G-buffers 4 to 6 for the lighting passes)
    GBufferSurface g = GBuffer_DefaultSurface();
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_SPECULAR) != 0u)
        g.specular = vec4(texture(specular_color_texture, in_uv_specular.zw).rgb, texture(specular_texture, in_uv_specular.xy).a);
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_COAT_SHEEN) != 0u) {
        g.sheen = vec4(texture(sheen_color_texture, in_uv_sheen.xy).rgb, texture(sheen_roughness_texture, in_uv_sheen.zw).a);
        g.coat = vec2(texture(clearcoat_texture, in_uv_clearcoat.xy).r, texture(clearcoat_roughness_texture, in_uv_clearcoat.zw).g);
    }
    vec3 P = in_world;
    vec3 V = normalize(frame.camera_position.xyz - P);
    vec3 N = f.normal;
    // the point's values as the G-buffer pass would encode them (unquantised: nothing is stored)
    g.baseColor = f.baseColor;
    g.metallic = f.metallic;
    g.roughness = f.roughness;
    g.anisotropyDirection = f.anisotropyDirection;
    ShadingSurface s = surface_terms(g, m, rtpbr_saturate(dot(N, V)));
    vec3 radiance = f.emission;
    shade_lights(P, N, V, s, 0u, ivec2(0), radiance);
    float alpha = rtpbr_saturate(f.alpha);
    out_radiance = vec4(radiance * alpha, alpha);
}
