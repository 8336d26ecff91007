// rtpbr shader library: punctual lights (glTF KHR_lights_punctual): point, spot, directional.
//
// A punctual light has no size, so its reflected radiance is exact, with no integral: at a
// point P with BRDF f, seen from wo,
//   point, spot:  Lo = f(wo, L) max(N.L, 0) I W(d) S(cd) / d^2,  L = (position - P) / d,
//   directional:  Lo = f(wo, L) max(N.L, 0) E,                   L = -direction,
// I the intensity (candela in glTF; here the renderer's radiance unit x m^2), E the
// illuminance (lux), W the range window and S the spot's falloff, both the extension's
// recommended forms (KhronosGroup/glTF, extensions/2.0/Khronos/KHR_lights_punctual):
//   W(d) = clamp(1 - (d / range)^4, 0, 1), 1 without a range,
//   S(cd) = t^2, t = clamp((cd - cos outer) / max(cos inner - cos outer, 1e-3), 0, 1),
//   cd = direction . (-L), the cosine from the spot's axis.
// The BRDF is the surface's, per direction (surface.h, Surface_Evaluate); area_light.h adds
// punctual lights to the same sum as polygons (RTPBR_AREA_LIGHT_PUNCTUAL).
//
// A light is given as the host stores it (one layout for the three; what the host bridge of
// area_light.h returns):
//   shape     RTPBR_PUNCTUAL_POINT, _SPOT or _DIRECTIONAL
//   position  xyz, w = 1 / range^2 (0: no range)
//   direction xyz: unit, the way the light travels (spot, directional)
//   cone      (cos outer, 1 / max(cos inner - cos outer, 1e-3)) (Punctual_SpotCone); a point
//             light's (-2, 1) makes S = 1 everywhere
//
// Public functions
//   Punctual_SpotCone      the cone pair from the spot's angles (host side, once per light)
//   Punctual_RangeWindow   W from d^2 and 1 / range^2
//   Punctual_SpotFalloff   S from cd and the cone pair
//   Punctual_Incident      L and the factor I multiplies (W S / d^2, or 1) at P
#ifndef RTPBR_PUNCTUAL_H
#define RTPBR_PUNCTUAL_H

#include "lang.h"
#include "config.h"

// The shapes (the values of the engine's light records, rtpbr_light_type).
#define RTPBR_PUNCTUAL_POINT 1
#define RTPBR_PUNCTUAL_SPOT 2
#define RTPBR_PUNCTUAL_DIRECTIONAL 3

RTPBR_NAMESPACE_BEGIN

// The spot's cone pair from its inner and outer angles (radians, 0 <= inner < outer <= pi/2).
RTPBR_FN rtpbr_float2 Punctual_SpotCone(float innerAngle, float outerAngle) {
    float cosOuter = cos(outerAngle);
    return rtpbr_float2(cosOuter, 1.0f / max(cos(innerAngle) - cosOuter, 1e-3f));
}

// The range window W = clamp(1 - (d / range)^4, 0, 1) from d^2 and 1 / range^2 (0: no range, 1).
RTPBR_FN float Punctual_RangeWindow(float d2, float invRange2) {
    float q = d2 * invRange2;
    return rtpbr_saturate(1.0f - q * q);
}

// The spot's falloff S = t^2 at cd, the cosine between its axis and the direction from it.
RTPBR_FN float Punctual_SpotFalloff(float cd, rtpbr_float2 cone) {
    float t = rtpbr_saturate((cd - cone.x) * cone.y);
    return t * t;
}

// At P: the unit direction to the light L (xyz) and the factor its intensity is multiplied by
// (w): W S / d^2 for a point or spot light, 1 for a directional light; w = 0 at the light's
// position.
RTPBR_FN rtpbr_float4 Punctual_Incident(rtpbr_float3 P, uint shape, rtpbr_float4 position, rtpbr_float3 direction,
                                        rtpbr_float2 cone) {
    if (shape == uint(RTPBR_PUNCTUAL_DIRECTIONAL)) return rtpbr_float4(-direction.x, -direction.y, -direction.z, 1.0f);
    rtpbr_float3 toLight = rtpbr_float3(position.x, position.y, position.z) - P;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0f)) return RTPBR_F4(0.0f);
    rtpbr_float3 L = toLight * rtpbr_rsqrt(d2);
    float w = Punctual_RangeWindow(d2, position.w) * Punctual_SpotFalloff(-dot(direction, L), cone) / d2;
    return rtpbr_float4(L.x, L.y, L.z, w);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_PUNCTUAL_H
