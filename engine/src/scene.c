// Scenes built through the API: validation, then upload to GPU buffers.
#include <float.h>
#include <math.h>
#include <string.h>

#include "internal.h"
#include "light_texture.h"
#include "passes/passes.h"
#include "rtpbr/rtpbr_gltf.h"

#define LIGHT_PI 3.14159265358979323846

// ---------------------------------------------------------------------------------------------
// Lights

// A light's derived facts (normal, centre, area, bounding sphere, fan;
// rtpbr_gltf_polygon_facts_of) are computed once where it is made: by the loader for the
// lights of rtpbr_gpu_scene_from_loaded, here for the lights given through the API. The checks
// and the light record read them.

// The facts of lights given through the API; NULL (and *result set) without memory.
static rtpbr_gltf_polygon_facts *derive_light_facts(const rtpbr_context *ctx, const rtpbr_light_desc *lights,
                                                    uint32_t count, rtpbr_result *result)
{
    rtpbr_gltf_polygon_facts *facts = rtpbr_alloc(&ctx->host, (count ? count : 1) * sizeof *facts);
    if (!facts) {
        *result = RTPBR_ERROR_OUT_OF_HOST_MEMORY;
        return NULL;
    }
    for (uint32_t i = 0; i < count; ++i) rtpbr_gltf_polygon_facts_of(lights[i].vertices, lights[i].vertex_count, &facts[i]);
    return facts;
}

// The angular diameter a directional light is shaded with (rtpbr_light_desc); 0: a true
// direction, also below RTPBR_SUN_MIN_ANGULAR_DIAMETER (the float octagon's edge integrals would
// lose the disk there; nothing but a mirror tells it from a direction).
static double directional_diameter(const rtpbr_light_desc *l)
{
    double d = l->angular_diameter == 0.0f ? (double)RTPBR_SUN_ANGULAR_DIAMETER : l->angular_diameter;
    return d >= RTPBR_SUN_MIN_ANGULAR_DIAMETER ? d : 0.0;
}

// A punctual light's checks (rtpbr_light_desc: the type's fields).
static rtpbr_result validate_punctual(const rtpbr_context *ctx, const rtpbr_light_desc *l, uint32_t index)
{
    float cones[3] = {l->range, l->inner_cone_angle, l->outer_cone_angle};
    if (!rtpbr_finite(l->emission, 3) || !rtpbr_finite(l->position, 3) || !rtpbr_finite(l->direction, 3) ||
        !rtpbr_finite(cones, 3)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has a NaN or infinite emission, position, direction, range or cone",
                  index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->emission[0] < 0.0f || l->emission[1] < 0.0f || l->emission[2] < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has negative emission", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->range < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has a negative range (%g; zero: infinite)", index, l->range);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->type == RTPBR_LIGHT_POINT && !(l->radius >= 0.0f && isfinite(l->radius))) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (point) has radius %g; finite and >= 0 is required (zero: a true point)",
                  index, l->radius);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->type == RTPBR_LIGHT_SPOT && l->radius != 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (spot) has radius %g; spots are true points (radius 0)", index,
                  l->radius);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->type == RTPBR_LIGHT_POINT && l->radius > 0.0f) {
        // its sphere's radiance emission / (pi r^2) (sphere_record) and pi r^2 must be floats
        double most = fmax(fmax(l->emission[0], l->emission[1]), l->emission[2]);
        double disk = LIGHT_PI * (double)l->radius * l->radius;
        if (!(most / disk <= 0.5 * FLT_MAX) || !(disk <= 0.5 * FLT_MAX)) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "light %u (point): intensity %g over a sphere of radius %g is a radiance (or area) beyond a float",
                      index, most, l->radius);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    if (l->type == RTPBR_LIGHT_DIRECTIONAL && !(isfinite(l->angular_diameter) && l->angular_diameter < LIGHT_PI / 2.0)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "light %u (directional) has angular diameter %g radians; below pi/2 is required (zero: the sun's "
                  "0.53 degrees; negative: a true direction)", index, l->angular_diameter);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->type == RTPBR_LIGHT_DIRECTIONAL && directional_diameter(l) > 0.0) {
        // its disk's radiance, about emission / (pi sin^2(d / 2)) (sun_record), must be a float
        double s = sin(0.5 * directional_diameter(l));
        double most = fmax(fmax(l->emission[0], l->emission[1]), l->emission[2]);
        if (!(most / (LIGHT_PI * s * s) <= 0.5 * FLT_MAX)) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "light %u (directional): illuminance %g lux over a disk of %g radians is a radiance beyond a float",
                      index, most, directional_diameter(l));
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    double len2 = 0.0;
    for (int k = 0; k < 3; ++k) len2 += (double)l->direction[k] * l->direction[k];
    if (l->type != RTPBR_LIGHT_POINT && !(len2 > 1e-30)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (%s) has a zero direction", index,
                  l->type == RTPBR_LIGHT_SPOT ? "spot" : "directional");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    double outer = l->outer_cone_angle == 0.0f ? LIGHT_PI / 4.0 : l->outer_cone_angle;
    // inner == outer is let through: glTF's inner < outer can round to equal floats (the
    // falloff's 1e-3 guard makes it a step)
    if (l->type == RTPBR_LIGHT_SPOT && !(l->inner_cone_angle >= 0.0f && l->inner_cone_angle <= outer && outer <= LIGHT_PI / 2.0 + 1e-6)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "light %u: spot cones inner %g, outer %g radians; 0 <= inner <= outer <= pi/2 is required", index,
                  l->inner_cone_angle, outer);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    return RTPBR_SUCCESS;
}

// A disk's checks (rtpbr_light_desc: position, direction, radius, emission).
static rtpbr_result validate_disk(const rtpbr_context *ctx, const rtpbr_light_desc *l, uint32_t index)
{
    if (!rtpbr_finite(l->emission, 3) || !rtpbr_finite(l->position, 3) || !rtpbr_finite(l->direction, 3) ||
        !isfinite(l->radius)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (disk) has a NaN or infinite emission, position, direction or radius",
                  index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->emission[0] < 0.0f || l->emission[1] < 0.0f || l->emission[2] < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has negative emission", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    double len2 = 0.0;
    for (int k = 0; k < 3; ++k) len2 += (double)l->direction[k] * l->direction[k];
    if (!(len2 > 1e-30)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (disk) has a zero direction (its normal)", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // pi r^2 (the record's area) must be a float
    if (!(l->radius > 0.0f) || !(LIGHT_PI * (double)l->radius * l->radius <= 0.5 * FLT_MAX)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (disk) has radius %g; > 0 is required (and pi r^2 a float)",
                  index, l->radius);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // An ellipse: its second half-axis as the radius, and an axis with a part in its plane.
    if (!isfinite(l->disk_radius2) || !(l->disk_radius2 >= 0.0f) ||
        !(LIGHT_PI * (double)l->disk_radius2 * l->disk_radius2 <= 0.5 * FLT_MAX)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "light %u (disk) has disk_radius2 %g; >= 0 is required (0: a circle; pi r2^2 a float)", index,
                  l->disk_radius2);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->disk_radius2 > 0.0f) {
        double an = 0.0, a2 = 0.0;
        for (int k = 0; k < 3; ++k) an += (double)l->disk_axis[k] * l->direction[k];
        for (int k = 0; k < 3; ++k) {
            double c = l->disk_axis[k] - an * l->direction[k] / len2;
            a2 += c * c;
        }
        double axis2 = 0.0;
        for (int k = 0; k < 3; ++k) axis2 += (double)l->disk_axis[k] * l->disk_axis[k];
        if (!rtpbr_finite(l->disk_axis, 3) || !(a2 > 1e-12 * axis2) || !(axis2 > 1e-30)) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "light %u (ellipse: disk_radius2 > 0) has a disk_axis that is zero, not finite or along its normal",
                      index);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    return RTPBR_SUCCESS;
}

// A tube's checks (rtpbr_light_desc: position, direction = its axis, length, radius, emission).
static rtpbr_result validate_tube(const rtpbr_context *ctx, const rtpbr_light_desc *l, uint32_t index)
{
    if (!rtpbr_finite(l->emission, 3) || !rtpbr_finite(l->position, 3) || !rtpbr_finite(l->direction, 3) ||
        !isfinite(l->radius) || !isfinite(l->length) || !isfinite(l->range)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "light %u (tube) has a NaN or infinite emission, position, direction, radius, length or range", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->emission[0] < 0.0f || l->emission[1] < 0.0f || l->emission[2] < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has negative emission", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    double len2 = 0.0;
    for (int k = 0; k < 3; ++k) len2 += (double)l->direction[k] * l->direction[k];
    if (!(len2 > 1e-30)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (tube) has a zero direction (its axis)", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!(l->length >= 0.0f)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (tube) has length %g; >= 0 is required (0: a sphere)", index,
                  l->length);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // 4 pi r^2 + 2 pi r L (the record's area) and the ends (centre +- L/2) must be floats
    double r = l->radius, area = 4.0 * LIGHT_PI * r * r + 2.0 * LIGHT_PI * r * l->length;
    if (!(l->radius > 0.0f) || !(area <= 0.5 * FLT_MAX) || !(0.5 * (double)l->length + r <= 0.25 * FLT_MAX)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "light %u (tube) has radius %g, length %g; radius > 0 is required (and its area 4 pi r^2 + 2 pi r L a float)",
                  index, l->radius, l->length);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->range < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u (tube) has a negative range (%g; zero: infinite)", index,
                  l->range);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    return RTPBR_SUCCESS;
}

rtpbr_result rtpbr_light_validate(const rtpbr_context *ctx, const rtpbr_light_desc *l,
                                   const rtpbr_gltf_polygon_facts *f, uint32_t index)
{
    if ((unsigned)l->type > (unsigned)RTPBR_LIGHT_TUBE) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has type %d; RTPBR_LIGHT_POLYGON .. _TUBE (0 .. 5) are allowed",
                  index, (int)l->type);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->emission_texture && l->type != RTPBR_LIGHT_POLYGON) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u: an emission texture on a light of type %d; polygons only", index,
                  (int)l->type);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->type == RTPBR_LIGHT_DISK) return validate_disk(ctx, l, index);
    if (l->type == RTPBR_LIGHT_TUBE) return validate_tube(ctx, l, index);
    if (l->type != RTPBR_LIGHT_POLYGON) return validate_punctual(ctx, l, index);
    if (l->vertex_count < 3 || l->vertex_count > RTPBR_MAX_POLYGON_VERTICES) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has %u vertices; 3 to %u are allowed", index, l->vertex_count,
                  RTPBR_MAX_POLYGON_VERTICES);
        return l->vertex_count > RTPBR_MAX_POLYGON_VERTICES ? RTPBR_ERROR_LIMIT_EXCEEDED
                                                            : RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!rtpbr_finite(&l->vertices[0][0], 3 * l->vertex_count) || !rtpbr_finite(l->emission, 3)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has a NaN or infinite vertex or emission", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (l->emission[0] < 0.0f || l->emission[1] < 0.0f || l->emission[2] < 0.0f) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has negative emission", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // Size of the polygon: its largest vertex distance from vertex 0.
    double extent = 0.0;
    for (uint32_t i = 1; i < l->vertex_count; ++i) {
        double d = 0.0;
        for (int k = 0; k < 3; ++k) d += ((double)l->vertices[i][k] - l->vertices[0][k]) * ((double)l->vertices[i][k] - l->vertices[0][k]);
        if (d > extent) extent = d;
    }
    extent = sqrt(extent);
    if (!(2.0 * (double)f->area > 1e-12 * extent * extent) || extent == 0.0) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u is degenerate (zero area)", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    for (uint32_t i = 1; i < l->vertex_count; ++i) {
        double d = 0.0;
        for (int k = 0; k < 3; ++k) d += (double)f->normal[k] * ((double)l->vertices[i][k] - l->vertices[0][k]);
        if (fabs(d) > 1e-3 * extent) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u is not planar (vertex %u is %g off the plane)", index, i, d);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    if (l->emission_texture) {
        // a parallelogram: v0 + v2 = v1 + v3 (the texture's (s, t) are affine over it)
        double gap = 0.0;
        for (int k = 0; k < 3; ++k) {
            double d = (double)l->vertices[0][k] + l->vertices[2][k] - l->vertices[1][k] - l->vertices[3][k];
            gap += d * d;
        }
        if (l->vertex_count != 4 || sqrt(gap) > 1e-3 * extent) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "light %u has an emission texture but is not a parallelogram of 4 vertices (v0 + v2 = v1 + v3)", index);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
        if (!rtpbr_finite(&l->emission_uv[0][0], 6)) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u has a NaN or infinite emission_uv", index);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    return RTPBR_SUCCESS;
}

