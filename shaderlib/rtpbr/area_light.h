// rtpbr shader library: the per-light evaluation of polygonal area lights.
//
// What a renderer calls to light a surface point with polygonal lights: for one light, its
// diffuse and specular contribution per unit of radiance, every lobe of the surface
// (surface.h) integrated with Linearly Transformed Cosines (ltc.h) and every correction the
// engine ships (ltc_corrections.h: the point correction, the tail and streak estimates; the
// energy bound across lights). The engine's lighting and forward passes, the shader-include
// sample and docs/library.md's snippet all call these functions, so that they shade alike.
//
//   AreaLightPixel px = AreaLight_Begin(s, N, V);    // once per point
//   AreaLightSum acc = AreaLight_SumBegin();
//   for each light i:
//       AreaLight_Add(px, acc, s, P, N, i);           // per light
//   rtpbr_float3 Lo = AreaLight_End(px, acc, s, P);   // after the loop
//
// Public functions
//   AreaLight_Begin      per-point setup: the tables' values, the lobes' matrices and scales
//   AreaLight_SumBegin   an empty sum over lights
//   AreaLight_Add        one light's reflected radiance (x its radiance and visibility) added
//   AreaLight_AddPunctual  the same for a punctual light (AreaLight_Add calls it)
//   AreaLight_End        the sum, held to the energy bound across lights, with the streak
//                        estimate (GGX, RTPBR_AREA_LIGHT_FULL 0)
//   AreaLight_Evaluate   one light alone (the four above with one light)
//   AreaLight_Lobe       one pass over a light's edges for one LTC lobe (the building block)
//   AreaLight_AddSphere  a sphere light's reflected radiance added, as AreaLight_Add's
//                        (RTPBR_AREA_LIGHT_SPHERES)
//   AreaLight_AddDisk    a disk (ellipse) light's reflected radiance added, as AreaLight_Add's
//                        (RTPBR_AREA_LIGHT_DISKS)
//   AreaLight_AddTexturedQuad  a quad light with an emission texture, as AreaLight_Add's
//                        (RTPBR_AREA_LIGHT_TEXTURED)
//   AreaLight_AddTube    a tube (capsule) light's reflected radiance added, as AreaLight_Add's
//                        (RTPBR_AREA_LIGHT_TUBES)
//   AreaLight_AddShape   AreaLight_Add or AreaLight_AddSphere by a run-time flag: one loop
//                        over polygons and spheres (RTPBR_AREA_LIGHT_SPHERES); with
//                        RTPBR_AREA_LIGHT_DISKS a last flag, diskLight: AreaLight_AddDisk
//   AreaLight_AddSimpleShape  AreaLight_AddShape without the tube flag (a loop over the other
//                        kinds carries no tube's code)
//   AreaLight_AddTubePart  one part of a tube (its facing quad or an end's sphere:
//                        AreaLight_AddTube lights the three as three lights)
//   AreaLight_AddPolygonShape, AreaLight_AddRoundShape  a polygon (textured by a run-time
//                        flag), a sphere or a disk (by a run-time flag): what AreaLight_Add and
//                        the per-kind functions call, each with only its own shape's code
//                        (compile time: docs/library.md, "Which entry point")
//   AreaLight_AddShapePart  AreaLight_AddSimpleShape or AreaLight_AddTubePart by a run-time part
//   AreaLight_ShapeLobe  AreaLight_Lobe over a polygon, a sphere, a disk or a tube's part
//   AreaLight_SimpleShapeLobe  the same without a tube's part
//   AreaLight_TubeLobe   AreaLight_Lobe over a whole tube (its three parts summed in one lobe)
//   AreaLight_WalkLobe   AreaLight_Lobe over a light's polygon or an explicit parallelogram
//                        (AreaLightQuad: a tube's facing quad)
//
// Flags (before the include)
//   RTPBR_AREA_LIGHT_PUNCTUAL  0 (default): every light is a polygon; 1: a light may also be
//                          a point, spot or directional light (punctual.h; Host_LightShape),
//                          its radiance exact (Surface_Evaluate), added to the same sum by
//                          AreaLight_Add; 2: the same, but the host calls AreaLight_AddPunctual
//                          for those itself, into a sum of its own, and AreaLight_Add only for
//                          polygons (the engine: its punctual lights are summed before
//                          AreaLight_Begin into the emission's sum, so that neither the
//                          polygons' per-point state and the whole BRDF's terms nor a sum of
//                          their own are live at once; docs/performance.md, 11)
//   RTPBR_AREA_LIGHT_SPHERES  0 (default); 1: AreaLight_AddSphere, which the host calls for
//                          its sphere lights (a point light with a radius: ltc_shapes.h,
//                          every lobe and correction of AreaLight_Add over the sphere's
//                          cone), into the same sum as its polygons
//   RTPBR_AREA_LIGHT_SPHERE_CLIP  1 (default): a sphere the horizon cuts is clipped exactly
//                          (its disk's 12-gon); 0: Heitz & Hill's sphere proxy (no walk, fewer
//                          registers; a glossy lobe leaks light from below the surface)
//   RTPBR_AREA_LIGHT_DISKS  0 (default); 1: AreaLight_AddDisk, which the host calls for its
//                          disk and ellipse lights (glTF EXT_lights_area disks: ltc_shapes.h,
//                          every lobe and correction of AreaLight_Add over the disk itself, the
//                          horizon as a sphere's: RTPBR_AREA_LIGHT_SPHERE_CLIP, _SPHERE_SIDES),
//                          into the same sum as its polygons
//   RTPBR_AREA_LIGHT_DISK_CLIP_SIDES  24 (default): where the horizon cuts a disk (with
//                          RTPBR_AREA_LIGHT_SPHERE_CLIP), the sides of the equal-area polygon its
//                          diffuse vector form factor is clipped and integrated over
//   RTPBR_AREA_LIGHT_ROUND_DISKS  0 (default); 1: the Lambert vector form factor of a round disk
//                          light (half-axes orthogonal, of one length) is a closed form
//                          (LTC_DiskVector) instead of an elliptic cone's; ellipses still take
//                          the cone's (a run-time choice: both codes in the shader)
//   RTPBR_AREA_LIGHT_TEXTURED  0 (default); 1: AreaLight_AddTexturedQuad, which the host calls
//                          for its quad lights with an emission texture (a screen, a window;
//                          ltc_textured.h: each lobe reads the host's prefiltered texture where
//                          its vector form factor meets the quad, Heitz et al. 2016), into the
//                          same sum as its polygons
//   RTPBR_AREA_LIGHT_TUBES  0 (default); 1: AreaLight_AddTube, which the host calls for its tube
//                          (capsule) lights (ltc_lines.h's LTC_EvaluateTube decomposition: the
//                          facing quad walked as a polygon plus the two end spheres, weighted by
//                          LTC_TubeWeights, each of the three evaluated as a light of its own,
//                          its radiance times its weight), into the same sum as its polygons;
//                          AreaLight_AddShape takes a last flag, tubeLight, and
//                          AreaLight_ShapeLobe a last part, tubePart (RTPBR_AREA_LIGHT_TUBE_*)
//   RTPBR_AREA_LIGHT_TUBE_UNROLL  0 (default): a tube's three parts in a loop (one copy of the
//                          evaluation: a quad's or a sphere's registers); 1: unrolled, three
//                          copies (faster where registers do not bind, e.g. on a CPU: lavapipe
//                          111 against 264 ns per pixel-light, but 112 VGPRs on navi21 in the
//                          engine's basic variant, where the loop takes 96; the engine builds
//                          its tube variants for a CPU device with it)
//   RTPBR_AREA_LIGHT_TUBE_RANGE  0 (default): tubes have no range; 1: a tube's radiance is
//                          windowed by Punctual_RangeWindow at the distance from its centre (the
//                          ends' midpoint) and Host_LightTubeInvRange2 (below)
//   RTPBR_AREA_LIGHT_CLIP_LOOPS  0 (default): where the horizon cuts a sphere's or a disk's
//                          disk, its equal-area polygons (RTPBR_AREA_LIGHT_SPHERE_SIDES,
//                          _DISK_CLIP_SIDES) are walked unrolled under a branch; 1: in loops of
//                          as many edges where it is cut and none where not (for a target whose
//                          branches run both of their sides, such as Mesa's llvmpipe: there
//                          such a loop costs one masked trip where no lane is cut, the unrolled
//                          walk every edge). The same results. Used in expressions only, never
//                          in #if (a GLSL host may make it a specialization constant: the
//                          engine does on a CPU device)
//   RTPBR_AREA_LIGHT_SHEEN_REFETCH  0 (default): the sheen lobe's LTC matrix (its table row
//                          at the point) kept in AreaLightPixel through the light loop; 1: read
//                          again from its table at each light (Host_TableLtc1 at the same
//                          coordinates: the same texel, the same results), four registers fewer
//                          through the loop for a table read per light (the engine's forward
//                          pass: its sphere variants spilled 2 VGPRs on gfx1100 without it; in
//                          its lighting pass it spilled 2 SGPRs in a sphere variant, so not there)
//   RTPBR_AREA_LIGHT_FULL  1 (default): every lobe surface.h resolves (Disney, coat, sheen,
//                          anisotropy); 0: metallic-roughness without them (the engine's
//                          basic variant: fewer registers, the streak estimate on GGX).
//   RTPBR_AREA_LIGHT_WALK_LOOP  0 (default): a polygon's walk over its edges has its first four
//                          unrolled and a loop over the rest only for 5 or more vertices,
//                          whose vertices 5 to 7 it reads before that loop (AreaLight_EdgeStep:
//                          on a CPU device a buffer read inside a loop over the edges cost a
//                          third of a quad light's time); 1: one loop over every edge, each
//                          vertex read in it (fewer registers: the engine's full variants over
//                          textured quads and tubes spilled 2 to 4 SGPRs on navi21 and gfx1100
//                          without it).
//   RTPBR_AREA_LIGHT_MAX_VERTICES  RTPBR_LTC_MAX_VERTICES (default): the most vertices of the
//                          host's polygons (Host_LightVertexCount); 3: triangles only, 4: no
//                          polygon beyond a quad. The walk's fourth edge (below 4) and its loop over
//                          edges 5 and on (below 5) are then compiled out (without the loop form,
//                          RTPBR_AREA_LIGHT_WALK_LOOP 0): on lavapipe, which runs the code of every
//                          branch and a loop's first trip whether any lane takes them or not, a
//                          quad light costs about 9 % less. Used in expressions only (never in #if), so
//                          that a GLSL host may make it a specialization constant (the engine: per
//                          frame, from its lights; engine/shaders/shade_lights.glsl).
//   RTPBR_AREA_LIGHT_STREAK_ON  1 (default): the streak estimate runs where it applies (GGX,
//                          RTPBR_AREA_LIGHT_FULL 0, RTPBR_LTC_STREAK 1); 0: it is skipped, its
//                          candidate neither chosen nor evaluated. The same result for a point
//                          none of whose lights can give the estimate any weight
//                          (LTC_StreakOutside: a host's culling proves it per tile), where its
//                          code would only cost: on lavapipe, which runs every branch, the
//                          estimate's two walks cost a tenth of the showcase's shader work. Used
//                          in expressions only (never in #if), so that a GLSL host may make it a
//                          specialization constant (the engine: a tile class of its own,
//                          engine/shaders/cull.comp).
//   RTPBR_UNROLL, RTPBR_DONT_UNROLL  loop attributes (GLSL: [[unroll]], [[dont_unroll]] with
//                          GL_EXT_control_flow_attributes; HLSL: [unroll], [loop]); empty by
//                          default.
//
// The host bridge. The library never reads a buffer or samples a texture: the host defines,
// before including this header, how a light and the tables are read (as RTXDI's bridge). Lights
// are named by an index the host chooses (uint):
//   uint         Host_LightVertexCount(uint light)  3 .. RTPBR_AREA_LIGHT_MAX_VERTICES
//   rtpbr_float3 Host_LightVertex(uint light, uint k)  world space, counter-clockwise seen
//                                     from the emitting side (ltc.h's conventions)
//   rtpbr_float4 Host_LightPlane(uint light)   unit normal xyz (the emitting side), w = -n.v0
//   rtpbr_float4 Host_LightSphere(uint light)  a bounding sphere: centre xyz, radius w
//   bool         Host_LightTwoSided(uint light)
//   rtpbr_float3 Host_LightRadiance(uint light)   emitted radiance
//   rtpbr_float3 Host_LightVisibility(uint light) its visibility from the point being shaded
//                                     (a shadow ratio; 1 without shadows), per channel
// and with RTPBR_AREA_LIGHT_PUNCTUAL (the polygon functions above are not called for the
// others; punctual.h's layout):
//   uint         Host_LightShape(uint light)      0: a polygon; RTPBR_PUNCTUAL_POINT, _SPOT,
//                                     _DIRECTIONAL
//   rtpbr_float4 Host_LightPosition(uint light)   position xyz, w = 1 / range^2 (0: none)
//   rtpbr_float3 Host_LightDirection(uint light)  unit, the way the light travels
//   rtpbr_float2 Host_LightSpotCone(uint light)   (Punctual_SpotCone; a point light's (-2, 1))
// (Host_LightRadiance is then a punctual light's intensity; Host_LightVisibility as above);
// with RTPBR_AREA_LIGHT_SPHERES a sphere light is read through Host_LightSphere (its centre and
// radius, exactly), Host_LightRadiance (its uniform radiance), Host_LightPosition's w (1 /
// range^2, 0 for none: its radiance is windowed by Punctual_RangeWindow at the distance from
// its centre) and Host_LightVisibility;
// with RTPBR_AREA_LIGHT_DISKS a disk or ellipse light (the points centre + u cos t + v sin t,
// t in [0, 2 pi), scaled by 0 .. 1; u, v conjugate half-axes, orthogonal and of one length for
// a disk) is read through
//   rtpbr_float3 Host_LightDiskAxis(uint light, uint k)  its half-axis u (k = 0) or v (k = 1),
//                                     world space; it emits toward cross(u, v) (both ways
//                                     where Host_LightTwoSided)
// with Host_LightSphere (its centre xyz, exactly; w a bounding radius, the longer half-axis'
// length, as a polygon's), Host_LightTwoSided, Host_LightRadiance (its uniform radiance) and
// Host_LightVisibility (the polygon functions are not called for it);
// with RTPBR_AREA_LIGHT_TEXTURED a textured quad (a polygon of 4 vertices, a parallelogram:
// texture coordinate (s, t) at v0 + s (v1 - v0) + t (v3 - v0), s, t in [0, 1]) is read as a
// polygon and through
//   rtpbr_float3 Host_LightTexture(uint light, rtpbr_float3 lookup)  the emission's factor (rgb,
//                                     times Host_LightRadiance) at lookup = (s, t, footprint)
//                                     (LTC_TextureLookup: s, t may fall outside [0, 1]; the
//                                     footprint in units of the quad's size): the host reads its
//                                     chain prefiltered for it (mip k blurred over 2^k texels:
//                                     lod = log2(footprint x size)), clamped to the edge;
// with RTPBR_AREA_LIGHT_TUBES a tube light (the capsule of radius r around the segment from one
// end's centre to the other's; radiance uniform over its surface) is read through
//   rtpbr_float4 Host_LightTube(uint light, uint k)  end k's (0, 1) centre xyz, world space, and
//                                     the radius w (the same for both ends; > 0)
// with Host_LightSphere (read, its value unused: any bounding sphere), Host_LightRadiance and
// Host_LightVisibility (the polygon functions are not called for it; no range window, unless
// RTPBR_AREA_LIGHT_TUBE_RANGE, with
//   float        Host_LightTubeInvRange2(uint light)  1 / range^2, 0 for none: its radiance is
//                                     windowed by Punctual_RangeWindow at the distance from the
//                                     tube's centre, the ends' midpoint, as a sphere's from its
//                                     centre);
//   rtpbr_float4 Host_TableLtc1(int table, rtpbr_float2 uv)  the LTC tables at uv
//   rtpbr_float4 Host_TableLtc2(int table, rtpbr_float2 uv)  (LTC_LutCoord), table one of
//                                     RTPBR_TABLE_LTC_SPECULAR (rtpbr_ltc_ggx_1/_2, or
//                                     _beckmann_ with RTPBR_NDF_BECKMANN), _DISNEY_DIFFUSE
//                                     (rtpbr_ltc_disney_diffuse_1/_2), _SHEEN (rtpbr_ltc_sheen_1/_2);
//                                     the last two are read only with RTPBR_AREA_LIGHT_FULL
// and surface.h's table reads (Host_TableE_EF, Host_TableE, Host_TableEavg, Host_TableEFavg,
// Host_TableSheenE). A complete bridge over one quad: samples/shader-include/quad_light.frag.
//
// Registers: the evaluation is written for the GPU's register file (docs/performance.md,
// "Registers of the lighting pass"): one lobe's clip state live at a time, values fetched again
// rather than kept live through the light loop where the full variant is at its limit.
#ifndef RTPBR_AREA_LIGHT_H
#define RTPBR_AREA_LIGHT_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "microfacet.h"
#include "ltc.h"
#include "ltc_anisotropy.h"
#include "ltc_corrections.h"
#include "kulla_conty.h"
#include "disney.h"
#include "sheen.h"
#include "surface.h"
#include "punctual.h"
#include "ltc_shapes.h"
#include "ltc_textured.h"
#if RTPBR_AREA_LIGHT_TUBES
#include "ltc_lines.h"
#endif

