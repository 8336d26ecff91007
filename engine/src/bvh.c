// A bounding volume hierarchy over the scene's triangles in world space, built on the host at
// scene upload by a binned SAH builder (Wald 2007, "On fast Construction of SAH-based Bounding
// Volume Hierarchies": RTPBR_BVH_BINS centroid bins per axis, traversal cost 1, intersection
// cost 1 per triangle), for the shadow rays of the shadow pass (passes/shadow.c, shaders/bvh.glsl).
//
// GPU layout (two storage buffers, std430; fields declared in rtpbr_shared.h, RTPBR_BVH_*_FIELDS):
//   nodes:     32 bytes each: vec3 box min, uint left_or_first, vec3 box max, uint count.
//              count == 0: an interior node whose children are nodes left_or_first and
//              left_or_first + 1 (siblings are adjacent); count > 0: a leaf holding triangles
//              left_or_first .. left_or_first + count - 1. Node 0 is the root. No node is deeper
//              than RTPBR_BVH_MAX_DEPTH, so a traversal stack of that many entries suffices.
//   triangles: 64 bytes each: vertex 0, edge v1 - v0, edge v2 - v0 (vec4s), ready for the
//              Moeller-Trumbore test, and the source vertices and material (for the alpha of MASK
//              and BLEND materials); ordered by leaf.
// A scene without triangles gets one empty leaf whose box (min > max) no ray enters.
// Both buffers are also viewed as R32G32B32A32_UINT texel buffers (a node 2 texels, a triangle
// 4), which the walks read on a CPU device (passes/shadow.c, RTPBR_SPEC_BVH_TEXELS).
#include <float.h>
#include <string.h>

#include "internal.h"

enum { RTPBR_BVH_BINS = 16, RTPBR_BVH_LEAF_SIZE = 4 };

typedef struct aabb {
    float min[3], max[3];
} aabb;

typedef struct build_state {
    const float (*tri)[9];     // world-space vertices per triangle
    float (*centroid)[3];
    uint32_t *order;           // triangle indices, partitioned in place
    rtpbr_shader_bvh_node *nodes;
    uint32_t node_count;
} build_state;

static aabb aabb_empty(void)
{
    return (aabb){{FLT_MAX, FLT_MAX, FLT_MAX}, {-FLT_MAX, -FLT_MAX, -FLT_MAX}};
}

static void aabb_grow(aabb *b, const float p[3])
{
    for (int k = 0; k < 3; ++k) {
        if (p[k] < b->min[k]) b->min[k] = p[k];
        if (p[k] > b->max[k]) b->max[k] = p[k];
    }
}

// Merging an empty box (min > max, as aabb_empty) changes nothing: growing by its corners
// would stretch b to +-FLT_MAX, and every SAH plane with an empty bin on one side would cost
// infinity (no split found: leaves of thousands of triangles).
static void aabb_merge(aabb *b, const aabb *o)
{
    if (o->min[0] > o->max[0]) return;
    aabb_grow(b, o->min);
    aabb_grow(b, o->max);
}