// The count and the array; each light is checked with its facts (validate_lights).
static rtpbr_result validate_light_array(const rtpbr_context *ctx, const rtpbr_light_desc *lights, uint32_t count)
{
    if (count > RTPBR_MAX_LIGHTS) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "%u lights; at most RTPBR_MAX_LIGHTS = %u are allowed", count, RTPBR_MAX_LIGHTS);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    if (count > 0 && !lights) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light_count is %u but lights is NULL", count);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    return RTPBR_SUCCESS;
}

static rtpbr_result validate_lights(const rtpbr_context *ctx, const rtpbr_light_desc *lights,
                                    const rtpbr_gltf_polygon_facts *facts, uint32_t count)
{
    for (uint32_t i = 0; i < count; ++i) {
        rtpbr_result result = rtpbr_light_validate(ctx, &lights[i], &facts[i], i);
        if (result != RTPBR_SUCCESS) return result;
    }
    return RTPBR_SUCCESS;
}

// A punctual light's record (RTPBR_LIGHT_FIELDS).
static void punctual_record(const rtpbr_light_desc *l, rtpbr_shader_light *out)
{
    rtpbr_shader_light g = {0};
    bool directional = l->type == RTPBR_LIGHT_DIRECTIONAL;
    double len = sqrt((double)l->direction[0] * l->direction[0] + (double)l->direction[1] * l->direction[1] +
                      (double)l->direction[2] * l->direction[2]);
    for (int k = 0; k < 3; ++k) {
        g.vertices[0][k] = directional ? 0.0f : l->position[k];
        g.vertices[1][k] = len > 0.0 ? (float)(l->direction[k] / len) : 0.0f;
        g.sphere[k] = g.vertices[0][k];
    }
    g.vertices[0][3] = l->range > 0.0f && !directional ? (float)(1.0 / ((double)l->range * l->range)) : 0.0f;
    // The spot's falloff (KHR_lights_punctual's recommended implementation): t = clamp((cos -
    // cos outer) / max(cos inner - cos outer, 1e-3), 0, 1); a point light's cone takes everything.
    double outer = l->outer_cone_angle == 0.0f ? LIGHT_PI / 4.0 : l->outer_cone_angle;
    bool spot = l->type == RTPBR_LIGHT_SPOT;
    g.vertices[2][0] = spot ? (float)cos(outer) : -2.0f;
    g.vertices[2][1] = spot ? (float)(1.0 / fmax(cos((double)l->inner_cone_angle) - cos(outer), 1e-3)) : 1.0f;
    memcpy(g.radiance, l->emission, sizeof g.radiance);
    g.two_sided = 1.0f;
    g.plane[3] = 1.0f;
    g.sphere[3] = l->range > 0.0f && !directional ? l->range : (float)RTPBR_LIGHT_INFINITE;
    g.shape = (uint32_t)l->type;
    *out = g;
}

// A directional light with an angular diameter (rtpbr_light_desc): a regular octagon of its
// disk's area, at RTPBR_SUN_DISTANCE from the origin toward the light, facing the origin, of the
// radiance that gives `emission` at normal incidence (the octagon's form factor there, Lambert's
// polygon formula in double precision); a polygon record, marked to be kept by the cull
// whatever its form factor (RTPBR_LIGHT_FIELDS: sun).
static void sun_record(const rtpbr_light_desc *l, double diameter, rtpbr_shader_light *out)
{
    enum { N = 8 };
    double len = sqrt((double)l->direction[0] * l->direction[0] + (double)l->direction[1] * l->direction[1] +
                      (double)l->direction[2] * l->direction[2]);
    double w[3]; // toward the light
    for (int k = 0; k < 3; ++k) w[k] = -l->direction[k] / len;
    // t1, t2: an orthonormal basis of the disk's plane (Duff et al. 2017, branchless ONB)
    double sign = w[2] >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + w[2]), b = w[0] * w[1] * a;
    double t1[3] = {1.0 + sign * w[0] * w[0] * a, sign * b, -sign * w[0]};
    double t2[3] = {b, sign + w[1] * w[1] * a, -w[1]};
    // At unit distance: the disk's radius tan(d/2), the octagon's circumradius for the same
    // area (pi r^2 = (N/2) R^2 sin(2 pi / N)).
    double r = tan(0.5 * diameter), R = r * sqrt(LIGHT_PI / (0.5 * N * sin(2.0 * LIGHT_PI / N)));
    double u[N][3];
    for (int v = 0; v < N; ++v) {
        // clockwise about w seen from the light's side: counter-clockwise about -w, the way the
        // light travels (the emitting side, rtpbr_gltf_polygon_facts' normal)
        double phi = -2.0 * LIGHT_PI * v / N;
        for (int k = 0; k < 3; ++k) u[v][k] = w[k] + R * (cos(phi) * t1[k] + sin(phi) * t2[k]);
    }
    // The form factor at the origin (Lambert: (1 / 2 pi) sum of the edges' angles x their
    // planes' normals . the surface normal w).
    double ff = 0.0;
    for (int v = 0; v < N; ++v) {
        const double *p = u[v], *q = u[(v + 1) % N];
        double c[3] = {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
        double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double dot = p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        ff += atan2(cl, dot) * (c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) / cl;
    }
    ff = fabs(ff) / (2.0 * LIGHT_PI);
    rtpbr_light_desc poly = {0};
    poly.vertex_count = N;
    for (int v = 0; v < N; ++v)
        for (int k = 0; k < 3; ++k) poly.vertices[v][k] = (float)(u[v][k] * RTPBR_SUN_DISTANCE);
    for (int k = 0; k < 3; ++k) poly.emission[k] = (float)(l->emission[k] / (LIGHT_PI * ff));
    rtpbr_gltf_polygon_facts facts;
    rtpbr_gltf_polygon_facts_of(poly.vertices, poly.vertex_count, &facts);
    rtpbr_light_record(&poly, &facts, out);
    out->sun = 1u;
}