#ifndef RTPBR_AREA_LIGHT_PUNCTUAL
#define RTPBR_AREA_LIGHT_PUNCTUAL 0
#endif
#ifndef RTPBR_AREA_LIGHT_MAX_VERTICES
#define RTPBR_AREA_LIGHT_MAX_VERTICES RTPBR_LTC_MAX_VERTICES
#endif
#ifndef RTPBR_AREA_LIGHT_SPHERES
#define RTPBR_AREA_LIGHT_SPHERES 0
#endif
#ifndef RTPBR_AREA_LIGHT_DISKS
#define RTPBR_AREA_LIGHT_DISKS 0
#endif
#ifndef RTPBR_AREA_LIGHT_DISK_CLIP_SIDES
#define RTPBR_AREA_LIGHT_DISK_CLIP_SIDES 24
#endif
#ifndef RTPBR_AREA_LIGHT_ROUND_DISKS
#define RTPBR_AREA_LIGHT_ROUND_DISKS 0
#endif
#ifndef RTPBR_AREA_LIGHT_SPHERE_CLIP
#define RTPBR_AREA_LIGHT_SPHERE_CLIP 1
#endif
#ifndef RTPBR_AREA_LIGHT_TEXTURED
#define RTPBR_AREA_LIGHT_TEXTURED 0
#endif
#ifndef RTPBR_AREA_LIGHT_TUBES
#define RTPBR_AREA_LIGHT_TUBES 0
#endif
#ifndef RTPBR_AREA_LIGHT_TUBE_UNROLL
#define RTPBR_AREA_LIGHT_TUBE_UNROLL 0
#endif
#ifndef RTPBR_AREA_LIGHT_TUBE_RANGE
#define RTPBR_AREA_LIGHT_TUBE_RANGE 0
#endif
#ifndef RTPBR_AREA_LIGHT_CLIP_LOOPS
#define RTPBR_AREA_LIGHT_CLIP_LOOPS 0
#endif
#ifndef RTPBR_AREA_LIGHT_STREAK_ON
#define RTPBR_AREA_LIGHT_STREAK_ON 1
#endif
// The sides of the equal-area polygon a sphere's disk is clipped as (RTPBR_AREA_LIGHT_SPHERE_CLIP).
#ifndef RTPBR_AREA_LIGHT_SPHERE_SIDES
#define RTPBR_AREA_LIGHT_SPHERE_SIDES 12
#endif
#ifndef RTPBR_AREA_LIGHT_SHEEN_REFETCH
#define RTPBR_AREA_LIGHT_SHEEN_REFETCH 0
#endif
#ifndef RTPBR_AREA_LIGHT_FULL
#define RTPBR_AREA_LIGHT_FULL 1
#endif
#ifndef RTPBR_AREA_LIGHT_WALK_LOOP
#define RTPBR_AREA_LIGHT_WALK_LOOP 0
#endif
// RTPBR_AREA_LIGHT_INV_MASS_PER_POINT 1 (default: the basic evaluation) | 0: the specular lobe's
// 1 / horizon mass taken once per point (AreaLightPixel.specularInvMass; docs/performance.md, 30)
// or per light. A register through the light loop: the full evaluation has none to spare, and a
// host may turn it off where its loop has none (the engine: its basic variants with other
// shapes than polygons).
#ifndef RTPBR_AREA_LIGHT_INV_MASS_PER_POINT
#define RTPBR_AREA_LIGHT_INV_MASS_PER_POINT (!RTPBR_AREA_LIGHT_FULL)
#endif
#if RTPBR_AREA_LIGHT_INV_MASS_PER_POINT && RTPBR_AREA_LIGHT_FULL
#error "RTPBR_AREA_LIGHT_INV_MASS_PER_POINT is the basic evaluation's: the full one's other lobes take theirs per light"
#endif
#ifndef RTPBR_UNROLL
#define RTPBR_UNROLL
#endif
#ifndef RTPBR_DONT_UNROLL
#define RTPBR_DONT_UNROLL
#endif
// With RTPBR_AREA_LIGHT_DISKS the functions that take a sphere light's kind (sphereLight)
// take a disk light's too: the parameter diskLight after it, the argument x.
#if RTPBR_AREA_LIGHT_DISKS
#define RTPBR_AREA_LIGHT_DISK_PARAM , bool diskLight
#define RTPBR_AREA_LIGHT_DISK_ARG(x) , x
#else
#define RTPBR_AREA_LIGHT_DISK_PARAM
#define RTPBR_AREA_LIGHT_DISK_ARG(x)
#endif
// With RTPBR_AREA_LIGHT_TEXTURED AreaLight_AddShape takes a last flag, texturedLight.
#if RTPBR_AREA_LIGHT_TEXTURED
#define RTPBR_AREA_LIGHT_TEXTURE_PARAM , bool texturedLight
#define RTPBR_AREA_LIGHT_TEXTURE_ARG(x) , x
#define RTPBR_AREA_LIGHT_TEXTURED_FLAG texturedLight
#else
#define RTPBR_AREA_LIGHT_TEXTURE_PARAM
#define RTPBR_AREA_LIGHT_TEXTURE_ARG(x)
#define RTPBR_AREA_LIGHT_TEXTURED_FLAG false
#endif
// With RTPBR_AREA_LIGHT_TUBES the functions that take a disk light's kind take a tube light's
// after it (and after texturedLight in AreaLight_AddShape): AreaLight_AddShape the flag
// tubeLight, AreaLight_ShapeLobe (and AreaLight_AddShapePart) the part tubePart, one of
// RTPBR_AREA_LIGHT_TUBE_NONE (not a tube), _QUAD (the facing quad alone), _END1, _END2 (an end's
// sphere alone); AreaLight_TubeLobe is the three parts summed in one lobe.
#if RTPBR_AREA_LIGHT_TUBES
#define RTPBR_AREA_LIGHT_TUBE_PARAM , bool tubeLight
#define RTPBR_AREA_LIGHT_TUBE_ARG(x) , x
#define RTPBR_AREA_LIGHT_TUBE_PART_PARAM , uint tubePart
#define RTPBR_AREA_LIGHT_TUBE_PART_ARG(x) , x
#else
#define RTPBR_AREA_LIGHT_TUBE_PARAM
#define RTPBR_AREA_LIGHT_TUBE_ARG(x)
#define RTPBR_AREA_LIGHT_TUBE_PART_PARAM
#define RTPBR_AREA_LIGHT_TUBE_PART_ARG(x)
#endif
// The streak estimate runs in the metallic-roughness evaluation on GGX (its registers do not
// fit the full one's).
#if RTPBR_LTC_STREAK && RTPBR_NDF == RTPBR_NDF_GGX && !RTPBR_AREA_LIGHT_FULL
#define RTPBR_AREA_LIGHT_STREAK 1
#else
#define RTPBR_AREA_LIGHT_STREAK 0
#endif

RTPBR_NAMESPACE_BEGIN

// No light (AreaLightPixel.streakLight).
RTPBR_CONST uint RTPBR_AREA_LIGHT_NONE = 0xffffffffu;
// A tube light's parts (AreaLight_ShapeLobe's tubePart, RTPBR_AREA_LIGHT_TUBES).
RTPBR_CONST uint RTPBR_AREA_LIGHT_TUBE_NONE = 0u; // not a tube
RTPBR_CONST uint RTPBR_AREA_LIGHT_TUBE_QUAD = 1u; // its facing quad (LTC_TubeQuad)
RTPBR_CONST uint RTPBR_AREA_LIGHT_TUBE_END1 = 2u; // its first end's sphere (_END2: the second's)
RTPBR_CONST uint RTPBR_AREA_LIGHT_TUBE_END2 = 3u;

