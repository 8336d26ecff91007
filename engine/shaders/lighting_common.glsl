// Shared by the lighting passes (lighting.comp: LTC, lighting_mc.comp: Monte Carlo reference):
// the G-buffer, tile and output bindings of the lighting set, on top of what shading a point
// needs (shading.glsl).
// Include after rtpbr_shared.h, the shader-library headers (fresnel.h, kulla_conty.h,
// disney.h, sheen.h, material.h), material.glsl and frame.glsl.

#include "shading.glsl"

// Per-tile light masks written by the culling pass (cull.comp): bit i of word w of a tile is
// light 32 w + i; per tile (RTPBR_TILE_MASK_STRIDE words, tiles row by row)
// RTPBR_TILE_MASK_WORDS words of its polygonal lights, then as many of its punctual lights,
// then of its spheres, then of its disks, then of its textured quads, then of its tubes; the
// shadow slots; and a summary word per kind (bit w: its word w is not zero; rtpbr_shared.h).
layout(set = 0, binding = RTPBR_BINDING_LIGHT_TILE_MASKS, std430) buffer TileMasks {
    uint tile_masks[];
};
// The culling pass's tile queues, one per tile class (RTPBR_TILE_CLASS_*): each class's
// indirect dispatch arguments (x = the number of tiles queued; RTPBR_TILE_QUEUE_SLOTS of them,
// the last unused), then the classes' tile lists, frame.tile_capacity entries each (tile index
// = tile y * frame.tiles_x + tile x).
layout(set = 0, binding = RTPBR_BINDING_LIGHT_TILE_LISTS, std430) buffer TileLists {
    uvec4 tile_dispatch[RTPBR_TILE_QUEUE_SLOTS]; // xyz: VkDispatchIndirectCommand, w unused
    uint tile_list[];
};

// The tile class a material needs (RTPBR_TILE_CLASS_BASIC or _FULL): the basic lighting
// variant shades metallic-roughness materials without clear coat, sheen or anisotropy.
uint material_tile_class(Material m)
{
    return (m.flags & RTPBR_MATERIAL_FLAGS_FULL) != 0u ? RTPBR_TILE_CLASS_FULL : RTPBR_TILE_CLASS_BASIC;
}

layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER0) uniform sampler2D gbuffer0;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER1) uniform sampler2D gbuffer1;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER2) uniform sampler2D gbuffer2;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER3) uniform sampler2D gbuffer3;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER4) uniform sampler2D gbuffer4;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER5) uniform sampler2D gbuffer5;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER6) uniform sampler2D gbuffer6;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_DEPTH) uniform sampler2D gbuffer_depth;

// A pixel's G-buffer values (gbuffer.h's GBufferSurface; g2 already fetched by the caller):
// g0 and g1 always; the anisotropy direction (g3) only in the full variant; the extension
// texels (g4 to g6, 1 where absent) only when the frame's scene has such textures (a uniform
// branch), and the basic variant reads only the specular ones.
GBufferSurface gbuffer_surface(ivec2 pixel, vec4 g2)
{
    GBufferSurface g = GBuffer_DecodeBase(texelFetch(gbuffer0, pixel, 0), texelFetch(gbuffer1, pixel, 0), g2);
#if RTPBR_LIGHTING_FULL
    g.anisotropyDirection = GBuffer_DecodeAnisotropy(texelFetch(gbuffer3, pixel, 0));
#endif
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_SPECULAR) != 0u)
        g.specular = texelFetch(gbuffer4, pixel, 0);
#if RTPBR_LIGHTING_FULL
    if ((frame.extension_textures & RTPBR_EXTENSION_TEXTURES_COAT_SHEEN) != 0u) {
        g.sheen = texelFetch(gbuffer5, pixel, 0);
        g.coat = texelFetch(gbuffer6, pixel, 0).rg;
    }
#endif
    return g;
}
// lighting_mc.comp adds to it across dispatches: it defines RTPBR_RADIANCE_ACCESS empty.
#ifndef RTPBR_RADIANCE_ACCESS
#define RTPBR_RADIANCE_ACCESS writeonly
#endif
layout(set = 0, binding = RTPBR_BINDING_LIGHT_RADIANCE, rgba32f) RTPBR_RADIANCE_ACCESS uniform image2D radiance;

// The shading point of a pixel: the position from the depth buffer is off by up to about one
// depth quantum along the view ray; an emitter's own surface could then land on its emitting
// side and light itself. The point is lifted along N by a few quanta (measured at this depth).
// point_lift: how far (P the point of depth at ndc); the cull bounds it per tile (cull.comp).
float point_lift(vec2 ndc, float depth, vec3 P)
{
    vec4 further = frame.inv_view_proj * vec4(ndc, min(depth * (1.0f + 4.0f / 16777216.0f), 1.0f), 1.0f);
    return length(further.xyz / further.w - P) + 1e-6f * length(frame.camera_position.xyz - P);
}
vec3 lifted_point(vec2 ndc, float depth, vec3 P, vec3 N)
{
    return P + N * point_lift(ndc, depth, P);
}
