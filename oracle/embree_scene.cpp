// rtpbr oracle: Embree device and scenes.
#include "embree_scene.h"

#include "internal.h"
#include "rng.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rtpbr_oracle {

namespace {

void embreeErrorCallback(void *user, RTCError code, const char *message) {
    auto *errors = static_cast<DeviceErrors *>(user);
    std::lock_guard<std::mutex> lock(errors->mutex);
    if (errors->first.empty())
        errors->first = fmt("Embree error %d: %s", int(code), message ? message : "(no message)");
}

unsigned attachTriangles(RTCDevice device, RTCScene scene, const float *positions, uint32_t vertexCount,
                         const uint32_t *indices, uint32_t triangleCount) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g)
        return RTC_INVALID_GEOMETRY_ID;
    auto *v = static_cast<float *>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    auto *ix = static_cast<uint32_t *>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangleCount));
    if (!v || !ix) {
        rtcReleaseGeometry(g);
        return RTC_INVALID_GEOMETRY_ID;
    }
    std::memcpy(v, positions, sizeof(float) * 3 * vertexCount);
    std::memcpy(ix, indices, sizeof(uint32_t) * 3 * triangleCount);
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return id;
}

// The back face of a single-sided surface: the ray direction points along the front normal
// (counter-clockwise winding, the loader's convention).
bool hitsBackFace(const SurfaceFilter &f, const RTCFilterFunctionNArguments *args, unsigned i) {
    float n[3];
    if (f.positions) {
        const uint32_t *ix = f.indices + 3 * size_t(RTCHitN_primID(args->hit, args->N, i));
        const float *p0 = f.positions + 3 * size_t(ix[0]), *p1 = f.positions + 3 * size_t(ix[1]),
                    *p2 = f.positions + 3 * size_t(ix[2]);
        const float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    } else {
        std::memcpy(n, f.lightNormal, sizeof n);
    }
    const float d = n[0] * RTCRayN_dir_x(args->ray, args->N, i) + n[1] * RTCRayN_dir_y(args->ray, args->N, i) +
                    n[2] * RTCRayN_dir_z(args->ray, args->N, i);
    return d > 0.0f;
}

uint32_t floatBits(float x) {
    uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

// glTF alpha at a hit (SurfaceFilter): MASK keeps coverage >= alphaCutoff; BLEND keeps a hit of
// coverage a when a hash of the ray (origin, direction) and the triangle is below a.
bool alphaKeeps(const SurfaceFilter &f, const RTCFilterFunctionNArguments *args, unsigned i) {
    const rtpbr_gltf_material &m = *f.alphaMaterial;
    float alpha = m.base_color[3];
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (f.alphaTexture) {
        const rtpbr_gltf_primitive &p = *f.alphaPrimitive;
        const uint32_t *ix = p.indices + 3 * size_t(prim);
        const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        glm::vec2 uv[2] = {glm::vec2(0.0f), glm::vec2(0.0f)};
        const float *sets[2] = {p.has_texcoords ? p.texcoords : nullptr, p.has_texcoords1 ? p.texcoords1 : nullptr};
        for (int set = 0; set < 2; set++)
            if (sets[set])
                uv[set] = (1.0f - u - v) * glm::make_vec2(sets[set] + 2 * ix[0]) +
                          u * glm::make_vec2(sets[set] + 2 * ix[1]) + v * glm::make_vec2(sets[set] + 2 * ix[2]);
        glm::vec2 st = slotUv(m.base_color_texture_transform, uv[0], uv[1]);
        alpha *= f.alphaTexture->sample(st.x, st.y).a;
    }
    if (m.alpha_mode == RTPBR_GLTF_ALPHA_MASK)
        return alpha >= m.alpha_cutoff;
    uint64_t h = mix64((uint64_t(floatBits(RTCRayN_org_x(args->ray, args->N, i))) << 32) ^
                       floatBits(RTCRayN_org_y(args->ray, args->N, i)));
    h = mix64(h ^ (uint64_t(floatBits(RTCRayN_org_z(args->ray, args->N, i))) << 32) ^
              floatBits(RTCRayN_dir_x(args->ray, args->N, i)));
    h = mix64(h ^ (uint64_t(floatBits(RTCRayN_dir_y(args->ray, args->N, i))) << 32) ^
              floatBits(RTCRayN_dir_z(args->ray, args->N, i)));
    h = mix64(h ^ (uint64_t(RTCHitN_geomID(args->hit, args->N, i)) << 32) ^ prim);
    return float(h >> 40) * (1.0f / 16777216.0f) < alpha;
}

// Embree filter (intersection and occlusion) of a SurfaceFilter.
void surfaceFilter(const RTCFilterFunctionNArguments *args) {
    const auto *f = static_cast<const SurfaceFilter *>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; i++) {
        if (args->valid[i] != -1)
            continue;
        if ((f->cullBackFaces && hitsBackFace(*f, args, i)) || (f->alphaMaterial && !alphaKeeps(*f, args, i)))
            args->valid[i] = 0;
    }
}

