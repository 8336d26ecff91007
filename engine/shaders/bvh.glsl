// Any-hit occlusion query against the scene's BVH (engine/src/bvh.c documents the layout):
// a short fixed-size stack (RTPBR_BVH_MAX_DEPTH entries, the builder's depth bound) is the
// only run-time-indexed private array; nodes and triangles are read from storage buffers.
// Include after rtpbr_shared.h; define BVH_SET before including (the descriptor set).

// Fields declared once, in rtpbr_shared.h (C: rtpbr_shader_bvh_node, rtpbr_shader_bvh_triangle).
struct BvhNode {
    RTPBR_BVH_NODE_FIELDS(RTPBR_SHARED_FIELD, BvhNode)
};
struct BvhTriangle {
    RTPBR_BVH_TRIANGLE_FIELDS(RTPBR_SHARED_FIELD, BvhTriangle)
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_BVH_NODES, std430) readonly buffer BvhNodes {
    BvhNode bvh_nodes[];
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_BVH_TRIANGLES, std430) readonly buffer BvhTriangles {
    BvhTriangle bvh_triangles[];
};

// Slab test: does the ray o + t d, t in [0, tMax], enter the box?
bool bvh_box_hit(vec3 boxMin, vec3 boxMax, vec3 o, vec3 invD, float tMax)
{
    vec3 t0 = (boxMin - o) * invD;
    vec3 t1 = (boxMax - o) * invD;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float tNear = max(max(tn.x, tn.y), max(tn.z, 0.0f));
    float tFar = min(min(tf.x, tf.y), min(tf.z, tMax));
    return tNear <= tFar;
}

// Moeller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection"; both sides of a
// double-sided triangle, the front of a single-sided one (v0.w, rtpbr_shared.h).
bool bvh_triangle_hit(BvhTriangle tri, vec3 o, vec3 d, float tMax)
{
    vec3 p = cross(d, tri.e2.xyz);
    float det = dot(tri.e1.xyz, p); // = -dot(d, e1 x e2): > 0 where the ray meets the counter-clockwise side
    if (abs(det) < 1e-20f || det * tri.v0.w < 0.0f) return false;
    float invDet = 1.0f / det;
    vec3 s = o - tri.v0.xyz;
    float u = dot(s, p) * invDet;
    vec3 q = cross(s, tri.e1.xyz);
    float v = dot(d, q) * invDet;
    float t = dot(tri.e2.xyz, q) * invDet;
    return u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f && t < tMax;
}

// True if any triangle crosses the segment o + t d, 0 < t < tMax.
bool bvh_occluded(vec3 o, vec3 d, float tMax)
{
    // Zero direction components become huge reciprocals of the right sign (no NaN in the slabs).
    vec3 invD = 1.0f / mix(d, vec3(1e-30f), lessThan(abs(d), vec3(1e-30f)));
    uint stack[RTPBR_BVH_MAX_DEPTH];
    int sp = 0;
    uint node = 0u;
    BvhNode root = bvh_nodes[0];
    if (!bvh_box_hit(root.box_min, root.box_max, o, invD, tMax)) return false;
    for (;;) {
        BvhNode n = bvh_nodes[node];
        if (n.count > 0u) {
            for (uint i = n.left_or_first; i < n.left_or_first + n.count; ++i)
                if (bvh_triangle_hit(bvh_triangles[i], o, d, tMax)) return true;
        } else {
            BvhNode left = bvh_nodes[n.left_or_first];
            BvhNode right = bvh_nodes[n.left_or_first + 1u];
            bool hitLeft = bvh_box_hit(left.box_min, left.box_max, o, invD, tMax);
            bool hitRight = bvh_box_hit(right.box_min, right.box_max, o, invD, tMax);
            if (hitLeft || hitRight) {
                // Descend into one, keep the other for later; the depth bound keeps sp in range.
                node = hitLeft ? n.left_or_first : n.left_or_first + 1u;
                if (hitLeft && hitRight) stack[sp++] = n.left_or_first + 1u;
                continue;
            }
        }
        if (sp == 0) return false;
        node = stack[--sp];
    }
    return false;
}