static float aabb_half_area(const aabb *b)
{
    float d[3];
    for (int k = 0; k < 3; ++k) d[k] = b->max[k] > b->min[k] ? b->max[k] - b->min[k] : 0.0f;
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

static void make_leaf(build_state *s, uint32_t node, const aabb *box, uint32_t first, uint32_t count)
{
    rtpbr_shader_bvh_node *n = &s->nodes[node];
    memcpy(n->box_min, box->min, sizeof n->box_min);
    memcpy(n->box_max, box->max, sizeof n->box_max);
    n->left_or_first = first;
    n->count = count;
}

// The bin of a centroid coordinate c on an axis from lo with RTPBR_BVH_BINS / extent = scale,
// clamped before the conversion: with coordinates near FLT_MAX a centroid or the extent is
// infinite and the position NaN, which (int) may not convert (found by fuzz_scene_api, UBSan);
// NaN goes to bin 0, the same in the binning and the partition.
static int bin_of(float c, float lo, float scale)
{
    float f = (c - lo) * scale;
    return f >= 0.0f ? (f < (float)RTPBR_BVH_BINS ? (int)f : RTPBR_BVH_BINS - 1) : 0;
}

// Builds the subtree of triangles order[first .. first + count) into nodes[node].
static void build(build_state *s, uint32_t node, uint32_t first, uint32_t count, uint32_t depth)
{
    aabb box = aabb_empty(), cbox = aabb_empty();
    for (uint32_t i = first; i < first + count; ++i) {
        const float *t = s->tri[s->order[i]];
        for (int v = 0; v < 3; ++v) aabb_grow(&box, t + 3 * v);
        aabb_grow(&cbox, s->centroid[s->order[i]]);
    }
    if (count <= 1 || depth + 1 >= RTPBR_BVH_MAX_DEPTH) {
        make_leaf(s, node, &box, first, count);
        return;
    }
    // The best of the (bins - 1) planes of each axis by the surface area heuristic.
    float best_cost = FLT_MAX;
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
        float lo = cbox.min[axis], extent = cbox.max[axis] - lo;
        if (!(extent > 0.0f)) continue;
        aabb bins[RTPBR_BVH_BINS];
        uint32_t counts[RTPBR_BVH_BINS] = {0};
        for (int b = 0; b < RTPBR_BVH_BINS; ++b) bins[b] = aabb_empty();
        float scale = RTPBR_BVH_BINS / extent;
        for (uint32_t i = first; i < first + count; ++i) {
            uint32_t t = s->order[i];
            int b = bin_of(s->centroid[t][axis], lo, scale);
            counts[b]++;
            for (int v = 0; v < 3; ++v) aabb_grow(&bins[b], s->tri[t] + 3 * v);
        }
        // Sweep from the right for the right sides' areas, then from the left.
        float right_area[RTPBR_BVH_BINS];
        uint32_t right_count[RTPBR_BVH_BINS];
        aabb acc = aabb_empty();
        uint32_t n = 0;
        for (int b = RTPBR_BVH_BINS - 1; b > 0; --b) {
            aabb_merge(&acc, &bins[b]);
            n += counts[b];
            right_area[b] = aabb_half_area(&acc);
            right_count[b] = n;
        }
        acc = aabb_empty();
        n = 0;
        for (int plane = 1; plane < RTPBR_BVH_BINS; ++plane) { // left = bins [0, plane)
            aabb_merge(&acc, &bins[plane - 1]);
            n += counts[plane - 1];
            if (n == 0 || right_count[plane] == 0) continue;
            float cost = aabb_half_area(&acc) * (float)n + right_area[plane] * (float)right_count[plane];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_plane = plane;
            }
        }
    }
    float area = aabb_half_area(&box);
    float split_cost = area > 0.0f ? 1.0f + best_cost / area : FLT_MAX;
    // No plane separates the centroids, or a small leaf is cheaper than its best split.
    if (best_axis < 0 || (count <= RTPBR_BVH_LEAF_SIZE && split_cost >= (float)count)) {
        make_leaf(s, node, &box, first, count);
        return;
    }
    float lo = cbox.min[best_axis], scale = RTPBR_BVH_BINS / (cbox.max[best_axis] - lo);
    uint32_t i = first, j = first + count;
    while (i < j) {
        int b = bin_of(s->centroid[s->order[i]][best_axis], lo, scale);
        if (b < best_plane) {
            ++i;
        } else {
            uint32_t t = s->order[i];
            s->order[i] = s->order[--j];
            s->order[j] = t;
        }
    }
    uint32_t left_count = i - first;
    uint32_t left = s->node_count;
    s->node_count += 2;
    rtpbr_shader_bvh_node *n = &s->nodes[node];
    memcpy(n->box_min, box.min, sizeof n->box_min);
    memcpy(n->box_max, box.max, sizeof n->box_max);
    n->left_or_first = left;
    n->count = 0;
    build(s, left, first, left_count, depth + 1);
    build(s, left + 1, first + left_count, count - left_count, depth + 1);
}

static void transform_point(const float m[16], const float p[3], float out[3])
{
    for (int k = 0; k < 3; ++k) out[k] = m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k];
}

// bvh.glsl's packet walk keeps a node index below 2^28 with the packet's 4 ray bits above it in
// a stack entry (RTPBR_BVH_PACKET_SHIFT): at most 2^27 triangles (8 GiB of them at 64 bytes).
#define RTPBR_BVH_MAX_TRIANGLES (1u << 27)