// A point's state across its lights (AreaLight_Begin).
struct AreaLightPixel {
    rtpbr_float3x3 frame;        // LTC_Frame(N, V)
    rtpbr_float3 vLocal;         // V in that frame
    rtpbr_float3x3 specularMinv; // the specular lobe's M^-1 (stretched when anisotropic)
    float specularInvMass;       // 1 / its LTC_HorizonMass, once per point (docs/performance.md, 30)
    rtpbr_float3 specularScale;  // its Fresnel scale, plus the shaped f_ms lobe's share
    rtpbr_float3 msColor;        // the separable f_ms lobe's colour
    float msScale;               // its (1 - Eo) / (1 - Eavg) (KC_PolygonLobe's per-point
                                 // factors, docs/performance.md, 18)
    rtpbr_float3 baseScale;      // the layered base's colour x (1 - Eso) / (1 - EsAvg)
                                 // (KC_PolygonLobe's per-point factors, docs/performance.md, 15);
                                 // for a Disney material (no layered base) Burley's diffuse
                                 // lobe's scale
    float pointNorm;             // the specular table's norm (ltc2.x)
    bool pointOn;                // the point correction applies (isotropic lobes)
    // RTPBR_AREA_LIGHT_FULL: the coat, Burley diffuse and sheen lobes (unused otherwise)
    bool coated;
    rtpbr_float4 ltc1c;
    rtpbr_float3 coatScale;
    rtpbr_float4 ltc1b;          // Burley's diffuse lobe's table row (Disney) or the KHR
                                 // sheen lobe's: never both (Disney materials have no KHR
                                 // sheen; registers: docs/performance.md, 27)
    // The per-light parameters of the base's lobes (RTPBR_AREA_LIGHT_FULL), one set of registers
    // for the two models a material may have (registers: docs/performance.md, 27): a Disney
    // material's (roughness, metallic, subsurface, sheen) and (baseColor, sheenTint), or a
    // KHR material's layered base and sheen, (specularWeight, EFavg, FmsDielectric,
    // sheenRoughness) and (sheenColor, EsheenO) (AreaLight_Begin; ShadingSurface's values).
    rtpbr_float4 baseParams;
    rtpbr_float4 baseColors;
    rtpbr_float3 sheenScale;
};

// What the evaluation gathers across a point's lights (AreaLight_Evaluate).
struct AreaLightSum {
    rtpbr_float3 sum;            // the lights' reflected radiance
    float specularMass;          // the sum of the specular lobe's corrected shares
    uint streakLight;            // the streak estimate's light, RTPBR_AREA_LIGHT_NONE for none
    float streakFF;              // its specular result in the loop
    rtpbr_float3 punctual;       // the punctual lights' reflected radiance (not held to the
                                 // polygons' energy bound: exact)
};

RTPBR_FN AreaLightSum AreaLight_SumBegin() {
    AreaLightSum acc;
    acc.sum = RTPBR_F3(0.0f);
    acc.specularMass = 0.0f;
    acc.streakLight = RTPBR_AREA_LIGHT_NONE;
    acc.streakFF = 0.0f;
    acc.punctual = RTPBR_F3(0.0f);
    return acc;
}

// A parallelogram walked in place of a light's own vertices (AreaLight_WalkLobe: a tube's facing
// quad, LTC_TubeQuad): corners o, o + u, o + u + v, o + v, in the LTC frame and relative to the
// shading point (o = ltcFrame (corner - P)); on = false: the light's own polygon
// (Host_LightVertex). (Registers: held in world space and moved into the frame at each vertex,
// it spilled the engine's full variant over tubes on gfx1100, 3 VGPRs; in the frame, none.)
struct AreaLightQuad {
    rtpbr_float3 o;
    rtpbr_float3 u;
    rtpbr_float3 v;
    bool on;
};

RTPBR_FN AreaLightQuad AreaLight_NoQuad() {
    AreaLightQuad q;
    q.o = RTPBR_F3(0.0f);
    q.u = RTPBR_F3(0.0f);
    q.v = RTPBR_F3(0.0f);
    q.on = false;
    return q;
}

// Vertex k of light i seen from P in the LTC frame ltcFrame (Host_LightVertex), or of the
// parallelogram quad where quad.on (already in that frame).
RTPBR_FN rtpbr_float3 AreaLight_Vertex(uint i, uint k, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, AreaLightQuad quad) {
    if (!quad.on)
        return rtpbr_mul(ltcFrame, Host_LightVertex(i, k) - P);
    return quad.o + (k == 1u || k == 2u ? quad.u : RTPBR_F3(0.0f)) + (k >= 2u ? quad.v : RTPBR_F3(0.0f));
}

// Edge k - 1 -> k (k in 1 .. count; vertex count is vertex 0, first) of a streamed walk over
// light i's count edges (vectors from P in the LTC frame ltcFrame; a = the previous vertex's,
// advanced here) clipped to the horizon; the walk ends with the segment that closes the clipped
// polygon along it (LTC_ClipClose). The vertices: light i's, or quad's where quad.on
// (AreaLight_Vertex). AreaLight_WalkLobe runs edges 1 to 4 unrolled (k a constant, the fourth
// where count >= 4) and a loop over the others only for polygons of 5 or more vertices, whose
// vertices 5 to 7 it reads before that loop (AreaLight_EdgeStepTail; with
// RTPBR_AREA_LIGHT_WALK_LOOP, one loop over every edge): on lavapipe (Mesa 22.3's llvmpipe) a
// storage-buffer read is a loop over the SIMD lanes, and the walk's read of vertex k inside its
// loop over the edges took a third of a quad light's time, even where it was masked off
// (docs/performance.md, 19). (AreaLight_StreakEstimate, once per point, keeps its loop.)
RTPBR_FN LtcSegment AreaLight_EdgeStep(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, uint k, uint count,
                                       rtpbr_float3 first, RTPBR_INOUT(LtcClipper) horizon,
                                       RTPBR_INOUT(rtpbr_float3) a, AreaLightQuad quad) {
    rtpbr_float3 b = k < count ? AreaLight_Vertex(i, k, P, ltcFrame, quad) : first;
    LtcSegment seg = LTC_ClipEdge(horizon, a, b);
    a = b;
    return seg;
}

// AreaLight_EdgeStep with its horizon clip's 1 / (a.z - b.z) given (rden: LTC_ClipEdgeRecip).
RTPBR_FN LtcSegment AreaLight_EdgeStepRecip(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, uint k, uint count,
                                            rtpbr_float3 first, float rden, RTPBR_INOUT(LtcClipper) horizon,
                                            RTPBR_INOUT(rtpbr_float3) a, AreaLightQuad quad) {
    rtpbr_float3 b = k < count ? AreaLight_Vertex(i, k, P, ltcFrame, quad) : first;
    LtcSegment seg = LTC_ClipEdgeRecip(horizon, a, b, rden);
    a = b;
    return seg;
}

#if RTPBR_LTC_MAX_VERTICES != 8
#error "AreaLight_EdgeStepTail holds vertices 5 to 7 of at most 8"
#endif
// AreaLight_EdgeStep for k >= 5 of a light's own polygon (not a quad's) whose vertices 5, 6 and
// 7 were read before the loop over those edges (v5, v6, v7: Host_LightVertex).
RTPBR_FN LtcSegment AreaLight_EdgeStepTail(rtpbr_float3 P, rtpbr_float3x3 ltcFrame, uint k, uint count, rtpbr_float3 first,
                                           rtpbr_float3 v5, rtpbr_float3 v6, rtpbr_float3 v7,
                                           RTPBR_INOUT(LtcClipper) horizon, RTPBR_INOUT(rtpbr_float3) a) {
    rtpbr_float3 b = k < count ? rtpbr_mul(ltcFrame, (k == 5u ? v5 : k == 6u ? v6 : v7) - P) : first;
    LtcSegment seg = LTC_ClipEdge(horizon, a, b);
    a = b;
    return seg;
}

// A segment of the horizon-clipped polygon (AreaLight_EdgeStep's, or its closing one) added to
// its vector form factor F and to the lobe's integral.
RTPBR_FN void AreaLight_LobeSegment(LtcSegment seg, RTPBR_INOUT(rtpbr_float3) F, RTPBR_INOUT(LtcLobe) lobe) {
    if (seg.valid) {
#if RTPBR_AREA_LIGHT_WALK_LOOP || RTPBR_AREA_LIGHT_TUBES // (registers: docs/performance.md, 30)
        F += LTC_EdgeIntegralOf(seg.a, seg.b);
        LTC_LobeEdge(lobe, seg.a, seg.b);
#else
        // (LTC_LobeEdge, its clip's division issued before F's integral: its latency under it)
        rtpbr_float3 la = rtpbr_mul(lobe.minv, seg.a), lb = rtpbr_mul(lobe.minv, seg.b);
        float rden = 1.0f / (la.z - lb.z);
        F += LTC_EdgeIntegralOf(seg.a, seg.b);
        LtcSegment s = LTC_ClipEdgeRecip(lobe.clip, la, lb, rden);
        if (s.valid)
            lobe.vec += LTC_EdgeIntegralOf(s.a, s.b);
#endif
    }
}

// LTC_HorizonFraction of lobe minv from invMass = LTC_InverseHorizonMass(minv), which a caller
// evaluating many lights takes once per point (AreaLightPixel.specularInvMass: a product per
// light, not a division; docs/performance.md, 30). Unless RTPBR_AREA_LIGHT_INV_MASS_PER_POINT,
// a negative invMass (a literal -1, so that the choice folds at compile time) has it taken here
// instead: the full evaluation's lobes and the other shapes' classes, whose per-point values
// would cost registers they have not got.
RTPBR_FN float AreaLight_HorizonFraction(float ff, float invMass, rtpbr_float3x3 minv) {
#if RTPBR_AREA_LIGHT_INV_MASS_PER_POINT
    RTPBR_UNUSED(minv);
    return LTC_HorizonFractionInv(ff, invMass);
#else
    return invMass >= 0.0f ? LTC_HorizonFractionInv(ff, invMass) : LTC_HorizonFraction(ff, LTC_HorizonMass(minv));
#endif
}

// The end of a lobe's pass (AreaLight_Lobe): its form factor, and its vector form factor in Fl.
// LTC_LobeEndVector and LTC_LobeEnd in one: the closing segment's integral once, its z the
// form factor's sum (the same value; the two calls left two copies: docs/performance.md, 9).
RTPBR_FN float AreaLight_LobeClose(LtcLobe lobe, float invMass, RTPBR_OUT(rtpbr_float3) Fl) {
    rtpbr_float3 v = lobe.vec;
    if (lobe.clip.crossed)
        v += LTC_EdgeIntegralOf(lobe.clip.exitPoint, lobe.clip.entryPoint);
    Fl = v.z < 0.0f ? -v : v;
    return AreaLight_HorizonFraction(abs(v.z), invMass, lobe.minv);
}

