// rtpbr oracle: sampling the area lights (polygons and disks); the punctual (delta) lights.
//
// A light is a convex planar polygon (3..8 vertices) or a disk (RTPBR_GLTF_LIGHT_DISK: the
// true disk, not the equal-area octagon the loader also gives), emitting constant radiance
// from its front face (both faces if two-sided). One light is picked with probability
// proportional to its power; a point on it is then sampled
//   - SolidAngle (default): a polygon uniformly in the solid angle it subtends: the fan
//     triangles are picked by solid angle and each is sampled by Arvo 1995, "Stratified
//     Sampling of Spherical Triangles"; polygons subtending less than kMinSolidAngle fall
//     back to area sampling (Arvo's formulas lose precision there, and both are equally
//     good for small lights);
//   - Area: a polygon uniformly in area (the fan triangles by area), for comparison.
// A disk is sampled uniformly in area in either mode (Shirley & Chiu's concentric map), its
// density converted to solid angle (distance^2 / (cos area)).
// The density of a direction is a deterministic function of (point, light, direction),
// which multiple importance sampling needs (pdf()).
#ifndef RTPBR_ORACLE_LIGHTS_H
#define RTPBR_ORACLE_LIGHTS_H

#include <rtpbr/rtpbr_gltf.h>

#include <glm/glm.hpp>

#include <vector>

namespace rtpbr_oracle {

enum class LightSampling { SolidAngle, Area };

// A disk light (RTPBR_GLTF_LIGHT_DISK, EXT_lights_area "disk") as itself: the points
// centre + x t + y b with x^2 + y^2 <= radius^2, (t, b, n) orthonormal, n its emitting side.
// The loader's facts give the centre and n; the frame is Duff et al.'s basis about n. Both the
// Embree geometry (embree_scene.h) and the light sampling use it, so a hit's disk coordinates
// and a sample's point are the same disk's.
struct DiskShape {
    glm::dvec3 centre{0.0}, n{0.0}, t{0.0}, b{0.0};
    double radius = 0.0, radius2 = 0.0; // the half-axes along t and b (an ellipse; equal: a disk)

    static DiskShape of(const rtpbr_gltf_light &L);
    glm::dvec3 point(double x, double y) const { return centre + x * t + y * b; }
    // The ray o + s w (any w != 0; either face) meets the disk at s in [sMin, sMax]: *s and the
    // point's disk coordinates (*x, *y), in double.
    bool intersect(glm::dvec3 o, glm::dvec3 w, double sMin, double sMax, double *s, double *x, double *y) const;
};

// A point light's capsule (rtpbr_gltf_punctual_light.length > 0): the segment centre +- axis
// half (half = length / 2) swept by the ball of radius `radius`, i.e. a cylinder of length
// 2 half and two hemispherical caps; (t, b, axis) orthonormal. It is convex, so a point x of its
// surface is visible from a point p outside it iff its outward normal faces p, n.(p - x) > 0
// (the tangent plane at x supports it: the open segment p -> x lies on its far side); a point
// with n.(p - x) <= 0 is hidden by the capsule itself. All in double.
struct CapsuleShape {
    glm::dvec3 centre{0.0}, axis{1.0, 0.0, 0.0}, t{0.0}, b{0.0};
    double radius = 0.0, half = 0.0;

