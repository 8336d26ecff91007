#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_EXT_ray_query : require
// The shadow rays by VK_KHR_ray_query (ray_query.glsl; rtpbr_context_desc.shadow_ray_query);
// shadow.comp walks the BVH instead. The pass itself: shadow_trace.glsl.
#define RTPBR_SHADOW_RAY_QUERY 1
#include "shadow_trace.glsl"