// One pass over light i's edges (vectors from P in the LTC frame): the horizon clip, then the
// LTC lobe minv; returns its form factor, the clipped polygon's vector form factor F (up to
// its sign) and the lobe's own vector form factor Fl (LTC_LobeEndVector; callers that do not
// read it leave its x, y to dead-code elimination). The full evaluation runs a pass per lobe
// the material has, so that one lobe's clip state is live at a time. AreaLight_WalkLobe: the
// same over the parallelogram quad instead where quad.on (a tube's facing quad).
RTPBR_FN float AreaLight_WalkLobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                  RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl, AreaLightQuad quad) {
    LtcClipper horizon = LTC_ClipperBegin();
    LtcLobe lobe = LTC_LobeBegin(minv);
    F = RTPBR_F3(0.0f);
    uint count = quad.on ? 4u : Host_LightVertexCount(i);
    rtpbr_float3 first = AreaLight_Vertex(i, 0u, P, ltcFrame, quad);
    rtpbr_float3 a = first;
#if RTPBR_AREA_LIGHT_WALK_LOOP
    RTPBR_UNROLL for (uint k = 1u; k <= count; ++k)
        AreaLight_LobeSegment(AreaLight_EdgeStep(i, P, ltcFrame, k, count, first, horizon, a, quad), F, lobe);
#else
    // (lavapipe: AreaLight_EdgeStep; the fourth edge and the loop only where the host's
    // polygons may have them, RTPBR_AREA_LIGHT_MAX_VERTICES: a tube's quad has four)
    bool four = (RTPBR_AREA_LIGHT_MAX_VERTICES >= 4u || quad.on) && count >= 4u;
#if !RTPBR_AREA_LIGHT_FULL
    // (latency: docs/performance.md, 30) The horizon clips' divisions of edges 1 to 4 before
    // the walk (from the heights of their ends, vertex k or the first where k = count): their
    // latencies overlap instead of opening each edge. Not in the full evaluation, which is at
    // its registers' limit (the values live across the walk spilled it on gfx1100).
    float z1 = AreaLight_Vertex(i, 1u, P, ltcFrame, quad).z;
    float z2 = AreaLight_Vertex(i, 2u, P, ltcFrame, quad).z;
    float z3 = first.z, z4 = first.z;
    if (four)
        z3 = AreaLight_Vertex(i, 3u, P, ltcFrame, quad).z;
    if (RTPBR_AREA_LIGHT_MAX_VERTICES > 4u && !quad.on && count > 4u)
        z4 = AreaLight_Vertex(i, 4u, P, ltcFrame, quad).z;
    float r1 = 1.0f / (first.z - z1), r2 = 1.0f / (z1 - z2);
    float r3 = 1.0f / (z2 - z3), r4 = 1.0f / (z3 - z4);
#endif
    RTPBR_UNROLL for (uint k = 1u; k <= 4u; ++k)
        if (k < 4u || four)
#if RTPBR_AREA_LIGHT_FULL
            AreaLight_LobeSegment(AreaLight_EdgeStep(i, P, ltcFrame, k, count, first, horizon, a, quad), F, lobe);
#else
            AreaLight_LobeSegment(AreaLight_EdgeStepRecip(i, P, ltcFrame, k, count, first, k == 1u ? r1 : k == 2u ? r2 : k == 3u ? r3 : r4,
                                                          horizon, a, quad), F, lobe);
#endif
    if (RTPBR_AREA_LIGHT_MAX_VERTICES > 4u && count > 4u) {
        rtpbr_float3 v5 = RTPBR_F3(0.0f), v6 = v5, v7 = v5; // (read only below count: the host's contract)
        if (count > 5u) v5 = Host_LightVertex(i, 5u);
        if (count > 6u) v6 = Host_LightVertex(i, 6u);
        if (count > 7u) v7 = Host_LightVertex(i, 7u);
        for (uint k = 5u; k <= count; ++k)
            AreaLight_LobeSegment(AreaLight_EdgeStepTail(P, ltcFrame, k, count, first, v5, v6, v7, horizon, a), F, lobe);
    }
#endif
    AreaLight_LobeSegment(LTC_ClipClose(horizon), F, lobe);
    return AreaLight_LobeClose(lobe, invMass, Fl);
}
RTPBR_FN float AreaLight_Lobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                              RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl) {
    return AreaLight_WalkLobe(i, P, ltcFrame, minv, invMass, F, Fl, AreaLight_NoQuad());
}

#if RTPBR_AREA_LIGHT_SPHERES || RTPBR_AREA_LIGHT_DISKS || RTPBR_AREA_LIGHT_TUBES
// The disk that stands for the sphere (centre xyz, radius w: a sphere light's Host_LightSphere,
// a tube's end) at P, in the LTC frame (LTC_SphereAsDisk's: it fills the sphere's cone, radius
// r d / sqrt(d^2 - r^2) about the axis c): centre c, orthogonal semi-axes u, w; the sphere's exact vector form factor in F
// (sin^2 of its angular radius along the axis, z the cap's horizon-clipped form factor:
// LTC_SphereCapFormFactor). False inside the sphere. The disk's in-plane basis is any (it is
// round): it is taken from the lobe's matrix minv, so that each lobe builds its own and the
// compiler keeps none live across lobes (registers).
RTPBR_FN bool AreaLight_SphereDisk(rtpbr_float4 sphere, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv,
                                   RTPBR_OUT(rtpbr_float3) c, RTPBR_OUT(rtpbr_float3) u, RTPBR_OUT(rtpbr_float3) w,
                                   RTPBR_OUT(rtpbr_float3) F) {
    c = rtpbr_mul(ltcFrame, rtpbr_float3(sphere.x, sphere.y, sphere.z) - P);
    float d2 = dot(c, c);
    float r2 = sphere.w * sphere.w;
    u = RTPBR_F3(0.0f);
    w = RTPBR_F3(0.0f);
    F = rtpbr_float3(0.0f, 0.0f, 1.0f);
    if (!(d2 > r2))
        return false;
    rtpbr_float3 axis = c * rtpbr_rsqrt(d2);
    rtpbr_float3 t = rtpbr_float3(rtpbr_mat3_at(minv, 0, 0), rtpbr_mat3_at(minv, 1, 0), rtpbr_mat3_at(minv, 2, 0));
    t = abs(dot(t, axis)) < 0.9f * length(t) ? t : rtpbr_float3(axis.y, axis.z, axis.x);
    rtpbr_float3 b1 = normalize(cross(t, axis));
    float R = sphere.w * sqrt(d2 / (d2 - r2));
    u = b1 * R;
    w = cross(axis, b1) * R;
    F = axis * (r2 / d2);
    F.z = LTC_SphereCapFormFactor(F);
    return true;
}

#if RTPBR_AREA_LIGHT_SPHERE_CLIP
// The ellipse (c, u, w)'s equal-area RTPBR_AREA_LIGHT_SPHERE_SIDES-gon (circumradius sqrt(2 pi /
// (n sin(2 pi / n))) x the ellipse's), walked one edge at a time through the horizon clip:
// call with k = 1 .. n + 1 and a = c + u x that scale (AreaLight_EllipseGonStart) at first;
// edge k ends at vertex k (vertex n is vertex 0), step n + 1 closes the clipped polygon.
RTPBR_FN float AreaLight_EllipseGonScale(uint sides) {
    const float n = float(sides);
    return sqrt(2.0f * RTPBR_PI / (n * sin(2.0f * RTPBR_PI / n)));
}
RTPBR_FN LtcSegment AreaLight_EllipseGonEdge(RTPBR_INOUT(LtcClipper) horizon, rtpbr_float3 c, rtpbr_float3 u,
                                             rtpbr_float3 w, uint k, uint sides, RTPBR_INOUT(rtpbr_float3) a) {
    if (k > sides)
        return LTC_ClipClose(horizon);
    float phi = 2.0f * RTPBR_PI * float(k) / float(sides);
    rtpbr_float3 b = c + u * cos(phi) + w * sin(phi);
    LtcSegment seg = LTC_ClipEdge(horizon, a, b);
    a = b;
    return seg;
}
#endif

#endif

#if RTPBR_AREA_LIGHT_DISKS
#if RTPBR_AREA_LIGHT_SPHERE_CLIP
// The vector form factor of the ellipse (c, u, w)'s equal-area RTPBR_AREA_LIGHT_DISK_CLIP_SIDES-gon
// clipped by the horizon: a walk of its own, not summed in the lobe's walk (registers: summed
// there, the engine's basic variant took 104 VGPRs on navi21, 96 here), and so with sides of its
// own: 24 (the lobes' 12-gon was 9e-3 of the peak off at a cut disk's rim on a Lambertian
// floor, 16 sides 2.1e-3, 24 and 32 5.3e-4: tests/engine/test_engine_punctual.c, disk_lambert).
// With RTPBR_AREA_LIGHT_CLIP_LOOPS, a loop of steps edges (sides + 1: all; 0: none, F = 0).
RTPBR_FN rtpbr_float3 AreaLight_EllipseClippedVectorSteps(rtpbr_float3 c, rtpbr_float3 u, rtpbr_float3 w, uint steps) {
    const uint sides = uint(RTPBR_AREA_LIGHT_DISK_CLIP_SIDES);
    float scale = AreaLight_EllipseGonScale(sides);
    u *= scale;
    w *= scale;
    LtcClipper horizon = LTC_ClipperBegin();
    rtpbr_float3 F = RTPBR_F3(0.0f), a = c + u;
    if (RTPBR_AREA_LIGHT_CLIP_LOOPS != 0) {
        RTPBR_DONT_UNROLL for (uint k = 1u; k <= steps; ++k) {
            LtcSegment seg = AreaLight_EllipseGonEdge(horizon, c, u, w, k, sides, a);
            if (seg.valid)
                F += LTC_EdgeIntegralOf(seg.a, seg.b);
        }
        return F;
    }
    RTPBR_UNROLL for (uint k = 1u; k <= sides + 1u; ++k) {
        LtcSegment seg = AreaLight_EllipseGonEdge(horizon, c, u, w, k, sides, a);
        if (seg.valid)
            F += LTC_EdgeIntegralOf(seg.a, seg.b);
    }
    return F;
}
RTPBR_FN rtpbr_float3 AreaLight_EllipseClippedVector(rtpbr_float3 c, rtpbr_float3 u, rtpbr_float3 w) {
    return AreaLight_EllipseClippedVectorSteps(c, u, w, uint(RTPBR_AREA_LIGHT_DISK_CLIP_SIDES) + 1u);
}
#endif

// The Lambert vector form factor of the ellipse (c, u, w), without the horizon: with
// RTPBR_AREA_LIGHT_ROUND_DISKS, for a round disk (u, w orthogonal, of one length to 1e-4 of
// their squares) LTC_DiskVector's closed form (no cubic: per disk light on navi21, 3439 -> 3295
// cycles in the engine's basic variant, 2526 -> 2330 in the full one; and exact in float where
// the elliptic cone loses a disk seen edge-on); otherwise, and for an ellipse, the elliptic
// cone's (LTC_EllipseVector under the identity).
RTPBR_FN rtpbr_float3 AreaLight_DiskLambertVector(rtpbr_float3 c, rtpbr_float3 u, rtpbr_float3 w) {
#if RTPBR_AREA_LIGHT_ROUND_DISKS
    float uu = dot(u, u), ww = dot(w, w);
    if (abs(uu - ww) <= 1e-4f * uu)
        return LTC_DiskVector(c, normalize(cross(u, w)), sqrt(uu));
#endif
    return LTC_EllipseVector(LTC_InverseMatrix(LTC_Identity()), c, u, w, true);
}

// Disk light i at P in the LTC frame: its centre c (Host_LightSphere's xyz) and half-axes u, w
// (Host_LightDiskAxis), read again for each lobe (registers, as AreaLight_SphereDisk). F: the
// disk's Lambert vector form factor where it is wholly above the horizon, exact (the cone's
// closed form, LTC_EllipseVector, under the identity); where the horizon cuts it, with
// RTPBR_AREA_LIGHT_SPHERE_CLIP its clipped polygon's (AreaLight_EllipseClippedVector), with 0
// the form factor of the cap with the same vector (the sphere proxy's, as a sphere's lobes).
// True where the horizon cuts it.
RTPBR_FN bool AreaLight_DiskEllipse(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, RTPBR_OUT(rtpbr_float3) c,
                                    RTPBR_OUT(rtpbr_float3) u, RTPBR_OUT(rtpbr_float3) w, RTPBR_OUT(rtpbr_float3) F) {
    rtpbr_float4 sphere = Host_LightSphere(i);
    c = rtpbr_mul(ltcFrame, rtpbr_float3(sphere.x, sphere.y, sphere.z) - P);
    u = rtpbr_mul(ltcFrame, Host_LightDiskAxis(i, 0u));
    w = rtpbr_mul(ltcFrame, Host_LightDiskAxis(i, 1u));
    bool cut = !(c.z >= sqrt(u.z * u.z + w.z * w.z)); // the ellipse spans c.z +- that in z
    F = RTPBR_F3(0.0f);
#if RTPBR_AREA_LIGHT_SPHERE_CLIP
    if (RTPBR_AREA_LIGHT_CLIP_LOOPS != 0) { // (both; the clipped walk's loop empty where not cut)
        rtpbr_float3 Fc = AreaLight_EllipseClippedVectorSteps(c, u, w, cut ? uint(RTPBR_AREA_LIGHT_DISK_CLIP_SIDES) + 1u : 0u);
        F = cut ? Fc : AreaLight_DiskLambertVector(c, u, w);
    } else if (!cut)
        F = AreaLight_DiskLambertVector(c, u, w);
    else
        F = AreaLight_EllipseClippedVector(c, u, w);
#else
    F = AreaLight_DiskLambertVector(c, u, w);
    if (cut)
        F.z = LTC_SphereCapFormFactor(F);
#endif
    return cut;
}
#endif