    static CapsuleShape of(const rtpbr_gltf_punctual_light &P);
    double cylinderArea() const; // 2 pi r (2 half)
    double area() const;         // 4 pi r^2 + 2 pi r (2 half)
    // Is p inside or on it (its distance to the segment <= radius)?
    bool contains(glm::dvec3 p) const;
    // The ray o + s w (w unit) meets its surface first at s in (0, sMax]: *s and the outward
    // normal there (from inside: where it leaves).
    bool intersect(glm::dvec3 o, glm::dvec3 w, double sMax, double *s, glm::dvec3 *n) const;
    // A point uniformly in its area from (u1, u2) in [0, 1)^2 (the cylinder or the caps by their
    // areas; the caps as one sphere split at its equator) and its outward normal *n.
    glm::dvec3 sample(double u1, double u2, glm::dvec3 *n) const;
};

struct LightSample {
    glm::vec3 wi;       // unit direction from the shading point to the light point
    float distance;     // to the light point
    glm::vec3 radiance; // emitted towards the shading point
    float pdf;          // solid-angle density, including the light selection probability
    uint32_t light;
};

class LightSet {
public:
    static constexpr double kMinSolidAngle = 1e-6;

    LightSet(const rtpbr_gltf_scene &scene, LightSampling mode);

    size_t size() const { return lights_.size(); }
    bool empty() const { return lights_.empty(); }
    // Radiance leaving light l towards direction -wi (wi points at the light).
    glm::vec3 emitted(uint32_t l, glm::vec3 wi) const;
    bool sample(glm::vec3 p, float uLight, float u1, float u2, LightSample *s) const;
    // Density (solid angle, with selection) of sampling direction wi towards light l from p.
    float pdf(glm::vec3 p, uint32_t l, glm::vec3 wi, float distance) const;
    // Light l's disk; nullptr for a polygon.
    const DiskShape *disk(uint32_t l) const { return lights_[l].isDisk ? &lights_[l].disk : nullptr; }

private:
    struct Light {
        std::vector<glm::dvec3> v; // vertices (a disk: none)
        glm::dvec3 n;              // unit normal of the emitting face
        glm::vec3 radiance;
        bool twoSided;
        double area;                 // a disk's: pi r^2
        std::vector<double> triArea; // fan triangles (v0, v[i], v[i+1])
        bool isDisk = false;
        DiskShape disk;
    };
    bool facing(const Light &L, glm::dvec3 p) const;
    // The density of the point at distance dist along dir on L when L is sampled uniformly in
    // area, in solid angle, times the selection probability sel.
    static double areaDensity(const Light &L, double sel, glm::dvec3 dir, double dist);
    bool sampleDisk(const Light &L, uint32_t l, glm::dvec3 p, float u1, float u2, LightSample *s) const;
    // Solid angles of the fan triangles seen from p; returns their sum.
    double fanSolidAngles(const Light &L, glm::dvec3 p, double *omega) const;
    double selectionPdf(uint32_t l) const;