// A point light with a radius (rtpbr_light_desc): the sphere of that radius around its
// position, of uniform radiance emission / (pi r^2) (RTPBR_LIGHT_FIELDS: SPHERE).
static void sphere_record(const rtpbr_light_desc *l, rtpbr_shader_light *out)
{
    rtpbr_shader_light g = {0};
    double disk = LIGHT_PI * (double)l->radius * l->radius;
    for (int k = 0; k < 3; ++k) {
        g.vertices[0][k] = l->position[k];
        g.sphere[k] = l->position[k];
        g.radiance[k] = (float)(l->emission[k] / disk);
    }
    g.vertices[0][3] = l->range > 0.0f ? (float)(1.0 / ((double)l->range * l->range)) : 0.0f;
    g.sphere[3] = l->radius;
    g.area = (float)disk;
    g.two_sided = 1.0f;
    g.plane[3] = 1.0f;
    g.shape = RTPBR_LIGHT_SHAPE_SPHERE;
    *out = g;
}

// A disk (rtpbr_light_desc): its centre, orthogonal half-axes of length radius (an ellipse's:
// radius along disk_axis, disk_radius2 across; cross(u, v) along the unit normal) and plane
// (RTPBR_LIGHT_FIELDS: DISK).
static void disk_record(const rtpbr_light_desc *l, rtpbr_shader_light *out)
{
    rtpbr_shader_light g = {0};
    double len = sqrt((double)l->direction[0] * l->direction[0] + (double)l->direction[1] * l->direction[1] +
                      (double)l->direction[2] * l->direction[2]);
    double n[3];
    for (int k = 0; k < 3; ++k) n[k] = l->direction[k] / len;
    // t1, t2: an orthonormal basis of the disk's plane with t1 x t2 = n (Duff et al. 2017)
    double sign = n[2] >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + n[2]), b = n[0] * n[1] * a;
    double t1[3] = {1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
    double t2[3] = {b, sign + n[1] * n[1] * a, -n[1]};
    double r = l->radius, r2 = l->radius;
    if (l->disk_radius2 > 0.0f) { // an ellipse: t1 along disk_axis' part in the plane, t2 = n x t1
        double an = 0.0, len1 = 0.0;
        r2 = l->disk_radius2;
        for (int k = 0; k < 3; ++k) an += l->disk_axis[k] * n[k];
        for (int k = 0; k < 3; ++k) t1[k] = l->disk_axis[k] - an * n[k], len1 += t1[k] * t1[k];
        len1 = sqrt(len1);
        for (int k = 0; k < 3; ++k) t1[k] /= len1;
        t2[0] = n[1] * t1[2] - n[2] * t1[1];
        t2[1] = n[2] * t1[0] - n[0] * t1[2];
        t2[2] = n[0] * t1[1] - n[1] * t1[0];
    }
    double dotc = 0.0;
    for (int k = 0; k < 3; ++k) {
        g.vertices[0][k] = l->position[k];
        g.vertices[1][k] = (float)(r * t1[k]);
        g.vertices[2][k] = (float)(r2 * t2[k]);
        g.sphere[k] = l->position[k];
        g.plane[k] = (float)n[k];
        dotc += n[k] * l->position[k];
    }
    g.plane[3] = (float)-dotc;
    g.sphere[3] = (float)fmax(r, r2);
    memcpy(g.radiance, l->emission, sizeof g.radiance);
    g.area = (float)(LIGHT_PI * r * r2);
    g.two_sided = l->two_sided ? 1.0f : 0.0f;
    g.shape = RTPBR_LIGHT_SHAPE_DISK;
    *out = g;
}

// A tube (rtpbr_light_desc): its ends' centres and radius, a bounding sphere (centre, L/2 + r),
// area 4 pi r^2 + 2 pi r L and its centre with 1 / range^2 (RTPBR_LIGHT_FIELDS: TUBE).
static void tube_record(const rtpbr_light_desc *l, rtpbr_shader_light *out)
{
    rtpbr_shader_light g = {0};
    double len = sqrt((double)l->direction[0] * l->direction[0] + (double)l->direction[1] * l->direction[1] +
                      (double)l->direction[2] * l->direction[2]);
    double half = 0.5 * l->length, r = l->radius;
    for (int k = 0; k < 3; ++k) {
        double a = l->direction[k] / len;
        g.vertices[0][k] = (float)(l->position[k] - half * a);
        g.vertices[1][k] = (float)(l->position[k] + half * a);
        g.vertices[2][k] = (float)a;
        g.vertices[3][k] = g.sphere[k] = l->position[k];
    }
    g.vertices[3][3] = l->range > 0.0f ? (float)(1.0 / ((double)l->range * l->range)) : 0.0f;
    g.vertices[0][3] = g.vertices[1][3] = l->radius;
    g.vertices[2][3] = l->length;
    g.sphere[3] = (float)(half + r);
    memcpy(g.radiance, l->emission, sizeof g.radiance);
    g.area = (float)(4.0 * LIGHT_PI * r * r + 2.0 * LIGHT_PI * r * l->length);
    g.two_sided = 1.0f;
    g.plane[3] = 1.0f;
    g.shape = RTPBR_LIGHT_SHAPE_TUBE;
    *out = g;
}

void rtpbr_light_record(const rtpbr_light_desc *l, const rtpbr_gltf_polygon_facts *f, rtpbr_shader_light *out)
{
    if (l->type == RTPBR_LIGHT_TUBE) {
        tube_record(l, out);
        return;
    }
    if (l->type == RTPBR_LIGHT_DISK) {
        disk_record(l, out);
        return;
    }
    if (l->type == RTPBR_LIGHT_DIRECTIONAL && directional_diameter(l) > 0.0) {
        sun_record(l, directional_diameter(l), out);
        return;
    }
    if (l->type == RTPBR_LIGHT_POINT && l->radius > 0.0f) {
        sphere_record(l, out);
        return;
    }
    if (l->type != RTPBR_LIGHT_POLYGON) {
        punctual_record(l, out);
        return;
    }
    rtpbr_shader_light g = {0};
    double fan = 0.0; // w of vertex v: the area of the fan polygon v0 .. v (RTPBR_LIGHT_FIELDS)
    for (uint32_t v = 0; v < l->vertex_count; ++v) {
        memcpy(g.vertices[v], l->vertices[v], 3 * sizeof(float));
        g.vertices[v][3] = (float)fan;
        if (v >= 1 && v + 1 < l->vertex_count) fan += f->fan_area[v - 1];
    }
    memcpy(g.radiance, l->emission, sizeof g.radiance);
    g.two_sided = l->two_sided ? 1.0f : 0.0f;
    memcpy(g.plane, f->normal, sizeof f->normal);
    g.plane[3] = -(g.plane[0] * l->vertices[0][0] + g.plane[1] * l->vertices[0][1] + g.plane[2] * l->vertices[0][2]);
    g.area = f->area;
    memcpy(g.sphere, f->center, sizeof f->center);
    g.sphere[3] = f->bound_radius;
    g.vertex_count = l->vertex_count;
    *out = g;
}

static bool is_zero(const float *v, size_t n);

// A textured light's key: its texture and coordinates, the defaults applied (all zero: the
// whole texture, (0, 0), (1, 0), (0, 1)).
static rtpbr_light_texture_key light_texture_key(const rtpbr_light_desc *l)
{
    rtpbr_light_texture_key key = {.texture = l->emission_texture};
    if (is_zero(&l->emission_uv[0][0], 6)) {
        key.uv[1][0] = 1.0f;
        key.uv[2][1] = 1.0f;
    } else {
        memcpy(key.uv, l->emission_uv, sizeof key.uv);
    }
    return key;
}

// The layer of the scene's light textures holding key's chain, or -1.
static int32_t light_texture_layer(const rtpbr_light_texture_key *keys, uint32_t count, const rtpbr_light_texture_key *key)
{
    for (uint32_t i = 0; i < count; ++i)
        if (keys[i].texture == key->texture && memcmp(keys[i].uv, key->uv, sizeof key->uv) == 0) return (int32_t)i;
    return -1;
}

// The textured lights' textures exist (texture_count: the desc's; a scene's images hold one more,
// the white stand-in); with a scene (set_lights),
// each light's chain is one the scene was created with.
static rtpbr_result validate_light_textures(const rtpbr_context *ctx, const rtpbr_light_desc *lights, uint32_t count,
                                            uint32_t texture_count, const rtpbr_gpu_scene *scene)
{
    for (uint32_t i = 0; i < count; ++i) {
        if (!lights[i].emission_texture) continue;
        if (lights[i].emission_texture > texture_count) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "light %u: emission_texture %u is past the scene's %u textures", i,
                      lights[i].emission_texture, texture_count);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
        rtpbr_light_texture_key key = light_texture_key(&lights[i]);
        if (scene && light_texture_layer(scene->light_texture_keys, scene->light_texture_layers, &key) < 0) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "light %u: rtpbr_gpu_scene_set_lights takes a textured light only with a texture and emission_uv "
                      "of the scene's creation (its chain is prefiltered then)", i);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    return RTPBR_SUCCESS;
}

