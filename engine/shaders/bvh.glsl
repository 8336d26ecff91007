// Any-hit occlusion query against the scene's BVH (engine/src/bvh.c documents the layout):
// a short fixed-size stack (RTPBR_BVH_MAX_DEPTH entries, the builder's depth bound) is the
// only run-time-indexed private array; nodes and triangles are read from storage buffers.
// Include after rtpbr_shared.h and material.glsl.
//
// Alpha (glTF alphaMode): a triangle of a MASK material lets the ray through where its coverage
// (the material's alpha x the base colour texture's alpha at the slot's transformed texture
// coordinates) is below the cutoff; one of a BLEND material blocks it with probability equal to
// the coverage (stochastic opacity: a hash of the ray's key and the triangle decides). The
// texture's alpha is read from the bytes the scene keeps for that (rtpbr_shared.h,
// RTPBR_ALPHA_TEXTURE_FIELDS), bilinearly at level 0 with the texture's wrap modes.

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
layout(set = 0, binding = RTPBR_BINDING_SHADOW_VERTICES, std430) readonly buffer BvhVertices {
    float bvh_vertices[];
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_MATERIALS, std430) readonly buffer BvhMaterials {
    Material bvh_materials[];
};
struct BvhTextureTransforms {
    RTPBR_TEXTURE_TRANSFORMS_FIELDS(RTPBR_SHARED_FIELD, BvhTextureTransforms)
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_TEXTURE_TRANSFORMS, std430) readonly buffer BvhTransforms {
    BvhTextureTransforms bvh_texture_transforms[];
};
// The same records as texel buffers (R32G32B32A32_UINT), for a CPU device: on lavapipe
// (gallivm, Mesa 22.3) a storage buffer's load at an index that differs between invocations is
// one scalar load per lane, each under its own branch, for every component; a texel fetch is a
// gather. The walk reads a node (8 components) or three at each step and a triangle (12) per
// test, at indices that differ between pixels: the shadowed showcase 483 -> 363 ms at 480 x 360.
// passes/shadow.c sets bvh_texel_reads on a CPU device; a GPU reads the storage buffers (a
// texel fetch goes through the texture unit's format conversion there, and bench/shader-stats
// holds the code as it was). Declared as textures without a sampler (texelFetch of
// GL_EXT_samplerless_texture_functions, which the includer enables): a sampled image of buffer
// dimension is deprecated in SPIR-V 1.6, and the validation layer warns of it on a Vulkan 1.3+
// device (Mesa 25's lavapipe).
layout(set = 0, binding = RTPBR_BINDING_SHADOW_BVH_NODE_TEXELS) uniform utextureBuffer bvh_node_texels;
layout(set = 0, binding = RTPBR_BINDING_SHADOW_BVH_TRIANGLE_TEXELS) uniform utextureBuffer bvh_triangle_texels;
layout(constant_id = RTPBR_SPEC_BVH_TEXELS) const bool bvh_texel_reads = false;

