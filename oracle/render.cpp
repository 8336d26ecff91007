// rtpbr oracle: the path tracer (integrator, tiles, threads, accumulation).
#include "oracle.h"

#include "bsdf.h"
#include "embree_scene.h"
#include "internal.h"
#include "microsurface.h"
#include "rng.h"
#include "texture.h"

#include <rtpbr/fresnel.h>
#include <rtpbr/material.h>
#include <rtpbr/ndf.h>

#include <embree3/rtcore.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

namespace rtpbr_oracle {


namespace {

using glm::vec3;

constexpr uint32_t kTileSize = 16;
// Walks per node of a dielectric layer's albedo table (standard error < 0.002 per node).
constexpr int kLayerAlbedoWalks = 512;

// The inputs of the shader library's material resolve from a loader material, before textures.
rtpbr::MaterialInputs materialInputs(const rtpbr_gltf_material &m) {
    rtpbr::MaterialInputs in;
    in.model = m.has_disney ? rtpbr::RTPBR_MATERIAL_MODEL_DISNEY : rtpbr::RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    in.baseColor = glm::make_vec3(m.base_color);
    in.metallic = m.metallic;
    in.roughness = m.roughness;
    in.ior = m.ior.ior;
    in.specularFactor = m.specular.specular_factor;
    in.specularColor = glm::make_vec3(m.specular.specular_color_factor);
    in.clearcoatFactor = m.clearcoat.clearcoat_factor;
    in.clearcoatRoughness = m.clearcoat.clearcoat_roughness_factor;
    in.sheenColorFactor = glm::make_vec3(m.sheen.sheen_color_factor);
    in.sheenRoughness = m.sheen.sheen_roughness_factor;
    in.anisotropyStrength = m.anisotropy.anisotropy_strength;
    in.disney = rtpbr::Disney_DefaultMaterial();
    in.disney.subsurface = m.disney.subsurface;
    in.disney.specular = m.disney.specular;
    in.disney.specularTint = m.disney.specular_tint;
    in.disney.anisotropic = m.disney.anisotropic;
    in.disney.sheen = m.disney.sheen;
    in.disney.sheenTint = m.disney.sheen_tint;
    in.disney.clearcoat = m.disney.clearcoat;
    in.disney.clearcoatGloss = m.disney.clearcoat_gloss;
    return in;
}

constexpr uint32_t kRussianRouletteDepth = 3;


uint32_t imageHeight(const rtpbr_gltf_scene &scene, const RenderSettings &s, uint32_t width) {
    if (s.height)
        return s.height;
    float aspect = s.camera < scene.camera_count ? scene.cameras[s.camera].aspect : 0.0f;
    if (aspect > 0.0f && std::isfinite(aspect))
        return std::max(1u, uint32_t(std::lround(double(width) / aspect)));
    return std::max(1u, width * 3 / 4);
}

// The oracle's own image of a scene: bumped when a scene's image changes with the same settings
// (2: EXT_lights_area disks rendered as disks, not their octagons; 3: point lights with a
// length rendered as capsules, not spheres), so that a resumed .acc never merges samples of two
// versions.
constexpr uint64_t kImageVersion = 3;

// Everything that changes the image except the sample range, the region and the thread count.
uint64_t settingsHash(const RenderSettings &s, uint32_t w, uint32_t h) {
    uint64_t x = mix64(0x6f7261636c65ull);
    x = mix64(x ^ (kImageVersion << 56));
    auto add = [&x](uint64_t v) { x = mix64(x ^ v); };
    add(w);
    add(h);
    add(s.camera);
    add(s.spp);
    add(s.seed);
    add(s.directOnly ? 1 : s.maxDepth);
    add(s.noShadows);
    add(s.singleScatter);
    add(uint64_t(s.lightSampling));
    return x;
}

// ---- the path tracer -----------------------------------------------------------------------

struct Hit {
    bool found = false;
    float t = 0.0f;
    unsigned geomID = 0, primID = 0;
    float u = 0.0f, v = 0.0f;
};

struct SurfacePoint {
    vec3 p = vec3(0.0f);
    vec3 ng = vec3(0.0f); // geometric normal, facing the incoming ray
    vec3 ns = vec3(0.0f); // shading normal, same side as ng
    vec3 tangent = vec3(0.0f); // shading tangent (anisotropy direction), orthogonal to ns
    float tangentSign = 1.0f;  // glTF TANGENT.w: the bitangent is tangentSign cross(ns, tangent)
    int32_t light = -1;
    int32_t material = -1;
    glm::vec2 uv[2] = {glm::vec2(0.0f), glm::vec2(0.0f)}; // TEXCOORD_0, TEXCOORD_1
};

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
void orthonormalBasis(vec3 n, vec3 *t, vec3 *b) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float bb = n.x * n.y * a;
    *t = vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    *b = vec3(bb, sign + n.y * n.y * a, -n.y);
}

class Integrator {
public:
    Integrator(const rtpbr_gltf_scene &scene, const EmbreeScene &es, const LightSet &lights,
               const PunctualLights &punctual, const RenderSettings &s, const std::vector<Texture> &textures,
               const std::vector<const LayerAlbedo *> &layers)
        : scene_(scene), es_(es), lights_(lights), punctual_(punctual), s_(s), textures_(textures), layers_(layers) {
        maxDepth_ = s.directOnly ? 1u : std::max(1u, s.maxDepth);
    }