// The prefiltered chain of each distinct (texture, coordinates) of the lights (light_texture.h),
// uploaded as one layer each.
static rtpbr_result create_light_textures(rtpbr_gpu_scene *scene, const rtpbr_gpu_scene_desc *desc)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    float *chains = NULL;
    uint32_t layers = 0;
    RTPBR_ALLOC(&ctx->host, scene->light_texture_keys, RTPBR_MAX_TEXTURED_LIGHTS * sizeof *scene->light_texture_keys);
    for (uint32_t i = 0; i < desc->light_count; ++i) {
        if (!desc->lights[i].emission_texture) continue;
        rtpbr_light_texture_key key = light_texture_key(&desc->lights[i]);
        if (light_texture_layer(scene->light_texture_keys, layers, &key) >= 0) continue;
        if (layers == RTPBR_MAX_TEXTURED_LIGHTS)
            RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED,
                       "more than RTPBR_MAX_TEXTURED_LIGHTS = %u distinct textured lights (texture and emission_uv)",
                       RTPBR_MAX_TEXTURED_LIGHTS);
        scene->light_texture_keys[layers++] = key;
    }
    if (layers == 0) goto cleanup;
    size_t floats = rtpbr_light_texture_floats();
    RTPBR_ALLOC(&ctx->host, chains, layers * floats * sizeof(float));
    for (uint32_t k = 0; k < layers; ++k) {
        const rtpbr_light_texture_key *key = &scene->light_texture_keys[k];
        const float du[2] = {key->uv[1][0] - key->uv[0][0], key->uv[1][1] - key->uv[0][1]};
        const float dv[2] = {key->uv[2][0] - key->uv[0][0], key->uv[2][1] - key->uv[0][1]};
        if (rtpbr_light_texture_prefilter(&desc->textures[key->texture - 1], key->uv[0], du, dv, chains + k * floats) != 0)
            RTPBR_FAIL(&ctx->host, RTPBR_ERROR_INVALID_ARGUMENT,
                       "textured light: texture %u with these emission_uv could not be prefiltered", key->texture - 1);
    }
    RTPBR_TRY(rtpbr_light_textures_create(ctx, chains, layers, &scene->light_textures));
    scene->light_texture_layers = layers;
cleanup:
    rtpbr_free(&ctx->host, chains);
    return result;
}

VkImageView rtpbr_gpu_scene_light_texture_view(const rtpbr_gpu_scene *scene)
{
    return scene->light_texture_layers ? scene->light_textures.view : scene->context->light_texture_stand_in.view;
}

static void write_lights(rtpbr_gpu_scene *scene, const rtpbr_light_desc *lights, const rtpbr_gltf_polygon_facts *facts,
                         uint32_t count)
{
    rtpbr_shader_light *gpu = scene->lights.mapped;
    for (uint32_t i = 0; i < count; ++i) {
        rtpbr_light_record(&lights[i], &facts[i], &gpu[i]);
        if (lights[i].emission_texture) { // validated: the scene holds its chain
            rtpbr_light_texture_key key = light_texture_key(&lights[i]);
            gpu[i].texture = 1u + (uint32_t)light_texture_layer(scene->light_texture_keys, scene->light_texture_layers, &key);
        }
    }
    scene->light_count = count;
}

rtpbr_result rtpbr_gpu_scene_set_lights(rtpbr_gpu_scene *scene, const rtpbr_light_desc *lights, uint32_t light_count)
{
    if (!scene) return rtpbr_null_object(__func__, "scene");
    rtpbr_result result = validate_light_array(scene->context, lights, light_count);
    if (result != RTPBR_SUCCESS) return result;
    rtpbr_gltf_polygon_facts *facts = derive_light_facts(scene->context, lights, light_count, &result);
    if (facts) result = validate_lights(scene->context, lights, facts, light_count);
    if (facts && result == RTPBR_SUCCESS)
        result = validate_light_textures(scene->context, lights, light_count, scene->texture_count - 1u, scene);
    if (result == RTPBR_SUCCESS) write_lights(scene, lights, facts, light_count);
    rtpbr_free(&scene->context->host, facts);
    return result;
}

// ---------------------------------------------------------------------------------------------
// Meshes and materials

static bool is_zero(const float *v, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (v[i] != 0.0f) return false;
    return true;
}

static rtpbr_result validate_mesh(const rtpbr_context *ctx, const rtpbr_mesh_desc *m, uint32_t index,
                                  uint32_t material_count)
{
#define FAIL(...) do { rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, __VA_ARGS__); return RTPBR_ERROR_INVALID_ARGUMENT; } while (0)
    if (!m->positions || m->vertex_count == 0) FAIL("mesh %u has no positions", index);
    if (m->indices ? (m->index_count == 0 || m->index_count % 3) : (m->vertex_count % 3))
        FAIL("mesh %u: the index (or, without indices, vertex) count is not a positive multiple of 3", index);
    if (material_count ? m->material >= material_count : m->material != 0)
        FAIL("mesh %u uses material %u but the scene has %u", index, m->material, material_count);
    if (!rtpbr_finite(m->positions, 3 * (size_t)m->vertex_count)) FAIL("mesh %u has a NaN or infinite position", index);
    if (m->normals && !rtpbr_finite(m->normals, 3 * (size_t)m->vertex_count))
        FAIL("mesh %u has a NaN or infinite normal", index);
    if ((m->texcoords && !rtpbr_finite(m->texcoords, 2 * (size_t)m->vertex_count)) ||
        (m->texcoords1 && !rtpbr_finite(m->texcoords1, 2 * (size_t)m->vertex_count)))
        FAIL("mesh %u has a NaN or infinite texture coordinate", index);
    if (m->tangents && !rtpbr_finite(m->tangents, 4 * (size_t)m->vertex_count))
        FAIL("mesh %u has a NaN or infinite tangent", index);
    if (!rtpbr_finite(m->transform, 16)) FAIL("mesh %u has a NaN or infinite transform", index);
    if (m->indices)
        for (uint32_t i = 0; i < m->index_count; ++i)
            if (m->indices[i] >= m->vertex_count)
                FAIL("mesh %u: index %u is %u, past its %u vertices", index, i, m->indices[i], m->vertex_count);
    return RTPBR_SUCCESS;
#undef FAIL
}

// The desc's defaults and flags applied, the values stored as glTF factors (KHR's own zeros:
// ior 0 is Fresnel 1, specularFactor 0 no lobe, alphaCutoff 0 nothing cut), the values
// rtpbr_material_validate checked taken as they are; the material rules (roughness floor, [0, 1]
// ranges, ior, clearcoat and Disney mappings) are applied by the shaders, in
// shaderlib/rtpbr/material.h's Material_Resolve, which the oracle calls as well.
rtpbr_shader_material rtpbr_material_record(const rtpbr_material_desc *m)
{
    rtpbr_shader_material g = {0};
    memcpy(g.base_color, m->base_color, sizeof g.base_color);
    g.metallic = m->metallic;
    memcpy(g.emission, m->emission, sizeof g.emission);
    g.roughness = m->roughness;
    if (is_zero(m->specular_color, 3)) g.specular_color[0] = g.specular_color[1] = g.specular_color[2] = 1.0f;
    else memcpy(g.specular_color, m->specular_color, sizeof g.specular_color);
    g.ior = m->flags & RTPBR_MATERIAL_FRESNEL_ONE ? 0.0f : m->ior == 0.0f ? 1.5f : m->ior;
    g.specular_factor = m->flags & RTPBR_MATERIAL_NO_SPECULAR ? 0.0f : m->specular_factor == 0.0f ? 1.0f : m->specular_factor;
    g.normal_scale = m->normal_scale == 0.0f ? 1.0f : m->normal_scale;
    g.anisotropy_strength = m->anisotropy_strength;
    g.anisotropy_rotation = m->anisotropy_rotation;
    memcpy(g.sheen_color_factor, m->sheen_color_factor, sizeof g.sheen_color_factor);
    g.sheen_roughness_factor = m->sheen_roughness_factor;
    g.clearcoat_factor = m->clearcoat_factor;
    g.clearcoat_roughness_factor = m->clearcoat_roughness_factor;
    const rtpbr_disney_params *d = &m->disney;
    g.disney_subsurface = d->subsurface;
    g.disney_specular = m->flags & RTPBR_MATERIAL_DISNEY_NO_SPECULAR ? 0.0f : d->specular == 0.0f ? 0.5f : d->specular;
    g.disney_specular_tint = d->specular_tint;
    g.disney_sheen = d->sheen;
    g.disney_sheen_tint = d->sheen_tint;
    g.disney_clearcoat = d->clearcoat;
    g.disney_clearcoat_gloss = d->clearcoat_gloss;
    g.disney_anisotropic = d->anisotropic;
    bool disney = m->model == RTPBR_MATERIAL_DISNEY;
    g.flags = (m->double_sided ? RTPBR_MATERIAL_FLAG_DOUBLE_SIDED : 0u) |
              (m->normal_texture ? RTPBR_MATERIAL_FLAG_NORMAL_MAPPED : 0u) |
              (disney ? RTPBR_MATERIAL_FLAG_DISNEY : 0u) |
              (!disney && m->clearcoat_factor > 0.0f ? RTPBR_MATERIAL_FLAG_CLEARCOAT : 0u) |
              (!disney && !(m->sheen_color_factor[0] <= 0.0f && m->sheen_color_factor[1] <= 0.0f && m->sheen_color_factor[2] <= 0.0f)
                   ? RTPBR_MATERIAL_FLAG_SHEEN : 0u) |
              (!disney && m->anisotropy_strength > 0.0f ? RTPBR_MATERIAL_FLAG_ANISOTROPY : 0u) |
              (m->alpha_mode == RTPBR_ALPHA_MASK ? RTPBR_MATERIAL_FLAG_ALPHA_MASK : 0u) |
              (m->alpha_mode == RTPBR_ALPHA_BLEND ? RTPBR_MATERIAL_FLAG_ALPHA_BLEND : 0u);
    g.alpha = fminf(fmaxf(m->alpha, 0.0f), 1.0f);
    g.alpha_cutoff = m->flags & RTPBR_MATERIAL_NO_ALPHA_CUTOFF ? 0.0f : m->alpha_cutoff == 0.0f ? 0.5f : m->alpha_cutoff;
    g.base_color_texture = m->base_color_texture;
    return g;
}

