// A host's HLSL pixel shader that includes the whole installed shader library and keeps its own
// helpers under the names engines usually give them: the library defines no unprefixed name in
// HLSL (issue 15). Compiled by tests/consumers against the installed headers:
//   glslangValidator -V -D -e main -S frag -I<prefix>/include host.hlsl
//   slangc host.hlsl -I <prefix>/include -target spirv -entry main -stage fragment
// The host's helpers before the library, as macros ...
#define sq(x) ((x) * (x))
#define mix(a, b, t) lerp((a), (b), (t))
#define RTPBR_HLSL 1 // glslang's HLSL front end does not define __HLSL_VERSION
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ndf.h"
#include "rtpbr/smith.h"
#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_anisotropy.h"
#include "rtpbr/ltc_clipless.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/ltc_shapes.h"
#include "rtpbr/ltc_lines.h"
#include "rtpbr/ltc_textured.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "rtpbr/gbuffer.h"

// ... and after it, as functions of its own.
float safe_sqrt(float x) { return sqrt(max(x, 0.0f)); }
float pos(float x) { return max(x, 0.0f); }

float4 main(float3 normal : NORMAL) : SV_Target
{
    float NoH = saturate(normal.z);
    float alpha = mix(0.1f, 0.5f, 0.5f);
    float d = D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoH, NoH, alpha);
    return float4(d, safe_sqrt(sq(normal.x)), pos(normal.y), rsqrt(2.0f));
}