    uint64_t rays = 0;

    vec3 radiance(vec3 org, vec3 dir, Rng &rng) {
        vec3 L(0.0f), beta(1.0f);
        vec3 prevP(0.0f);
        float prevPdf = 0.0f;
        for (uint32_t depth = 0;; depth++) {
            Hit h = intersect(es_.full, org, dir, std::numeric_limits<float>::infinity());
            // A BSDF ray may see a sphere or a capsule before its hit, or a sun's disk if it
            // leaves the scene (MIS against sampling them; with noShadows the light-only test
            // below counted them already). Camera rays do not: like the punctual lights, spheres,
            // capsules and the sun are not drawn.
            if (depth > 0 && !s_.noShadows && punctual_.anyVisible())
                L += beta * punctualSeen(prevP, dir, h.found ? h.t : std::numeric_limits<float>::infinity(), prevPdf);
            if (!h.found)
                break;
            SurfacePoint sp = surfacePoint(h, dir);
            // Emission: seen directly, or found by BSDF sampling (MIS against light sampling;
            // with noShadows the unoccluded light-only ray below did that already).
            if (sp.light >= 0 && (depth == 0 || !s_.noShadows)) {
                vec3 Le = emittedAt(uint32_t(sp.light), dir, sp.p);
                if (Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f) {
                    float w = 1.0f;
                    if (depth > 0)
                        w = misWeight(prevPdf, lights_.pdf(prevP, uint32_t(sp.light), dir, h.t));
                    L += beta * Le * w;
                }
            }
            if (depth >= maxDepth_ || sp.material < 0)
                break;

            SurfaceMaterial mat = material(sp);
            vec3 bt = glm::cross(sp.ns, sp.tangent);
            auto toLocal = [&](vec3 w) { return vec3(glm::dot(w, sp.tangent), glm::dot(w, bt), glm::dot(w, sp.ns)); };
            auto toWorld = [&](vec3 w) { return w.x * sp.tangent + w.y * bt + w.z * sp.ns; };
            vec3 wo = toLocal(-dir);
            Bsdf bsdf(mat, s_.singleScatter, wo);
            if (bsdf.isBlack())
                break;
            vec3 origin = offset(sp, sp.ng);

            // Light sampling.
            LightSample ls;
            float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            // Lights are sampled from the offset point (on the side the ray arrived from): a
            // point on a light's own plane (the back of a one-sided light, seen by the camera)
            // then sees that light from behind or not at all, instead of a degenerate
            // zero-solid-angle sample with an unbounded weight.
            if (lights_.sample(origin, ul, u1, u2, &ls) && glm::dot(ls.wi, sp.ng) > 0.0f &&
                (ls.radiance.x > 0.0f || ls.radiance.y > 0.0f || ls.radiance.z > 0.0f)) {
                vec3 wiL = toLocal(ls.wi);
                vec3 f = bsdf.eval(wiL, rng);
                if (f.x > 0.0f || f.y > 0.0f || f.z > 0.0f) {
                    bool visible = s_.noShadows || unoccluded(origin, origin + ls.wi * ls.distance);
                    if (visible)
                        L += beta * f * emittedAt(ls.light, ls.wi, origin + ls.wi * ls.distance) *
                             (misWeight(ls.pdf, bsdf.pdfMis(wiL)) / ls.pdf);
                }
            }
            // The punctual lights: each one, weight 1 (no other strategy finds a delta light).
            for (uint32_t l = 0; l < punctual_.size(); l++)
                L += beta * punctualLight(l, sp, bt, origin, bsdf, rng);

            // BSDF sampling.
            BsdfSample bs;
            if (!bsdf.sample(rng, &bs))
                break;
            vec3 wi = glm::normalize(toWorld(bs.wi));
            if (!(glm::dot(wi, sp.ng) > 0.0f))
                break;
            beta *= bs.weight;
            if (!(beta.x > 0.0f || beta.y > 0.0f || beta.z > 0.0f))
                break;
            if (s_.noShadows) {
                Hit lh = intersect(es_.lightsOnly, origin, wi, std::numeric_limits<float>::infinity());
                if (lh.found) {
                    uint32_t l = es_.lightOnlyGeoms[lh.geomID];
                    vec3 Le = emittedAt(l, wi, origin + wi * lh.t);
                    L += beta * Le * misWeight(bs.pdfMis, lights_.pdf(sp.p, l, wi, lh.t));
                }
                if (punctual_.anyVisible())
                    L += beta * punctualSeen(sp.p, wi, std::numeric_limits<float>::infinity(), bs.pdfMis);
                if (depth + 1 >= maxDepth_)
                    break; // the next vertex would only add emission, already counted
            }
            if (depth + 1 >= kRussianRouletteDepth) {
                float q = std::min(0.95f, std::max(beta.x, std::max(beta.y, beta.z)));
                if (rng.uniform() >= q)
                    break;
                beta /= q;
            }
            prevP = sp.p;
            prevPdf = bs.pdfMis;
            org = origin;
            dir = wi;
        }
        return L;
    }

private:
    static float misWeight(float a, float b) {
        // Balance heuristic (Veach 1997, sec. 9.2).
        return a > 0.0f ? a / (a + b) : 0.0f;
    }

