// rtpbr oracle: multiple scattering on the Smith microsurface by random walk.
//
// Heitz, Hanika, d'Eon, Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the
// Smith Model". The microsurface is the Smith model made explicit: microfacet normals are
// distributed by the GGX NDF (anisotropic, alphaX along +x, alphaY along +y), heights are
// independent of normals and uniformly distributed in [-1, 1] (the paper's "uniform height
// distribution"; the result does not depend on that choice). A ray walks down into the
// microsurface: the height of its next intersection is sampled from the Smith masking
// (sampleHeight), the microfacet it hits from the visible normals (sampleVisibleNormal),
// and the facet reflects (conductors) or reflects / refracts (dielectrics) with its Fresnel
// term, until the ray leaves the microsurface.
//
// Conventions (the paper's): everything is in the local frame with the macro normal +z.
// wi is the direction the walk starts from (the ray arrives along -wi), wo the direction it
// leaves along. eval*() returns an unbiased one-sample estimate of f(wi, wo) |wo.z|, the
// projected BSDF; sample*() returns a direction distributed as the walk leaves, with a
// weight whose expectation given the direction is f |wo.z| / pdf (for a conductor with
// F = 1 and for a lossless dielectric the weight is exactly 1).
//
// All Lambda, G1 and visible-normal computations for directions above the macro surface use
// the shaderlib (Lambda_GGX_Aniso, Sample_GGX_VNDF, D_GGX_Aniso, F_Dielectric); the walk
// also needs them for downward directions, which this file derives from those (Heitz 2016,
// sec. 3: Lambda(-w) = -1 - Lambda(w)).
#ifndef RTPBR_ORACLE_MICROSURFACE_H
#define RTPBR_ORACLE_MICROSURFACE_H

#include "rng.h"

#include <glm/glm.hpp>

namespace rtpbr_oracle {

using vec3 = glm::vec3;

// Fresnel of a reflection-only walk: Schlick (F0, F90 per channel), the exact conductor
// (complex IOR eta + i k) or the exact dielectric (eta.x; the refracted part is lost to the
// walk: it enters the material below).
struct ConductorFresnel {
    enum class Kind { Schlick, Conductor, Dielectric };
    Kind kind = Kind::Schlick;
    vec3 f0 = vec3(1.0f);
    float f90 = 1.0f;
    vec3 eta = vec3(1.0f);
    vec3 k = vec3(0.0f);
    vec3 eval(float cosTheta) const;
};

class MicrosurfaceGGX {
public:
    MicrosurfaceGGX(float alphaX, float alphaY);

    float alphaX() const { return ax_; }
    float alphaY() const { return ay_; }

    // Smith Lambda of any direction (downward directions by Lambda(-w) = -1 - Lambda(w)).
    float lambda(vec3 w) const;
    // (1 + Lambda(w)) w.z: the projected area of the microsurface seen along w, > 0 for all w.
    float projectedArea(vec3 w) const;
    // Height-dependent masking of an upward direction at height h: C1(h)^Lambda(w).
    float G1(vec3 w, float h) const;
    float D(vec3 wm) const;
    // Distribution of visible normals seen from w (any w): <w, wm>+ D(wm) / projectedArea(w).
    float Dvis(vec3 w, vec3 wm) const;
    // Samples wm from Dvis(w, .) for any w.
    vec3 sampleVisibleNormal(vec3 w, float u1, float u2) const;
    // Height of the next intersection of a ray leaving height h along wr, or +Inf when it
    // leaves the microsurface (Heitz 2016, sec. 4.2).
    float sampleHeight(vec3 wr, float h, float u) const;

private:
    float ax_, ay_;
};

// The longest walk followed; longer walks (vanishingly rare) are cut, losing their energy.
constexpr int kMaxScatteringOrder = 256;

// Conductor (reflection only). order: 0 = all orders, n > 0 = only the n-th order,
// n < 0 = orders >= -n (e.g. -2: the multiple-scattering part alone, which added to the
// closed-form single-scattering BRDF gives a lower-variance estimate of the whole).
vec3 conductorEval(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, vec3 wo, Rng &rng,
                   int order = 0);
// Returns false when the walk was cut (no direction). *weight is the product of the
// Fresnel terms met along the walk; *orderOut the number of scattering events.
bool conductorSample(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng, vec3 *wo,
                     vec3 *weight, int *orderOut = nullptr);

// Dielectric interface with relative IOR eta = n_inside / n_outside (inside is -z), rough
// reflection and transmission, lossless. wi may be on either side (wi.z < 0: from inside).
// As in Heitz 2016 the walk transports flux: for transmission eval() is Walter et al.'s f_t,
// which obeys f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2, not plain symmetry.
float dielectricEval(const MicrosurfaceGGX &ms, float eta, vec3 wi, vec3 wo, Rng &rng, int order = 0);
bool dielectricSample(const MicrosurfaceGGX &ms, float eta, vec3 wi, Rng &rng, vec3 *wo,
                      int *orderOut = nullptr);

} // namespace rtpbr_oracle

#endif