#if RTPBR_AREA_LIGHT_SPHERES || RTPBR_AREA_LIGHT_DISKS || RTPBR_AREA_LIGHT_TUBES
// AreaLight_SphereLobe's lobe over the ellipse (c, u, w) in the LTC frame (a sphere's disk,
// AreaLight_SphereDisk, or a disk light's, AreaLight_DiskEllipse): its form factor, Fl its
// vector form factor (see there).
RTPBR_FN float AreaLight_EllipseLobe(rtpbr_float3 c, rtpbr_float3 u, rtpbr_float3 w, rtpbr_float3x3 minv, float invMass,
                                     RTPBR_OUT(rtpbr_float3) Fl) {
#if RTPBR_AREA_LIGHT_SPHERE_CLIP
    rtpbr_float3 cl = rtpbr_mul(minv, c), ul = rtpbr_mul(minv, u), wl = rtpbr_mul(minv, w);
    bool cut = !(c.z >= sqrt(u.z * u.z + w.z * w.z) && cl.z >= sqrt(ul.z * ul.z + wl.z * wl.z));
    // (RTPBR_AREA_LIGHT_CLIP_LOOPS: the loop's edges, none where nothing is cut; chosen out here,
    // where the compiler cannot take cut for true)
    uint steps = cut ? uint(RTPBR_AREA_LIGHT_SPHERE_SIDES) + 1u : 0u;
    if (cut) {
        LtcClipper horizon = LTC_ClipperBegin();
        LtcLobe lobe = LTC_LobeBegin(minv);
        float scale = AreaLight_EllipseGonScale(uint(RTPBR_AREA_LIGHT_SPHERE_SIDES));
        u *= scale;
        w *= scale;
        rtpbr_float3 a = c + u;
        if (RTPBR_AREA_LIGHT_CLIP_LOOPS != 0) {
            RTPBR_DONT_UNROLL for (uint k = 1u; k <= steps; ++k) {
                LtcSegment seg = AreaLight_EllipseGonEdge(horizon, c, u, w, k, uint(RTPBR_AREA_LIGHT_SPHERE_SIDES), a);
                if (seg.valid)
                    LTC_LobeEdge(lobe, seg.a, seg.b);
            }
        } else {
            RTPBR_UNROLL for (uint k = 1u; k <= uint(RTPBR_AREA_LIGHT_SPHERE_SIDES) + 1u; ++k) {
                LtcSegment seg = AreaLight_EllipseGonEdge(horizon, c, u, w, k, uint(RTPBR_AREA_LIGHT_SPHERE_SIDES), a);
                if (seg.valid)
                    LTC_LobeEdge(lobe, seg.a, seg.b);
            }
        }
        // (a sphere's F keeps the whole cap's direction, its z the clipped cap's form factor:
        // the clipped polygon's own F, summed here, took the basic variant from 96 to 112 VGPRs;
        // a disk has no such closed form)
        return AreaLight_LobeClose(lobe, invMass, Fl);
    }
#endif
    rtpbr_float3 v = LTC_EllipseVector(minv, c, u, w, true);
    Fl = v.z < 0.0f ? -v : v;
#if RTPBR_AREA_LIGHT_SPHERE_CLIP
    return AreaLight_HorizonFraction(abs(v.z), invMass, minv);
#else
    return AreaLight_HorizonFraction(LTC_SphereCapFormFactor(v), invMass, minv);
#endif
}

// AreaLight_SphereLobe over the sphere (centre xyz, radius w) rather than a light's: a sphere
// light's (Host_LightSphere) or a tube's end.
RTPBR_FN float AreaLight_SphereLobeAt(rtpbr_float4 sphere, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                      RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl) {
    rtpbr_float3 c, u, w;
    if (!AreaLight_SphereDisk(sphere, P, ltcFrame, minv, c, u, w, F)) {
        Fl = F;
        return 1.0f;
    }
    return AreaLight_EllipseLobe(c, u, w, minv, invMass, Fl);
}
#endif

#if RTPBR_AREA_LIGHT_SPHERES || RTPBR_AREA_LIGHT_DISKS
// AreaLight_Lobe over sphere light i, or with diskLight (RTPBR_AREA_LIGHT_DISKS) over disk
// light i (AreaLight_DiskEllipse: the disk itself instead of the sphere's; the rest alike). While the sphere's cone is above the horizon and its
// image under minv above the LTC's own, the disk's closed form (LTC_EllipseVector: exact).
// Across either horizon, with RTPBR_AREA_LIGHT_SPHERE_CLIP (1) the disk's equal-area polygon
// (RTPBR_AREA_LIGHT_SPHERE_SIDES) clipped exactly and integrated (its error against the disk,
// measured); with 0, Heitz & Hill's sphere proxy (the cap of the same vector form factor, clipped by the LTC's
// own horizon: LTC_SphereCapFormFactor), which lights a glossy lobe from the part of the sphere
// below the surface (measured: tests/engine/test_engine_punctual.c, sphere_ggx) but has no
// walk (fewer registers). F: the sphere's exact vector form factor (a disk's: AreaLight_DiskEllipse's, or
// its clipped polygon's where the horizon cuts it). Inside the sphere: 1.
RTPBR_FN float AreaLight_SphereLobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                    RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl RTPBR_AREA_LIGHT_DISK_PARAM) {
#if RTPBR_AREA_LIGHT_DISKS
    if (diskLight) {
        rtpbr_float3 c, u, w;
        AreaLight_DiskEllipse(i, P, ltcFrame, c, u, w, F);
        return AreaLight_EllipseLobe(c, u, w, minv, invMass, Fl);
    }
#endif
    return AreaLight_SphereLobeAt(Host_LightSphere(i), P, ltcFrame, minv, invMass, F, Fl);
}
#endif

#if RTPBR_AREA_LIGHT_TUBES
// AreaLight_Lobe over tube (capsule) light i (Host_LightTube: its ends' centres, its radius)
// seen from P: LTC_EvaluateTube's decomposition, the facing quad (LTC_TubeQuad, walked as a
// polygon through the horizon clip: AreaLight_WalkLobe) and the two end spheres
// (AreaLight_SphereLobeAt), weighted by LTC_TubeWeights w: the form factor, the vector form
// factor F (the quad's oriented to z >= 0) and the lobe's Fl each w.x quad + w.y end 1 + w.z
// end 2 (linear in the emitter, so that every later step sees one consistent emitter). The form
// factor held to 1 (as LTC_EvaluateTube). Inside the capsule: 1, F = Fl = (0, 0, 1). Unlike
// LTC_EvaluateTube, a quad thinner than RTPBR_LTC_TUBE_THIN is walked too (no line branch:
// registers): measured against its line branch, 3.6e-5 relative at a radius of 6e-4 of the
// distance, 3.2e-4 at 6e-5 and 6e-6 (test_area_light.cpp, test_tube_limits).
RTPBR_FN float AreaLight_TubeLobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                  RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl) {
    rtpbr_float4 end1 = Host_LightTube(i, 0u), end2 = Host_LightTube(i, 1u);
    rtpbr_float3 p1 = rtpbr_float3(end1.x, end1.y, end1.z), p2 = rtpbr_float3(end2.x, end2.y, end2.z);
    float radius = end1.w;
    rtpbr_float3 axis = p2 - p1;
    float len2 = dot(axis, axis);
    float h = len2 > 0.0f ? rtpbr_saturate(dot(P - p1, axis) / len2) : 0.0f;
    rtpbr_float3 nearest = p1 + axis * h - P; // the axis' nearest point
    F = rtpbr_float3(0.0f, 0.0f, 1.0f);
    Fl = F;
    if (!(dot(nearest, nearest) > radius * radius))
        return 1.0f;
    rtpbr_float3 wt = LTC_TubeWeights(P, p1, p2, radius);
    F = RTPBR_F3(0.0f);
    Fl = RTPBR_F3(0.0f);
    float ff = 0.0f;
    rtpbr_float3 Fp, Flp;
    if (wt.x > 0.0f) {
        LtcPolygon q = LTC_TubeQuad(P, p1, p2, radius);
        if (q.count > 0) {
            AreaLightQuad quad;
            quad.o = rtpbr_mul(ltcFrame, q.v[0] - P);
            quad.u = rtpbr_mul(ltcFrame, q.v[1] - q.v[0]);
            quad.v = rtpbr_mul(ltcFrame, q.v[3] - q.v[0]);
            quad.on = true;
            ff += wt.x * AreaLight_WalkLobe(i, P, ltcFrame, minv, invMass, Fp, Flp, quad);
            F += (Fp.z < 0.0f ? -Fp : Fp) * wt.x;
            Fl += Flp * wt.x;
        }
    }
    // (registers: one copy of a sphere's lobe for both ends; unrolled, the engine's basic
    // variant over one tube took 104 VGPRs on navi21 instead of 96: bench/shader-stats' _tube)
    RTPBR_DONT_UNROLL for (uint e = 0u; e < 2u; ++e) {
        float we = e == 0u ? wt.y : wt.z;
        if (we > 0.0f) {
            ff += we * AreaLight_SphereLobeAt(e == 0u ? rtpbr_float4(p1, radius) : rtpbr_float4(p2, radius), P, ltcFrame, minv, invMass, Fp, Flp);
            F += Fp * we;
            Fl += Flp * we;
        }
    }
    return min(ff, 1.0f);
}

// The weight of tube light i's part (RTPBR_AREA_LIGHT_TUBE_QUAD, _END1, _END2) at P: its
// LTC_TubeWeights component; inside the capsule, 1 for the quad (AreaLight_TubePartLobe: the
// light fills the view) and 0 for the ends.
RTPBR_FN float AreaLight_TubePartWeight(uint i, uint part, rtpbr_float3 P) {
    rtpbr_float4 end1 = Host_LightTube(i, 0u), end2 = Host_LightTube(i, 1u);
    rtpbr_float3 p1 = rtpbr_float3(end1.x, end1.y, end1.z), p2 = rtpbr_float3(end2.x, end2.y, end2.z);
    rtpbr_float3 axis = p2 - p1;
    float len2 = dot(axis, axis);
    float h = len2 > 0.0f ? rtpbr_saturate(dot(P - p1, axis) / len2) : 0.0f;
    rtpbr_float3 nearest = p1 + axis * h - P;
    if (!(dot(nearest, nearest) > end1.w * end1.w))
        return part == RTPBR_AREA_LIGHT_TUBE_QUAD ? 1.0f : 0.0f;
    rtpbr_float3 wt = LTC_TubeWeights(P, p1, p2, end1.w);
    return part == RTPBR_AREA_LIGHT_TUBE_QUAD ? wt.x : part == RTPBR_AREA_LIGHT_TUBE_END1 ? wt.y : wt.z;
}

// AreaLight_Lobe over one part of tube light i (RTPBR_AREA_LIGHT_TUBE_QUAD: the facing quad,
// walked as AreaLight_TubeLobe walks it, F oriented to z >= 0; _END1, _END2: an end's sphere,
// AreaLight_SphereLobeAt), unweighted (AreaLight_TubePartWeight). Inside the capsule the quad
// gives 1, F = Fl = (0, 0, 1). The three parts weighted and summed are AreaLight_TubeLobe; one
// at a time each holds a quad's or a sphere's state alone (registers: AreaLight_AddShapePart).
RTPBR_FN float AreaLight_TubePartLobe(uint i, uint part, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                      RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl) {
    rtpbr_float4 end1 = Host_LightTube(i, 0u), end2 = Host_LightTube(i, 1u);
    rtpbr_float3 p1 = rtpbr_float3(end1.x, end1.y, end1.z), p2 = rtpbr_float3(end2.x, end2.y, end2.z);
    if (part != RTPBR_AREA_LIGHT_TUBE_QUAD)
        return AreaLight_SphereLobeAt(rtpbr_float4(part == RTPBR_AREA_LIGHT_TUBE_END1 ? p1 : p2, end1.w), P, ltcFrame, minv, invMass, F, Fl);
    rtpbr_float3 axis = p2 - p1;
    float len2 = dot(axis, axis);
    float h = len2 > 0.0f ? rtpbr_saturate(dot(P - p1, axis) / len2) : 0.0f;
    rtpbr_float3 nearest = p1 + axis * h - P;
    F = rtpbr_float3(0.0f, 0.0f, 1.0f);
    Fl = F;
    if (!(dot(nearest, nearest) > end1.w * end1.w))
        return 1.0f;
    F = RTPBR_F3(0.0f);
    Fl = F;
    LtcPolygon q = LTC_TubeQuad(P, p1, p2, end1.w);
    if (q.count == 0)
        return 0.0f;
    AreaLightQuad quad;
    quad.o = rtpbr_mul(ltcFrame, q.v[0] - P);
    quad.u = rtpbr_mul(ltcFrame, q.v[1] - q.v[0]);
    quad.v = rtpbr_mul(ltcFrame, q.v[3] - q.v[0]);
    quad.on = true;
    float ff = AreaLight_WalkLobe(i, P, ltcFrame, minv, invMass, F, Fl, quad);
    F = F.z < 0.0f ? -F : F;
    return ff;
}
#endif

