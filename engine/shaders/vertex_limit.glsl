// The polygon vertex limit has one value, 8, under four names: RTPBR_MAX_POLYGON_VERTICES
// (rtpbr/rtpbr.h, the C API, the source of truth), RTPBR_SHADER_MAX_POLYGON_VERTICES
// (rtpbr_shared.h, the light buffer), RTPBR_GLTF_MAX_POLYGON_VERTICES (rtpbr/rtpbr_gltf.h, the
// loader) and RTPBR_LTC_MAX_VERTICES (shaderlib's ltc.h, the polygon integration). The C
// build checks the first three against each other (engine/src/internal.h, scene_gltf.c);
// this file, included after rtpbr_shared.h and rtpbr/ltc.h (lighting.comp), checks the last.
#ifndef RTPBR_VERTEX_LIMIT_GLSL
#define RTPBR_VERTEX_LIMIT_GLSL
#if RTPBR_SHADER_MAX_POLYGON_VERTICES != RTPBR_LTC_MAX_VERTICES
#error "RTPBR_SHADER_MAX_POLYGON_VERTICES (rtpbr_shared.h) differs from RTPBR_LTC_MAX_VERTICES (shaderlib/rtpbr/ltc.h)"
#endif
#endif