void setSurfaceFilter(RTCScene scene, unsigned id, const SurfaceFilter *f) {
    RTCGeometry g = rtcGetGeometry(scene, id);
    rtcSetGeometryUserData(g, const_cast<SurfaceFilter *>(f));
    rtcSetGeometryIntersectFilterFunction(g, surfaceFilter);
    rtcSetGeometryOccludedFilterFunction(g, surfaceFilter);
    rtcCommitGeometry(g);
}

// ---- disk lights: an Embree user geometry of one primitive (DiskGeometry) ----

void diskBounds(const RTCBoundsFunctionArguments *args) {
    const DiskShape &D = static_cast<const DiskGeometry *>(args->geometryUserPtr)->shape;
    // Along axis k the ellipse reaches sqrt((r1 t_k)^2 + (r2 b_k)^2) from its centre (a disk:
    // r sqrt(1 - n_k^2)); rounded outwards.
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        const double e = std::hypot(D.radius * D.t[k], D.radius2 * D.b[k]);
        lo[k] = std::nextafter(float(D.centre[k] - e), -INFINITY);
        hi[k] = std::nextafter(float(D.centre[k] + e), INFINITY);
    }
    RTCBounds *b = args->bounds_o;
    b->lower_x = lo[0];
    b->lower_y = lo[1];
    b->lower_z = lo[2];
    b->upper_x = hi[0];
    b->upper_y = hi[1];
    b->upper_z = hi[2];
}

// Does ray i of a packet meet the disk within [tnear, tfar] (not its back, if culled)? *t,
// *x, *y: where (the hit distance in float, within the interval).
bool diskHit(const DiskGeometry &g, RTCRayN *ray, unsigned N, unsigned i, float *t, float *x, float *y) {
    const glm::dvec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const glm::dvec3 w(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    if (g.cullBackFaces && glm::dot(w, g.shape.n) > 0.0)
        return false;
    const float tnear = RTCRayN_tnear(ray, N, i), tfar = RTCRayN_tfar(ray, N, i);
    double s, dx, dy;
    if (!g.shape.intersect(o, w, double(tnear), double(tfar), &s, &dx, &dy))
        return false;
    *t = glm::clamp(float(s), tnear, tfar);
    *x = float(dx);
    *y = float(dy);
    return true;
}

void diskIntersect(const RTCIntersectFunctionNArguments *args) {
    const auto &g = *static_cast<const DiskGeometry *>(args->geometryUserPtr);
    RTCRayN *ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN *hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; i++) {
        float t, x, y;
        if (args->valid[i] != -1 || !diskHit(g, ray, args->N, i, &t, &x, &y))
            continue;
        RTCRayN_tfar(ray, args->N, i) = t;
        RTCHitN_Ng_x(hit, args->N, i) = float(g.shape.n.x);
        RTCHitN_Ng_y(hit, args->N, i) = float(g.shape.n.y);
        RTCHitN_Ng_z(hit, args->N, i) = float(g.shape.n.z);
        RTCHitN_u(hit, args->N, i) = x;
        RTCHitN_v(hit, args->N, i) = y;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
    }
}

void diskOccluded(const RTCOccludedFunctionNArguments *args) {
    const auto &g = *static_cast<const DiskGeometry *>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; i++) {
        float t, x, y;
        if (args->valid[i] == -1 && diskHit(g, args->ray, args->N, i, &t, &x, &y))
            RTCRayN_tfar(args->ray, args->N, i) = -INFINITY;
    }
}

unsigned attachDisk(RTCDevice device, RTCScene scene, DiskGeometry *d) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!g)
        return RTC_INVALID_GEOMETRY_ID;
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, d);
    rtcSetGeometryBoundsFunction(g, diskBounds, d);
    rtcSetGeometryIntersectFunction(g, diskIntersect);
    rtcSetGeometryOccludedFunction(g, diskOccluded);
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return id;
}

unsigned attachLight(RTCDevice device, RTCScene scene, const rtpbr_gltf_light &L) {
    float pos[3 * RTPBR_GLTF_MAX_POLYGON_VERTICES];
    uint32_t idx[3 * RTPBR_GLTF_MAX_POLYGON_VERTICES];
    for (uint32_t k = 0; k < L.vertex_count; k++)
        for (int c = 0; c < 3; c++)
            pos[3 * k + c] = L.vertices[k][c];
    uint32_t tris = 0;
    for (uint32_t k = 1; k + 1 < L.vertex_count; k++, tris++) {
        idx[3 * tris] = 0;
        idx[3 * tris + 1] = k;
        idx[3 * tris + 2] = k + 1;
    }
    return attachTriangles(device, scene, pos, L.vertex_count, idx, tris);
}

} // namespace

