// rtpbr oracle: sampling the polygonal area lights; the punctual (delta) lights.
//
// A light is a convex planar polygon (3..8 vertices) emitting constant radiance from its
// front face (both faces if two-sided). One light is picked with probability proportional
// to its power; a point on it is then sampled
//   - SolidAngle (default): uniformly in the solid angle the polygon subtends: the fan
//     triangles are picked by solid angle and each is sampled by Arvo 1995, "Stratified
//     Sampling of Spherical Triangles"; polygons subtending less than kMinSolidAngle fall
//     back to area sampling (Arvo's formulas lose precision there, and both are equally
//     good for small lights);
//   - Area: uniformly in area (the fan triangles by area), for comparison.
// The density of a direction is a deterministic function of (point, light, direction),
// which multiple importance sampling needs (pdf()).
#ifndef RTPBR_ORACLE_LIGHTS_H
#define RTPBR_ORACLE_LIGHTS_H

#include <rtpbr/rtpbr_gltf.h>

#include <glm/glm.hpp>

#include <vector>

namespace rtpbr_oracle {

enum class LightSampling { SolidAngle, Area };

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

private:
    struct Light {
        std::vector<glm::dvec3> v; // vertices
        glm::dvec3 n;              // unit normal of the emitting face
        glm::vec3 radiance;
        bool twoSided;
        double area;
        std::vector<double> triArea; // fan triangles (v0, v[i], v[i+1])
    };
    bool facing(const Light &L, glm::dvec3 p) const;
    // Solid angles of the fan triangles seen from p; returns their sum.
    double fanSolidAngles(const Light &L, glm::dvec3 p, double *omega) const;
    double selectionPdf(uint32_t l) const;

    std::vector<Light> lights_;
    std::vector<double> cdf_; // light selection by power
    LightSampling mode_;
};

// KHR_lights_punctual lights (rtpbr_gltf_punctual_light): point, spot and directional, as
// true delta lights. A delta light has no surface: no ray meets it, so it enters only through
// next-event estimation, with weight 1 (no MIS: the BSDF strategy cannot find it), and every
// light is taken at every vertex (no selection: scenes have few, and a sum adds no noise).
// What one light gives at a point p (the extension's text):
//   reflected radiance = f(wo, wi) max(N.wi, 0) x irradiance,
//   point:       wi = normalize(position - p), irradiance = intensity W(d) / d^2, d = |position - p|
//   spot:        the point's, times the cone's falloff t^2 (PunctualLights::spotFalloff)
//   directional: wi = -direction, irradiance = intensity (no distance falloff, range unused)
//   W(d) = clamp(1 - (d / range)^4, 0, 1) for range > 0, else 1 (the spec's recommended window).
struct PunctualSample {
    glm::vec3 wi;         // unit direction from p to the light
    float distance;       // to the light position; infinity for a directional light
    glm::vec3 irradiance; // on a surface facing the light: reflected = f cos(theta) x this
};

class PunctualLights {
public:
    explicit PunctualLights(const rtpbr_gltf_scene &scene);

    size_t size() const { return lights_.size(); }
    bool empty() const { return lights_.empty(); }
    // Light l seen from p; false where it gives nothing (outside its cone or range, a black
    // light, p at the light's position).
    bool illuminate(uint32_t l, glm::vec3 p, PunctualSample *s) const;
    // KHR_lights_punctual's spot falloff: t = clamp((cd - cos outer) / max(1e-3, cos inner -
    // cos outer), 0, 1), returned as t^2; cd = cos of the angle from the spot's axis.
    static double spotFalloff(double cd, double innerConeAngle, double outerConeAngle);
    // The spec's recommended range window clamp(1 - (d / range)^4, 0, 1); 1 for range <= 0.
    static double rangeWindow(double d, double range);

private:
    std::vector<rtpbr_gltf_punctual_light> lights_; // the scene's, with any intensity > 0
};

} // namespace rtpbr_oracle

#endif