rtpbr_result rtpbr_bvh_create(rtpbr_gpu_scene *scene)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    uint64_t triangles = 0;
    for (uint32_t d = 0; d < scene->draw_count; ++d) triangles += scene->draws[d].index_count / 3;
    uint32_t tri_count = triangles > RTPBR_BVH_MAX_TRIANGLES ? 0 : (uint32_t)triangles;

    build_state s = {0};
    float (*tri)[9] = NULL;
    uint32_t *draw_of = NULL; // the draw of each triangle, in the order of s.tri
    uint32_t *first_index_of = NULL; // its first index in the scene's index buffer
    if (triangles > RTPBR_BVH_MAX_TRIANGLES)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED,
                   "the scene has %llu triangles; the shadow rays' BVH holds at most %u",
                   (unsigned long long)triangles, (unsigned)RTPBR_BVH_MAX_TRIANGLES);
    uint32_t node_slots = tri_count ? 2 * tri_count - 1 : 1;
    if (tri_count) {
        RTPBR_ALLOC(&ctx->host, tri, tri_count * sizeof *tri);
        RTPBR_ALLOC(&ctx->host, draw_of, tri_count * sizeof *draw_of);
        RTPBR_ALLOC(&ctx->host, first_index_of, tri_count * sizeof *first_index_of);
        RTPBR_ALLOC(&ctx->host, s.centroid, tri_count * sizeof *s.centroid);
        RTPBR_ALLOC(&ctx->host, s.order, tri_count * sizeof *s.order);
    }
    RTPBR_ALLOC(&ctx->host, s.nodes, node_slots * sizeof *s.nodes);
    // World-space triangles from the scene's (already uploaded, host-visible) buffers.
    const float *vertices = scene->vertices.mapped;
    const uint32_t *indices = scene->indices.mapped;
    uint32_t t = 0;
    for (uint32_t d = 0; d < scene->draw_count; ++d) {
        const rtpbr_draw *draw = &scene->draws[d];
        for (uint32_t k = 0; k + 2 < draw->index_count; k += 3, ++t) {
            for (int v = 0; v < 3; ++v)
                transform_point(draw->push.world_from_object,
                                vertices + RTPBR_VERTEX_FLOATS * (size_t)indices[draw->first_index + k + v], tri[t] + 3 * v);
            for (int c = 0; c < 3; ++c) s.centroid[t][c] = (tri[t][c] + tri[t][3 + c] + tri[t][6 + c]) / 3.0f;
            s.order[t] = t;
            draw_of[t] = d;
            first_index_of[t] = draw->first_index + k;
        }
    }
    s.tri = (const float (*)[9])tri;
    s.node_count = 1;
    if (tri_count) {
        build(&s, 0, 0, tri_count, 0);
    } else {
        aabb none = aabb_empty();
        make_leaf(&s, 0, &none, 0, 0);
    }

    RTPBR_TRY(rtpbr_buffer_create_host(ctx, s.node_count * sizeof(rtpbr_shader_bvh_node),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                       &scene->bvh_nodes));
    memcpy(scene->bvh_nodes.mapped, s.nodes, s.node_count * sizeof(rtpbr_shader_bvh_node));
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, (tri_count ? tri_count : 1) * sizeof(rtpbr_shader_bvh_triangle),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                       &scene->bvh_triangles));
    rtpbr_shader_bvh_triangle *out = scene->bvh_triangles.mapped;
    if (!tri_count) memset(out, 0, sizeof *out);
    for (uint32_t i = 0; i < tri_count; ++i) {
        const float *p = tri[s.order[i]];
        const uint32_t *ix = indices + first_index_of[s.order[i]];
        rtpbr_shader_bvh_triangle g = {{p[0], p[1], p[2], 0.0f},
                                       {p[3] - p[0], p[4] - p[1], p[5] - p[2], 0.0f},
                                       {p[6] - p[0], p[7] - p[1], p[8] - p[2], 0.0f},
                                       {ix[0], ix[1], ix[2], scene->draws[draw_of[s.order[i]]].push.material}};
        out[i] = g;
    }
    // Texel views of both (read on a CPU device: passes/shadow.c, bvh.glsl), within the device's
    // maxTexelBufferElements; where that cuts a view short the device reads the storage buffers.
    const VkDeviceSize node_bytes = s.node_count * sizeof(rtpbr_shader_bvh_node);
    const VkDeviceSize triangle_bytes = (tri_count ? tri_count : 1) * sizeof(rtpbr_shader_bvh_triangle);
    const VkDeviceSize limit = ctx->shadow.texel_view_range;
    VkBufferViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
                                   .buffer = scene->bvh_nodes.buffer,
                                   .format = VK_FORMAT_R32G32B32A32_UINT,
                                   .range = node_bytes < limit ? node_bytes : limit};
    RTPBR_VK(&ctx->host, vkCreateBufferView(ctx->device, &view, NULL, &scene->bvh_node_texels));
    view.buffer = scene->bvh_triangles.buffer;
    view.range = triangle_bytes < limit ? triangle_bytes : limit;
    RTPBR_VK(&ctx->host, vkCreateBufferView(ctx->device, &view, NULL, &scene->bvh_triangle_texels));
    scene->bvh_node_count = s.node_count;
    scene->bvh_triangle_count = tri_count;
    RTPBR_ALLOC(&ctx->host, scene->bvh_triangle_draws, (tri_count ? tri_count : 1) * sizeof *scene->bvh_triangle_draws);
    for (uint32_t i = 0; i < tri_count; ++i) scene->bvh_triangle_draws[i] = draw_of[s.order[i]];
    rtpbr_bvh_update_material_flags(scene);