// AreaLight_Lobe, or AreaLight_SphereLobe where sphereLight (RTPBR_AREA_LIGHT_SPHERES; a disk
// where diskLight too, RTPBR_AREA_LIGHT_DISKS): AreaLight_ShapeLobe without a tube's part.
RTPBR_FN float AreaLight_SimpleShapeLobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                         RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl, bool sphereLight RTPBR_AREA_LIGHT_DISK_PARAM) {
#if RTPBR_AREA_LIGHT_SPHERES || RTPBR_AREA_LIGHT_DISKS
    if (sphereLight)
        return AreaLight_SphereLobe(i, P, ltcFrame, minv, invMass, F, Fl RTPBR_AREA_LIGHT_DISK_ARG(diskLight));
#else
    RTPBR_UNUSED(sphereLight);
#endif
    return AreaLight_Lobe(i, P, ltcFrame, minv, invMass, F, Fl);
}

// AreaLight_SimpleShapeLobe, or with RTPBR_AREA_LIGHT_TUBES a tube's part where tubePart is not
// RTPBR_AREA_LIGHT_TUBE_NONE (AreaLight_TubePartLobe; the others then do not matter). (The whole
// tube in one lobe, AreaLight_TubeLobe, is not a case here: in a loop over a tube's parts its
// state joined every part's and took the registers it saves.)
RTPBR_FN float AreaLight_ShapeLobe(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, rtpbr_float3x3 minv, float invMass,
                                   RTPBR_OUT(rtpbr_float3) F, RTPBR_OUT(rtpbr_float3) Fl, bool sphereLight RTPBR_AREA_LIGHT_DISK_PARAM
                                       RTPBR_AREA_LIGHT_TUBE_PART_PARAM) {
#if RTPBR_AREA_LIGHT_TUBES
    if (tubePart != RTPBR_AREA_LIGHT_TUBE_NONE)
        return AreaLight_TubePartLobe(i, tubePart, P, ltcFrame, minv, invMass, F, Fl);
#endif
    return AreaLight_SimpleShapeLobe(i, P, ltcFrame, minv, invMass, F, Fl, sphereLight RTPBR_AREA_LIGHT_DISK_ARG(diskLight));
}

// D V (ndf.h, smith.h: the BRDF with F = 1, without the cosine) for the point correction's two
// directions L, from h = V + L unnormalised (hz = h.z, hh = |h|^2 > 0) and NoL, the view's terms
// given (AreaLightPointDV: alpha clamped and squared, and GGX's height-correlated Smith term of
// the view, taken once per light). With GGX and that Smith term, one division, no root of hh and
// no branch (latency: docs/performance.md, 30); other models: D_Microfacet V_Microfacet. 0
// where hz, NoL or NoV is not above 0 (test_point_dv: against D_Microfacet V_Microfacet).
struct AreaLightPointDV {
    float alpha;
    float NoV;
    float a2;
    float sV; // sqrt(NoV^2 (1 - a2) + a2)
};

RTPBR_FN AreaLightPointDV AreaLight_PointDVBegin(float alpha, float NoV) {
    AreaLightPointDV t;
    t.alpha = alpha;
    t.NoV = NoV;
    t.a2 = rtpbr_sq(Alpha_Clamp(alpha));
    float v = min(NoV, 1.0f);
    t.sV = sqrt(v * v * (1.0f - t.a2) + t.a2);
    return t;
}

RTPBR_FN float AreaLight_PointDV(AreaLightPointDV t, float hz, float hh, float NoL) {
#if RTPBR_NDF == RTPBR_NDF_GGX && RTPBR_SMITH == RTPBR_SMITH_HEIGHT_CORRELATED && !RTPBR_SMITH_FAST
    // D_GGX x V_SmithGGXCorrelated, from h unnormalised (NoH^2 = hz^2 / hh, no root): with
    // q = hh + (a2 - 1) hz^2 = hh ((a2 - 1) NoH^2 + 1), D = a2 hh^2 / (pi q^2); V = 0.5 / (l sV + v sL)
    float l = min(NoL, 1.0f), v = min(t.NoV, 1.0f);
    float q = (t.a2 - 1.0f) * (hz * hz) + hh;
    float sL = sqrt(l * l * (1.0f - t.a2) + t.a2);
    float den = (RTPBR_PI * q) * (q * (l * t.sV + v * sL));
    float dv = (0.5f * t.a2) * (hh * hh) / den;
    return hz > 0.0f && NoL > 0.0f && t.NoV > 0.0f ? dv : 0.0f;
#else
    return D_Microfacet(hz * rtpbr_rsqrt(hh), t.alpha) * V_Microfacet(t.NoV, NoL, t.alpha);
#endif
}