    std::vector<Light> lights_;
    std::vector<double> cdf_; // light selection by power
    LightSampling mode_;
};

// KHR_lights_punctual lights (rtpbr_gltf_punctual_light): point, spot and directional.
// Point and spot lights, and directional lights of angular_diameter 0, are true delta lights.
// A delta light has no surface: no ray meets it, so it enters only through next-event
// estimation, with weight 1 (no MIS: the BSDF strategy cannot find it), and every light is
// taken at every vertex (no selection: scenes have few, and a sum adds no noise).
// What one delta light gives at a point p (the extension's text):
//   reflected radiance = f(wo, wi) max(N.wi, 0) x irradiance,
//   point:       wi = normalize(position - p), irradiance = intensity W(d) / d^2, d = |position - p|
//   spot:        the point's, times the cone's falloff t^2 (PunctualLights::spotFalloff)
//   directional: wi = -direction, irradiance = intensity (no distance falloff, range unused)
//   W(d) = clamp(1 - (d / range)^4, 0, 1) for range > 0, else 1 (the spec's recommended window).
// A directional light of angular_diameter d > 0 is the sun's disk: the spherical cap of
// half-angle a = d / 2 around -direction, at infinity, of uniform radiance
// L = intensity / (pi sin^2 a) (its illuminance at normal incidence is intensity). It is
// sampled uniformly in the cap (solid-angle pdf 1 / (2 pi (1 - cos a))) and combined by MIS
// with the BSDF rays that escape the scene inside the cap (diskRadiance). Its constants are
// computed in double: 1 - cos a = 2 sin^2(a / 2) stays exact for a tiny disk, and a sample's
// irradiance L / pdf = intensity 2 / (1 + cos a) stays finite where L and the pdf do not fit
// a float.
// A point light of radius r > 0 is a sphere around its position, of uniform radiance
// L W(d), L = intensity / (pi r^2) (far away its intensity is intensity), W the range window
// at the distance d from the shading point to the centre. It is transparent to everything
// else (it occludes nothing: not scene geometry) and emits towards every point outside it
// (and, seen from inside, towards every point inside). From p outside it (d > r) it is the cone
// of half-angle s, sin s = r / d: next-event estimation samples a direction uniformly in the
// cone (solid-angle pdf 1 / (2 pi (1 - cos s)), 1 - cos s = sin^2 s / (1 + cos s)) with a
// shadow ray to the sphere's near surface, combined by MIS with the BSDF rays that meet the
// sphere before the scene (sphereRadiance); a sample's L W / pdf = intensity W 2 / (d^2 (1 +
// cos s)) stays finite for a tiny sphere. From p inside (d <= r) every direction sees it: BSDF
// rays alone find it, with weight 1.
// A point light of radius r > 0 and length L > 0 is a capsule (CapsuleShape: the segment
// position +- axis L / 2 swept by the ball of radius r) of uniform radiance L_e W(d),
// L_e = 2 intensity / (pi r (2 r + L)) (its power stays 4 pi intensity; at L = 0 the sphere's
// intensity / (pi r^2)), W at the distance d from the shading point to its centre. Transparent
// to everything else as the sphere is. Next-event estimation takes a point uniformly in its area
// (CapsuleShape::sample), keeps it if it faces the shading point (exact visibility on a convex
// body) and converts the density to solid angle, dist^2 / (cos_light area); BSDF rays that meet
// it first before the scene carry L_e W with that density's MIS weight (capsuleRadiance). From
// inside it, BSDF rays alone, weight 1.
struct PunctualSample {
    glm::vec3 wi;         // unit direction from p to the light
    float distance;       // to the light position (a sphere: to its near surface along wi);
                          // infinity for a directional light
    glm::vec3 irradiance; // on a surface facing the light: reflected = f cos(theta) x this
                          // (for a sun's disk or a sphere, the one-sample estimate L W / pdf)
    double pdf;           // 0 for a delta light; a sun's disk, a sphere: the solid-angle density
                          // of wi
};

class PunctualLights {
public:
    explicit PunctualLights(const rtpbr_gltf_scene &scene);