// KHR_texture_transform as the rows of its 2x3 matrix T R S (rtpbr.h states it; rtpbr_shared.h
// how the G-buffer pass reads it).
static void texture_transform_rows(const rtpbr_texture_transform *t, float rows[2][4])
{
    float sx = t->scale[0], sy = t->scale[1];
    if (sx == 0.0f && sy == 0.0f) sx = sy = 1.0f;
    float c = cosf(t->rotation), s = sinf(t->rotation);
    float r[2][4] = {{c * sx, s * sy, t->offset[0], (float)t->texcoord}, {-s * sx, c * sy, t->offset[1], 0.0f}};
    memcpy(rows, r, sizeof r);
}

static rtpbr_shader_texture_transforms convert_texture_transforms(const rtpbr_material_desc *m)
{
    rtpbr_shader_texture_transforms g;
#define SLOT_TRANSFORM(unused_a, unused_b, name, slot) texture_transform_rows(&m->name##_texture_transform, g.name);
    RTPBR_MATERIAL_TEXTURE_SLOTS(SLOT_TRANSFORM, 0, 0)
#undef SLOT_TRANSFORM
    return g;
}

// The material's texture index of each slot (rtpbr_shared.h's slot list), by binding.
static void material_texture_indices(const rtpbr_material_desc *m, uint32_t index[RTPBR_MATERIAL_TEXTURE_COUNT])
{
#define SLOT_INDEX(unused_a, unused_b, name, slot) index[slot] = m->name##_texture;
    RTPBR_MATERIAL_TEXTURE_SLOTS(SLOT_INDEX, 0, 0)
#undef SLOT_INDEX
}

// Which G-buffers of extension textures a material needs (RTPBR_EXTENSION_TEXTURES_*): a
// texture of a lobe the material has (metallic-roughness only: Disney reads no KHR field).
static uint8_t material_extension_textures(const rtpbr_material_desc *m)
{
    if (m->model == RTPBR_MATERIAL_DISNEY) return 0;
    bool sheen = !(m->sheen_color_factor[0] <= 0.0f && m->sheen_color_factor[1] <= 0.0f && m->sheen_color_factor[2] <= 0.0f);
    bool coat_sheen = (m->clearcoat_factor > 0.0f && (m->clearcoat_texture || m->clearcoat_roughness_texture)) ||
                      (sheen && (m->sheen_color_texture || m->sheen_roughness_texture));
    bool specular = !(m->flags & RTPBR_MATERIAL_NO_SPECULAR) && (m->specular_texture || m->specular_color_texture);
    return (uint8_t)((specular ? RTPBR_EXTENSION_TEXTURES_SPECULAR : 0u) |
                     (coat_sheen ? RTPBR_EXTENSION_TEXTURES_COAT_SHEEN : 0u));
}

uint32_t rtpbr_gpu_scene_extension_textures(const rtpbr_gpu_scene *scene)
{
    uint32_t bits = 0;
    for (uint32_t i = 0; i < scene->material_count; ++i) bits |= scene->material_extension_textures[i];
    return bits;
}

rtpbr_result rtpbr_material_validate(const rtpbr_context *ctx, const rtpbr_material_desc *m, uint32_t index)
{
    if (!rtpbr_finite(m->base_color, 3) || !rtpbr_finite(&m->metallic, 1) || !rtpbr_finite(&m->roughness, 1) ||
        !rtpbr_finite(m->emission, 3) || !rtpbr_finite(&m->ior, 1) || !rtpbr_finite(&m->specular_factor, 1) ||
        !rtpbr_finite(m->specular_color, 3) || !rtpbr_finite(&m->normal_scale, 1) ||
        !rtpbr_finite(&m->clearcoat_factor, 1) || !rtpbr_finite(&m->clearcoat_roughness_factor, 1) ||
        !rtpbr_finite(&m->anisotropy_strength, 1) || !rtpbr_finite(&m->anisotropy_rotation, 1) || !rtpbr_finite(m->sheen_color_factor, 3) || !rtpbr_finite(&m->sheen_roughness_factor, 1) ||
        !rtpbr_finite((const float *)&m->disney, sizeof m->disney / sizeof(float)) || !rtpbr_finite(&m->alpha, 1) ||
        !rtpbr_finite(&m->alpha_cutoff, 1)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u has a NaN or infinite parameter", index);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
#define SLOT_TRANSFORM(unused_a, unused_b, name, slot) &m->name##_texture_transform,
    const rtpbr_texture_transform *transforms[] = {RTPBR_MATERIAL_TEXTURE_SLOTS(SLOT_TRANSFORM, 0, 0)};
#undef SLOT_TRANSFORM
    for (size_t i = 0; i < sizeof transforms / sizeof transforms[0]; ++i) {
        const rtpbr_texture_transform *t = transforms[i];
        if (!rtpbr_finite(t->offset, 2) || !rtpbr_finite(&t->rotation, 1) || !rtpbr_finite(t->scale, 2) ||
            t->texcoord > 1) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                      "material %u has a texture transform with a NaN or infinite value or a texcoord other than 0, 1",
                      index);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    }
    if ((unsigned)m->alpha_mode > RTPBR_ALPHA_BLEND) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u has an unknown alpha mode %d", index, (int)m->alpha_mode);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if ((unsigned)m->model > RTPBR_MATERIAL_DISNEY) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u has an unknown model %d", index, (int)m->model);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (m->ior < 0.0f || (m->ior > 0.0f && m->ior < 1.0f)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "material %u has ior %g; it must be >= 1 (or 0 for the default 1.5; KHR's ior 0, Fresnel 1: "
                  "flag RTPBR_MATERIAL_FRESNEL_ONE)", index, m->ior);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // Absence is a flag, never a negative value (what was -1 before issue 29).
    const struct {
        float value;
        const char *name, *flag;
    } non_negative[] = {
        {m->specular_factor, "specular_factor", "RTPBR_MATERIAL_NO_SPECULAR"},
        {m->alpha_cutoff, "alpha_cutoff", "RTPBR_MATERIAL_NO_ALPHA_CUTOFF"},
        {m->disney.specular, "disney.specular", "RTPBR_MATERIAL_DISNEY_NO_SPECULAR"},
    };
    for (size_t i = 0; i < sizeof non_negative / sizeof non_negative[0]; ++i)
        if (non_negative[i].value < 0.0f) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u has %s %g; it must be >= 0 (0: the default; none: flag %s)",
                      index, non_negative[i].name, non_negative[i].value, non_negative[i].flag);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    if (m->flags & ~(uint32_t)(RTPBR_MATERIAL_FRESNEL_ONE | RTPBR_MATERIAL_NO_SPECULAR | RTPBR_MATERIAL_NO_ALPHA_CUTOFF |
                               RTPBR_MATERIAL_DISNEY_NO_SPECULAR)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u has unknown flags 0x%x", index, m->flags);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    return RTPBR_SUCCESS;
}

// Area-weighted vertex normals of an indexed triangle list.
static void smooth_normals(const float *positions, const uint32_t *indices, uint32_t index_count,
                           uint32_t vertex_count, float *out_normals /* 3 per vertex, stride RTPBR_VERTEX_FLOATS */)
{
    for (uint32_t i = 0; i < vertex_count; ++i) out_normals[RTPBR_VERTEX_FLOATS * i] = out_normals[RTPBR_VERTEX_FLOATS * i + 1] = out_normals[RTPBR_VERTEX_FLOATS * i + 2] = 0.0f;
    for (uint32_t t = 0; t + 2 < index_count; t += 3) {
        uint32_t a = indices ? indices[t] : t, b = indices ? indices[t + 1] : t + 1, c = indices ? indices[t + 2] : t + 2;
        const float *pa = positions + 3 * a, *pb = positions + 3 * b, *pc = positions + 3 * c;
        float e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        float e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        uint32_t corners[3] = {a, b, c};
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) out_normals[RTPBR_VERTEX_FLOATS * corners[k] + j] += n[j];
    }
}

static void normal_matrix(const float m[16], float out[3][4])
{
    float inv[16];
    memset(out, 0, 3 * sizeof out[0]);
    if (!rtpbr_mat4_invert(inv, m)) return;
    // Columns of the transpose of the inverse's upper 3x3.
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) out[c][r] = inv[r * 4 + c];
}

static uint32_t sampler_key(const rtpbr_texture_desc *t)
{
    return ((((uint32_t)t->wrap_s * 3u + (uint32_t)t->wrap_t) * 2u + (uint32_t)t->mag_filter) * 2u +
            (uint32_t)t->min_filter) * 3u + (uint32_t)t->mipmap;
}

