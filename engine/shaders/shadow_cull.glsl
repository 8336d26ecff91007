// Shadow-ray culling (issue 32; rtpbr_render_desc.shadow_cull): which tiles can have no shadow
// ray toward a light blocked, proved without tracing. Include after bvh.glsl, light.glsl and
// the lights' buffer.
//
// A ray of shadow.comp runs from the lifted point o to e = o + 0.999 (y - o), y a point of the
// light, and every such y lies in the light's bounding sphere (light.sphere; a point or spot
// light's position). A triangle T can block one only if
//   1. T meets the hull of o and that sphere, and
//   2. o and e lie on different sides of T's plane (or touch it): for some y, the signed
//      distances d(o) and d(e) = 0.001 d(o) + 0.999 d(y) differ in sign. Its extent along T's
//      normal bounds d(y) over the light: the polygon's vertices (a polygon's samples lie in its
//      fan triangles), a disk's centre and half-axes, or the bounding sphere.
// shadow_select.comp applies both per lighting tile and shadowed light, to all the tile's ray
// origins at once (their box): test 1 with the hull of the box's bounding sphere and the
// light's, test 2 with the box's extent along T's normal. Test 1 is made conservative with T's
// bounding sphere against supersets of the hull (one side of its outer tangent line in the
// plane through its axis, and two slabs across the axis); test 2 counts a side only beyond a
// margin of float rounding of the distances. The candidates come from one walk of the BVH
// through the nodes whose bounding spheres pass test 1 and whose boxes no coordinate axis
// separates from the origins and the rays' ends (test 2 with the box's faces: a tessellated
// floor or wall under the tile's own points is passed over whole); it stops at the first
// triangle that passes both (the tile then traces) or after RTPBR_SHADOW_CULL_STEPS nodes and
// triangles (the tile traces: this bounds the walk's cost where the hull holds much of the
// scene).
// Where no triangle passes both, every ray would have been unoccluded: shadow.comp traces none
// and adds each weight to both sums, exactly as when each ray is traced (the image does not
// change), and the denoiser writes ratio 1 where its whole window is in such tiles.

#define RTPBR_SHADOW_CULL_STEPS 256u

// Can the sphere (c, r) meet the convex hull of the spheres (a, ra) and (b, rb)? False only
// where it cannot. In the plane through the axis a -> b and c, the hull lies on the inner side
// of the two spheres' outer tangent line (unit normal (-sin, cos) in (along, across)
// coordinates, sin = (rb - ra) / |b - a|, at distance ra from a) and between the planes
// across the axis at -ra and |b - a| + rb; where one sphere holds the other, the hull is it.
bool shadow_cull_hull_meets(vec3 a, float ra, vec3 b, float rb, vec3 c, float r)
{
    vec3 ab = b - a;
    float len = length(ab);
    if (!(len > abs(rb - ra))) return distance(c, ra > rb ? a : b) < (max(ra, rb) + r) * 1.00001f;
    vec3 axis = ab / len, w = c - a;
    float along = dot(w, axis);
    float across = length(w - along * axis);
    float s = (rb - ra) / len;
    float side = across * sqrt(max(1.0f - s * s, 0.0f)) - along * s - ra;
    r += 1e-5f * (len + ra + rb + r + length(w)); // float rounding, to the safe side
    return side < r && along > -ra - r && along < len + rb + r;
}

// The bounding sphere of every point of the light a shadow ray aims at.
vec4 shadow_cull_light_sphere(Light light)
{
    bool punctual = light.shape == uint(RTPBR_LIGHT_SHAPE_POINT) || light.shape == uint(RTPBR_LIGHT_SHAPE_SPOT);
    return punctual ? vec4(light.vertices[0].xyz, 0.0f) : light.sphere;
}

// The least and largest dot(n, y) over the light's points y (see above).
vec2 shadow_cull_light_extent(Light light, vec3 n)
{
    if (light.vertex_count >= 3u) {
        float lo = dot(n, light.vertices[0].xyz), hi = lo;
        for (uint i = 1u; i < light.vertex_count; ++i) {
            float d = dot(n, light.vertices[i].xyz);
            lo = min(lo, d);
            hi = max(hi, d);
        }
        return vec2(lo, hi);
    }
    if (light.shape == uint(RTPBR_LIGHT_SHAPE_DISK)) {
        float c = dot(n, light.vertices[0].xyz);
        float e = length(vec2(dot(n, light.vertices[1].xyz), dot(n, light.vertices[2].xyz)));
        return vec2(c - e, c + e);
    }
    vec4 s = shadow_cull_light_sphere(light);
    float c = dot(n, s.xyz);
    return vec2(c - s.w, c + s.w);
}

// Can the culling prove anything for this light? Not for a directional light or the sun's far
// polygon (their rays run 1e7 and more: the hull is the scene).
bool shadow_cull_applies(Light light)
{
    return light.shape != uint(RTPBR_LIGHT_SHAPE_DIRECTIONAL) && light.sun == 0u;
}