    // The Embree ray org + t dir, 0 <= t <= tfar, every mask bit set.
    static RTCRay makeRay(vec3 org, vec3 dir, float tfar) {
        RTCRay r;
        r.org_x = org.x;
        r.org_y = org.y;
        r.org_z = org.z;
        r.dir_x = dir.x;
        r.dir_y = dir.y;
        r.dir_z = dir.z;
        r.tnear = 0.0f;
        r.tfar = tfar;
        r.time = 0.0f;
        r.mask = 0xffffffffu;
        r.id = 0;
        r.flags = 0;
        return r;
    }

    Hit intersect(RTCScene scene, vec3 org, vec3 dir, float tfar) {
        rays++;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        rh.ray = makeRay(org, dir, tfar);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return h;
        h.found = true;
        h.t = rh.ray.tfar;
        h.geomID = rh.hit.geomID;
        h.primID = rh.hit.primID;
        h.u = rh.hit.u;
        h.v = rh.hit.v;
        return h;
    }

    bool occluded(vec3 org, vec3 dir, float tfar) {
        rays++;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay r = makeRay(org, dir, tfar);
        rtcOccluded1(es_.full, &ctx, &r);
        return r.tfar < 0.0f;
    }

    // The offset that moves a point at p off its surface: relative to its magnitude.
    static float offsetScale(vec3 p) {
        return 1e-4f * (1.0f + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z))));
    }
    static vec3 offset(const SurfacePoint &sp, vec3 n) { return sp.p + n * offsetScale(sp.p); }

    // Shadow ray from origin (already off its surface) to a point on a light, stopping short
    // of the light's surface by the same relative offset.
    bool unoccluded(vec3 origin, vec3 target) {
        vec3 d = target - origin;
        float len = glm::length(d);
        float tfar = len - offsetScale(target);
        if (!(tfar > 0.0f))
            return true;
        return !occluded(origin, d / len, tfar);
    }

    // What punctual light l reflects toward wo at sp (bt: the shading frame's bitangent):
    // f cos x its irradiance there (PunctualLights), if a shadow ray from origin (sp.p off
    // its surface) reaches the light (a directional light: to infinity), or with noShadows.
    // The light's direction and distance are taken from sp.p itself, the point the
    // extension's formulas speak of. A sun's disk or a sphere: one direction sampled in its
    // cap or cone (two random numbers, drawn for them alone: delta lights draw none), weighted
    // by MIS against the BSDF rays that see it (punctualSeen), the shadow ray to infinity or
    // to the sphere's near surface; the part of the cap or cone below the surface's horizon
    // gives nothing. A capsule: one point on its surface (two random numbers too), the shadow
    // ray to it, a point below the horizon or facing away giving nothing.
    vec3 punctualLight(uint32_t l, const SurfacePoint &sp, vec3 bt, vec3 origin, const Bsdf &bsdf, Rng &rng) {
        PunctualSample ps;
        float u1 = 0.0f, u2 = 0.0f;
        if (punctual_.hasDisk(l) || punctual_.hasSphere(l) || punctual_.hasCapsule(l)) {
            u1 = rng.uniform();
            u2 = rng.uniform();
        }
        if (!punctual_.illuminate(l, sp.p, u1, u2, &ps) || !(glm::dot(ps.wi, sp.ng) > 0.0f))
            return vec3(0.0f);
        const vec3 wiLocal(glm::dot(ps.wi, sp.tangent), glm::dot(ps.wi, bt), glm::dot(ps.wi, sp.ns));
        vec3 f = bsdf.eval(wiLocal, rng);
        if (!(f.x > 0.0f || f.y > 0.0f || f.z > 0.0f))
            return vec3(0.0f);
        if (!s_.noShadows) {
            bool blocked = std::isinf(ps.distance)
                               ? occluded(origin, ps.wi, std::numeric_limits<float>::infinity())
                               : !unoccluded(origin, sp.p + ps.wi * ps.distance);
            if (blocked)
                return vec3(0.0f);
        }
        if (ps.pdf > 0.0) // balance heuristic, in double: a tiny disk's density exceeds a float
            return f * ps.irradiance * float(ps.pdf / (ps.pdf + double(bsdf.pdfMis(wiLocal))));
        return f * ps.irradiance;
    }

    // What the punctual lights a BSDF ray from shading point p towards wi sees give, weighted
    // by MIS against sampling them (punctualLight); bsdfPdf: the BSDF sample's pdfMis. The
    // spheres and capsules it meets before tmax (the scene's hit; infinity with noShadows), the
    // suns' disks where tmax is infinite (it met nothing, or noShadows). From inside a sphere or
    // a capsule no light sample competes: weight 1.
    vec3 punctualSeen(vec3 p, vec3 wi, float tmax, float bsdfPdf) const {
        glm::dvec3 sum(0.0);
        for (uint32_t l = 0; l < punctual_.size(); l++) {
            glm::dvec3 Le;
            double pdf;
            if (std::isinf(tmax) && bsdfPdf > 0.0f && punctual_.diskRadiance(l, wi, &Le, &pdf))
                sum += Le * (double(bsdfPdf) / (double(bsdfPdf) + pdf));
            else if (punctual_.sphereRadiance(l, p, wi, tmax, &Le, &pdf) ||
                     punctual_.capsuleRadiance(l, p, wi, tmax, &Le, &pdf))
                sum += pdf > 0.0 ? Le * (double(bsdfPdf) / (double(bsdfPdf) + pdf)) : Le;
        }
        return vec3(sum);
    }

    // Light l's radiance toward -wi at its point q: LightSet::emitted, times the emission
    // texture there for the triangle lights of textured emitters (rtpbr_gltf_light.triangle,
    // RTPBR_GLTF_EMISSIVE_EXACT), the triangle's texture coordinates at q's barycentrics.
    vec3 emittedAt(uint32_t l, vec3 wi, vec3 q) const {
        vec3 Le = lights_.emitted(l, wi);
        const rtpbr_gltf_light &L = scene_.lights[l];
        if (L.triangle < 0 || L.primitive < 0 || uint32_t(L.primitive) >= scene_.primitive_count ||
            !(Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f))
            return Le;
        const rtpbr_gltf_primitive &prim = scene_.primitives[L.primitive];
        const rtpbr_gltf_material &m = scene_.materials[prim.material];
        if (m.emission_texture < 0 || uint32_t(L.triangle) * 3 + 2 >= prim.index_count)
            return Le;
        const uint32_t *ix = prim.indices + 3 * uint32_t(L.triangle);
        vec3 p0 = glm::make_vec3(prim.positions + 3 * ix[0]), p1 = glm::make_vec3(prim.positions + 3 * ix[1]),
             p2 = glm::make_vec3(prim.positions + 3 * ix[2]);
        vec3 n = glm::cross(p1 - p0, p2 - p0);
        float nn = glm::dot(n, n);
        if (!(nn > 0.0f))
            return Le;
        float b1 = glm::dot(glm::cross(q - p0, p2 - p0), n) / nn, b2 = glm::dot(glm::cross(p1 - p0, q - p0), n) / nn;
        float b0 = 1.0f - b1 - b2;
        SurfacePoint sp;
        const float *sets[2] = {prim.has_texcoords ? prim.texcoords : nullptr, prim.has_texcoords1 ? prim.texcoords1 : nullptr};
        for (int set = 0; set < 2; set++)
            if (sets[set])
                sp.uv[set] = b0 * glm::make_vec2(sets[set] + 2 * ix[0]) + b1 * glm::make_vec2(sets[set] + 2 * ix[1]) +
                             b2 * glm::make_vec2(sets[set] + 2 * ix[2]);
        return Le * vec3(sampleSlot(m.emission_texture, m.emission_texture_transform, sp));
    }

    SurfacePoint surfacePoint(const Hit &h, vec3 dir) const {
        SurfacePoint sp;
        const GeometryRecord &g = es_.fullGeoms[h.geomID];
        vec3 p0, p1, p2;
        // A textured emitter's triangle (rtpbr_gltf_light.triangle; its vertices in the
        // primitive's order, so the hit's barycentrics are the triangle's): shaded as the
        // primitive's own surface, with its texture coordinates, normals and tangents.
        const bool lightTriangle = g.isLight && scene_.lights[g.index].triangle >= 0 &&
                                   scene_.lights[g.index].primitive >= 0;
        const DiskShape *disk = g.isLight ? lights_.disk(g.index) : nullptr;
        if (disk) { // the hit's u, v: its disk coordinates (DiskGeometry)
            const rtpbr_gltf_light &L = scene_.lights[g.index];
            sp.light = int32_t(g.index);
            sp.material = L.material;
            sp.ng = vec3(disk->n);
            sp.ns = sp.ng;
            sp.p = vec3(disk->point(double(h.u), double(h.v)));
        } else if (g.isLight && !lightTriangle) {
            const rtpbr_gltf_light &L = scene_.lights[g.index];
            p0 = glm::make_vec3(L.vertices[0]);
            p1 = glm::make_vec3(L.vertices[h.primID + 1]);
            p2 = glm::make_vec3(L.vertices[h.primID + 2]);
            sp.light = int32_t(g.index);
            sp.material = L.material;
            sp.ng = glm::make_vec3(L.facts.normal);
            sp.ns = sp.ng;
            sp.p = (1.0f - h.u - h.v) * p0 + h.u * p1 + h.v * p2;
        } else {
            const rtpbr_gltf_light *light = lightTriangle ? &scene_.lights[g.index] : nullptr;
            const rtpbr_gltf_primitive &prim = scene_.primitives[light ? uint32_t(light->primitive) : g.index];
            const uint32_t *ix = prim.indices + 3 * (light ? uint32_t(light->triangle) : h.primID);
            if (light)
                sp.light = int32_t(g.index);
            p0 = glm::make_vec3(prim.positions + 3 * ix[0]);
            p1 = glm::make_vec3(prim.positions + 3 * ix[1]);
            p2 = glm::make_vec3(prim.positions + 3 * ix[2]);
            float b0 = 1.0f - h.u - h.v;
            sp.p = b0 * p0 + h.u * p1 + h.v * p2;
            sp.ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
            sp.ns = b0 * glm::make_vec3(prim.normals + 3 * ix[0]) + h.u * glm::make_vec3(prim.normals + 3 * ix[1]) +
                    h.v * glm::make_vec3(prim.normals + 3 * ix[2]);
            sp.material = int32_t(prim.material);
            const float *sets[2] = {prim.has_texcoords ? prim.texcoords : nullptr,
                                    prim.has_texcoords1 ? prim.texcoords1 : nullptr};
            for (int set = 0; set < 2; set++)
                if (sets[set])
                    sp.uv[set] = b0 * glm::make_vec2(sets[set] + 2 * ix[0]) + h.u * glm::make_vec2(sets[set] + 2 * ix[1]) +
                                 h.v * glm::make_vec2(sets[set] + 2 * ix[2]);
            if (prim.has_tangents) {
                vec3 t = b0 * glm::make_vec3(prim.tangents + 4 * ix[0]) + h.u * glm::make_vec3(prim.tangents + 4 * ix[1]) +
                         h.v * glm::make_vec3(prim.tangents + 4 * ix[2]);
                sp.tangent = t;
                sp.tangentSign = prim.tangents[4 * ix[0] + 3] < 0.0f ? -1.0f : 1.0f;
                applyNormalMap(prim, ix, &sp);
            }
        }
        if (glm::dot(sp.ng, dir) > 0.0f)
            sp.ng = -sp.ng;
        float nl = glm::length(sp.ns);
        sp.ns = nl > 0.0f && std::isfinite(nl) ? sp.ns / nl : sp.ng;
        if (glm::dot(sp.ns, sp.ng) < 0.0f)
            sp.ns = -sp.ns;
        // A shading normal facing away from the viewer would make wo.z <= 0: use the geometry.
        if (!(glm::dot(sp.ns, -dir) > 1e-4f))
            sp.ns = sp.ng;
        vec3 t = sp.tangent - glm::dot(sp.tangent, sp.ns) * sp.ns;
        float tl = glm::length(t);
        if (tl > 1e-6f && std::isfinite(tl)) {
            sp.tangent = t / tl;
        } else {
            vec3 b;
            orthonormalBasis(sp.ns, &sp.tangent, &b);
        }
        return sp;
    }

    // A material slot's texture at a surface point: the slot's texture coordinate set through its
    // KHR_texture_transform (rtpbr_gltf.h states the matrix). White without a texture, so that
    // the factor passes through.
    glm::vec4 sampleSlot(int32_t texture, const rtpbr_gltf_texture_transform &t, const SurfacePoint &sp) const {
        if (texture < 0 || uint32_t(texture) >= textures_.size())
            return glm::vec4(1.0f);
        glm::vec2 uv = slotUv(t, sp.uv[0], sp.uv[1]);
        return textures_[uint32_t(texture)].sample(uv.x, uv.y);
    }

    // glTF normalTexture: tangent-space normal (2 rgb - 1) scaled in xy by normal_scale, with
    // the bitangent B = w cross(N, T) (glTF 2.0, meshes: TANGENT). Done in the primitive's
    // own orientation, before the normal is turned towards the viewer.
    void applyNormalMap(const rtpbr_gltf_primitive &prim, const uint32_t *ix, SurfacePoint *sp) const {
        const rtpbr_gltf_material &m = scene_.materials[prim.material];
        if (m.normal_texture < 0 || uint32_t(m.normal_texture) >= textures_.size())
            return;
        vec3 n = sp->ns;
        float nl = glm::length(n);
        if (!(nl > 0.0f) || !std::isfinite(nl))
            return;
        n /= nl;
        vec3 t = sp->tangent - glm::dot(sp->tangent, n) * n;
        float tl = glm::length(t);
        if (!(tl > 1e-6f) || !std::isfinite(tl))
            return;
        t /= tl;
        float w = prim.tangents[4 * ix[0] + 3] < 0.0f ? -1.0f : 1.0f;
        vec3 b = w * glm::cross(n, t);
        glm::vec4 c = sampleSlot(m.normal_texture, m.normal_texture_transform, *sp);
        vec3 ts(2.0f * c.x - 1.0f, 2.0f * c.y - 1.0f, 2.0f * c.z - 1.0f);
        ts.x *= m.normal_scale;
        ts.y *= m.normal_scale;
        vec3 mapped = ts.x * t + ts.y * b + ts.z * n;
        float ml = glm::length(mapped);
        if (ml > 1e-6f && std::isfinite(ml))
            sp->ns = mapped / ml;
    }

    // The material at a surface point: the loader's factors times the textures, resolved by the
    // shader library's Material_Resolve (material.h), the function the engine's shaders call.
    SurfaceMaterial material(SurfacePoint &sp) const {
        const rtpbr_gltf_material &m = scene_.materials[sp.material];
        rtpbr::MaterialInputs in = materialInputs(m);
        // glTF: each texture multiplies its factor in the channels its slot names.
        in.baseColor *= vec3(sampleSlot(m.base_color_texture, m.base_color_texture_transform, sp));
        glm::vec4 mr = sampleSlot(m.metallic_roughness_texture, m.metallic_roughness_texture_transform, sp);
        in.roughness *= mr.y;
        in.metallic *= mr.z;
        if (m.has_specular) {
            in.specularFactor *= sampleSlot(m.specular.specular_texture, m.specular.specular_texture_transform, sp).a;
            in.specularColor *= vec3(
                sampleSlot(m.specular.specular_color_texture, m.specular.specular_color_texture_transform, sp));
        }
        if (m.has_clearcoat) {
            in.clearcoatFactor *= sampleSlot(m.clearcoat.clearcoat_texture, m.clearcoat.clearcoat_texture_transform, sp).r;
            in.clearcoatRoughness *= sampleSlot(m.clearcoat.clearcoat_roughness_texture,
                                                m.clearcoat.clearcoat_roughness_texture_transform, sp).g;
        }
        if (m.has_sheen) {
            in.sheenColorFactor *= vec3(sampleSlot(m.sheen.sheen_color_texture, m.sheen.sheen_color_texture_transform, sp));
            in.sheenRoughness *=
                sampleSlot(m.sheen.sheen_roughness_texture, m.sheen.sheen_roughness_texture_transform, sp).a;
        }
        rtpbr::MaterialParams p = rtpbr::Material_Resolve(in);
        SurfaceMaterial out;
        out.baseColor = p.baseColor;
        out.metallic = p.metallic;
        out.alphaX = p.alphas.x;
        out.alphaY = p.alphas.y;
        out.tableRoughness = p.tableRoughness;
        out.specularWeight = p.specularWeight;
        out.layer = layers_[uint32_t(sp.material)];
        float rotation = m.anisotropy.anisotropy_rotation;
        if (p.alphas.x != p.alphas.y && !p.disney && rotation != 0.0f) {
            // KHR_materials_anisotropy: direction = T cos + B sin, B = w cross(N, T) (glTF).
            vec3 b = sp.tangentSign * glm::cross(sp.ns, sp.tangent);
            float c = std::cos(rotation), s = std::sin(rotation);
            sp.tangent = c * sp.tangent + s * b;
        }
        if (p.disney) { // Burley's coat is part of the closed-form Disney lobes (bsdf.h)
            out.disney = true;
            out.disneyParams = p.dm;
        } else {
            out.coat = p.coat;
            out.coatAlpha = p.coatAlpha;
            out.sheenColor = p.sheenColor; // KHR_materials_sheen (bsdf.h)
            out.sheenRoughness = p.sheenRoughness;
        }
        return out;
    }

    const rtpbr_gltf_scene &scene_;
    const EmbreeScene &es_;
    const LightSet &lights_;
    const PunctualLights &punctual_;
    const RenderSettings &s_;
    const std::vector<Texture> &textures_;
    const std::vector<const LayerAlbedo *> &layers_; // per material
    uint32_t maxDepth_;
};