Result buildEmbree(const rtpbr_gltf_scene &scene, const std::vector<Texture> &textures, EmbreeScene *es,
                   std::string *error) {
    es->device = rtcNewDevice("threads=1,user_threads=0");
    if (!es->device) {
        *error = fmt("cannot create the Embree device (error %d)", int(rtcGetDeviceError(nullptr)));
        return Result::Embree;
    }
    rtcSetDeviceErrorFunction(es->device, embreeErrorCallback, &es->errors);
    es->full = rtcNewScene(es->device);
    es->lightsOnly = rtcNewScene(es->device);
    if (!es->full || !es->lightsOnly) {
        *error = es->errors.first.empty() ? "cannot create Embree scenes" : es->errors.first;
        return Result::Embree;
    }
    rtcSetSceneBuildQuality(es->full, RTC_BUILD_QUALITY_HIGH);
    // Emissive primitives are represented by their light polygons (which the loader made
    // from exactly their triangles), so that every light hit knows its light.
    std::vector<bool> isLightPrimitive(scene.primitive_count, false);
    for (uint32_t l = 0; l < scene.light_count; l++)
        if (scene.lights[l].primitive >= 0 && uint32_t(scene.lights[l].primitive) < scene.primitive_count)
            isLightPrimitive[uint32_t(scene.lights[l].primitive)] = true;
    for (uint32_t p = 0; p < scene.primitive_count; p++) {
        const rtpbr_gltf_primitive &prim = scene.primitives[p];
        if (isLightPrimitive[p] || prim.index_count < 3)
            continue;
        unsigned id = attachTriangles(es->device, es->full, prim.positions, prim.vertex_count, prim.indices,
                                      prim.index_count / 3);
        if (id == RTC_INVALID_GEOMETRY_ID)
            break;
        es->fullGeoms.resize(std::max<size_t>(es->fullGeoms.size(), id + 1));
        es->fullGeoms[id] = {false, p};
        if (prim.material < scene.material_count) {
            const rtpbr_gltf_material &m = scene.materials[prim.material];
            SurfaceFilter f;
            f.cullBackFaces = !m.double_sided;
            f.positions = prim.positions;
            f.indices = prim.indices;
            if (m.alpha_mode == RTPBR_GLTF_ALPHA_MASK || m.alpha_mode == RTPBR_GLTF_ALPHA_BLEND) {
                f.alphaPrimitive = &prim;
                f.alphaMaterial = &m;
                if (m.base_color_texture >= 0 && uint32_t(m.base_color_texture) < textures.size())
                    f.alphaTexture = &textures[uint32_t(m.base_color_texture)];
            }
            if (f.cullBackFaces || f.alphaMaterial) {
                es->filters.push_back(f);
                setSurfaceFilter(es->full, id, &es->filters.back());
            }
        }
    }
    for (uint32_t l = 0; l < scene.light_count; l++) {
        const rtpbr_gltf_light &L = scene.lights[l];
        const bool singleSided = L.material >= 0 && uint32_t(L.material) < scene.material_count &&
                                 !scene.materials[L.material].double_sided;
        unsigned id, id2;
        if (L.shape == RTPBR_GLTF_LIGHT_DISK) {
            // Back faces dropped in `full` only, as the light polygons' filters are.
            es->disks.push_back(DiskGeometry{DiskShape::of(L), singleSided});
            id = attachDisk(es->device, es->full, &es->disks.back());
            es->disks.push_back(DiskGeometry{DiskShape::of(L), false});
            id2 = attachDisk(es->device, es->lightsOnly, &es->disks.back());
        } else {
            id = attachLight(es->device, es->full, L);
            id2 = attachLight(es->device, es->lightsOnly, L);
        }
        if (id == RTC_INVALID_GEOMETRY_ID || id2 == RTC_INVALID_GEOMETRY_ID)
            break;
        es->fullGeoms.resize(std::max<size_t>(es->fullGeoms.size(), id + 1));
        es->fullGeoms[id] = {true, l};
        if (singleSided && L.shape != RTPBR_GLTF_LIGHT_DISK) {
            SurfaceFilter f;
            f.cullBackFaces = true;
            std::memcpy(f.lightNormal, L.facts.normal, sizeof f.lightNormal);
            es->filters.push_back(f);
            setSurfaceFilter(es->full, id, &es->filters.back());
        }
        es->lightOnlyGeoms.resize(std::max<size_t>(es->lightOnlyGeoms.size(), id2 + 1));
        es->lightOnlyGeoms[id2] = l;
    }
    rtcCommitScene(es->full);
    rtcCommitScene(es->lightsOnly);
    if (!es->errors.first.empty()) {
        *error = es->errors.first;
        return Result::Embree;
    }
    return Result::Success;
}

} // namespace rtpbr_oracle