// The specular lobe's LTC result ltcFF corrected (ltc_corrections.h): the point correction
// (LTC_PointFactor: the true f NoL (F = 1, the lobe the tables were fitted to) at the centre of
// the part of the light the LTC sees, against the LTC's value there, the table's norm x its
// density) or, for a light in the LTC's tail, the tail estimate (LTC_PointTail: f at the
// direction of the light's vector form factor F x pi x its form factor ff), whichever is larger
// (LTC_PointCombine); lenF = |F| (LTC_PointWidthRatio).
// tableRoughness: ShadingSurface's, resolved (in [RTPBR_MATERIAL_MIN_ROUGHNESS, 1]: squared as is).
RTPBR_FN float AreaLight_SpecularCorrected(rtpbr_float3 Fl, rtpbr_float4 ltc1, float invMass, float norm, float NoV, float tableRoughness,
                                           float ltcFF, rtpbr_float3 F, float ff, float lenF) {
    // recomputed here rather than kept live through the light loop
    float alpha = tableRoughness * tableRoughness;
    rtpbr_float3 vLocal = rtpbr_float3(sqrt(max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);
    AreaLightPointDV dvView = AreaLight_PointDVBegin(alpha, NoV);
    LtcPoint pt = LTC_LobePointInvMass(Fl, ltc1, invMass);
    float weight = LTC_PointTailWeight(Fl, ltcFF, ff);
    float NoL = pt.dir.z;
    rtpbr_float3 h = vLocal + pt.dir;
    float hh = dot(h, h);
    float fCos = hh > 1e-12f
                     ? AreaLight_PointDV(dvView, h.z, hh, NoL) * NoL
                     : 0.0f;
    float corrected =
        ltcFF * LTC_PointFactor(fCos, norm * pt.density, ltcFF, LTC_PointWidthRatio(alpha, sqrt(hh), lenF));
    float tail = 0.0f;
    if (weight > 0.0f) {
        rtpbr_float3 c = F / lenF;
        rtpbr_float3 hc = vLocal + c;
        float hc2 = dot(hc, hc);
        float f = hc2 > 1e-12f
                      ? AreaLight_PointDV(dvView, hc.z, hc2, c.z)
                      : 0.0f;
        tail = LTC_PointTail(f, ff, norm);
    }
    return LTC_PointCombine(corrected, tail, weight);
}

// ltc1 = (m00, m02, m20, m22) of an isotropic lobe's M^-1 (LTC_InverseMatrix): read back from
// the matrix, so that ltc1 need not stay live through the light loop.
RTPBR_FN rtpbr_float4 AreaLight_IsotropicLtc1(rtpbr_float3x3 minv) {
    return rtpbr_float4(rtpbr_mat3_at(minv, 0, 0), rtpbr_mat3_at(minv, 0, 2), rtpbr_mat3_at(minv, 2, 0),
                        rtpbr_mat3_at(minv, 2, 2));
}

// Per-point setup for surface s seen from V with shading normal N (unit): the tables' values
// at NoV (through the host's Host_TableLtc1/2), the specular lobe's matrix (stretched when
// anisotropic) and Fresnel scale, the other lobes' (RTPBR_AREA_LIGHT_FULL).
RTPBR_FN AreaLightPixel AreaLight_Begin(ShadingSurface s, rtpbr_float3 N, rtpbr_float3 V) {
    AreaLightPixel px;
    rtpbr_float2 uv = LTC_LutCoord(s.NoV, s.tableRoughness);
    rtpbr_float4 ltc1 = Host_TableLtc1(RTPBR_TABLE_LTC_SPECULAR, uv);
    rtpbr_float4 ltc2 = Host_TableLtc2(RTPBR_TABLE_LTC_SPECULAR, uv);
    px.specularScale = LTC_FresnelScale(ltc2, s.f0, s.f90);
    px.frame = LTC_Frame(N, V);
    px.specularMinv = LTC_InverseMatrix(ltc1);
    px.vLocal = rtpbr_float3(sqrt(max(1.0f - s.NoV * s.NoV, 0.0f)), 0.0f, s.NoV);
    // The point correction and tail estimate (AreaLight_SpecularCorrected) on the isotropic
    // specular lobe: the table's norm, and whether the lobe is isotropic.
    px.pointNorm = ltc2.x;
    px.pointOn = RTPBR_LTC_POINT_CORRECTION != 0;
    px.coated = false;
    px.ltc1c = LTC_Identity();
    px.coatScale = RTPBR_F3(0.0f);
    px.ltc1b = LTC_Identity();
    px.baseParams = rtpbr_float4(s.specularWeight, s.EFavg, s.FmsDielectric, s.sheenRoughness);
    px.baseColors = rtpbr_float4(s.sheenColor.x, s.sheenColor.y, s.sheenColor.z, s.EsheenO);
    px.sheenScale = RTPBR_F3(0.0f);
    px.baseScale = s.diffuseColor * KC_PolygonLobe(s.Eso, 0.0f, s.EsAvg, 1.0f);
#if RTPBR_AREA_LIGHT_FULL
    px.coated = s.coat > 0.0f;
    if (px.coated) {
        rtpbr_float2 uvc = LTC_LutCoord(s.NoV, s.coatRoughness);
        px.ltc1c = Host_TableLtc1(RTPBR_TABLE_LTC_SPECULAR, uvc);
        px.coatScale = s.coat * LTC_FresnelScale(Host_TableLtc2(RTPBR_TABLE_LTC_SPECULAR, uvc),
                                                 RTPBR_F3(RTPBR_MATERIAL_COAT_F0), 1.0f);
    }
    // Burley's diffuse (Disney): its LTC fit, column = the material's roughness.
    if (s.disney) {
        rtpbr_float2 uvd = LTC_LutCoord(s.NoV, s.roughness);
        px.ltc1b = Host_TableLtc1(RTPBR_TABLE_LTC_DISNEY_DIFFUSE, uvd);
        px.baseScale = ((1.0f - s.dm.subsurface) * Host_TableLtc2(RTPBR_TABLE_LTC_DISNEY_DIFFUSE, uvd).x) *
                         s.diffuseColor;
        px.baseParams = rtpbr_float4(s.dm.roughness, s.dm.metallic, s.dm.subsurface, s.dm.sheen);
        px.baseColors = rtpbr_float4(s.dm.baseColor.x, s.dm.baseColor.y, s.dm.baseColor.z, s.dm.sheenTint);
    }
    // KHR sheen: its LTC fit (sheen.h); the layer below is scaled by the KHR albedo scaling
    // with E_sheen at NoV and at the polygon's representative direction. Not on a Disney
    // material (Surface_Resolve never makes one with it: Disney's sheen is its own lobe), whose
    // registers it would share.
    if (s.sheen && !s.disney) {
        rtpbr_float2 uvs = LTC_LutCoord(s.NoV, s.sheenRoughness);
        px.ltc1b = Host_TableLtc1(RTPBR_TABLE_LTC_SHEEN, uvs);
        px.sheenScale = Sheen_LtcScale(Host_TableLtc2(RTPBR_TABLE_LTC_SHEEN, uvs), s.sheenColor);
    }
    // The anisotropic stretch about the mirror direction (LTC_AnisotropicInverseMatrix): the
    // anisotropy direction made orthogonal to it; no stretch without one.
    rtpbr_float3 mirror = rtpbr_float3(-px.vLocal.x, 0.0f, px.vLocal.z);
    rtpbr_float3 anisoLocal = rtpbr_mul(px.frame, s.anisoDir);
    rtpbr_float3 e1 = anisoLocal - mirror * dot(anisoLocal, mirror);
    float e1Length = length(e1);
    if (s.anisoK > 1.0001f && e1Length > 1e-4f) {
        px.specularMinv = LTC_AnisotropicInverseMatrix(ltc1, mirror, e1 / e1Length, s.anisoK);
        px.specularScale *= LTC_AnisotropicAlbedoScale(ltc1, px.specularMinv);
        px.pointOn = false; // no point correction for anisotropic lobes
    }
#endif
    // The multiple-scattering lobe: with RTPBR_KC_SHAPE the shaped lobe (kulla_conty.h,
    // KC_PolygonLobeShaped): beta (1 - Eo) x the specular lobe's corrected form factor, which
    // joins the specular term's scale, plus (1 - beta) x the separable lobe.
#if RTPBR_KC_SHAPE
    float kcBeta = KC_ShapeWeight(s.tableRoughness, s.NoV);
    px.specularScale += s.msColor * (kcBeta * rtpbr_pos(1.0f - s.Eo));
    px.msColor = s.msColor * (1.0f - kcBeta);
#else
    px.msColor = s.msColor;
#endif
#if RTPBR_AREA_LIGHT_INV_MASS_PER_POINT
    px.specularInvMass = LTC_InverseHorizonMass(px.specularMinv);
#else
    px.specularInvMass = -1.0f; // (registers: each walk takes its own, docs/performance.md, 30)
#endif
    px.msScale = KC_PolygonLobe(s.Eo, 0.0f, s.Eavg, 1.0f);
    return px;
}

#if RTPBR_AREA_LIGHT_PUNCTUAL
// Punctual light i (shape, punctual.h) at P: exact, the surface's BRDF (Surface_Evaluate) in
// the direction of the light, added to sum (AreaLight_Add: AreaLightSum.punctual; a host
// summing punctual lights apart, RTPBR_AREA_LIGHT_PUNCTUAL 2, passes its own, which is not held
// to the polygons' energy bound either). frame: LTC_Frame(N, V) (AreaLightPixel's), the BRDF's
// local frame (z = N) for isotropic lobes; an anisotropic lobe's is turned about N to its
// direction.
RTPBR_FN void AreaLight_AddPunctual(RTPBR_INOUT(rtpbr_float3) sum, ShadingSurface s, rtpbr_float3x3 frame,
                                    rtpbr_float3 P, uint i, uint shape) {
    rtpbr_float4 incident = Punctual_Incident(P, shape, Host_LightPosition(i), Host_LightDirection(i), Host_LightSpotCone(i));
    rtpbr_float3 wi = rtpbr_mul(frame, rtpbr_float3(incident.x, incident.y, incident.z));
    if (!(wi.z > 0.0f && incident.w > 0.0f)) return;
    rtpbr_float3 wo = rtpbr_float3(sqrt(max(1.0f - s.NoV * s.NoV, 0.0f)), 0.0f, s.NoV);
#if RTPBR_AREA_LIGHT_FULL
    rtpbr_float3 t = rtpbr_mul(frame, s.anisoDir);
    float tl2 = t.x * t.x + t.y * t.y;
    if (s.anisoK > 1.0f && tl2 > 1e-10f) {
        rtpbr_float2 tx = rtpbr_float2(t.x, t.y) * rtpbr_rsqrt(tl2); // B = N x T = (-t.y, t.x, 0)
        wo = rtpbr_float3(wo.x * tx.x + wo.y * tx.y, wo.y * tx.x - wo.x * tx.y, wo.z);
        wi = rtpbr_float3(wi.x * tx.x + wi.y * tx.y, wi.y * tx.x - wi.x * tx.y, wi.z);
    }
#endif
#if RTPBR_AREA_LIGHT_FULL
    rtpbr_float3 f = Surface_EvaluateLobes(s, wo, wi, true);
#else
    rtpbr_float3 f = Surface_EvaluateLobes(s, wo, wi, false); // the lobes AreaLight_Add integrates
#endif
    sum += Host_LightRadiance(i) * f * (wi.z * incident.w) * Host_LightVisibility(i);
}
#endif

#if RTPBR_AREA_LIGHT_TEXTURED
// Textured quad i's emission factor at the point of its Lambert vector (the whole quad's,
// unclipped: four edges, no other state) from P, in the LTC frame ltcFrame (Host_LightTexture at
// LTC_TextureLookup's point and footprint).
RTPBR_FN rtpbr_float3 AreaLight_TexturedQuadLambert(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame) {
    rtpbr_float3 v0 = Host_LightVertex(i, 0u);
    rtpbr_float3 F = RTPBR_F3(0.0f);
    rtpbr_float3 a = LTC_SafeNormalize(rtpbr_mul(ltcFrame, v0 - P));
    rtpbr_float3 first = a;
    RTPBR_UNROLL for (uint k = 1u; k <= 4u; ++k) {
        rtpbr_float3 b = k < 4u ? LTC_SafeNormalize(rtpbr_mul(ltcFrame, Host_LightVertex(i, k) - P)) : first;
        F += LTC_EdgeIntegral(a, b);
        a = b;
    }
    return Host_LightTexture(i, LTC_TextureLookup(ltcFrame, P, v0, Host_LightVertex(i, 1u) - v0,
                                                  Host_LightVertex(i, 3u) - v0, LTC_InverseMatrix(LTC_Identity()), F));
}
#endif

// Light i's reflected radiance at P (x its radiance and visibility) added to acc; nothing when
// the light cannot contribute: P on its plane, behind a one-sided light, its bounding sphere
// below the horizon, or nothing of it above the horizon. Every lobe's polygon integral: LTC
// (ltc.h) for the specular lobes and Burley's diffuse, the clipped polygon's vector form
// factor F for Lambert, Kulla-Conty (kulla_conty.h) for the multiple-scattering lobes and the
// dielectric-over-diffuse layering: separable lobes (f_ms, the layered base) integrate as
// (1 - E(mu_o)) / (1 - E_avg) x the form factor x (1 - the cosine-weighted mean of E over the
// polygon), from E at the representative direction (F's) widened towards E_avg with the
// polygon's size (KC_PolygonLobe, KC_PolygonMeanE). Disney's subsurface shape and sheen are
// evaluated at the representative direction x pi x the form factor; its GTR1 coat is
// integrated as GGX at the same alpha.
// AreaLight_AddShape: AreaLight_Add for a polygon, AreaLight_AddSphere where sphereLight
// (RTPBR_AREA_LIGHT_SPHERES), which may vary at run time: a loop over both kinds of light calls
// it once (one copy of the evaluation's code; but the disk's state then lives beside the
// polygon's: in the engine's full variant that spilled, so the engine calls the two in loops
// of their own, docs/performance.md, 12). With RTPBR_AREA_LIGHT_DISKS, AreaLight_AddDisk where
// the last flag, diskLight (sphereLight then does not matter).
// AreaLight_AddSimpleShape: AreaLight_AddShape without its last flag, tubeLight (a polygon, a
// sphere, a disk or a textured quad: a host that lights its tubes in a loop of their own calls
// it in its loops over the other kinds, and none of them carries a tube's code).
// AreaLight_AddTubePart: one part of a tube light (tubePart, RTPBR_AREA_LIGHT_TUBE_QUAD, _END1,
// _END2; any other value is lit as _END2; AreaLight_AddTube calls it for each).
// AreaLight_AddPolygonShape: a polygon, textured where texturedLight (RTPBR_AREA_LIGHT_TEXTURED;
// AreaLight_Add, AreaLight_AddTexturedQuad). AreaLight_AddRoundShape: a sphere, a disk where
// diskLight (RTPBR_AREA_LIGHT_SPHERES or _DISKS; AreaLight_AddSphere, AreaLight_AddDisk).
// AreaLight_AddShapePart: AreaLight_AddSimpleShape or AreaLight_AddTubePart, by tubePart at run
// time (RTPBR_AREA_LIGHT_TUBE_NONE: the first).
// The four are one body (area_light_part.inl) compiled once for each, each with only its own
// shapes' lobes: the same results, a fraction of the compile time (a driver inlines every call
// before it folds the flags: docs/performance.md, "Pipeline compile time").
#define RTPBR_AREA_LIGHT_KIND_ANY 0
#define RTPBR_AREA_LIGHT_KIND_POLYGON 1
#define RTPBR_AREA_LIGHT_KIND_ROUND 2
#define RTPBR_AREA_LIGHT_KIND_TUBE 3
#define RTPBR_AREA_LIGHT_PART_FN AreaLight_AddSimpleShape
#define RTPBR_AREA_LIGHT_PART_KIND RTPBR_AREA_LIGHT_KIND_ANY
#include "area_light_part.inl"
#define RTPBR_AREA_LIGHT_PART_FN AreaLight_AddPolygonShape
#define RTPBR_AREA_LIGHT_PART_KIND RTPBR_AREA_LIGHT_KIND_POLYGON
#include "area_light_part.inl"
#if RTPBR_AREA_LIGHT_SPHERES || RTPBR_AREA_LIGHT_DISKS
#define RTPBR_AREA_LIGHT_PART_FN AreaLight_AddRoundShape
#define RTPBR_AREA_LIGHT_PART_KIND RTPBR_AREA_LIGHT_KIND_ROUND
#include "area_light_part.inl"
#endif
#if RTPBR_AREA_LIGHT_TUBES
#define RTPBR_AREA_LIGHT_PART_FN AreaLight_AddTubePart
#define RTPBR_AREA_LIGHT_PART_KIND RTPBR_AREA_LIGHT_KIND_TUBE
#include "area_light_part.inl"
#endif

RTPBR_FN void AreaLight_AddShapePart(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                     rtpbr_float3 N, uint i, bool sphereLight RTPBR_AREA_LIGHT_DISK_PARAM
                                         RTPBR_AREA_LIGHT_TEXTURE_PARAM RTPBR_AREA_LIGHT_TUBE_PART_PARAM) {
#if RTPBR_AREA_LIGHT_TUBES
    if (tubePart != RTPBR_AREA_LIGHT_TUBE_NONE) {
        AreaLight_AddTubePart(px, acc, s, P, N, i, tubePart);
        return;
    }
#endif
    AreaLight_AddSimpleShape(px, acc, s, P, N, i, sphereLight RTPBR_AREA_LIGHT_DISK_ARG(diskLight) RTPBR_AREA_LIGHT_TEXTURE_ARG(texturedLight));
}

#if RTPBR_AREA_LIGHT_TUBES
// Tube (capsule) light i's reflected radiance at P (x its radiance and visibility) added to acc,
// as AreaLight_Add's for a polygon: LTC_EvaluateTube's decomposition, the facing quad and the
// end spheres weighted by LTC_TubeWeights, each part lit as a light of its own (its radiance x
// its weight: AreaLight_AddTubePart), every lobe with Kulla-Conty and the energy bound, the point
// correction in the metallic-roughness evaluation (RTPBR_AREA_LIGHT_FULL 0; not in the full one:
// as a sphere's); no streak estimate, no range window without RTPBR_AREA_LIGHT_TUBE_RANGE. Every
// lobe's form factor is the sum of the parts' (AreaLight_TubeLobe's); the corrections are each
// part's. Nothing when the tube is wholly below the horizon. A point inside the capsule sees only
// the light.
// The parts (three lights, each of its part's radiance times its weight, each corrected on its
// own: Kulla-Conty's mean albedo, the point correction) in a loop: one copy of the evaluation for
// the three. A tube then costs up to three lights' time but a quad's or a sphere's registers (its
// parts summed in one lobe, AreaLight_TubeLobe, took the engine's basic variant to 112 VGPRs on
// navi21 and spilled the full one on gfx1100). RTPBR_AREA_LIGHT_TUBE_UNROLL: three calls.
// Error: LTC_EvaluateTube's (ltc_lines.h: its ends), plus the LTC fit's.
RTPBR_FN void AreaLight_AddTube(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                rtpbr_float3 N, uint i) {
#if RTPBR_AREA_LIGHT_TUBE_UNROLL
    // (three calls, each with its part known: an unroll hint is only a hint, and Mesa's
    // llvmpipe left the loop as it was, every part running every part's code)
    AreaLight_AddTubePart(px, acc, s, P, N, i, RTPBR_AREA_LIGHT_TUBE_QUAD);
    AreaLight_AddTubePart(px, acc, s, P, N, i, RTPBR_AREA_LIGHT_TUBE_END1);
    AreaLight_AddTubePart(px, acc, s, P, N, i, RTPBR_AREA_LIGHT_TUBE_END2);
#else
    RTPBR_DONT_UNROLL for (uint part = RTPBR_AREA_LIGHT_TUBE_QUAD; part <= RTPBR_AREA_LIGHT_TUBE_END2; ++part)
        AreaLight_AddTubePart(px, acc, s, P, N, i, part);
#endif
}
#endif

// AreaLight_AddSimpleShape, or with RTPBR_AREA_LIGHT_TUBES and tubeLight AreaLight_AddTube.
// tubeLight known at compile time leaves one of the two paths; a run-time flag keeps both (two
// copies of the evaluation: a loop over the parts for every light kept every tube branch in
// every other light's code, 3x the instructions of the engine's variants).
RTPBR_FN void AreaLight_AddShape(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                 rtpbr_float3 N, uint i, bool sphereLight RTPBR_AREA_LIGHT_DISK_PARAM
                                     RTPBR_AREA_LIGHT_TEXTURE_PARAM RTPBR_AREA_LIGHT_TUBE_PARAM) {
#if RTPBR_AREA_LIGHT_TUBES
    if (tubeLight) {
        AreaLight_AddTube(px, acc, s, P, N, i);
        return;
    }
#endif
    AreaLight_AddSimpleShape(px, acc, s, P, N, i, sphereLight RTPBR_AREA_LIGHT_DISK_ARG(diskLight) RTPBR_AREA_LIGHT_TEXTURE_ARG(texturedLight));
}

// Polygon light i's reflected radiance at P (x its radiance and visibility) added to acc
// (AreaLight_AddShape above); with RTPBR_AREA_LIGHT_PUNCTUAL 1, a punctual light's.
RTPBR_FN void AreaLight_Add(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                           rtpbr_float3 N, uint i) {
#if RTPBR_AREA_LIGHT_PUNCTUAL == 1
    uint shape = Host_LightShape(i);
    if (shape != 0u) {
        AreaLight_AddPunctual(acc.punctual, s, px.frame, P, i, shape);
        return;
    }
#endif
    AreaLight_AddPolygonShape(px, acc, s, P, N, i RTPBR_AREA_LIGHT_TEXTURE_ARG(false));
}

#if RTPBR_AREA_LIGHT_SPHERES
// Sphere light i's reflected radiance at P (x its radiance, range window and visibility) added
// to acc, as AreaLight_Add's for a polygon: every lobe over the sphere's cone (AreaLight_ShapeLobe),
// with Kulla-Conty and the energy bound, the point correction in the metallic-roughness
// evaluation (RTPBR_AREA_LIGHT_FULL 0; not in the full one); no streak estimate. Nothing when
// the sphere is wholly below the horizon. A point inside the sphere sees only the light.
RTPBR_FN void AreaLight_AddSphere(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                  rtpbr_float3 N, uint i) {
    AreaLight_AddRoundShape(px, acc, s, P, N, i RTPBR_AREA_LIGHT_DISK_ARG(false));
}
#endif

#if RTPBR_AREA_LIGHT_DISKS
// Disk (or ellipse) light i's reflected radiance at P (x its radiance and visibility) added
// to acc, as AreaLight_Add's for a polygon: every lobe over the disk itself (AreaLight_ShapeLobe:
// the ellipse's closed form while it is above the horizon and its image above the LTC's, its
// equal-area RTPBR_AREA_LIGHT_SPHERE_SIDES-gon clipped exactly across either), the diffuse
// lobe's vector form factor exact above the horizon, Kulla-Conty and the energy bound, the point
// correction in the metallic-roughness evaluation (RTPBR_AREA_LIGHT_FULL 0; not in the full one:
// as a sphere's); no streak estimate. Nothing on its plane, behind a one-sided disk or when it
// is wholly below the horizon.
RTPBR_FN void AreaLight_AddDisk(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                rtpbr_float3 N, uint i) {
    AreaLight_AddRoundShape(px, acc, s, P, N, i RTPBR_AREA_LIGHT_DISK_ARG(true));
}
#endif

#if RTPBR_AREA_LIGHT_TEXTURED
// Textured quad light i's reflected radiance at P (x its radiance, its texture where each lobe
// looks, and its visibility) added to acc, as AreaLight_Add's for a polygon, each lobe's result
// times the host's prefiltered emission texture (Host_LightTexture) at the point where the
// lobe's vector form factor meets the quad (LTC_TextureLookup; the footprint picks the blur).
// Metallic-roughness evaluation: the specular lobe's (and its multiple scattering's) at its
// own, the diffuse lobe's at the Lambert vector's. Full evaluation (registers): one texel for
// every lobe of the base at the unclipped quad's Lambert point, the coat's at its own. No
// streak estimate (it would read the untextured radiance).
// Error: ltc_textured.h's (one blurred read per lobe stands for the lobe's weighted mean of the
// emission over the quad).
RTPBR_FN void AreaLight_AddTexturedQuad(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s,
                                        rtpbr_float3 P, rtpbr_float3 N, uint i) {
    AreaLight_AddPolygonShape(px, acc, s, P, N, i RTPBR_AREA_LIGHT_TEXTURE_ARG(true));
}
#endif


#if RTPBR_AREA_LIGHT_STREAK
// The streak estimate (ltc_corrections.h, LTC_StreakEnd) of light i's specular lobe: two more
// passes over its horizon-clipped edges, one for its vector form factor F and its elevations,
// one for the chords through the nodes. Returns the estimate (F = 1), its weight
// (LTC_StreakWeight x its trust) and V.h at the streak; (-1, 0, .) for none. tableRoughness:
// ShadingSurface's (resolved: squared as is).
RTPBR_FN rtpbr_float3 AreaLight_StreakEstimate(uint i, rtpbr_float3 P, rtpbr_float3x3 ltcFrame, float NoV, float tableRoughness) {
    uint count = Host_LightVertexCount(i);
    rtpbr_float3 vLocal = rtpbr_float3(sqrt(max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);
    rtpbr_float3 F = RTPBR_F3(0.0f);
    LtcStreak st = LTC_StreakBegin();
    RTPBR_DONT_UNROLL for (int pass = 0; pass < 2; ++pass) {
        LtcClipper horizon = LTC_ClipperBegin();
        rtpbr_float3 first = rtpbr_mul(ltcFrame, Host_LightVertex(i, 0u) - P);
        rtpbr_float3 a = first;
        for (uint k = 1u; k <= count + 1u; ++k) {
            LtcSegment seg;
            if (k <= count)
                seg = AreaLight_EdgeStep(i, P, ltcFrame, k, count, first, horizon, a, AreaLight_NoQuad());
            else
                seg = LTC_ClipClose(horizon);
            if (seg.valid) {
                if (pass == 0) {
                    F += LTC_EdgeIntegralOf(seg.a, seg.b);
                    LTC_StreakEdge(st, seg.a, seg.b);
                } else {
                    LTC_StreakChordEdge(st, seg.a, seg.b);
                }
            }
        }
        if (pass == 0) {
            LTC_StreakNodes(st, F);
            // no trust whatever the chords (LTC_StreakSpan): neither the second pass nor the end
            // (docs/performance.md, 29)
            if (!LTC_StreakSpanTrusted(LTC_StreakSpan(st, vLocal, tableRoughness * tableRoughness)))
                return rtpbr_float3(-1.0f, 0.0f, 0.0f);
        }
    }
    rtpbr_float2 e = LTC_StreakEnd(st, vLocal, tableRoughness * tableRoughness);
    return rtpbr_float3(e.x, e.y * LTC_StreakWeight(vLocal, F), LTC_StreakVoH(st, vLocal));
}
#endif

// The point's reflected radiance after the last AreaLight_Add.
// Energy conservation across lights: each light's specular result is a share of the lobe's
// mass (LTC_LobeEnd divides by the horizon's), and over disjoint lights the shares of the true
// lobe sum to at most 1; the point correction and the tail estimate correct each light on its
// own, so over lights that surround the point their shares summed past 1 (1.02-1.04 in the
// furnace). Where they do, the whole sum is scaled back to a mass of 1: the other lobes lose
// the same fraction 1 - 1 / mass at such points, up to 4 % in the furnace. Not in the full
// evaluation, whose point correction runs only for lights holding under half the lobe's mass
// (registers: docs/performance.md, 5).
// Then the streak estimate for one light per point (where little else is live): the light's
// specular term moved from specularScale x streakFF toward F(V.h) x the estimate by its weight
// (Schlick's Fresnel at the streak, the tables' Fresnel model).
RTPBR_FN rtpbr_float3 AreaLight_End(AreaLightPixel px, AreaLightSum acc, ShadingSurface s, rtpbr_float3 P) {
    rtpbr_float3 sum = acc.sum;
#if !RTPBR_AREA_LIGHT_STREAK
    RTPBR_UNUSED(px);
    RTPBR_UNUSED(s);
    RTPBR_UNUSED(P);
#endif
#if RTPBR_LTC_POINT_CORRECTION && !RTPBR_AREA_LIGHT_FULL
    if (acc.specularMass > 1.0f) sum *= 1.0f / acc.specularMass;
#endif
#if RTPBR_AREA_LIGHT_PUNCTUAL
    sum += acc.punctual;
#endif
#if RTPBR_AREA_LIGHT_STREAK
    if (RTPBR_AREA_LIGHT_STREAK_ON != 0 && acc.streakLight != RTPBR_AREA_LIGHT_NONE) {
        rtpbr_float3 e = AreaLight_StreakEstimate(acc.streakLight, P, px.frame, s.NoV, s.tableRoughness);
        if (e.x >= 0.0f && e.y > 0.0f && px.pointNorm > 0.0f) {
            // specularScale = the Fresnel scale f0 (ltc2.x - ltc2.y) + f90 ltc2.y
            // (LTC_FresnelScale) + the shaped multiple-scattering lobe's part folded into it by
            // AreaLight_Begin, msColor beta / (1 - beta) (1 - Eo) (msColor being s.msColor
            // (1 - beta)); f0 from there and the table's texel fetched again (registers:
            // docs/performance.md, 4). Where 1 - beta is too small to split them, the tables'
            // Fresnel scale as it is.
            rtpbr_float3 next = px.specularScale * (e.x / px.pointNorm);
#if RTPBR_KC_SHAPE
            float beta = KC_ShapeWeight(s.tableRoughness, s.NoV);
            rtpbr_float3 msShaped = px.msColor * (beta / max(1.0f - beta, 1e-3f) * rtpbr_pos(1.0f - s.Eo));
            bool split = 1.0f - beta > 1e-3f;
#else
            rtpbr_float3 msShaped = RTPBR_F3(0.0f);
            bool split = true;
#endif
            if (split) {
                rtpbr_float4 t2 = Host_TableLtc2(RTPBR_TABLE_LTC_SPECULAR, LTC_LutCoord(s.NoV, s.tableRoughness));
                rtpbr_float3 f0 = (px.specularScale - msShaped - s.f90 * t2.y) / max(t2.x - t2.y, 1e-6f);
                next = F_Schlick(f0, s.f90, e.z) * e.x + msShaped * (e.x / px.pointNorm);
            }
            sum += Host_LightRadiance(acc.streakLight) * ((next - px.specularScale * acc.streakFF) * e.y) *
                   Host_LightVisibility(acc.streakLight);
        }
    }
#endif
    return sum;
}

// One light alone: its reflected radiance at P (AreaLight_Begin, _Add, _End with one light).
RTPBR_FN rtpbr_float3 AreaLight_Evaluate(ShadingSurface s, rtpbr_float3 P, rtpbr_float3 N, rtpbr_float3 V, uint light) {
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    AreaLightSum acc = AreaLight_SumBegin();
    AreaLight_Add(px, acc, s, P, N, light);
    return AreaLight_End(px, acc, s, P);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_AREA_LIGHT_H
