// Shadow rays by VK_KHR_ray_query (shadow.comp built with RTPBR_SHADOW_RAY_QUERY; the
// structures: engine/src/accel.c). The same answer as bvh.glsl's walks for the same ray: the
// same triangles (world space, the BVH's, the same vertex order), the same sides (single-sided
// triangles block the rays that meet their front: their instances' back faces are culled), the same
// alpha test (bvh_alpha_blocks, on the BVH triangle's index and barycentrics). Where they can
// differ is a ray through a triangle's edge or vertex, which the driver's watertight test and
// the walk's Moeller-Trumbore decide each in its own way.
// Include after bvh.glsl (the includer enables GL_EXT_ray_query).

layout(set = 0, binding = RTPBR_BINDING_SHADOW_ACCEL) uniform accelerationStructureEXT shadow_accel;
layout(set = 0, binding = RTPBR_BINDING_SHADOW_ACCEL_TRIANGLES, std430) readonly buffer AccelTriangles {
    uint accel_triangles[];
};

// True if a triangle crosses the segment o + t d, 0 < t < tMax, and blocks it (bvh_occluded's
// contract). Opaque triangles end the query in the driver; an alpha-tested one (a candidate) is
// confirmed where its alpha blocks.
bool rq_occluded(vec3 o, vec3 d, float tMax, uint rayKey)
{
    rayQueryEXT q;
    uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsCullBackFacingTrianglesEXT;
    if (!bvh_alpha_tested) flags |= gl_RayFlagsOpaqueEXT;
    rayQueryInitializeEXT(q, shadow_accel, flags, 0xffu, o, 0.0f, d, tMax);
    while (rayQueryProceedEXT(q)) {
        uint triangle = accel_triangles[rayQueryGetIntersectionInstanceCustomIndexEXT(q, false) +
                                        rayQueryGetIntersectionPrimitiveIndexEXT(q, false)];
        vec2 b = rayQueryGetIntersectionBarycentricsEXT(q, false);
        if (bvh_alpha_blocks(triangle, b.x, b.y, rayKey)) rayQueryConfirmIntersectionEXT(q);
    }
    return rayQueryGetIntersectionTypeEXT(q, true) != gl_RayQueryCommittedIntersectionNoneEXT;
}