__int128 toFixed(double v) { return __int128(std::ldexp(v, 64)); }

// The settings with their defaults resolved (size, sample range, region), checked.
Result resolveSettings(const rtpbr_gltf_scene &scene, const RenderSettings &settings, RenderSettings *out,
                       uint32_t *sampleEnd, Region *region, std::string *error) {
    RenderSettings s = settings;
    s.width = s.width ? s.width : 512;
    s.height = imageHeight(scene, s, s.width);
    if (s.width > 65536 || s.height > 65536 || uint64_t(s.width) * s.height > (1ull << 28)) {
        *error = fmt("image %ux%u too large", s.width, s.height);
        return Result::InvalidArgument;
    }
    if (s.spp == 0) {
        *error = "spp must be at least 1";
        return Result::InvalidArgument;
    }
    uint32_t sEnd = s.sampleEnd ? s.sampleEnd : s.spp;
    if (s.sampleBegin >= sEnd || sEnd > s.spp) {
        *error = fmt("sample range %u:%u is empty or outside 0:%u", s.sampleBegin, sEnd, s.spp);
        return Result::InvalidArgument;
    }
    Region reg = s.region;
    if (reg.x0 == 0 && reg.y0 == 0 && reg.x1 == 0 && reg.y1 == 0)
        reg = {0, 0, s.width, s.height};
    if (reg.x0 >= reg.x1 || reg.y0 >= reg.y1 || reg.x1 > s.width || reg.y1 > s.height) {
        *error = fmt("region %u:%u:%u:%u is empty or outside the %ux%u image", reg.x0, reg.y0, reg.x1, reg.y1, s.width,
                     s.height);
        return Result::InvalidArgument;
    }
    *out = s;
    *sampleEnd = sEnd;
    *region = reg;
    return Result::Success;
}