BvhNode bvh_node(uint i)
{
    if (bvh_texel_reads) {
        uvec4 a = texelFetch(bvh_node_texels, int(2u * i)), b = texelFetch(bvh_node_texels, int(2u * i + 1u));
        return BvhNode(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
    }
    return bvh_nodes[i];
}

// A triangle's vertex and edges (its `source`, which only the alpha test reads, left 0 when
// read as texels: bvh_alpha_blocks reads it from the storage buffer).
BvhTriangle bvh_triangle(uint i)
{
    if (bvh_texel_reads) {
        uvec4 v0 = texelFetch(bvh_triangle_texels, int(4u * i)), e1 = texelFetch(bvh_triangle_texels, int(4u * i + 1u));
        uvec4 e2 = texelFetch(bvh_triangle_texels, int(4u * i + 2u));
        return BvhTriangle(uintBitsToFloat(v0), uintBitsToFloat(e1), uintBitsToFloat(e2), uvec4(0u));
    }
    return bvh_triangles[i];
}

struct AlphaTexture {
    RTPBR_ALPHA_TEXTURE_FIELDS(RTPBR_SHARED_FIELD, AlphaTexture)
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_ALPHA_TEXTURES, std430) readonly buffer AlphaTextures {
    AlphaTexture alpha_textures[];
};
layout(set = 0, binding = RTPBR_BINDING_SHADOW_ALPHA_TEXELS, std430) readonly buffer AlphaTexels {
    uint alpha_texels[];
};

// A texel index along an axis of n texels under a glTF wrap mode (0 repeat, 1 clamp, 2 mirrored).
int bvh_wrap(int i, int n, uint mode)
{
    if (mode == 1u) return clamp(i, 0, n - 1);
    if (mode == 2u) {
        int p = ((i % (2 * n)) + 2 * n) % (2 * n);
        return p < n ? p : 2 * n - 1 - p;
    }
    return ((i % n) + n) % n;
}

float bvh_alpha_texel(AlphaTexture t, int x, int y)
{
    uint i = uint(bvh_wrap(y, int(t.height), t.wrap >> 2u)) * t.width + uint(bvh_wrap(x, int(t.width), t.wrap & 3u));
    return float((alpha_texels[t.first + i / 4u] >> (8u * (i % 4u))) & 255u) / 255.0f;
}

// The alpha of a texture at uv, bilinear, level 0 (oracle/texture.h samples the same way).
float bvh_texture_alpha(uint texture, vec2 uv)
{
    AlphaTexture t = alpha_textures[texture];
    if (t.first == RTPBR_ALPHA_TEXTURE_OPAQUE) return 1.0f;
    if (any(isnan(uv)) || any(greaterThan(abs(uv), vec2(1e6f)))) uv = vec2(0.0f);
    vec2 xy = uv * vec2(t.width, t.height) - 0.5f;
    vec2 f = floor(xy), a = xy - f;
    int x = int(f.x), y = int(f.y);
    return mix(mix(bvh_alpha_texel(t, x, y), bvh_alpha_texel(t, x + 1, y), a.x),
               mix(bvh_alpha_texel(t, x, y + 1), bvh_alpha_texel(t, x + 1, y + 1), a.x), a.y);
}

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering": PCG.
uint bvh_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Does the hit at barycentrics (u, v) on triangle i block the ray (its material's alpha)?
bool bvh_alpha_blocks(uint i, float u, float v, uint rayKey)
{
    uvec4 source = bvh_triangles[i].source;
    Material m = bvh_materials[source.w];
    if ((m.flags & (RTPBR_MATERIAL_FLAG_ALPHA_MASK | RTPBR_MATERIAL_FLAG_ALPHA_BLEND)) == 0u) return true;
    float alpha = m.alpha;
    if (m.base_color_texture != 0u) {
        vec4 rows[2] = bvh_texture_transforms[source.w].base_color;
        uint offset = rows[0].w != 0.0f ? RTPBR_VERTEX_UV1_OFFSET : RTPBR_VERTEX_UV_OFFSET;
        vec2 uv = vec2(0.0f);
        for (uint k = 0u; k < 3u; ++k) {
            float w = k == 0u ? 1.0f - u - v : k == 1u ? u : v;
            uint base = source[k] * RTPBR_VERTEX_FLOATS + offset;
            uv += w * vec2(bvh_vertices[base], bvh_vertices[base + 1u]);
        }
        vec3 uv1 = vec3(uv, 1.0f);
        alpha *= bvh_texture_alpha(m.base_color_texture, vec2(dot(rows[0].xyz, uv1), dot(rows[1].xyz, uv1)));
    }
    if ((m.flags & RTPBR_MATERIAL_FLAG_ALPHA_MASK) != 0u) return alpha >= m.alpha_cutoff;
    return float(bvh_hash(rayKey ^ bvh_hash(i)) >> 8u) * (1.0f / 16777216.0f) < alpha;
}

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

// Moeller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection": does the
// segment o + t d, 0 < t < tMax, cross triangle i (both sides of a double-sided one, the front of
// a single-sided one: v0.w, rtpbr_shared.h)? bary: the crossing's barycentrics (u, v).
bool bvh_triangle_crossed(BvhTriangle tri, vec3 o, vec3 d, float tMax, out vec2 bary)
{
    vec3 p = cross(d, tri.e2.xyz);
    float det = dot(tri.e1.xyz, p); // = -dot(d, e1 x e2): > 0 where the ray meets the counter-clockwise side
    bary = vec2(0.0f);
    if (abs(det) < 1e-20f || det * tri.v0.w < 0.0f) return false;
    float invDet = 1.0f / det;
    vec3 s = o - tri.v0.xyz;
    float u = dot(s, p) * invDet;
    vec3 q = cross(s, tri.e1.xyz);
    float v = dot(d, q) * invDet;
    float t = dot(tri.e2.xyz, q) * invDet;
    bary = vec2(u, v);
    return u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f && t < tMax;
}

#define RTPBR_BVH_NONE 0xffffffffu

// Off (passes/shadow.c, for scenes without MASK or BLEND materials): every crossed triangle
// blocks, and the alpha's code is compiled out.
// (RTPBR_BVH_ALPHA_DEFAULT: the default a build may change, bench/shader-stats's
// shadow_comp_opaque, which compiles the pipeline as the engine specializes it)
#ifndef RTPBR_BVH_ALPHA_DEFAULT
#define RTPBR_BVH_ALPHA_DEFAULT true
#endif
layout(constant_id = RTPBR_SPEC_BVH_ALPHA) const bool bvh_alpha_tested = RTPBR_BVH_ALPHA_DEFAULT;
// The trace's packets also where the alpha is tested (rtpbr_shared.h; passes/shadow.c: a CPU device).
layout(constant_id = RTPBR_SPEC_BVH_PACKET_ALPHA) const bool bvh_packet_alpha = false;

// True if any triangle crosses the segment o + t d, 0 < t < tMax, and blocks it (an opaque one,
// or one whose alpha blocks: bvh_alpha_blocks). rayKey: a random number of this ray, for the
// stochastic opacity of BLEND materials.
// The alpha is looked at outside the walk: the walk stops at the first crossed triangle whose
// alpha is tested (e1.w, rtpbr_shared.h), its alpha is read, and the walk resumes where it
// stopped if the ray passes. On lavapipe a branch's code runs whether taken or not, so the
// alpha's reads (material, three vertices, four texels) inside the walk cost every step of
// every ray, also in scenes without a MASK or BLEND material (showcase: 3.1x the trace time);
// and for those scenes bvh_alpha_tested compiles it out.
// The result is the same as testing each triangle's alpha in the walk: whether a triangle
// blocks depends on the triangle and the ray only, not on the order of the tests.
bool bvh_occluded(vec3 o, vec3 d, float tMax, uint rayKey)
{
    // Zero direction components become huge reciprocals of the right sign (no NaN in the slabs).
    vec3 invD = 1.0f / mix(d, vec3(1e-30f), lessThan(abs(d), vec3(1e-30f)));
    uint stack[RTPBR_BVH_MAX_DEPTH];
    int sp = 0;
    BvhNode root = bvh_node(0);
    if (!bvh_box_hit(root.box_min, root.box_max, o, invD, tMax)) return false;
    uint node = 0u;             // the next node to visit; RTPBR_BVH_NONE: the next one kept on the stack
    uint first = 0u, end = 0u;  // the current leaf's triangles not tested yet
    for (;;) { // one trip per crossed triangle whose alpha is tested, and a last one
        uint candidate = RTPBR_BVH_NONE;
        vec2 bary = vec2(0.0f);
        for (;;) { // one trip per leaf
            // The nodes, until this ray holds a leaf (Aila & Laine 2009, "while-while"): the
            // boxes' and the triangles' code in loops of their own, each run only as often as
            // some ray needs it (on lavapipe the code of a branch runs whether taken or not).
            while (first == end) {
                if (node == RTPBR_BVH_NONE) {
                    if (sp == 0) return false;
                    node = stack[--sp];
                }
                BvhNode n = bvh_node(node);
                node = RTPBR_BVH_NONE;
                if (n.count > 0u) {
                    first = n.left_or_first;
                    end = first + n.count;
                } else {
                    BvhNode left = bvh_node(n.left_or_first);
                    BvhNode right = bvh_node(n.left_or_first + 1u);
                    bool hitLeft = bvh_box_hit(left.box_min, left.box_max, o, invD, tMax);
                    bool hitRight = bvh_box_hit(right.box_min, right.box_max, o, invD, tMax);
                    // Descend into one, keep the other for later; the depth bound keeps sp in range.
                    if (hitLeft || hitRight) node = hitLeft ? n.left_or_first : n.left_or_first + 1u;
                    if (hitLeft && hitRight) stack[sp++] = n.left_or_first + 1u;
                }
            }
            // The leaf's triangles.
            for (; first < end; ++first) {
                BvhTriangle tri = bvh_triangle(first);
                vec2 b;
                if (bvh_triangle_crossed(tri, o, d, tMax, b)) {
                    if (!bvh_alpha_tested || tri.e1.w == 0.0f) return true; // opaque
                    candidate = first++;
                    bary = b;
                    break;
                }
            }
            if (candidate != RTPBR_BVH_NONE) break;
        }
        if (bvh_alpha_blocks(candidate, bary.x, bary.y, rayKey)) return true;
    }
    return false;
}

// Rays per bvh_occluded_packet: the shadow rays of one pixel toward one light (shadow.comp).
#define RTPBR_BVH_PACKET 4
// A stack entry of bvh_occluded_packet: the node (below 2^RTPBR_BVH_PACKET_SHIFT, bvh.c) and
// the packet's rays that reach it (the bits above).
#define RTPBR_BVH_PACKET_SHIFT 28u

// The rays of a packet (bits) that enter a box: bvh_box_hit for each, written out (a loop
// would count against lavapipe's loop budget at every step of the walk: shadow.c).
uint bvh_box_rays(vec3 boxMin, vec3 boxMax, vec3 o, vec3 invD[RTPBR_BVH_PACKET], float tMax)
{
    return (bvh_box_hit(boxMin, boxMax, o, invD[0], tMax) ? 1u : 0u) |
           (bvh_box_hit(boxMin, boxMax, o, invD[1], tMax) ? 2u : 0u) |
           (bvh_box_hit(boxMin, boxMax, o, invD[2], tMax) ? 4u : 0u) |
           (bvh_box_hit(boxMin, boxMax, o, invD[3], tMax) ? 8u : 0u);
}

// The rays of a packet (bits) that cross a triangle, written out likewise.
uint bvh_triangle_rays(BvhTriangle tri, vec3 o, vec3 d[RTPBR_BVH_PACKET], float tMax)
{
    vec2 b;
    return (bvh_triangle_crossed(tri, o, d[0], tMax, b) ? 1u : 0u) |
           (bvh_triangle_crossed(tri, o, d[1], tMax, b) ? 2u : 0u) |
           (bvh_triangle_crossed(tri, o, d[2], tMax, b) ? 4u : 0u) |
           (bvh_triangle_crossed(tri, o, d[3], tMax, b) ? 8u : 0u);
}

#if RTPBR_BVH_PACKET != 4
#error "bvh_box_rays and bvh_triangle_rays are written for packets of 4 rays"
#endif

// Does triangle i (read: tri), which the ray o + t d crosses, block it? Its alpha at the
// crossing (bvh_alpha_blocks), the ray's key bvh_hash(key).
bool bvh_alpha_ray(BvhTriangle tri, uint i, vec3 o, vec3 d, float tMax, uint key)
{
    vec2 bary;
    bvh_triangle_crossed(tri, o, d, tMax, bary);
    return bvh_alpha_blocks(i, bary.x, bary.y, bvh_hash(key));
}

// Which rays of a packet from one origin are blocked: bit i set where some triangle crosses
// o + t d[i], 0 < t < tMax, and blocks it, for the rays of `traced`. Every crossed triangle
// blocks but one whose alpha is tested (with bvh_alpha_tested: bvh_alpha_blocks, ray i's key
// bvh_hash(keyBase + i), as bvh_occluded's).
// One walk for the packet: a node is visited once for all the rays that reach it (those that
// enter its box and its parents'), a leaf's triangles tested against those rays only; so each
// ray meets the nodes and triangles it meets in its own walk (bvh_occluded), and its answer is
// the same. The rays of a pixel toward a light are close: the walk and its reads (a node's two
// children, a triangle) are shared by up to RTPBR_BVH_PACKET rays instead of repeated.
// The alpha is looked at outside the walk, as in bvh_occluded: the walk stops at the first
// crossed triangle whose alpha is tested, reads its alpha for the rays that cross it, and
// resumes where it stopped with those it did not block (in the walk, on lavapipe, the alpha's
// reads would cost every step of every packet).
uint bvh_occluded_packet(vec3 o, vec3 d[RTPBR_BVH_PACKET], float tMax, uint traced, uint keyBase)
{
    // Zero direction components become huge reciprocals of the right sign (no NaN in the slabs).
    vec3 invD[RTPBR_BVH_PACKET] = vec3[](1.0f / mix(d[0], vec3(1e-30f), lessThan(abs(d[0]), vec3(1e-30f))),
                                         1.0f / mix(d[1], vec3(1e-30f), lessThan(abs(d[1]), vec3(1e-30f))),
                                         1.0f / mix(d[2], vec3(1e-30f), lessThan(abs(d[2]), vec3(1e-30f))),
                                         1.0f / mix(d[3], vec3(1e-30f), lessThan(abs(d[3]), vec3(1e-30f))));
    BvhNode root = bvh_node(0);
    uint rays = traced & bvh_box_rays(root.box_min, root.box_max, o, invD, tMax); // the rays that reach the current node
    uint blocked = 0u;
    uint stack[RTPBR_BVH_MAX_DEPTH];
    int sp = 0;
    uint node = rays != 0u ? 0u : RTPBR_BVH_NONE;
    uint first = 0u, end = 0u;
    for (;;) { // one trip per crossed triangle whose alpha is tested (bvh_alpha_tested), and a last one
        uint candidate = RTPBR_BVH_NONE, crossing = 0u;
        for (;;) { // one trip per leaf
            while (first == end) {
                if (node == RTPBR_BVH_NONE) {
                    if (sp == 0) return blocked;
                    uint entry = stack[--sp];
                    node = entry & ((1u << RTPBR_BVH_PACKET_SHIFT) - 1u);
                    rays = (entry >> RTPBR_BVH_PACKET_SHIFT) & ~blocked;
                    if (rays == 0u) { node = RTPBR_BVH_NONE; continue; } // its rays are blocked already
                }
                BvhNode n = bvh_node(node);
                node = RTPBR_BVH_NONE;
                if (n.count > 0u) {
                    first = n.left_or_first;
                    end = first + n.count;
                } else {
                    BvhNode left = bvh_node(n.left_or_first);
                    BvhNode right = bvh_node(n.left_or_first + 1u);
                    uint raysLeft = rays & bvh_box_rays(left.box_min, left.box_max, o, invD, tMax);
                    uint raysRight = rays & bvh_box_rays(right.box_min, right.box_max, o, invD, tMax);
                    // Descend into one, keep the other for later; the depth bound keeps sp in range.
                    if (raysLeft != 0u || raysRight != 0u) {
                        node = raysLeft != 0u ? n.left_or_first : n.left_or_first + 1u;
                        rays = raysLeft != 0u ? raysLeft : raysRight;
                    }
                    if (raysLeft != 0u && raysRight != 0u)
                        stack[sp++] = (n.left_or_first + 1u) | (raysRight << RTPBR_BVH_PACKET_SHIFT);
                }
            }
            // The leaf's triangles, against the rays that reach it and are not blocked yet.
            for (; first < end; ++first) {
                BvhTriangle tri = bvh_triangle(first);
                uint hit = rays & bvh_triangle_rays(tri, o, d, tMax);
                if (bvh_alpha_tested && hit != 0u && tri.e1.w != 0.0f) { // its alpha decides
                    candidate = first++;
                    crossing = hit;
                    break;
                }
                blocked |= hit;
                rays &= ~blocked;
                if (rays == 0u) first = end - 1u; // the loop's increment ends the leaf
            }
            if (candidate != RTPBR_BVH_NONE) break;
            if ((traced & ~blocked) == 0u) return blocked;
        }
        // The candidate's alpha for each ray that crosses it, where it crosses it: a loop over
        // those rays (the four written out took the alpha-tested scenes' frames 4 % longer on
        // lavapipe, which ran all four every time; at most 4 trips a stop, well inside lavapipe's
        // loop budget, shadow.c).
        BvhTriangle tri = bvh_triangle(candidate);
        for (uint left = crossing; left != 0u; left &= left - 1u) {
            uint i = uint(findLSB(left));
            if (bvh_alpha_ray(tri, candidate, o, d[i], tMax, keyBase + i)) blocked |= 1u << i;
        }
        rays &= ~blocked;
        if (rays == 0u) first = end; // the leaf's rest: none of its rays left
        if ((traced & ~blocked) == 0u) return blocked;
    }
    return blocked;
}