// The sampler of a key (sampler_key), created on first use.
static rtpbr_result scene_sampler(rtpbr_gpu_scene *scene, uint32_t key)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    if (scene->samplers[key]) return RTPBR_SUCCESS;
    static const VkSamplerAddressMode wraps[] = {VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                                 VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT};
    uint32_t mipmap = key % 3u, min = key / 3u % 2u, mag = key / 6u % 2u, wrap_t = key / 12u % 3u, wrap_s = key / 36u;
    bool linear = min == RTPBR_FILTER_LINEAR && mag == RTPBR_FILTER_LINEAR;
    VkSamplerCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = mag == RTPBR_FILTER_NEAREST ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
        .minFilter = min == RTPBR_FILTER_NEAREST ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
        .mipmapMode = mipmap == RTPBR_MIPMAP_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = wraps[wrap_s],
        .addressModeV = wraps[wrap_t],
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT,
        // Anisotropic only where the filtering is linear and mipmapped, and the device allows it.
        .anisotropyEnable = linear && mipmap != RTPBR_MIPMAP_NONE && ctx->max_anisotropy > 1.0f,
        .maxAnisotropy = linear && mipmap != RTPBR_MIPMAP_NONE && ctx->max_anisotropy > 1.0f ? ctx->max_anisotropy : 1.0f,
        .minLod = 0.0f,
        .maxLod = mipmap == RTPBR_MIPMAP_NONE ? 0.0f : VK_LOD_CLAMP_NONE,
    };
    RTPBR_VK(&ctx->host, vkCreateSampler(ctx->device, &info, NULL, &scene->samplers[key]));
cleanup:
    return result;
}

// The textures' alpha channels for the shadow rays (rtpbr_shared.h, RTPBR_ALPHA_TEXTURE_FIELDS):
// bytes only for the textures with an alpha below 255 somewhere. Which texture a material uses
// may change (rtpbr_gpu_scene_set_material), so every such texture is kept, not only the
// base colour textures of MASK and BLEND materials.
static rtpbr_result create_alpha_textures(rtpbr_gpu_scene *scene, const rtpbr_gpu_scene_desc *desc)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, (desc->texture_count + 1) * sizeof(rtpbr_shader_alpha_texture),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &scene->alpha_textures));
    rtpbr_shader_alpha_texture *records = scene->alpha_textures.mapped;
    records[0] = (rtpbr_shader_alpha_texture){.first = RTPBR_ALPHA_TEXTURE_OPAQUE, .width = 1, .height = 1};
    uint64_t words = 0;
    for (uint32_t i = 0; i < desc->texture_count; ++i) {
        const rtpbr_texture_desc *t = &desc->textures[i];
        size_t texels = (size_t)t->width * t->height;
        bool opaque = true;
        for (size_t k = 0; k < texels && opaque; ++k) opaque = t->rgba[4 * k + 3] == 255;
        records[i + 1] = (rtpbr_shader_alpha_texture){
            .first = opaque ? RTPBR_ALPHA_TEXTURE_OPAQUE : (uint32_t)words,
            .width = t->width,
            .height = t->height,
            .wrap = (uint32_t)t->wrap_s | (uint32_t)t->wrap_t << 2,
        };
        if (!opaque) words += (texels + 3) / 4;
    }
    if (words >= RTPBR_ALPHA_TEXTURE_OPAQUE) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "textures with alpha: %llu texels in all, too many for the shadow rays",
                  (unsigned long long)words * 4);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, (words ? words : 1) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       &scene->alpha_texels));
    uint32_t *texels = scene->alpha_texels.mapped;
    memset(texels, 0, (words ? words : 1) * sizeof(uint32_t));
    for (uint32_t i = 0; i < desc->texture_count; ++i) {
        const rtpbr_shader_alpha_texture *r = &records[i + 1];
        if (r->first == RTPBR_ALPHA_TEXTURE_OPAQUE) continue;
        const uint8_t *rgba = desc->textures[i].rgba;
        for (size_t k = 0; k < (size_t)r->width * r->height; ++k)
            texels[r->first + k / 4] |= (uint32_t)rgba[4 * k + 3] << (8 * (k % 4));
    }
cleanup:
    return result; // rtpbr_gpu_scene_destroy frees a half-built state
}

// Uploads the textures (image 0 is a 1x1 white stand-in for "no texture", image i texture i)
// with their mip chains and samplers, and writes one descriptor set per material slot.
static rtpbr_result create_textures(rtpbr_gpu_scene *scene, const rtpbr_gpu_scene_desc *desc, uint32_t material_slots)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_ALLOC(&ctx->host, scene->textures, (desc->texture_count + 1) * sizeof *scene->textures);
    RTPBR_ALLOC(&ctx->host, scene->texture_samplers, (desc->texture_count + 1) * sizeof *scene->texture_samplers);
    static const uint8_t white[4] = {255, 255, 255, 255};
    static const rtpbr_texture_desc white_desc = {.width = 1, .height = 1, .rgba = white, .mipmap = RTPBR_MIPMAP_NONE};
    RTPBR_TRY(rtpbr_texture_create(ctx, 1, 1, VK_FORMAT_R8G8B8A8_UNORM, white, 4, false, &scene->textures[0]));
    scene->texture_samplers[0] = sampler_key(&white_desc);
    RTPBR_TRY(scene_sampler(scene, scene->texture_samplers[0]));
    scene->texture_count = 1;
    for (uint32_t i = 0; i < desc->texture_count; ++i) {
        const rtpbr_texture_desc *t = &desc->textures[i];
        RTPBR_TRY(rtpbr_texture_create(ctx, t->width, t->height,
                                       t->srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM, t->rgba,
                                       (size_t)t->width * t->height * 4, t->mipmap != RTPBR_MIPMAP_NONE,
                                       &scene->textures[i + 1]));
        scene->texture_samplers[i + 1] = sampler_key(t);
        scene->texture_count++;
        RTPBR_TRY(scene_sampler(scene, scene->texture_samplers[i + 1]));
    }
    RTPBR_TRY(rtpbr_gbuffer_material_sets_create(scene, material_slots));
    for (uint32_t m = 0; m < material_slots; ++m) {
        uint32_t index[RTPBR_MATERIAL_TEXTURE_COUNT] = {0};
        if (desc->material_count) material_texture_indices(&desc->materials[m], index);
        rtpbr_gbuffer_write_material_textures(scene, m, index);
    }
cleanup:
    return result; // rtpbr_gpu_scene_destroy frees a half-built set
}

// ---------------------------------------------------------------------------------------------

rtpbr_result rtpbr_gpu_scene_create(rtpbr_context *ctx, const rtpbr_gpu_scene_desc *desc, rtpbr_gpu_scene **out_scene)
{
    return rtpbr_gpu_scene_create_with_light_facts(ctx, desc, NULL, out_scene);
}