// The memory need, stated and checked before anything large is allocated: the accumulator
// (76 bytes per pixel) and the resolved image with its standard error (24), the textures as
// linear float RGBA (16 per texel), Embree's copy of the triangles and its BVH (about 64
// bytes per triangle, measured as an upper bound on the bundled scenes).
bool checkRenderMemory(const rtpbr_gltf_scene &scene, const RenderSettings &s, std::string *error) {
    uint64_t texels = 0, triangles = 0;
    for (uint32_t t = 0; t < scene.texture_count; t++)
        texels += uint64_t(scene.textures[t].width) * scene.textures[t].height;
    for (uint32_t p = 0; p < scene.primitive_count; p++)
        triangles += scene.primitives[p].index_count / 3;
    const uint64_t need = uint64_t(s.width) * s.height * kBytesPerPixel + texels * 16 + triangles * 64;
    return checkMemory(need, s.memoryLimit, fmt("rendering %ux%u with %llu texels and %llu triangles", s.width, s.height,
                                                (unsigned long long)texels, (unsigned long long)triangles),
                       error);
}

// The albedo tables of the dielectric layers, one per distinct IOR (in *tables); per material,
// its table or nullptr.
std::vector<const LayerAlbedo *> layerAlbedoTables(const rtpbr_gltf_scene &scene,
                                                   std::vector<std::unique_ptr<LayerAlbedo>> *tables) {
    std::vector<const LayerAlbedo *> layers(scene.material_count, nullptr);
    for (uint32_t m = 0; m < scene.material_count; m++) {
        const rtpbr_gltf_material &mat = scene.materials[m];
        bool mayBeDielectric = mat.metallic < 1.0f || mat.metallic_roughness_texture >= 0;
        if (!mayBeDielectric || !(mat.specular.specular_factor > 0.0f))
            continue;
        float eta = rtpbr::Material_DielectricEta(mat.ior.ior); // KHR_materials_ior (material.h)
        for (const auto &t : *tables)
            if (t->eta() == eta)
                layers[m] = t.get();
        if (!layers[m]) {
            tables->push_back(std::make_unique<LayerAlbedo>(eta, kLayerAlbedoWalks));
            layers[m] = tables->back().get();
        }
    }
    return layers;
}