cleanup:
    rtpbr_free(&ctx->host, tri);
    rtpbr_free(&ctx->host, draw_of);
    rtpbr_free(&ctx->host, first_index_of);
    rtpbr_free(&ctx->host, s.centroid);
    rtpbr_free(&ctx->host, s.order);
    rtpbr_free(&ctx->host, s.nodes);
    return result;
}

// Nodes are made parent first (build: a node's children are allocated after it), so a pass
// from the last node to the root meets every child before its parent.
void rtpbr_bvh_refit(rtpbr_gpu_scene *scene)
{
    const float *vertices = scene->vertices.mapped;
    rtpbr_shader_bvh_triangle *tris = scene->bvh_triangles.mapped;
    rtpbr_shader_bvh_node *nodes = scene->bvh_nodes.mapped;
    for (uint32_t i = 0; i < scene->bvh_triangle_count; ++i) {
        const float *m = scene->draws[scene->bvh_triangle_draws[i]].push.world_from_object;
        float p[3][3];
        for (int v = 0; v < 3; ++v)
            transform_point(m, vertices + RTPBR_VERTEX_FLOATS * (size_t)tris[i].source[v], p[v]);
        for (int k = 0; k < 3; ++k) {
            tris[i].v0[k] = p[0][k];
            tris[i].e1[k] = p[1][k] - p[0][k];
            tris[i].e2[k] = p[2][k] - p[0][k];
        }
    }
    for (uint32_t n = scene->bvh_node_count; n-- > 0;) {
        aabb box = aabb_empty();
        if (nodes[n].count > 0) {
            for (uint32_t i = nodes[n].left_or_first; i < nodes[n].left_or_first + nodes[n].count; ++i) {
                // the same vertices build() boxed: transform_point's, not v0 + e1
                const float *m = scene->draws[scene->bvh_triangle_draws[i]].push.world_from_object;
                for (int v = 0; v < 3; ++v) {
                    float p[3];
                    transform_point(m, vertices + RTPBR_VERTEX_FLOATS * (size_t)tris[i].source[v], p);
                    aabb_grow(&box, p);
                }
            }
        } else if (scene->bvh_triangle_count > 0) {
            for (uint32_t c = 0; c < 2; ++c) {
                const rtpbr_shader_bvh_node *child = &nodes[nodes[n].left_or_first + c];
                aabb b;
                memcpy(b.min, child->box_min, sizeof b.min);
                memcpy(b.max, child->box_max, sizeof b.max);
                aabb_merge(&box, &b);
            }
        }
        memcpy(nodes[n].box_min, box.min, sizeof box.min);
        memcpy(nodes[n].box_max, box.max, sizeof box.max);
    }
    rtpbr_bvh_update_material_flags(scene); // a transform may now mirror, or no longer
}

void rtpbr_bvh_update_material_flags(rtpbr_gpu_scene *scene)
{
    rtpbr_shader_bvh_triangle *out = scene->bvh_triangles.mapped;
    const rtpbr_shader_material *materials = scene->materials.mapped;
    for (uint32_t i = 0; i < scene->bvh_triangle_count; ++i) {
        const rtpbr_draw *d = &scene->draws[scene->bvh_triangle_draws[i]];
        uint32_t flags = materials[d->push.material].flags;
        bool single_sided = !(flags & RTPBR_MATERIAL_FLAG_DOUBLE_SIDED);
        out[i].v0[3] = !single_sided ? 0.0f : rtpbr_mat4_mirrors(d->push.world_from_object) ? -1.0f : 1.0f;
        out[i].e1[3] = (flags & (RTPBR_MATERIAL_FLAG_ALPHA_MASK | RTPBR_MATERIAL_FLAG_ALPHA_BLEND)) ? 1.0f : 0.0f;
    }
}

void rtpbr_bvh_destroy(rtpbr_gpu_scene *scene)
{
    rtpbr_free(&scene->context->host, scene->bvh_triangle_draws);
    scene->bvh_triangle_draws = NULL;
    vkDestroyBufferView(scene->context->device, scene->bvh_node_texels, NULL);
    vkDestroyBufferView(scene->context->device, scene->bvh_triangle_texels, NULL);
    scene->bvh_node_texels = scene->bvh_triangle_texels = VK_NULL_HANDLE;
    rtpbr_buffer_destroy(scene->context, &scene->bvh_nodes);
    rtpbr_buffer_destroy(scene->context, &scene->bvh_triangles);
}