rtpbr_result rtpbr_gpu_scene_create_with_light_facts(rtpbr_context *ctx, const rtpbr_gpu_scene_desc *desc,
                                                     const rtpbr_gltf_polygon_facts *light_facts,
                                                     rtpbr_gpu_scene **out_scene)
{
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!desc || !out_scene) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_create: desc or out_scene is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out_scene = NULL;
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_gltf_polygon_facts *derived_facts = NULL;
    const rtpbr_gltf_polygon_facts *facts = light_facts;
    if ((desc->mesh_count && !desc->meshes) || (desc->material_count && !desc->materials) ||
        (desc->camera_count && !desc->cameras)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_create: a non-zero count with a NULL array");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (desc->material_count > RTPBR_MAX_MATERIALS) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "%u materials; at most %u are allowed", desc->material_count, RTPBR_MAX_MATERIALS);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    RTPBR_TRY(validate_light_array(ctx, desc->lights, desc->light_count));
    if (!facts && !(facts = derived_facts = derive_light_facts(ctx, desc->lights, desc->light_count, &result)))
        goto cleanup;
    RTPBR_TRY(validate_lights(ctx, desc->lights, facts, desc->light_count));
    uint64_t total_vertices = 0, total_indices = 0;
    for (uint32_t i = 0; i < desc->mesh_count; ++i) {
        const rtpbr_mesh_desc *m = &desc->meshes[i];
        RTPBR_TRY(validate_mesh(ctx, m, i, desc->material_count));
        total_vertices += m->vertex_count;
        total_indices += m->indices ? m->index_count : m->vertex_count;
    }
    if (total_vertices > UINT32_MAX / 2 || total_indices > UINT32_MAX / 2) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "scene too large (%llu vertices)", (unsigned long long)total_vertices);
        result = RTPBR_ERROR_LIMIT_EXCEEDED;
        goto cleanup; // frees the derived facts
    }
    for (uint32_t i = 0; i < desc->material_count; ++i) {
        const rtpbr_material_desc *m = &desc->materials[i];
        RTPBR_TRY(rtpbr_material_validate(ctx, m, i));
        uint32_t index_of[RTPBR_MATERIAL_TEXTURE_COUNT];
        material_texture_indices(m, index_of);
        for (uint32_t b = 0; b < RTPBR_MATERIAL_TEXTURE_COUNT; ++b)
            if (index_of[b] > desc->texture_count) {
                rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u refers to a texture past the scene's %u", i,
                          desc->texture_count);
                result = RTPBR_ERROR_INVALID_ARGUMENT;
        goto cleanup; // frees the derived facts
            }
    }
    if (desc->texture_count && !desc->textures) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "texture_count is %u but textures is NULL", desc->texture_count);
        result = RTPBR_ERROR_INVALID_ARGUMENT;
        goto cleanup; // frees the derived facts
    }
    for (uint32_t i = 0; i < desc->texture_count; ++i) {
        const rtpbr_texture_desc *t = &desc->textures[i];
        if (!t->rgba || t->width == 0 || t->height == 0 || t->width > RTPBR_MAX_RENDER_SIZE ||
            t->height > RTPBR_MAX_RENDER_SIZE) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "texture %u: no texels or size %ux%u outside 1..%u", i, t->width, t->height,
                      RTPBR_MAX_RENDER_SIZE);
            result = RTPBR_ERROR_INVALID_ARGUMENT;
        goto cleanup; // frees the derived facts
        }
        if ((unsigned)t->wrap_s > RTPBR_WRAP_MIRRORED_REPEAT || (unsigned)t->wrap_t > RTPBR_WRAP_MIRRORED_REPEAT ||
            (unsigned)t->mag_filter > RTPBR_FILTER_NEAREST || (unsigned)t->min_filter > RTPBR_FILTER_NEAREST ||
            (unsigned)t->mipmap > RTPBR_MIPMAP_NONE) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "texture %u: unknown wrap, filter or mipmap mode", i);
            result = RTPBR_ERROR_INVALID_ARGUMENT;
        goto cleanup; // frees the derived facts
        }
    }
    RTPBR_TRY(validate_light_textures(ctx, desc->lights, desc->light_count, desc->texture_count, NULL));
    for (uint32_t i = 0; i < desc->camera_count; ++i)
        if (!rtpbr_finite((const float *)&desc->cameras[i], sizeof desc->cameras[i] / sizeof(float))) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "camera %u has a NaN or infinite parameter", i);
            result = RTPBR_ERROR_INVALID_ARGUMENT;
        goto cleanup; // frees the derived facts
        }

    RTPBR_ALLOC(&ctx->host, scene, sizeof *scene);
    scene->context = ctx;
    RTPBR_LIST_LINK(ctx->scenes, scene);

    // Geometry: one interleaved vertex buffer and one index buffer for all meshes.
    VkDeviceSize vertex_bytes = (total_vertices ? total_vertices : 1) * RTPBR_VERTEX_FLOATS * sizeof(float);
    VkDeviceSize index_bytes = (total_indices ? total_indices : 3) * sizeof(uint32_t);
    // Also a storage buffer: the shadow rays read texture coordinates for alpha (bvh.glsl).
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       &scene->vertices));
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &scene->indices));
    if (desc->mesh_count) {
        RTPBR_ALLOC(&ctx->host, scene->draws, desc->mesh_count * sizeof *scene->draws);
        RTPBR_ALLOC(&ctx->host, scene->blend_order, desc->mesh_count * sizeof *scene->blend_order);
    }
    float *vertices = scene->vertices.mapped;
    uint32_t *indices = scene->indices.mapped;
    uint32_t vertex_base = 0, index_base = 0;
    for (uint32_t i = 0; i < desc->mesh_count; ++i) {
        const rtpbr_mesh_desc *m = &desc->meshes[i];
        float *dst = vertices + RTPBR_VERTEX_FLOATS * (size_t)vertex_base;
        uint32_t count = m->indices ? m->index_count : m->vertex_count;
        if (m->normals) {
            for (uint32_t v = 0; v < m->vertex_count; ++v) memcpy(dst + RTPBR_VERTEX_FLOATS * v + 3, m->normals + 3 * v, 3 * sizeof(float));
        } else {
            smooth_normals(m->positions, m->indices, count, m->vertex_count, dst + 3);
        }
        // An attribute the mesh does not have is written as zeros, which the shaders read as
        // "none" (fragment_material.glsl: a zero tangent, no anisotropy direction and no normal
        // map frame). Host-visible memory is not zeroed by Vulkan: left unwritten, on lavapipe a
        // scene created after another one's destruction read that scene's bytes there
        // (test_engine_materials' material_specialization, anisotropy: up to 0.98 apart, run to run).
        static const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (uint32_t v = 0; v < m->vertex_count; ++v) {
            float *out = dst + RTPBR_VERTEX_FLOATS * v;
            memcpy(out, m->positions + 3 * v, 3 * sizeof(float));
            memcpy(out + RTPBR_VERTEX_UV_OFFSET, m->texcoords ? m->texcoords + 2 * v : zeros, 2 * sizeof(float));
            memcpy(out + 8, m->tangents ? m->tangents + 4 * v : zeros, 4 * sizeof(float));
            memcpy(out + RTPBR_VERTEX_UV1_OFFSET, m->texcoords1 ? m->texcoords1 + 2 * v : zeros, 2 * sizeof(float));
        }
        for (uint32_t k = 0; k < count; ++k) indices[index_base + k] = vertex_base + (m->indices ? m->indices[k] : k);

        rtpbr_draw *draw = &scene->draws[scene->draw_count++];
        draw->first_index = index_base;
        draw->index_count = count;
        if (is_zero(m->transform, 16)) rtpbr_mat4_identity(draw->push.world_from_object);
        else memcpy(draw->push.world_from_object, m->transform, sizeof m->transform);
        normal_matrix(draw->push.world_from_object, draw->push.normal_matrix);
        draw->push.material = m->material;
        float lo[3], hi[3];
        for (int k = 0; k < 3; ++k) lo[k] = hi[k] = m->positions[k];
        for (uint32_t v = 1; v < m->vertex_count; ++v)
            for (int k = 0; k < 3; ++k) {
                lo[k] = fminf(lo[k], m->positions[3 * v + k]);
                hi[k] = fmaxf(hi[k], m->positions[3 * v + k]);
            }
        for (int k = 0; k < 3; ++k) draw->center[k] = 0.5f * (lo[k] + hi[k]);
        vertex_base += m->vertex_count;
        index_base += count;
    }

    uint32_t material_slots = desc->material_count ? desc->material_count : 1;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, material_slots * sizeof(rtpbr_shader_material),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &scene->materials));
    rtpbr_shader_material *materials = scene->materials.mapped;
    if (desc->material_count == 0) {
        rtpbr_material_desc grey = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 0.5f};
        materials[0] = rtpbr_material_record(&grey);
    }
    for (uint32_t i = 0; i < desc->material_count; ++i) materials[i] = rtpbr_material_record(&desc->materials[i]);
    scene->material_count = desc->material_count;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, material_slots * sizeof(rtpbr_shader_texture_transforms),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &scene->texture_transforms));
    rtpbr_shader_texture_transforms *transforms = scene->texture_transforms.mapped;
    if (desc->material_count == 0) transforms[0] = convert_texture_transforms(&(rtpbr_material_desc){0});
    for (uint32_t i = 0; i < desc->material_count; ++i) transforms[i] = convert_texture_transforms(&desc->materials[i]);
    RTPBR_ALLOC(&ctx->host, scene->material_extension_textures, material_slots);
    RTPBR_ALLOC(&ctx->host, scene->material_gbuffer_slots, material_slots); // (no desc material: none)
    for (uint32_t i = 0; i < desc->material_count; ++i) {
        scene->material_extension_textures[i] = material_extension_textures(&desc->materials[i]);
        scene->material_gbuffer_slots[i] = rtpbr_gbuffer_material_slots(&desc->materials[i]);
    }

    RTPBR_TRY(rtpbr_bvh_create(scene)); // the shadow rays' (passes/shadow.c); reads the materials' sidedness and alpha modes
    RTPBR_TRY(rtpbr_accel_create(scene)); // the same triangles for ray queries (with ctx->ray_query)
    RTPBR_TRY(create_textures(scene, desc, material_slots));
    RTPBR_TRY(create_alpha_textures(scene, desc));

    RTPBR_TRY(create_light_textures(scene, desc));
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, RTPBR_MAX_LIGHTS * sizeof(rtpbr_shader_light),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                       &scene->lights));
    write_lights(scene, desc->lights, facts, desc->light_count);

    scene->camera_count = desc->camera_count ? desc->camera_count : 1;
    RTPBR_ALLOC(&ctx->host, scene->cameras, scene->camera_count * sizeof *scene->cameras);
    if (desc->camera_count) memcpy(scene->cameras, desc->cameras, desc->camera_count * sizeof *scene->cameras);
    else scene->cameras[0] = (rtpbr_camera_desc){.position = {0.0f, 0.0f, 5.0f}};

    *out_scene = scene;
    scene = NULL;
cleanup:
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_free(&ctx->host, derived_facts);
    return result;
}