// The camera's primary rays: through a jittered point of pixel (x, y).
struct CameraRays {
    vec3 pos, f, u, r;
    float tanHalf, aspect;
    uint32_t width, height;

    CameraRays(const rtpbr_gltf_camera &cam, uint32_t w, uint32_t h)
        : pos(glm::make_vec3(cam.position)), f(glm::normalize(glm::make_vec3(cam.forward))),
          u(glm::normalize(glm::make_vec3(cam.up))), r(glm::normalize(glm::make_vec3(cam.right))),
          tanHalf(std::tan(0.5f * cam.yfov)), aspect(float(w) / float(h)), width(w), height(h) {}

    vec3 direction(uint32_t x, uint32_t y, float jx, float jy) const {
        float ndcX = (2.0f * (float(x) + jx) / float(width) - 1.0f) * tanHalf * aspect;
        float ndcY = (1.0f - 2.0f * (float(y) + jy) / float(height)) * tanHalf;
        return glm::normalize(f + ndcX * r + ndcY * u);
    }
};

// Per worker: samples [begin, end) of a pixel, their sums (fixed point, so that merged ranges
// add up exactly) and sums of squares into the accumulator; non-finite samples count as 0,
// samples above kMaxSampleValue are clamped (both counted).
struct PixelSampler {
    Integrator &integ;
    const CameraRays &cam;
    uint64_t seed;
    uint32_t begin, end;
    Accumulator *out;
    uint64_t nonFinite = 0, clamped = 0;

