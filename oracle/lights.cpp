// rtpbr oracle: area light sampling (see lights.h).
#include "lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtpbr_oracle {

namespace {

using glm::dvec3;
constexpr double kPi = 3.14159265358979323846;

// Angle at vertex P of the spherical triangle (P, Q, R) of unit vectors.
double vertexAngle(dvec3 P, dvec3 Q, dvec3 R) {
    dvec3 n1 = glm::cross(P, Q);
    dvec3 n2 = glm::cross(P, R);
    double l = glm::length(n1) * glm::length(n2);
    if (!(l > 0.0))
        return 0.0;
    return std::acos(glm::clamp(glm::dot(n1, n2) / l, -1.0, 1.0));
}

// Van Oosterom & Strackee 1983, "The Solid Angle of a Plane Triangle":
// tan(Omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a) for unit a, b, c.
double triangleSolidAngle(dvec3 a, dvec3 b, dvec3 c) {
    double num = std::fabs(glm::dot(a, glm::cross(b, c)));
    double den = 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
    double o = 2.0 * std::atan2(num, den);
    return o < 0.0 ? o + 2.0 * kPi : o;
}

// Arvo 1995, "Stratified Sampling of Spherical Triangles", fig. 2: a point uniformly
// distributed in solid angle on the spherical triangle (A, B, C).
dvec3 sampleSphericalTriangle(dvec3 A, dvec3 B, dvec3 C, double u1, double u2) {
    double alpha = vertexAngle(A, B, C);
    double beta = vertexAngle(B, C, A);
    double gamma = vertexAngle(C, A, B);
    double area = alpha + beta + gamma - kPi;
    double aHat = u1 * area;
    double s = std::sin(aHat - alpha);
    double t = std::cos(aHat - alpha);
    double u = t - std::cos(alpha);
    double v = s + std::sin(alpha) * glm::dot(A, B);
    double den = (v * s + u * t) * std::sin(alpha);
    double q = den != 0.0 ? ((v * t - u * s) * std::cos(alpha) - v) / den : 1.0;
    q = glm::clamp(q, -1.0, 1.0);
    dvec3 cPerp = C - glm::dot(C, A) * A;
    double lc = glm::length(cPerp);
    dvec3 cHat = lc > 0.0 ? q * A + std::sqrt(std::max(0.0, 1.0 - q * q)) * (cPerp / lc) : A;
    double z = 1.0 - u2 * (1.0 - glm::dot(cHat, B));
    dvec3 pPerp = cHat - glm::dot(cHat, B) * B;
    double lp = glm::length(pPerp);
    if (!(lp > 0.0))
        return B;
    return z * B + std::sqrt(std::max(0.0, 1.0 - z * z)) * (pPerp / lp);
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (n unit).
void orthonormalBasis(dvec3 n, dvec3 *t, dvec3 *b) {
    double sign = std::copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double bb = n.x * n.y * a;
    *t = dvec3(1.0 + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    *b = dvec3(bb, sign + n.y * n.y * a, -n.y);
}

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// A direction uniform in the solid angle of the cap around axis ((t, b, axis) orthonormal)
// whose half-angle has 1 - cos = oneMinusCosMax, from (u1, u2) in [0, 1)^2: 1 - cos(theta)
// uniform in [0, oneMinusCosMax).
dvec3 sampleCap(dvec3 axis, dvec3 t, dvec3 b, double oneMinusCosMax, double u1, double u2) {
    const double oneMinusCos = u1 * oneMinusCosMax;
    const double cosTheta = 1.0 - oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
    const double phi = 2.0 * kPi * u2;
    return glm::normalize(cosTheta * axis + sinTheta * (std::cos(phi) * t + std::sin(phi) * b));
}

// Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square": (u1, u2) in [0, 1)^2 to
// the unit disk, preserving area (so uniform in, uniform out), by concentric squares to circles.
glm::dvec2 concentricDisk(double u1, double u2) {
    const double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
    if (a == 0.0 && b == 0.0)
        return glm::dvec2(0.0);
    double r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = (kPi / 4.0) * (b / a);
    } else {
        r = b;
        phi = kPi / 2.0 - (kPi / 4.0) * (a / b);
    }
    return glm::dvec2(r * std::cos(phi), r * std::sin(phi));
}

} // namespace

DiskShape DiskShape::of(const rtpbr_gltf_light &L) {
    DiskShape D;
    D.centre = dvec3(L.facts.center[0], L.facts.center[1], L.facts.center[2]);
    D.n = glm::normalize(dvec3(L.facts.normal[0], L.facts.normal[1], L.facts.normal[2]));
    orthonormalBasis(D.n, &D.t, &D.b);
    D.radius = double(L.radius);
    D.radius2 = L.radius2 > 0.0f ? double(L.radius2) : D.radius; // 0: a circle (lights built by hand)
    const dvec3 axis(L.axis[0], L.axis[1], L.axis[2]);
    const dvec3 inPlane = axis - glm::dot(axis, D.n) * D.n;
    if (glm::dot(inPlane, inPlane) > 1e-12) { // the ellipse's half-axis `radius` along it; t x b = n
        D.t = glm::normalize(inPlane);
        D.b = glm::cross(D.n, D.t);
    }
    return D;
}

bool DiskShape::intersect(dvec3 o, dvec3 w, double sMin, double sMax, double *s, double *x, double *y) const {
    const double wn = glm::dot(w, n);
    if (wn == 0.0)
        return false;
    const dvec3 fromCentre = o - centre;
    const double hit = -glm::dot(fromCentre, n) / wn;
    if (!(hit >= sMin && hit <= sMax))
        return false;
    const dvec3 q = fromCentre + hit * w;
    const double qx = glm::dot(q, t), qy = glm::dot(q, b);
    if (!((qx / radius) * (qx / radius) + (qy / radius2) * (qy / radius2) <= 1.0))
        return false;
    *s = hit;
    *x = qx;
    *y = qy;
    return true;
}

LightSet::LightSet(const rtpbr_gltf_scene &scene, LightSampling mode) : mode_(mode) {
    double total = 0.0;
    for (uint32_t i = 0; i < scene.light_count; i++) {
        const rtpbr_gltf_light &s = scene.lights[i];
        Light L;
        L.radiance = glm::vec3(s.radiance[0], s.radiance[1], s.radiance[2]);
        L.twoSided = s.two_sided;
        if (s.shape == RTPBR_GLTF_LIGHT_DISK) { // the disk itself, not its octagon
            L.isDisk = true;
            L.disk = DiskShape::of(s);
            L.n = L.disk.n;
            L.area = kPi * L.disk.radius * L.disk.radius2;
        } else {
            for (uint32_t k = 0; k < s.vertex_count && k < RTPBR_GLTF_MAX_POLYGON_VERTICES; k++)
                L.v.push_back(dvec3(s.vertices[k][0], s.vertices[k][1], s.vertices[k][2]));
            // The loader's derived facts (rtpbr_gltf_polygon_facts), read, not derived again.
            L.n = glm::normalize(dvec3(s.facts.normal[0], s.facts.normal[1], s.facts.normal[2]));
            L.area = double(s.facts.area);
            for (size_t k = 1; k + 1 < L.v.size(); k++)
                L.triArea.push_back(double(s.facts.fan_area[k - 1]));
        }
        double power = double(std::max(luminance(L.radiance), 0.0f)) * L.area * (L.twoSided ? 2.0 : 1.0);
        if (!(power > 0.0) || !std::isfinite(power))
            power = 0.0;
        total += power;
        cdf_.push_back(total);
        lights_.push_back(std::move(L));
    }
    if (total > 0.0)
        for (double &c : cdf_)
            c /= total;
    else
        cdf_.assign(cdf_.size(), 1.0); // nothing emits: nothing is ever selected
}

double LightSet::selectionPdf(uint32_t l) const {
    double prev = l == 0 ? 0.0 : cdf_[l - 1];
    return cdf_[l] - prev;
}

bool LightSet::facing(const Light &L, dvec3 p) const {
    return L.twoSided || glm::dot(p - (L.isDisk ? L.disk.centre : L.v[0]), L.n) > 0.0;
}

double LightSet::areaDensity(const Light &L, double sel, dvec3 dir, double dist) {
    const double cosL = std::fabs(glm::dot(dir, L.n));
    if (!(cosL > 0.0) || !(L.area > 0.0))
        return 0.0;
    return sel * dist * dist / (cosL * L.area);
}

glm::vec3 LightSet::emitted(uint32_t l, glm::vec3 wi) const {
    const Light &L = lights_[l];
    if (L.twoSided || glm::dot(dvec3(wi), L.n) < 0.0)
        return L.radiance;
    return glm::vec3(0.0f);
}

double LightSet::fanSolidAngles(const Light &L, dvec3 p, double *omega) const {
    dvec3 a = glm::normalize(L.v[0] - p);
    double sum = 0.0;
    for (size_t k = 1; k + 1 < L.v.size(); k++) {
        dvec3 b = glm::normalize(L.v[k] - p);
        dvec3 c = glm::normalize(L.v[k + 1] - p);
        omega[k - 1] = triangleSolidAngle(a, b, c);
        sum += omega[k - 1];
    }
    return sum;
}

bool LightSet::sample(glm::vec3 pf, float uLight, float u1, float u2, LightSample *s) const {
    if (lights_.empty())
        return false;
    uint32_t l = uint32_t(std::lower_bound(cdf_.begin(), cdf_.end(), double(uLight)) - cdf_.begin());
    // lower_bound can land on a zero-probability light only when uLight equals a CDF step.
    while (l < cdf_.size() && selectionPdf(l) <= 0.0)
        l++;
    if (l >= lights_.size())
        return false;
    const Light &L = lights_[l];
    dvec3 p(pf);
    if (!facing(L, p))
        return false;
    if (L.isDisk)
        return sampleDisk(L, l, p, u1, u2, s);
    double omega[RTPBR_GLTF_MAX_POLYGON_VERTICES];
    double total = mode_ == LightSampling::SolidAngle ? fanSolidAngles(L, p, omega) : 0.0;
    bool bySolidAngle = mode_ == LightSampling::SolidAngle && total >= kMinSolidAngle;
    const std::vector<double> &weights = L.triArea;
    double wsum = bySolidAngle ? total : L.area;
    // Pick a fan triangle and reuse u1 within it.
    double x = double(u1) * wsum;
    size_t k = 0;
    size_t n = weights.size();
    for (; k + 1 < n; k++) {
        double w = bySolidAngle ? omega[k] : weights[k];
        if (x < w)
            break;
        x -= w;
    }
    double wk = bySolidAngle ? omega[k] : weights[k];
    double v1 = wk > 0.0 ? glm::clamp(x / wk, 0.0, 1.0) : 0.0;
    dvec3 q;
    dvec3 dir;
    double dist;
    if (bySolidAngle) {
        dvec3 A = glm::normalize(L.v[0] - p);
        dvec3 B = glm::normalize(L.v[k + 1] - p);
        dvec3 C = glm::normalize(L.v[k + 2] - p);
        dir = sampleSphericalTriangle(A, B, C, v1, double(u2));
        // Distance to the light plane along dir.
        double dn = glm::dot(dir, L.n);
        if (dn == 0.0)
            return false;
        dist = glm::dot(L.v[0] - p, L.n) / dn;
        if (!(dist > 0.0))
            return false;
    } else {
        // Uniform point on the triangle (v0, v[k+1], v[k+2]) by the square-root map.
        double su = std::sqrt(v1);
        double b0 = 1.0 - su;
        double b1 = su * (1.0 - double(u2));
        q = b0 * L.v[0] + b1 * L.v[k + 1] + (1.0 - b0 - b1) * L.v[k + 2];
        dvec3 d = q - p;
        dist = glm::length(d);
        if (!(dist > 0.0))
            return false;
        dir = d / dist;
    }
    s->wi = glm::vec3(dir);
    s->distance = float(dist);
    s->light = l;
    s->radiance = emitted(l, s->wi);
    // The same density pdf() computes, from the quantities at hand.
    double sel = selectionPdf(l);
    if (bySolidAngle) {
        s->pdf = float(sel / total);
    } else {
        double cosL = std::fabs(glm::dot(dir, L.n));
        s->pdf = cosL > 0.0 && L.area > 0.0 ? float(sel * dist * dist / (cosL * L.area)) : 0.0f;
    }
    return s->pdf > 0.0f && std::isfinite(s->pdf);
}

// A point uniform in the disk's area (Shirley & Chiu's map of (u1, u2)), seen from p.
bool LightSet::sampleDisk(const Light &L, uint32_t l, dvec3 p, float u1, float u2, LightSample *s) const {
    const glm::dvec2 d = concentricDisk(double(u1), double(u2)) * glm::dvec2(L.disk.radius, L.disk.radius2);
    const dvec3 toPoint = L.disk.point(d.x, d.y) - p;
    const double dist = glm::length(toPoint);
    if (!(dist > 0.0))
        return false;
    const dvec3 dir = toPoint / dist;
    s->wi = glm::vec3(dir);
    s->distance = float(dist);
    s->light = l;
    s->radiance = emitted(l, s->wi);
    s->pdf = float(areaDensity(L, selectionPdf(l), dir, dist)); // as pdf() computes it
    return s->pdf > 0.0f && std::isfinite(s->pdf);
}

float LightSet::pdf(glm::vec3 pf, uint32_t l, glm::vec3 wi, float distance) const {
    if (l >= lights_.size())
        return 0.0f;
    const Light &L = lights_[l];
    dvec3 p(pf);
    if (!facing(L, p))
        return 0.0f;
    double sel = selectionPdf(l);
    if (mode_ == LightSampling::SolidAngle && !L.isDisk) {
        double omega[RTPBR_GLTF_MAX_POLYGON_VERTICES];
        double total = fanSolidAngles(L, p, omega);
        if (total >= kMinSolidAngle)
            return float(sel / total);
    }
    return float(areaDensity(L, sel, dvec3(wi), double(distance)));
}

// ---- capsules -----------------------------------------------------------------------------------

namespace {

// The roots of a s^2 - 2 b s + c = 0 (a > 0) given disc = b^2 - a c, computed by the caller
// without cancellation: q = b + sign(b) sqrt(disc), roots q / a and c / q (Press et al.,
// Numerical Recipes, 5.6), ascending. False where there is none.
bool quadraticRoots(double a, double b, double c, double disc, double *s0, double *s1) {
    if (!(disc >= 0.0) || !(a > 0.0))
        return false;
    const double q = b + std::copysign(std::sqrt(disc), b);
    double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
    if (r0 > r1)
        std::swap(r0, r1);
    *s0 = r0;
    *s1 = r1;
    return true;
}

} // namespace

CapsuleShape CapsuleShape::of(const rtpbr_gltf_punctual_light &P) {
    CapsuleShape c;
    c.centre = dvec3(P.position[0], P.position[1], P.position[2]);
    const dvec3 axis(P.axis[0], P.axis[1], P.axis[2]);
    const double len = glm::length(axis);
    c.axis = len > 0.0 && std::isfinite(len) ? axis / len : dvec3(1.0, 0.0, 0.0);
    orthonormalBasis(c.axis, &c.t, &c.b);
    c.radius = double(P.radius);
    c.half = 0.5 * double(P.length);
    return c;
}

double CapsuleShape::cylinderArea() const { return 2.0 * kPi * radius * (2.0 * half); }

double CapsuleShape::area() const { return 4.0 * kPi * radius * radius + cylinderArea(); }

bool CapsuleShape::contains(dvec3 p) const {
    const dvec3 q = p - centre;
    const double z = glm::clamp(glm::dot(q, axis), -half, half);
    const dvec3 off = q - z * axis;
    return glm::dot(off, off) <= radius * radius;
}

bool CapsuleShape::intersect(dvec3 o, dvec3 w, double sMax, double *sHit, dvec3 *nHit) const {
    const dvec3 D = centre - o; // o + s w - centre = s w - D
    const double Du = glm::dot(D, axis), wu = glm::dot(w, axis);
    double best = std::numeric_limits<double>::infinity();
    dvec3 bestN(0.0);
    auto consider = [&](double s, dvec3 n) {
        if (s > 0.0 && s <= sMax && s < best) {
            best = s;
            bestN = n;
        }
    };
    // The cylinder |(s w - D)_perp| = r, with |z| <= half, z = s wu - Du the axial coordinate:
    // a = |w_perp|^2, b = w_perp.D_perp, c = |D_perp|^2 - r^2, b^2 - a c = a r^2 - |w_perp x
    // D_perp|^2 (no cancellation where the ray passes close to the axis).
    const dvec3 wp = w - wu * axis, Dp = D - Du * axis;
    const dvec3 cr = glm::cross(wp, Dp);
    const double a = glm::dot(wp, wp);
    double s0, s1;
    if (quadraticRoots(a, glm::dot(wp, Dp), glm::dot(Dp, Dp) - radius * radius, a * radius * radius - glm::dot(cr, cr),
                       &s0, &s1)) {
        for (double s : {s0, s1}) {
            const double z = s * wu - Du;
            if (std::fabs(z) <= half)
                consider(s, (s * wp - Dp) / radius);
        }
    }
    // The caps: spheres at centre +- half axis, the part beyond the cylinder's end (z >= half,
    // z <= -half): s^2 - 2 (w.Dc) s + |Dc|^2 - r^2 = 0, b^2 - c = r^2 - |w x Dc|^2.
    for (double side : {1.0, -1.0}) {
        const dvec3 Dc = D + side * half * axis;
        const dvec3 x = glm::cross(w, Dc);
        if (quadraticRoots(1.0, glm::dot(w, Dc), glm::dot(Dc, Dc) - radius * radius, radius * radius - glm::dot(x, x),
                           &s0, &s1)) {
            for (double s : {s0, s1}) {
                const double z = s * wu - Du;
                if (side * z >= half)
                    consider(s, (s * w - Dc) / radius);
            }
        }
    }
    if (!(best <= sMax) || std::isinf(best)) // no root in (0, sMax] (sMax may be infinite)
        return false;
    *sHit = best;
    *nHit = bestN;
    return true;
}

dvec3 CapsuleShape::sample(double u1, double u2, dvec3 *n) const {
    const double pCylinder = cylinderArea() / area();
    const double phi = 2.0 * kPi * u2;
    if (u1 < pCylinder) { // the cylinder: z uniform along the axis, phi uniform around it
        const double z = (2.0 * (u1 / pCylinder) - 1.0) * half;
        *n = std::cos(phi) * t + std::sin(phi) * b;
        return centre + z * axis + radius * *n;
    }
    // The caps: a direction uniform on the unit sphere (cos uniform in [-1, 1]); its upper half
    // on the cap at +half, its lower half on the cap at -half.
    const double v = std::min(1.0, (u1 - pCylinder) / (1.0 - pCylinder));
    const double cz = 1.0 - 2.0 * v, sz = std::sqrt(std::max(0.0, (1.0 - cz) * (1.0 + cz)));
    *n = sz * std::cos(phi) * t + sz * std::sin(phi) * b + cz * axis;
    return centre + (cz >= 0.0 ? half : -half) * axis + radius * *n;
}

// ---- punctual lights ---------------------------------------------------------------------------

PunctualLights::PunctualLights(const rtpbr_gltf_scene &scene) {
    for (uint32_t i = 0; i < scene.punctual_light_count; i++) {
        const rtpbr_gltf_punctual_light &P = scene.punctual_lights[i];
        if (!(P.intensity[0] > 0.0f || P.intensity[1] > 0.0f || P.intensity[2] > 0.0f))
            continue;
        lights_.push_back(P);
        Disk D;
        if (P.type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL && P.angular_diameter > 0.0f) {
            D.halfAngle = 0.5 * double(P.angular_diameter);
            D.axis = -glm::normalize(dvec3(P.direction[0], P.direction[1], P.direction[2]));
            orthonormalBasis(D.axis, &D.t, &D.b);
            const double s = std::sin(D.halfAngle), sHalf = std::sin(0.5 * D.halfAngle);
            D.sin2 = s * s;
            D.oneMinusCos = 2.0 * sHalf * sHalf;
            D.pdf = 1.0 / (2.0 * kPi * D.oneMinusCos);
            const dvec3 E(P.intensity[0], P.intensity[1], P.intensity[2]);
            D.radiance = E / (kPi * D.sin2);
            D.perSample = E * (2.0 / (2.0 - D.oneMinusCos));
            anyVisible_ = true;
        }
        disks_.push_back(D);
        Capsule C;
        if (P.type == RTPBR_GLTF_PUNCTUAL_POINT && P.radius > 0.0f && P.length > 0.0f) {
            C.radius = double(P.radius);
            C.shape = CapsuleShape::of(P);
            C.area = C.shape.area();
            C.radiance = dvec3(P.intensity[0], P.intensity[1], P.intensity[2]) * (4.0 / C.area);
            anyVisible_ = true;
        }
        capsules_.push_back(C);
        Sphere S;
        if (P.type == RTPBR_GLTF_PUNCTUAL_POINT && P.radius > 0.0f && !(P.length > 0.0f)) {
            S.radius = double(P.radius);
            S.centre = dvec3(P.position[0], P.position[1], P.position[2]);
            S.intensity = dvec3(P.intensity[0], P.intensity[1], P.intensity[2]);
            S.radiance = S.intensity / (kPi * S.radius * S.radius);
            anyVisible_ = true;
        }
        spheres_.push_back(S);
    }
}

double PunctualLights::spotFalloff(double cd, double innerConeAngle, double outerConeAngle) {
    // KHR_lights_punctual, "Inner and Outer Cone Angles": lightAngleScale, lightAngleOffset.
    double cosOuter = std::cos(outerConeAngle);
    double scale = 1.0 / std::max(1e-3, std::cos(innerConeAngle) - cosOuter);
    double t = glm::clamp((cd - cosOuter) * scale, 0.0, 1.0);
    return t * t;
}

double PunctualLights::rangeWindow(double d, double range) {
    if (!(range > 0.0))
        return 1.0;
    // KHR_lights_punctual, "Range Property": the recommended clamp(1 - (d / range)^4, 0, 1).
    double r = d / range;
    return glm::clamp(1.0 - r * r * r * r, 0.0, 1.0);
}

bool PunctualLights::illuminate(uint32_t l, glm::vec3 pf, float u1, float u2, PunctualSample *s) const {
    const rtpbr_gltf_punctual_light &P = lights_[l];
    s->pdf = 0.0;
    if (hasDisk(l)) {
        const Disk &D = disks_[l];
        s->wi = glm::vec3(sampleCap(D.axis, D.t, D.b, D.oneMinusCos, double(u1), double(u2)));
        s->distance = std::numeric_limits<float>::infinity();
        s->irradiance = glm::vec3(D.perSample);
        s->pdf = D.pdf;
        return true;
    }
    if (hasCapsule(l)) {
        const Capsule &C = capsules_[l];
        const dvec3 p(pf);
        const double window = rangeWindow(glm::length(C.shape.centre - p), double(P.range));
        if (C.shape.contains(p) || !(window > 0.0)) // inside the capsule: BSDF rays alone see it
            return false;
        dvec3 n;
        const dvec3 x = C.shape.sample(double(u1), double(u2), &n);
        const dvec3 d = x - p;
        const double dist = glm::length(d);
        const dvec3 wi = d / dist;
        // Convex: the point is visible from p iff it faces p; else the capsule hides it.
        const double cosLight = -glm::dot(n, wi);
        if (!(dist > 0.0) || !(cosLight > 0.0))
            return false;
        s->wi = glm::vec3(wi);
        s->distance = float(dist);
        // L_e W / pdf, pdf = dist^2 / (cos_light area): the density of area sampling in solid angle.
        s->irradiance = glm::vec3(C.radiance * (window * cosLight * C.area / (dist * dist)));
        s->pdf = dist * dist / (cosLight * C.area);
        return true;
    }
    if (hasSphere(l)) {
        const Sphere &S = spheres_[l];
        const Cone c = sphereCone(S, dvec3(pf));
        const double window = rangeWindow(c.d, double(P.range));
        if (!(c.d > S.radius) || !(window > 0.0)) // inside the sphere: BSDF rays alone see it
            return false;
        dvec3 t, b;
        orthonormalBasis(c.axis, &t, &b);
        const dvec3 wi = sampleCap(c.axis, t, b, c.oneMinusCos, double(u1), double(u2));
        // The near surface along wi: the smaller root of t^2 - 2 t d cos(theta) + d^2 - r^2,
        // written (d^2 - r^2) / (d cos(theta) + sqrt(r^2 - d^2 sin^2(theta))) (no cancellation
        // for a small sphere); |wi x axis| d = d sin(theta).
        const dvec3 off = glm::cross(wi, c.axis) * c.d;
        const double h2 = std::max(0.0, S.radius * S.radius - glm::dot(off, off));
        s->wi = glm::vec3(wi);
        s->distance = float((c.d - S.radius) * (c.d + S.radius) / (glm::dot(wi, c.axis) * c.d + std::sqrt(h2)));
        // L W / pdf = intensity / (pi r^2) W 2 pi sin^2 s / (1 + cos s), sin s = r / d.
        s->irradiance = glm::vec3(S.intensity * (window * 2.0 / (c.d * c.d * c.onePlusCos)));
        s->pdf = 1.0 / (2.0 * kPi * c.oneMinusCos);
        return true;
    }
    const dvec3 dir(P.direction[0], P.direction[1], P.direction[2]); // the way the light travels
    dvec3 wi;
    double scale;
    if (P.type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) {
        wi = -dir;
        s->distance = std::numeric_limits<float>::infinity();
        scale = 1.0;
    } else {
        dvec3 d = dvec3(P.position[0], P.position[1], P.position[2]) - dvec3(pf);
        double d2 = glm::dot(d, d);
        if (!(d2 > 0.0))
            return false;
        double dist = std::sqrt(d2);
        wi = d / dist;
        s->distance = float(dist);
        // Inverse square law, windowed by the range.
        scale = rangeWindow(dist, double(P.range)) / d2;
        if (P.type == RTPBR_GLTF_PUNCTUAL_SPOT)
            scale *= spotFalloff(glm::dot(dir, -wi), double(P.inner_cone_angle), double(P.outer_cone_angle));
    }
    if (!(scale > 0.0) || !std::isfinite(scale))
        return false;
    s->wi = glm::vec3(wi);
    s->irradiance = glm::vec3(dvec3(P.intensity[0], P.intensity[1], P.intensity[2]) * scale);
    return true;
}

bool PunctualLights::diskRadiance(uint32_t l, glm::vec3 wi, dvec3 *radiance, double *pdf) const {
    const Disk &D = disks_[l];
    if (!(D.halfAngle > 0.0))
        return false;
    // Inside the cap: in front of the light and sin^2 of the angle from its axis within
    // sin^2 a (a < pi / 4); the cross product keeps its precision for a tiny disk, where the
    // cosine would round to 1.
    const dvec3 w = glm::normalize(dvec3(wi));
    const dvec3 c = glm::cross(w, D.axis);
    if (!(glm::dot(w, D.axis) > 0.0) || !(glm::dot(c, c) <= D.sin2))
        return false;
    *radiance = D.radiance;
    *pdf = D.pdf;
    return true;
}

bool PunctualLights::capsuleRadiance(uint32_t l, glm::vec3 pf, glm::vec3 wif, float tmax, dvec3 *radiance,
                                     double *pdf) const {
    const Capsule &C = capsules_[l];
    if (!(C.radius > 0.0))
        return false;
    const dvec3 p(pf), w = glm::normalize(dvec3(wif));
    double t;
    dvec3 n;
    if (!C.shape.intersect(p, w, double(tmax), &t, &n))
        return false;
    const double window = rangeWindow(glm::length(C.shape.centre - p), double(lights_[l].range));
    if (!(window > 0.0))
        return false;
    const double cosLight = -glm::dot(n, w);
    // From inside (the ray leaves through the surface: cos <= 0) no light sample competes.
    *pdf = !C.shape.contains(p) && cosLight > 0.0 ? t * t / (cosLight * C.area) : 0.0;
    *radiance = C.radiance * window;
    return true;
}

PunctualLights::Cone PunctualLights::sphereCone(const Sphere &S, dvec3 p) {
    const dvec3 toCentre = S.centre - p;
    const double d = glm::length(toCentre);
    // sin s = r / d, cos s = sqrt((d - r)(d + r)) / d; 1 - cos s = sin^2 s / (1 + cos s) keeps
    // its precision for a small sphere, where cos s rounds to 1.
    const double sinS = S.radius / d, cosS = std::sqrt(std::max(0.0, (d - S.radius) * (d + S.radius))) / d;
    return Cone{toCentre / d, d, sinS * sinS / (1.0 + cosS), 1.0 + cosS};
}

bool PunctualLights::sphereRadiance(uint32_t l, glm::vec3 pf, glm::vec3 wif, float tmax, dvec3 *radiance,
                                    double *pdf) const {
    const Sphere &S = spheres_[l];
    if (!(S.radius > 0.0))
        return false;
    const dvec3 p(pf), w = glm::normalize(dvec3(wif)), toCentre = S.centre - p;
    const double d = glm::length(toCentre), along = glm::dot(w, toCentre);
    // r^2 minus the squared distance from the centre to the ray's line (the cross product keeps
    // its precision where the angle to the centre is tiny).
    const dvec3 off = glm::cross(w, toCentre);
    const double h2 = S.radius * S.radius - glm::dot(off, off);
    if (!(h2 >= 0.0))
        return false;
    double t;
    if (d > S.radius) { // outside: the near surface, ahead only
        if (!(along > 0.0))
            return false;
        t = (d - S.radius) * (d + S.radius) / (along + std::sqrt(h2));
        *pdf = 1.0 / (2.0 * kPi * sphereCone(S, p).oneMinusCos);
    } else { // inside: the surface ahead; no light sample competes
        t = along + std::sqrt(h2);
        *pdf = 0.0;
    }
    const double window = rangeWindow(d, double(lights_[l].range));
    if (!(t <= double(tmax)) || !(window > 0.0))
        return false;
    *radiance = S.radiance * window;
    return true;
}

} // namespace rtpbr_oracle