void rtpbr_gpu_scene_destroy(rtpbr_gpu_scene *scene)
{
    if (!scene) return;
    rtpbr_context *ctx = scene->context;
    rtpbr_buffer_destroy(ctx, &scene->vertices);
    rtpbr_buffer_destroy(ctx, &scene->indices);
    rtpbr_buffer_destroy(ctx, &scene->materials);
    rtpbr_buffer_destroy(ctx, &scene->texture_transforms);
    rtpbr_buffer_destroy(ctx, &scene->lights);
    rtpbr_accel_destroy(scene);
    rtpbr_bvh_destroy(scene);
    rtpbr_buffer_destroy(ctx, &scene->alpha_textures);
    rtpbr_buffer_destroy(ctx, &scene->alpha_texels);
    rtpbr_image_destroy(ctx, &scene->light_textures);
    rtpbr_free(&ctx->host, scene->light_texture_keys);
    rtpbr_gbuffer_material_sets_destroy(scene);
    for (uint32_t i = 0; i < scene->texture_count; ++i) rtpbr_image_destroy(ctx, &scene->textures[i]);
    for (uint32_t i = 0; i < RTPBR_SAMPLER_KEY_COUNT; ++i)
        if (scene->samplers[i]) vkDestroySampler(ctx->device, scene->samplers[i], NULL);
    rtpbr_free(&ctx->host, scene->textures);
    rtpbr_free(&ctx->host, scene->texture_samplers);
    rtpbr_free(&ctx->host, scene->material_extension_textures);
    rtpbr_free(&ctx->host, scene->material_gbuffer_slots);
    rtpbr_free(&ctx->host, scene->draws);
    rtpbr_free(&ctx->host, scene->blend_order);
    rtpbr_free(&ctx->host, scene->cameras);
    RTPBR_LIST_UNLINK(ctx->scenes, scene);
    rtpbr_free(&ctx->host, scene);
}

// The checks of a setter of one element of a scene (`function`): its argument `arg` (named
// arg_name) is not NULL, and `index` is below the scene's `count` of `what`.
static rtpbr_result check_set(const rtpbr_gpu_scene *scene, const char *function, const void *arg,
                              const char *arg_name, const char *what, uint32_t index, uint32_t count)
{
    if (!arg) {
        rtpbr_log(&scene->context->host, RTPBR_LOG_ERROR, "%s: %s is NULL", function, arg_name);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (index >= count) {
        rtpbr_log(&scene->context->host, RTPBR_LOG_ERROR, "%s: %s %u, the scene has %u", function, what, index, count);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    return RTPBR_SUCCESS;
}

rtpbr_result rtpbr_gpu_scene_set_material(rtpbr_gpu_scene *scene, uint32_t index, const rtpbr_material_desc *material)
{
    if (!scene) return rtpbr_null_object(__func__, "scene");
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = check_set(scene, __func__, material, "material", "material", index, scene->material_count);
    if (result == RTPBR_SUCCESS) result = rtpbr_material_validate(ctx, material, index);
    if (result != RTPBR_SUCCESS) return result;
    uint32_t textures = scene->texture_count - 1; // the host's; image 0 is the white stand-in
    uint32_t index_of[RTPBR_MATERIAL_TEXTURE_COUNT] = {0};
    material_texture_indices(material, index_of);
    for (uint32_t b = 0; b < RTPBR_MATERIAL_TEXTURE_COUNT; ++b)
        if (index_of[b] > textures) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "material %u refers to a texture past the scene's %u", index, textures);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
    rtpbr_shader_material *record = &((rtpbr_shader_material *)scene->materials.mapped)[index];
    // The BVH's triangles keep their material's sidedness and whether its alpha is tested.
    const uint32_t triangle_flags =
        RTPBR_MATERIAL_FLAG_DOUBLE_SIDED | RTPBR_MATERIAL_FLAG_ALPHA_MASK | RTPBR_MATERIAL_FLAG_ALPHA_BLEND;
    uint32_t old_flags = record->flags;
    *record = rtpbr_material_record(material);
    bool triangle_flags_changed = ((old_flags ^ record->flags) & triangle_flags) != 0;
    ((rtpbr_shader_texture_transforms *)scene->texture_transforms.mapped)[index] = convert_texture_transforms(material);
    scene->material_extension_textures[index] = material_extension_textures(material);
    scene->material_gbuffer_slots[index] = rtpbr_gbuffer_material_slots(material);
    rtpbr_gbuffer_write_material_textures(scene, index, index_of);
    if (triangle_flags_changed) rtpbr_bvh_update_material_flags(scene);
    // The acceleration structures' classes follow the flags (accel.c): built again, and also
    // where an earlier rebuild failed (rtpbr_render refuses shadows without them).
    if (ctx->ray_query && (triangle_flags_changed || !scene->accel_tlas)) {
        rtpbr_accel_destroy(scene);
        rtpbr_result built = rtpbr_accel_create(scene);
        if (built != RTPBR_SUCCESS) {
            rtpbr_accel_destroy(scene);
            return built;
        }
    }
    return RTPBR_SUCCESS;
}

rtpbr_result rtpbr_gpu_scene_set_transform(rtpbr_gpu_scene *scene, uint32_t mesh, const float transform[16])
{
    if (!scene) return rtpbr_null_object(__func__, "scene");
    rtpbr_result result = check_set(scene, __func__, transform, "transform", "mesh", mesh, scene->draw_count);
    if (result != RTPBR_SUCCESS) return result;
    if (!rtpbr_finite(transform, 16)) {
        rtpbr_log(&scene->context->host, RTPBR_LOG_ERROR, "rtpbr_gpu_scene_set_transform: mesh %u: NaN or infinite transform", mesh);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    rtpbr_draw *draw = &scene->draws[mesh];
    if (is_zero(transform, 16)) rtpbr_mat4_identity(draw->push.world_from_object);
    else memcpy(draw->push.world_from_object, transform, sizeof draw->push.world_from_object);
    normal_matrix(draw->push.world_from_object, draw->push.normal_matrix);
    // The shadow rays' occluders move with it: the BVH refitted, the acceleration structures
    // built again (accel.c).
    rtpbr_bvh_refit(scene);
    if (scene->context->ray_query) {
        rtpbr_accel_destroy(scene);
        rtpbr_result built = rtpbr_accel_create(scene);
        if (built != RTPBR_SUCCESS) {
            rtpbr_accel_destroy(scene);
            return built;
        }
    }
    return RTPBR_SUCCESS;
}

uint32_t rtpbr_lights_shapes(const rtpbr_shader_light *lights, uint32_t count)
{
    uint32_t shapes = 0;
    for (uint32_t i = 0; i < count; ++i) {
        if (lights[i].shape == RTPBR_LIGHT_SHAPE_TUBE) shapes = 3;
        else if (lights[i].texture != 0 && shapes < 2) shapes = 2;
        else if ((lights[i].shape == RTPBR_LIGHT_SHAPE_SPHERE || lights[i].shape == RTPBR_LIGHT_SHAPE_DISK) && shapes < 1) shapes = 1;
    }
    return shapes;
}

rtpbr_lighting_needs rtpbr_lighting_needs_of(const rtpbr_shader_light *lights, uint32_t count,
                                             const rtpbr_shader_material *materials, uint32_t material_count)
{
    rtpbr_lighting_needs needs = {
        .shapes = rtpbr_lights_shapes(lights, count), .max_vertices = 3, .punctual = false, .light_count = count};
    for (uint32_t i = 0; i < material_count; ++i) {
        needs.material_features |= (materials[i].flags & RTPBR_MATERIAL_FLAG_DISNEY) != 0u
                                       ? RTPBR_MATERIAL_FLAGS_FULL
                                       : materials[i].flags & RTPBR_MATERIAL_FLAGS_FULL;
        // (the G-buffer's emission is the material's times its texture: 0 where the material's is)
        for (int c = 0; c < 3; ++c) needs.emission = needs.emission || materials[i].emission[c] != 0.0f;
    }
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t shape = lights[i].shape;
        if (shape == RTPBR_LIGHT_SHAPE_POINT || shape == RTPBR_LIGHT_SHAPE_SPOT || shape == RTPBR_LIGHT_SHAPE_DIRECTIONAL)
            needs.punctual = true;
        else if (shape == RTPBR_LIGHT_SHAPE_POLYGON && lights[i].vertex_count > needs.max_vertices)
            needs.max_vertices = lights[i].vertex_count > 4 ? RTPBR_SHADER_MAX_POLYGON_VERTICES : 4;
    }
    return needs;
}

bool rtpbr_lights_have_spheres(const rtpbr_shader_light *lights, uint32_t count)
{
    for (uint32_t i = 0; i < count; ++i)
        if (lights[i].shape == RTPBR_LIGHT_SHAPE_SPHERE || lights[i].shape == RTPBR_LIGHT_SHAPE_DISK ||
            lights[i].shape == RTPBR_LIGHT_SHAPE_TUBE || lights[i].texture != 0)
            return true;
    return false;
}

bool rtpbr_scene_has_alpha_test(const rtpbr_gpu_scene *scene)
{
    const rtpbr_shader_material *materials = scene->materials.mapped;
    for (uint32_t i = 0; i < scene->material_count; ++i)
        if (materials[i].flags & (RTPBR_MATERIAL_FLAG_ALPHA_MASK | RTPBR_MATERIAL_FLAG_ALPHA_BLEND)) return true;
    return false;
}

bool rtpbr_scene_has_blend(const rtpbr_gpu_scene *scene)
{
    const rtpbr_shader_material *materials = scene->materials.mapped;
    for (uint32_t i = 0; i < scene->material_count; ++i)
        if (materials[i].flags & RTPBR_MATERIAL_FLAG_ALPHA_BLEND) return true;
    return false;
}

uint32_t rtpbr_gpu_scene_camera_count(const rtpbr_gpu_scene *scene)
{
    return scene ? scene->camera_count : 0;
}

uint32_t rtpbr_gpu_scene_light_count(const rtpbr_gpu_scene *scene)
{
    return scene ? scene->light_count : 0;
}