// Can a segment from the box [lo, hi] to the light (its axis extents lightMin, lightMax),
// shortened as the rays are, enter the node's box? Not where an axis separates them: every
// origin and every ray end beyond the same face of the box (the ends are convex combinations
// 0.001 o + 0.999 y, as is every point of a segment). Floors, walls and ceilings are
// axis-aligned slabs that the tile's own origins and the light lie on one side of: their
// subtrees are passed over whole (one by one their triangles filled the walk's budget).
bool shadow_cull_node_meets(BvhNode n, vec3 lo, vec3 hi, vec3 lightMin, vec3 lightMax, vec3 centre, float radius,
                            vec4 ls)
{
    if (any(greaterThan(n.box_min, n.box_max))) return false; // empty (no triangles)
    vec3 margin = 1e-6f * (abs(n.box_min) + abs(n.box_max) + abs(lo) + abs(hi) + abs(lightMin) + abs(lightMax));
    bvec3 above = bvec3(uvec3(greaterThan(lo, n.box_max + margin)) &
                        uvec3(greaterThan(0.001f * lo + 0.999f * lightMin, n.box_max + margin)));
    bvec3 below = bvec3(uvec3(lessThan(hi, n.box_min - margin)) &
                        uvec3(lessThan(0.001f * hi + 0.999f * lightMax, n.box_min - margin)));
    if (any(above) || any(below)) return false;
    vec3 nc = 0.5f * (n.box_min + n.box_max);
    return shadow_cull_hull_meets(centre, radius, ls.xyz, ls.w, nc, distance(nc, n.box_max));
}

// May a ray from any origin in the box [lo, hi] (a tile's) to the light be blocked? True at
// the first triangle that passes both tests, or after RTPBR_SHADOW_CULL_STEPS.
bool shadow_cull_may_block(vec3 lo, vec3 hi, Light light)
{
    vec4 ls = shadow_cull_light_sphere(light);
    vec2 ex = shadow_cull_light_extent(light, vec3(1.0f, 0.0f, 0.0f));
    vec2 ey = shadow_cull_light_extent(light, vec3(0.0f, 1.0f, 0.0f));
    vec2 ez = shadow_cull_light_extent(light, vec3(0.0f, 0.0f, 1.0f));
    vec3 lightMin = vec3(ex.x, ey.x, ez.x), lightMax = vec3(ex.y, ey.y, ez.y);
    vec3 centre = 0.5f * (lo + hi), halfSize = 0.5f * (hi - lo);
    float radius = max(distance(centre, lo), distance(centre, hi));
    if (!shadow_cull_node_meets(bvh_node(0), lo, hi, lightMin, lightMax, centre, radius, ls)) return false;
    uint stack[RTPBR_BVH_MAX_DEPTH];
    int sp = 0;
    uint node = 0u, steps = 0u;
    for (;;) {
        BvhNode n = bvh_node(node);
        steps += max(n.count, 1u);
        if (steps > RTPBR_SHADOW_CULL_STEPS) return true;
        if (n.count > 0u) {
            for (uint i = n.left_or_first; i < n.left_or_first + n.count; ++i) {
                BvhTriangle tri = bvh_triangle(i);
                vec3 v0 = tri.v0.xyz, v1 = v0 + tri.e1.xyz, v2 = v0 + tri.e2.xyz;
                vec3 tc = (v0 + v1 + v2) * (1.0f / 3.0f);
                float tr = sqrt(max(max(dot(v0 - tc, v0 - tc), dot(v1 - tc, v1 - tc)), dot(v2 - tc, v2 - tc)));
                if (!shadow_cull_hull_meets(centre, radius, ls.xyz, ls.w, tc, tr)) continue;
                vec3 normal = cross(tri.e1.xyz, tri.e2.xyz);
                float nl = length(normal);
                // A degenerate triangle blocks nothing (bvh_triangle_hit's determinant test).
                if (!(nl > 0.0f)) continue;
                normal /= nl;
                float plane = dot(normal, v0);
                vec2 lightD = shadow_cull_light_extent(light, normal) - plane;
                float oc = dot(normal, centre) - plane, oh = dot(halfSize, abs(normal));
                vec2 origins = vec2(oc - oh, oc + oh);
                // float rounding of the dot products (coordinates to about 2^-24 each)
                float margin = 1e-6f * (abs(oc) + oh + abs(plane) + abs(lightD.x) + abs(lightD.y) + length(centre) +
                                        length(v0) + ls.w);
                bool front = origins.x > margin && 0.001f * origins.x + 0.999f * lightD.x > margin;
                bool back = origins.y < -margin && 0.001f * origins.y + 0.999f * lightD.y < -margin;
                if (!front && !back) return true;
            }
        } else {
            bool hitLeft =
                shadow_cull_node_meets(bvh_node(n.left_or_first), lo, hi, lightMin, lightMax, centre, radius, ls);
            bool hitRight =
                shadow_cull_node_meets(bvh_node(n.left_or_first + 1u), lo, hi, lightMin, lightMax, centre, radius, ls);
            if (hitLeft || hitRight) {
                node = hitLeft ? n.left_or_first : n.left_or_first + 1u;
                if (hitLeft && hitRight) stack[sp++] = n.left_or_first + 1u;
                continue;
            }
        }
        if (sp == 0) return false;
        node = stack[--sp];
    }
    return true;
}