    void pixel(uint32_t x, uint32_t y) {
        size_t pix = size_t(y) * cam.width + x;
        __int128 sum[3] = {0, 0, 0};
        double sq[3] = {0.0, 0.0, 0.0};
        for (uint32_t k = begin; k < end; k++) {
            Rng rng = Rng::forSample(x, y, k, seed);
            float jx = rng.uniform(), jy = rng.uniform();
            vec3 L = integ.radiance(cam.pos, cam.direction(x, y, jx, jy), rng);
            if (!std::isfinite(L.x) || !std::isfinite(L.y) || !std::isfinite(L.z)) {
                nonFinite++;
                L = vec3(0.0f);
            }
            for (int c = 0; c < 3; c++) {
                double v = std::max(double(L[c]), 0.0);
                if (v > kMaxSampleValue) {
                    v = kMaxSampleValue;
                    clamped++;
                }
                sum[c] += toFixed(v);
                sq[c] += v * v;
            }
        }
        out->samples[pix] = end - begin;
        for (int c = 0; c < 3; c++) {
            out->sum[3 * pix + c] = sum[c];
            out->sumSquares[3 * pix + c] = sq[c];
        }
    }
};

} // namespace


// ---- render ----------------------------------------------------------------------------------

Result render(const rtpbr_gltf_scene &scene, const RenderSettings &settings, Accumulator *out, std::string *error,
              const ProgressCallback &progress, RenderStats *stats) {
    std::string localError;
    if (!error)
        error = &localError;
    Result r = validateScene(scene, settings, error);
    if (r != Result::Success)
        return r;
    RenderSettings s;
    uint32_t sEnd = 0;
    Region reg;
    r = resolveSettings(scene, settings, &s, &sEnd, &reg, error);
    if (r != Result::Success)
        return r;
    if (!checkRenderMemory(scene, s, error))
        return Result::InvalidArgument;

    std::vector<Texture> textures;
    for (uint32_t t = 0; t < scene.texture_count; t++)
        textures.emplace_back(scene.textures[t]);
    std::vector<std::unique_ptr<LayerAlbedo>> layerTables;
    const std::vector<const LayerAlbedo *> layers = layerAlbedoTables(scene, &layerTables);
    LightSet lights(scene, s.lightSampling);
    PunctualLights punctual(scene);
    EmbreeScene es;
    r = buildEmbree(scene, textures, &es, error);
    if (r != Result::Success)
        return r;

    out->width = s.width;
    out->height = s.height;
    out->seed = s.seed;
    out->settingsHash = settingsHash(s, s.width, s.height);
    size_t npix = size_t(s.width) * s.height;
    out->samples.assign(npix, 0);
    out->sum.assign(3 * npix, 0);
    out->sumSquares.assign(3 * npix, 0.0);
    out->nonFinite = 0;
    out->clamped = 0;

    const CameraRays cam(scene.cameras[s.camera], s.width, s.height);
    uint32_t tilesX = (reg.x1 - reg.x0 + kTileSize - 1) / kTileSize;
    uint32_t tilesY = (reg.y1 - reg.y0 + kTileSize - 1) / kTileSize;
    uint32_t tileCount = tilesX * tilesY;
    std::atomic<uint32_t> nextTile{0};
    std::atomic<uint64_t> nonFinite{0}, clamped{0}, totalRays{0};
    std::mutex progressMutex;
    uint64_t pixelsDone = 0;
    const uint64_t pixelsTotal = uint64_t(reg.x1 - reg.x0) * (reg.y1 - reg.y0);

    // Each thread takes the next tile until none is left.
    auto worker = [&]() {
        Integrator integ(scene, es, lights, punctual, s, textures, layers);
        PixelSampler sampler{integ, cam, s.seed, s.sampleBegin, sEnd, out};
        for (;;) {
            uint32_t tile = nextTile.fetch_add(1);
            if (tile >= tileCount)
                break;
            uint32_t tx0 = reg.x0 + (tile % tilesX) * kTileSize;
            uint32_t ty0 = reg.y0 + (tile / tilesX) * kTileSize;
            uint32_t tx1 = std::min(tx0 + kTileSize, reg.x1);
            uint32_t ty1 = std::min(ty0 + kTileSize, reg.y1);
            for (uint32_t y = ty0; y < ty1; y++)
                for (uint32_t x = tx0; x < tx1; x++)
                    sampler.pixel(x, y);
            if (progress) {
                std::lock_guard<std::mutex> lock(progressMutex);
                pixelsDone += uint64_t(tx1 - tx0) * (ty1 - ty0);
                progress(pixelsDone, pixelsTotal);
            }
        }
        nonFinite += sampler.nonFinite;
        clamped += sampler.clamped;
        totalRays += integ.rays;
    };

    auto t0 = std::chrono::steady_clock::now();
    uint32_t threads = s.threads ? s.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min(threads, std::max(1u, tileCount));
    std::vector<std::thread> pool;
    for (uint32_t t = 1; t < threads; t++)
        pool.emplace_back(worker);
    worker();
    for (std::thread &t : pool)
        t.join();
    out->nonFinite = nonFinite;
    out->clamped = clamped;
    if (stats) {
        stats->samples = pixelsTotal * (sEnd - s.sampleBegin);
        stats->rays = totalRays;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (!es.errors.first.empty()) {
        *error = es.errors.first;
        return Result::Embree;
    }
    return Result::Success;
}

} // namespace rtpbr_oracle