    size_t size() const { return lights_.size(); }
    bool empty() const { return lights_.empty(); }
    // Is light l a sun's disk (a directional light of angular_diameter > 0)? Only then does
    // illuminate() use u1, u2, and only then can a ray see the light (diskRadiance).
    bool hasDisk(uint32_t l) const { return disks_[l].halfAngle > 0.0; }
    // Is light l a sphere (a point light of radius > 0)? Only then does illuminate() use u1,
    // u2, and only then can a ray from a point see it (sphereRadiance).
    bool hasSphere(uint32_t l) const { return spheres_[l].radius > 0.0; }
    // Is light l a capsule (a point light of radius > 0 and length > 0)? Only then does
    // illuminate() use u1, u2 as a point on it, and only then can a ray see it (capsuleRadiance).
    bool hasCapsule(uint32_t l) const { return capsules_[l].radius > 0.0; }
    // Can a ray see any light (is any a disk, a sphere or a capsule)?
    bool anyVisible() const { return anyVisible_; }
    // Light l seen from p; false where it gives nothing (outside its cone or range, a black
    // light, p at the light's position or inside its sphere or capsule, a capsule's point that
    // faces away from p). A sun's disk or a sphere: a direction uniform in its cap (cone) from
    // (u1, u2) in [0, 1)^2, with its density in s->pdf (a sphere: s->distance to its near
    // surface); a capsule: a point uniform in its area (s->distance to it), s->pdf its density
    // in solid angle; a delta light ignores u1, u2.
    bool illuminate(uint32_t l, glm::vec3 p, float u1, float u2, PunctualSample *s) const;
    // A ray leaving towards wi sees sun l's disk: its radiance (double: a tiny disk's may not
    // fit a float) and the density illuminate() samples wi with; false outside the cap (and
    // for every delta light).
    bool diskRadiance(uint32_t l, glm::vec3 wi, glm::dvec3 *radiance, double *pdf) const;
    // The ray p + t wi (0 < t <= tmax: the scene's hit, or infinity) meets sphere l: its
    // radiance L W(|centre - p|) and the density illuminate() samples wi with from p (0 from
    // inside the sphere, where it does not sample); false where it misses (and for every other
    // light).
    bool sphereRadiance(uint32_t l, glm::vec3 p, glm::vec3 wi, float tmax, glm::dvec3 *radiance,
                        double *pdf) const;
    // The ray p + t wi (0 < t <= tmax) meets capsule l: its radiance L_e W(|centre - p|) and
    // the density (solid angle) illuminate() samples wi with from p (0 from inside it, where it
    // does not sample); false where it misses (and for every other light).
    bool capsuleRadiance(uint32_t l, glm::vec3 p, glm::vec3 wi, float tmax, glm::dvec3 *radiance,
                         double *pdf) const;
    // KHR_lights_punctual's spot falloff: t = clamp((cd - cos outer) / max(1e-3, cos inner -
    // cos outer), 0, 1), returned as t^2; cd = cos of the angle from the spot's axis.
    static double spotFalloff(double cd, double innerConeAngle, double outerConeAngle);
    // The spec's recommended range window clamp(1 - (d / range)^4, 0, 1); 1 for range <= 0.
    static double rangeWindow(double d, double range);

private:
    // A sun's cap around axis (= -direction), with (t, b, axis) an orthonormal frame.
    struct Disk {
        double halfAngle = 0.0; // a; 0: a delta light
        glm::dvec3 axis{0.0}, t{0.0}, b{0.0};
        double oneMinusCos = 0.0; // 1 - cos a = 2 sin^2(a / 2)
        double sin2 = 0.0;        // sin^2 a
        double pdf = 0.0;         // 1 / (2 pi (1 - cos a))
        glm::dvec3 radiance{0.0}; // intensity / (pi sin^2 a)
        glm::dvec3 perSample{0.0}; // radiance / pdf = intensity 2 / (1 + cos a)
    };
    // A point light's sphere.
    struct Sphere {
        double radius = 0.0; // r; 0: a delta light
        glm::dvec3 centre{0.0};
        glm::dvec3 intensity{0.0};
        glm::dvec3 radiance{0.0}; // intensity / (pi r^2)
    };
    // The cone sphere S subtends from p (outside it): axis towards the centre, d, 1 - cos s and
    // 1 + cos s of its half-angle s, all in double.
    struct Cone {
        glm::dvec3 axis;
        double d, oneMinusCos, onePlusCos;
    };
    static Cone sphereCone(const Sphere &S, glm::dvec3 p);
    // A point light's capsule.
    struct Capsule {
        double radius = 0.0; // r; 0: not a capsule
        CapsuleShape shape;
        double area = 0.0;
        glm::dvec3 radiance{0.0}; // 2 intensity / (pi r (2 r + L)) = 4 intensity / area
    };

    std::vector<rtpbr_gltf_punctual_light> lights_; // the scene's, with any intensity > 0
    std::vector<Disk> disks_;                         // one per light
    std::vector<Sphere> spheres_;                     // one per light
    std::vector<Capsule> capsules_;                   // one per light
    bool anyVisible_ = false;
};

} // namespace rtpbr_oracle

#endif
