#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#extension GL_EXT_control_flow_attributes : require
// The shadow rays by the BVH walk (bvh.glsl); shadow_ray_query.comp traces them with
// VK_KHR_ray_query. The pass itself: shadow_trace.glsl.
#include "shadow_trace.glsl"
