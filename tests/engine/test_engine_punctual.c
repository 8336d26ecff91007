#define _DEFAULT_SOURCE // M_PI
// Engine: punctual lights (KHR_lights_punctual's point, spot and directional lights; issue 30)
// against their closed forms, computed here in double precision from the extension's text,
// independently of the shader library:
//   Lo = f (N.L) I W(d) S / d^2 (point, spot),  Lo = f (N.L) E (directional),
//   W(d) = clamp(1 - (d / range)^4, 0, 1),  S = t^2, t = clamp((cd - cos outer) / (cos inner -
//   cos outer), 0, 1).
// A Lambertian plane (f = 0.8 / pi) under all four kinds, in the LTC pass and the Monte Carlo
// pass (exact for punctual lights: no sample), a GGX metal plane (single scattering: D G / (4
// N.L N.V), Smith's height-correlated G, F = 1), and shadows of an occluder, every pixel
// checked. Point lights with a radius (spheres) against the cap they subtend: closed forms and
// double-precision quadratures, the Monte Carlo pass, shadows (sphere_light, sphere_ggx,
// sphere_shadow). Disk lights against the disk's quadrature and the octagon it replaces
// (disk_lambert, disk_ggx).
#include <stdlib.h>

#include "engine_test.h"

enum { W = 120, H = 90 };

static const rtpbr_camera_desc camera = {.position = {0.3f, -0.2f, 3.0f}, .target = {0.2f, 0.0f, 0.0f}, .yfov = 1.2f,
                                         .znear = 0.1f, .zfar = 100.0f};

// The four lights: a point light, a spot light (tilted, cones 0.25 and 0.5 radians), a
// directional light and a point light with a range that ends above the plane's middle.
static const rtpbr_light_desc punctual_lights[4] = {
    {.type = RTPBR_LIGHT_POINT, .position = {-1.0f, 0.5f, 1.5f}, .emission = {2.0f, 1.0f, 0.5f}},
    {.type = RTPBR_LIGHT_SPOT, .position = {1.5f, -1.0f, 2.0f}, .direction = {-0.3f, 0.2f, -1.0f},
     .inner_cone_angle = 0.25f, .outer_cone_angle = 0.5f, .emission = {6.0f, 6.0f, 6.0f}},
    {.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0.3f, 0.2f, -1.0f}, .emission = {0.3f, 0.4f, 0.5f},
     .angular_diameter = -1.0f}, // a true direction: the closed forms are a delta light's (sun_disk: the disk)
    {.type = RTPBR_LIGHT_POINT, .position = {0.5f, 1.5f, 0.6f}, .range = 1.5f, .emission = {0.5f, 0.5f, 2.0f}},
};

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Light l at the plane's point p (normal +Z): the unit direction to it in L and the factor its
// emission is multiplied by (W S / d^2, or 1), from the extension's text; 0 when it is off.
static double incident(const rtpbr_light_desc *l, const double p[3], double L[3])
{
    double dir[3] = {l->direction[0], l->direction[1], l->direction[2]};
    double dl = sqrt(dot3(dir, dir));
    if (l->type == RTPBR_LIGHT_DIRECTIONAL) {
        for (int k = 0; k < 3; ++k) L[k] = -dir[k] / dl;
        return 1.0;
    }
    double d[3] = {l->position[0] - p[0], l->position[1] - p[1], l->position[2] - p[2]};
    double d2 = dot3(d, d), dist = sqrt(d2);
    for (int k = 0; k < 3; ++k) L[k] = d[k] / dist;
    double factor = 1.0 / d2;
    if (l->range > 0.0f) {
        double q = dist / l->range;
        factor *= fmin(fmax(1.0 - q * q * q * q, 0.0), 1.0);
    }
    if (l->type == RTPBR_LIGHT_SPOT) {
        double cd = -dot3(dir, L) / dl, co = cos(l->outer_cone_angle), ci = cos(l->inner_cone_angle);
        double t = fmin(fmax((cd - co) / (ci - co), 0.0), 1.0);
        factor *= t * t;
    }
    return factor;
}

// The anisotropic lobe of ggx_single: alpha_t along (cos, sin) of this angle in the plane's
// xy (the tangent +X turned toward the bitangent +Y), alpha_b across it; 0: isotropic.
static double aniso_alpha_t, aniso_angle;

// Smith's Lambda of direction w (anisotropic GGX: Heitz 2014, "Understanding the
// Masking-Shadowing Function", Eq. 86).
static double ggx_lambda(const double w[3], double at, double ab, double c, double s)
{
    double wt = c * w[0] + s * w[1], wb = -s * w[0] + c * w[1];
    return (-1.0 + sqrt(1.0 + (at * at * wt * wt + ab * ab * wb * wb) / (w[2] * w[2]))) / 2.0;
}

// Smith's height-correlated GGX masking-shadowing, D and the specular BRDF (F = 1) at alpha
// (alpha_b; alpha_t = aniso_alpha_t when set).
static double ggx_single(const double wo[3], const double wi[3], double alpha)
{
    double at = aniso_alpha_t > 0.0 ? aniso_alpha_t : alpha, ab = alpha;
    double c = cos(aniso_angle), sn = sin(aniso_angle);
    double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    double hl = sqrt(dot3(h, h));
    for (int k = 0; k < 3; ++k) h[k] /= hl;
    double ht = c * h[0] + sn * h[1], hb = -sn * h[0] + c * h[1];
    double q = (ht / at) * (ht / at) + (hb / ab) * (hb / ab) + h[2] * h[2];
    double D = 1.0 / (M_PI * at * ab * q * q);
    double lo = ggx_lambda(wo, at, ab, c, sn), li = ggx_lambda(wi, at, ab, c, sn);
    return D / (1.0 + lo + li) / (4.0 * wo[2] * wi[2]);
}

// The expected radiance at p, toward the camera, of the plane (Lambert 0.8, or the GGX metal
// of alpha > 0), from lights[0 .. n), light l weighted by visible[l] (1 without shadows).
static void expected(const rtpbr_light_desc *lights, int n, const double visible[], double alpha, const double p[3],
                     double out[3])
{
    double wo[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
    double ol = sqrt(dot3(wo, wo));
    for (int k = 0; k < 3; ++k) wo[k] /= ol;
    out[0] = out[1] = out[2] = 0.0;
    for (int l = 0; l < n; ++l) {
        double L[3];
        double factor = incident(&lights[l], p, L) * visible[l];
        if (!(L[2] > 0.0) || factor == 0.0) continue;
        double f = alpha > 0.0 ? ggx_single(wo, L, alpha) : 0.8 / M_PI;
        for (int c = 0; c < 3; ++c) out[c] += f * L[2] * lights[l].emission[c] * factor;
    }
}

// Every pixel of the plane (or those `filter` keeps, with its visibilities) against
// expected() for `lights` (n of them): the largest error relative to the pixel's value plus
// `floor` (an absolute allowance where the radiance is near 0), over every channel, or over
// the red one alone (red_only). *checked_out: the pixels compared.
typedef bool (*pixel_filter)(const double p[3], double visible[]);
static double largest_error(const float *px, const rtpbr_light_desc *lights, int n, double alpha, double floor,
                            pixel_filter filter, bool red_only, int *checked_out)
{
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3], visible[4] = {1.0, 1.0, 1.0, 1.0}, want[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            if (filter && !filter(p, visible)) continue;
            expected(lights, n, visible, alpha, p, want);
            for (int c = 0; c < (red_only ? 1 : 3); ++c)
                worst = fmax(worst, fabs(px[4 * (y * W + x) + c] - want[c]) / (want[c] + floor));
            ++checked;
        }
    if (checked_out) *checked_out = checked;
    return worst;
}

// largest_error over every channel must be at most `bound`, over more than min_pixels pixels.
static void compare(const float *px, double alpha, double bound, double floor, pixel_filter filter, int min_pixels,
                    const char *what)
{
    int checked = 0;
    double worst = largest_error(px, punctual_lights, 4, alpha, floor, filter, false, &checked);
    printf("%s: %d pixels, largest error %.3g (bound %.3g)\n", what, checked, worst, bound);
    assert_true(worst <= bound);
    assert_true(checked > min_pixels);
}

// The plane z = 0 of `material` under `lights` (4), seen by the camera; `mesh`: its mesh, with
// positions in `plane` (tangent +X where tangents are given).
static const float plane_normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static const float plane_tangents[16] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
static rtpbr_gpu_scene *plane_scene(rtpbr_context *ctx, const rtpbr_material_desc *material,
                                    const rtpbr_light_desc *lights, float plane[12], rtpbr_mesh_desc *mesh)
{
    square_positions(4.0f, 0.0f, plane);
    *mesh = (rtpbr_mesh_desc){.positions = plane, .normals = plane_normals, .tangents = plane_tangents,
                              .indices = square_indices, .vertex_count = 4, .index_count = 6};
    return test_mesh_scene(ctx, mesh, material, lights, 4, &camera);
}

// One render of the plane scene with `desc` (the caller frees the pixels).
static float *render_plane(rtpbr_context *ctx, const rtpbr_material_desc *material, const rtpbr_light_desc *lights,
                           const rtpbr_render_desc *desc)
{
    float plane[12];
    rtpbr_mesh_desc mesh;
    rtpbr_gpu_scene *scene = plane_scene(ctx, material, lights, plane, &mesh);
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *px = test_render_radiance(r, scene, desc, W, H);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    return px;
}

// A Lambertian plane under the four lights: the LTC pass (basic and full variants:
// multiscatter on and off) and the Monte Carlo pass. Float rounding only (the G-buffer's depth
// and the float light record): 1e-3 relative, 1e-5 absolute where a light's window or cone ends.
static void lambert_plane(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const struct {
        rtpbr_render_desc desc;
        const char *what;
    } passes[] = {
        {{.multiscatter = RTPBR_MULTISCATTER_ON}, "lambert, LTC pass"},
        {{.multiscatter = RTPBR_MULTISCATTER_OFF}, "lambert, LTC pass, no multiscatter"},
        {{.mc_samples = 4, .mc_seed = 3}, "lambert, Monte Carlo pass"},
    };
    for (size_t i = 0; i < sizeof passes / sizeof passes[0]; ++i) {
        float *px = render_plane(ctx, &test_lambert_material, punctual_lights, &passes[i].desc);
        compare(px, 0.0, 1e-3, 1e-5, NULL, W * H / 2, passes[i].what);
        free(px);
    }
}

// The lights must each be there: a render without the spot differs from the closed form with
// it, in its cone.
static void each_light_counts(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    rtpbr_light_desc lights[4];
    memcpy(lights, punctual_lights, sizeof lights);
    lights[1].emission[0] = lights[1].emission[1] = lights[1].emission[2] = 0.0f;
    float *px = render_plane(ctx, &test_lambert_material, lights, &(rtpbr_render_desc){0});
    int lit = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3], L[3];
            if (test_plane_point(&camera, x, y, W, H, p) && incident(&punctual_lights[1], p, L) > 0.0) ++lit;
        }
    double worst = largest_error(px, punctual_lights, 4, 0.0, 1e-5, NULL, true, NULL);
    printf("without the spot: %d pixels in its cone; largest error against the closed form with it %.3g\n", lit, worst);
    assert_true(lit > 200);
    assert_true(worst > 0.1);
    free(px);
}

// A GGX metal plane (base colour 1, metallic 1: F = 1; roughness 0.625, alpha 0.390625: exact
// in the G-buffer's half float, where 0.6 would be stored as 0.59961, 0.25% on the highlight's
// peak) under the four lights, multiple scattering off: the single-scattering closed form.
static void ggx_plane(void **state)
{
    const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f, .roughness = 0.625f};
    float *px = render_plane(test_env_context(state), &metal, punctual_lights,
                             &(rtpbr_render_desc){.multiscatter = RTPBR_MULTISCATTER_OFF});
    compare(px, 0.390625, 1e-3, 1e-5, NULL, W * H / 2, "GGX metal, LTC pass");
    free(px);
}

// The same plane anisotropic (KHR_materials_anisotropy strength 0.6, rotation 0.4 from the
// mesh's tangent +X): alpha_t = mix(alpha, 1, 0.36) along (cos 0.4, sin 0.4, 0), alpha_b =
// alpha; the full lighting variant, the BRDF's frame turned to the anisotropy direction.
static void anisotropic_plane(void **state)
{
    const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f, .roughness = 0.625f,
                                       .anisotropy_strength = 0.6f, .anisotropy_rotation = 0.4f};
    float *px = render_plane(test_env_context(state), &metal, punctual_lights,
                             &(rtpbr_render_desc){.multiscatter = RTPBR_MULTISCATTER_OFF});
    aniso_alpha_t = 0.390625 + (1.0 - 0.390625) * 0.36;
    aniso_angle = 0.4;
    compare(px, 0.390625, 1e-3, 1e-5, NULL, W * H / 2, "anisotropic GGX metal, LTC pass");
    // and not the isotropic lobe
    aniso_alpha_t = 0.0;
    double iso = largest_error(px, punctual_lights, 4, 0.390625, 1e-5, NULL, true, NULL);
    printf("anisotropic plane against the isotropic closed form: largest error %.3g\n", iso);
    assert_true(iso > 0.1);
    free(px);
}

// Shadows: a square occluder at z = 0.8 under the point light (light 0) and in the way of the
// directional light (light 2), facing the plane. Its shadow from each light, computed here, is
// 0; elsewhere the
// closed form (the denoiser off); pixels within 0.01 of a shadow's edge or showing the occluder
// are skipped.
static const double occluder_z = 0.8, occluder_min[2] = {-1.4, 0.1}, occluder_max[2] = {-0.6, 0.9};

// How far the segment from p toward light l (unit direction L) passes inside the occluder's
// square at its height: > 0 inside, < 0 outside (in distance from the nearest edge); -1 when it
// does not reach that height.
static double occluder_depth(const double p[3], const double L[3])
{
    if (!(L[2] > 0.0)) return -1.0;
    double t = (occluder_z - p[2]) / L[2];
    double q[2] = {p[0] + t * L[0], p[1] + t * L[1]};
    double inside = 1e30;
    for (int k = 0; k < 2; ++k) inside = fmin(inside, fmin(q[k] - occluder_min[k], occluder_max[k] - q[k]));
    return inside;
}

static bool shadow_filter(const double p[3], double visible[])
{
    // The camera ray hits the occluder first?
    double e[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
    double el = sqrt(dot3(e, e));
    for (int k = 0; k < 3; ++k) e[k] /= el;
    if (occluder_depth(p, e) > -0.05) return false;
    for (int l = 0; l < 4; ++l) {
        double L[3];
        incident(&punctual_lights[l], p, L);
        if (l == 1 || l == 3) continue; // the spot and the ranged light: no occluder in their way
        if (l == 0 && punctual_lights[0].position[2] < occluder_z) continue;
        double depth = occluder_depth(p, L);
        if (fabs(depth) < 0.01) return false;
        visible[l] = depth > 0.0 ? 0.0 : 1.0;
    }
    return true;
}

// The pixels shadow_filter keeps, every light visible.
static bool shadow_pixels(const double p[3], double visible[])
{
    (void)visible;
    double unused[4];
    return shadow_filter(p, unused);
}

// The plane and the occluder under `lights` (4 of them).
static rtpbr_gpu_scene *occluder_scene(rtpbr_context *ctx, const rtpbr_light_desc *lights)
{
    float plane[12];
    float occluder[12] = {(float)occluder_min[0], (float)occluder_min[1], (float)occluder_z,
                          (float)occluder_max[0], (float)occluder_min[1], (float)occluder_z,
                          (float)occluder_max[0], (float)occluder_max[1], (float)occluder_z,
                          (float)occluder_min[0], (float)occluder_max[1], (float)occluder_z};
    // facing down, toward the plane: a one-sided triangle blocks rays that meet its front
    // (the shadow rays go up); the camera above sees its back, which is culled
    static const uint32_t down[6] = {0, 2, 1, 0, 3, 2};
    rtpbr_mesh_desc meshes[2] = {test_square_mesh(4.0f, 0.0f, plane),
                                 {.positions = occluder, .indices = down, .vertex_count = 4, .index_count = 6}};
    return test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = 2,
                                                    .materials = &test_lambert_material, .material_count = 1,
                                                    .lights = lights, .light_count = 4, .cameras = &camera,
                                                    .camera_count = 1});
}

static void shadows(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    rtpbr_gpu_scene *scene = occluder_scene(ctx, punctual_lights);
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    // The denoiser off: each pixel's own ray (its filter would blur the edges over several pixels).
    float *px = test_render_radiance(
        r, scene, &(rtpbr_render_desc){.shadows = RTPBR_SHADOWS_ON, .shadow_denoiser = RTPBR_SHADOW_DENOISER_OFF}, W, H);
    int umbra = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3], visible[4] = {1, 1, 1, 1};
            if (test_plane_point(&camera, x, y, W, H, p) && fabs(p[0]) < 3.9 && fabs(p[1]) < 3.9 &&
                shadow_filter(p, visible) && (visible[0] == 0.0 || visible[2] == 0.0))
                ++umbra;
        }
    printf("shadows on: %d pixels in a shadow\n", umbra);
    assert_true(umbra > 100);
    // An absolute allowance of 1e-3 x 1e-2 (a light leaking 1% through the occluder is 7e-4
    // here): where the other lights are in shadow, the ranged light's window ends steeply
    // (dW/dd = -4 d^3 / range^4) and the position from the depth buffer is off by ~1e-5:
    // 2.5e-6 of 2.2e-4.
    compare(px, 0.0, 1e-3, 1e-2, shadow_filter, W * H / 3, "shadows on");
    free(px);
    // Without shadows the same pixels are lit as if the occluder were not there.
    px = test_render_radiance(r, scene, &(rtpbr_render_desc){.shadows = RTPBR_SHADOWS_OFF}, W, H);
    compare(px, 0.0, 1e-3, 1e-5, shadow_pixels, W * H / 3, "shadows off, against the unshadowed closed form");
    free(px);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// Bad punctual lights are refused with RTPBR_ERROR_INVALID_ARGUMENT, before the GPU.
static void bad_lights(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    rtpbr_mesh_desc mesh = test_square_mesh(4.0f, 0.0f, plane);
    const rtpbr_light_desc bad[] = {
        {.type = (rtpbr_light_type)7, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .position = {0, 0, NAN}, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .emission = {1, -1, 1}},
        {.type = RTPBR_LIGHT_POINT, .range = -1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_SPOT, .emission = {1, 1, 1}},                                       // no direction
        {.type = RTPBR_LIGHT_SPOT, .direction = {0, 0, -1}, .inner_cone_angle = 0.5f, .outer_cone_angle = 0.4f},
        {.type = RTPBR_LIGHT_SPOT, .direction = {0, 0, -1}, .outer_cone_angle = 2.0f},
        {.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, INFINITY, 0}, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DIRECTIONAL, .emission = {1, 1, 1}},                                // no direction
        {.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = NAN, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = 1.6f, .emission = {1, 1, 1}},
        // the sun's radiance 1e35 / 6.7e-5 would overflow a float
        {.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .emission = {1e35f, 1, 1}},
        // spheres: a negative, NaN or infinite radius, a radius on a spot, a radiance (3e69) or an
        // area (3e40) beyond a float
        {.type = RTPBR_LIGHT_POINT, .radius = -0.1f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .radius = NAN, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .radius = INFINITY, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_SPOT, .direction = {0, 0, -1}, .radius = 0.1f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .radius = 1e-20f, .emission = {1e30f, 1, 1}},
        {.type = RTPBR_LIGHT_POINT, .radius = 1e20f, .emission = {1, 1, 1}},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        rtpbr_result result = rtpbr_gpu_scene_create(
            ctx,
            &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1, .materials = &test_lambert_material,
                                    .material_count = 1, .lights = &bad[i], .light_count = 1},
            &scene);
        if (result != RTPBR_ERROR_INVALID_ARGUMENT) fail_msg("bad light %zu: result %d", i, (int)result);
        assert_null(scene);
    }
}

// A directional light with an angular diameter (the sun's disk, rtpbr_light_desc): the engine
// shades an equal-area octagon far away, of the radiance that gives `emission` lux at normal
// incidence. Against the uniform disk (a spherical cap of half-angle a, radiance E / (pi
// sin^2 a)) it stands for, computed here: a Lambertian plane's radiance is 0.8 / pi x L x the
// cap's projected solid angle above the plane, E cos(theta) in closed form where the cap is
// wholly above the horizon (every pixel the same), and a quadrature where it straddles it.

// The cap's projected solid angle above z = 0 (int max(w.z, 0) dw over the cap around c, half
// angle a), by the midpoint rule in (t, phi), in double precision.
// An orthonormal frame (t1, t2, c) about the unit vector c.
static void cap_frame(const double c[3], double t1[3], double t2[3])
{
    t1[0] = fabs(c[0]) > 0.9 ? 0.0 : 1.0;
    t1[1] = fabs(c[0]) > 0.9 ? 1.0 : 0.0;
    t1[2] = 0.0;
    double d = dot3(t1, c);
    for (int k = 0; k < 3; ++k) t1[k] -= d * c[k];
    double tl = sqrt(dot3(t1, t1));
    for (int k = 0; k < 3; ++k) t1[k] /= tl;
    t2[0] = c[1] * t1[2] - c[2] * t1[1];
    t2[1] = c[2] * t1[0] - c[0] * t1[2];
    t2[2] = c[0] * t1[1] - c[1] * t1[0];
}

static double cap_projected_n(const double c[3], double a, int n);
static double cap_projected(const double c[3], double a)
{
    return cap_projected_n(c, a, 1500);
}
static double cap_projected_n(const double c[3], double a, int n)
{
    double t1[3], t2[3];
    cap_frame(c, t1, t2);
    const int NT = n, NP = n;
    double sum = 0.0;
    for (int i = 0; i < NT; ++i) {
        double t = (i + 0.5) * a / NT, st = sin(t), ct = cos(t);
        for (int j = 0; j < NP; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / NP;
            double z = ct * c[2] + st * (cos(phi) * t1[2] + sin(phi) * t2[2]);
            if (z > 0.0) sum += z * st;
        }
    }
    return sum * (a / NT) * (2.0 * M_PI / NP);
}

// The plane's pixels (channel 0) against one value: the largest difference, the mean and the
// mean's standard error (from the pixels' spread).
typedef struct {
    double worst, mean, stderr_mean;
    int checked;
} uniform_stats;
static uniform_stats uniform_error(const float *px, double want)
{
    uniform_stats u = {0};
    double sum = 0.0, sum2 = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double v = px[4 * (y * W + x)];
            u.worst = fmax(u.worst, fabs(v - want));
            sum += v;
            sum2 += v * v;
            ++u.checked;
        }
    u.mean = sum / u.checked;
    u.stderr_mean = sqrt(fmax(sum2 / u.checked - u.mean * u.mean, 0.0) / u.checked);
    return u;
}

// Errors in units of the light's radiance on the plane head-on (0.8 / pi x E): the LTC pass's
// on every pixel; the Monte Carlo pass's (16 samples, every pixel its own estimate) on the mean,
// within 4 standard errors. The sun's LTC error per pixel (measured 9.4e-4 at 40 degrees, 9.0e-4
// at 3, 9.5e-4 on a sliver just below the horizon) is float rounding, which varies from pixel to
// pixel: its edges subtend 3.6e-3 rad and their cross products' z components cancel to a form
// factor of 7e-5 x sin(elevation); the plane's mean is within 3e-6 relative (at 40 and 3
// degrees; the sliver's 4%, 7e-6 of the head-on: the octagon against the disk where the horizon
// cuts it). A 20-degree disk: 1.5e-6, and 6.5e-5 straddling the horizon.
static void sun_disk(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const struct {
        double elevation, diameter; // degrees; diameter 0: the default (the sun's 0.53 degrees)
        double bound_ltc;
        const char *what;
    } cases[] = {
        {40.0, 0.0, 2e-3, "the sun (0.53 degrees) at 40 degrees elevation"},
        {3.0, 0.0, 2e-3, "the sun at 3 degrees"},
        {-0.1, 0.0, 2e-3, "the sun with its centre 0.1 degrees below the horizon"},
        {35.0, 20.0, 1e-4, "a 20-degree disk at 35 degrees"},
        {4.0, 20.0, 2e-4, "a 20-degree disk straddling the horizon (centre at 4 degrees)"},
        {40.0, 5.7e-5, 2e-4, "a 1e-6 rad disk (below RTPBR_SUN_MIN_ANGULAR_DIAMETER: a true direction)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        double el = cases[i].elevation * M_PI / 180.0, az = 0.7;
        double c[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)}; // toward the light
        double diameter = cases[i].diameter > 0.0 ? cases[i].diameter * M_PI / 180.0 : (double)RTPBR_SUN_ANGULAR_DIAMETER;
        double a = 0.5 * diameter, E = 2.0, headOn = 0.8 / M_PI * E;
        double want = headOn / (M_PI * sin(a) * sin(a)) * cap_projected(c, a);
        if (c[2] > sin(a)) // wholly above: the closed form, which the quadrature must match
            assert_true(fabs(want - headOn * c[2]) < 1e-6 * want);
        rtpbr_light_desc lights[4] = {{.type = RTPBR_LIGHT_DIRECTIONAL,
                                       .direction = {(float)-c[0], (float)-c[1], (float)-c[2]},
                                       .emission = {(float)E, (float)E, (float)E},
                                       .angular_diameter = cases[i].diameter > 0.0 ? (float)diameter : 0.0f}};
        for (int l = 1; l < 4; ++l) // render_plane's other three: dark
            lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
        const rtpbr_render_desc descs[2] = {{0}, {.mc_samples = 16, .mc_seed = 5}};
        for (int pass = 0; pass < 2; ++pass) {
            float *px = render_plane(ctx, &test_lambert_material, lights, &descs[pass]);
            uniform_stats u = uniform_error(px, want);
            assert_true(u.checked > W * H / 2);
            if (pass == 0) {
                printf("%s, LTC pass: %d pixels, mean %.6g, want %.6g, largest error %.3g of the head-on %.4g (bound %.3g)\n",
                       cases[i].what, u.checked, u.mean, want, u.worst / headOn, headOn, cases[i].bound_ltc);
                assert_true(u.worst <= cases[i].bound_ltc * headOn);
            } else {
                double err = fabs(u.mean - want);
                printf("%s, Monte Carlo pass: mean %.6g, want %.6g: %.2f standard errors (%.3g)\n", cases[i].what,
                       u.mean, want, err / u.stderr_mean, u.stderr_mean);
                assert_true(err <= 4.0 * u.stderr_mean + 1e-4 * headOn);
            }
            free(px);
        }
    }
    // A rough GGX metal (alpha 0.39) under the sun: its lobe is too wide to tell the disk from a
    // direction (their difference is of order a^2 = 2e-5), so the delta light's closed form
    // (expected()) holds; the polygon goes through the LTC lobe and its corrections. Measured
    // 9.7e-4 on every pixel (LTC); the Monte Carlo pass (16 samples, half of them from the lobe,
    // which all but miss the disk: every pixel is 0 or 2x, unbiased) on the plane's mean of
    // (pixel - closed form), within 4 standard errors.
    const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f, .roughness = 0.625f};
    rtpbr_light_desc sun[4] = {{.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0.3f, 0.2f, -1.0f}, .emission = {2, 2, 2}}};
    for (int l = 1; l < 4; ++l) sun[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
    const rtpbr_render_desc metalDescs[2] = {{.multiscatter = RTPBR_MULTISCATTER_OFF},
                                             {.multiscatter = RTPBR_MULTISCATTER_OFF, .mc_samples = 16, .mc_seed = 5}};
    for (int pass = 0; pass < 2; ++pass) {
        float *px = render_plane(ctx, &metal, sun, &metalDescs[pass]);
        int checked = 0;
        double worst = largest_error(px, sun, 4, 0.390625, 1e-5, NULL, false, &checked);
        double sum = 0.0, sum2 = 0.0, wantSum = 0.0;
        const double visible[4] = {1, 1, 1, 1};
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double p[3], want[3];
                if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
                expected(sun, 4, visible, 0.390625, p, want);
                double d = px[4 * (y * W + x)] - want[0];
                sum += d, sum2 += d * d, wantSum += want[0];
            }
        double meanDiff = sum / checked, se = sqrt(fmax(sum2 / checked - meanDiff * meanDiff, 0.0) / checked);
        printf("GGX metal under the sun, %s pass: %d pixels, largest error %.3g against the direction's closed form; "
               "mean difference %.3g of the mean %.4g (%.2f standard errors)\n",
               pass == 0 ? "LTC" : "Monte Carlo", checked, worst, meanDiff, wantSum / checked, fabs(meanDiff) / se);
        assert_true(checked > W * H / 2);
        if (pass == 0)
            assert_true(worst <= 2e-3);
        else
            assert_true(fabs(meanDiff) <= 4.0 * se + 1e-5 * wantSum / checked);
        free(px);
    }
}

// A point light with a radius (rtpbr_light_desc.radius): a sphere of uniform radiance
// I / (pi r^2), windowed by its range at the distance from its centre. Against its cap, computed
// here: a Lambertian plane's radiance is 0.8 / pi x L x the cap's projected solid angle above
// the plane (I cos(theta) / d^2 x 0.8 in closed form where the sphere is wholly above the
// horizon, cap_projected_n's quadrature where the horizon cuts it), and 0.8 L inside the sphere
// (every direction sees it). Pixels within 0.02 of the sphere's surface are skipped (the disk
// that stands for the sphere grows without bound there).
static double sphere_want(const double centre[3], double r, double I, double range, const double p[3], bool *skip)
{
    double c[3] = {centre[0] - p[0], centre[1] - p[1], centre[2] - p[2]};
    double d = sqrt(dot3(c, c));
    *skip = fabs(d - r) < 0.02;
    double L = I / (M_PI * r * r), window = 1.0;
    if (range > 0.0) {
        double q = d / range;
        window = fmin(fmax(1.0 - q * q * q * q, 0.0), 1.0);
    }
    if (d <= r) return 0.8 * L * window;
    for (int k = 0; k < 3; ++k) c[k] /= d;
    double a = asin(r / d);
    double projected = c[2] > sin(a) ? M_PI * sin(a) * sin(a) * c[2] : c[2] < -sin(a) ? 0.0 : cap_projected_n(c, a, 120);
    return 0.8 / M_PI * L * projected * window;
}

static void sphere_light(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const struct {
        double centre[3], radius, range;
        double bound_ltc; // relative to the largest expected pixel
        const char *what;
    } cases[] = {
        {{-0.5, 0.3, 1.2}, 0.3, 0.0, 1e-3, "a sphere above the plane (r 0.3 at height 1.2)"},
        {{0.4, 0.2, 0.15}, 0.5, 0.0, 1e-3, "a sphere the plane cuts (r 0.5 at height 0.15)"},
        {{0.2, -0.3, 0.6}, 0.2, 1.8, 1e-3, "a sphere with a range of 1.8 (r 0.2 at height 0.6)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0] + 1; ++i) {
        // the last: the first case on a BLEND plane of alpha 1 (the forward pass's spheres
        // variant shades it; the background behind it is black)
        bool blend = i == sizeof cases / sizeof cases[0];
        size_t ci = blend ? 0 : i;
        const double I = 3.0;
        rtpbr_light_desc lights[4] = {{.type = RTPBR_LIGHT_POINT,
                                       .position = {(float)cases[ci].centre[0], (float)cases[ci].centre[1], (float)cases[ci].centre[2]},
                                       .radius = (float)cases[ci].radius, .range = (float)cases[ci].range,
                                       .emission = {(float)I, (float)I, (float)I}}};
        for (int l = 1; l < 4; ++l)
            lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
        const rtpbr_render_desc descs[2] = {{0}, {.mc_samples = 16, .mc_seed = 7}};
        for (int pass = 0; pass < 2; ++pass) {
            rtpbr_material_desc material = test_lambert_material;
            if (blend) material.alpha_mode = RTPBR_ALPHA_BLEND, material.alpha = 1.0f;
            if (blend && pass == 1) continue; // (the Monte Carlo pass draws BLEND with the forward pass too: once is enough)
            float *px = render_plane(ctx, &material, lights, &descs[pass]);
            double worst = 0.0, peak = 0.0, sum = 0.0, sum2 = 0.0, wantSum = 0.0;
            int checked = 0, inside = 0, cut = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    double p[3];
                    bool skip;
                    if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
                    double want = sphere_want(cases[ci].centre, cases[ci].radius, I, cases[ci].range, p, &skip);
                    if (skip) continue;
                    double dc[3] = {cases[ci].centre[0] - p[0], cases[ci].centre[1] - p[1], cases[ci].centre[2] - p[2]};
                    double d = sqrt(dot3(dc, dc));
                    inside += d <= cases[ci].radius;
                    cut += d > cases[ci].radius && dc[2] < cases[ci].radius * sqrt(dot3(dc, dc)) / d;
                    double v = px[4 * (y * W + x)];
                    worst = fmax(worst, fabs(v - want));
                    peak = fmax(peak, want);
                    sum += v - want, sum2 += (v - want) * (v - want), wantSum += want;
                    ++checked;
                }
            assert_true(checked > W * H / 2);
            if (pass == 0) {
                printf("%s%s, LTC pass: %d pixels (%d inside it, %d with the horizon cutting it), largest error %.3g of "
                       "the peak %.4g (bound %.3g)\n",
                       cases[ci].what, blend ? ", BLEND (forward pass)" : "", checked, inside, cut, worst / peak, peak,
                       cases[ci].bound_ltc);
                assert_true(worst <= cases[ci].bound_ltc * peak);
            } else {
                double mean = sum / checked, se = sqrt(fmax(sum2 / checked - mean * mean, 0.0) / checked);
                printf("%s, Monte Carlo pass: mean difference %.3g of the mean %.4g: %.2f standard errors\n",
                       cases[ci].what, mean, wantSum / checked, fabs(mean) / se);
                assert_true(fabs(mean) <= 4.0 * se + 1e-5 * wantSum / checked);
            }
            free(px);
        }
    }
}

// The integral of f(wo, w) max(w.z, 0) over the cap around c (unit) of half-angle a, f the GGX
// metal of ggx_single (F = 1, single scattering) at alpha: the midpoint rule in (t, phi), n x n.
static double cap_ggx(const double c[3], double a, const double wo[3], double alpha, int n)
{
    double t1[3], t2[3];
    cap_frame(c, t1, t2);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        double t = (i + 0.5) * a / n, st = sin(t), ct = cos(t);
        for (int j = 0; j < n; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / n, w[3];
            for (int k = 0; k < 3; ++k) w[k] = ct * c[k] + st * (cos(phi) * t1[k] + sin(phi) * t2[k]);
            if (w[2] > 0.0) sum += ggx_single(wo, w, alpha) * w[2] * st;
        }
    }
    return sum * (a / n) * (2.0 * M_PI / n);
}

// A GGX metal plane (F = 1, multiple scattering off) under a sphere: against cap_ggx on every
// 3rd pixel in x and y. The LTC pass is the LTC fit's approximation (its error stated, not
// float rounding); the Monte Carlo pass's mean within 4 standard errors.
static void sphere_ggx(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const struct {
        double roughness, alpha, radius, height, bound_ltc;
        bool full; // a full-variant material (anisotropy 1e-4: alpha_t = alpha + 6e-9)
    } cases[] = {
        {0.625, 0.390625, 0.3, 1.0, 0.025, false}, // measured 0.0164
        {0.25, 0.0625, 0.3, 1.0, 0.005, false},    // 0.0019
        {0.25, 0.0625, 0.4, 0.1, 0.03, false},     // 0.018: the horizon cuts it (its 12-gon, clipped)
        {0.25, 0.0625, 0.3, 1.0, 0.02, true},      // the full variant: no point correction
        {0.25, 0.0625, 0.4, 0.1, 0.2, true},       // 0.152: and the sphere proxy at the horizon (leaks)
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f,
                                           .roughness = (float)cases[i].roughness,
                                           .anisotropy_strength = cases[i].full ? 1e-4f : 0.0f};
        const double centre[3] = {-0.4, 0.6, cases[i].height}, r = cases[i].radius, I = 2.0, L = I / (M_PI * r * r);
        rtpbr_light_desc lights[4] = {{.type = RTPBR_LIGHT_POINT,
                                       .position = {(float)centre[0], (float)centre[1], (float)centre[2]},
                                       .radius = (float)r, .emission = {(float)I, (float)I, (float)I}}};
        for (int l = 1; l < 4; ++l)
            lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
        const rtpbr_render_desc descs[2] = {{.multiscatter = RTPBR_MULTISCATTER_OFF},
                                            {.multiscatter = RTPBR_MULTISCATTER_OFF, .mc_samples = 64, .mc_seed = 9}};
        for (int pass = 0; pass < 2; ++pass) {
            float *px = render_plane(ctx, &metal, lights, &descs[pass]);
            double worst = 0.0, peak = 0.0, sum = 0.0, sum2 = 0.0, wantSum = 0.0, errSum = 0.0;
            int checked = 0;
            for (int y = 1; y < H; y += 3)
                for (int x = 1; x < W; x += 3) {
                    double p[3];
                    if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
                    double c[3] = {centre[0] - p[0], centre[1] - p[1], centre[2] - p[2]};
                    double d = sqrt(dot3(c, c));
                    if (d < r + 0.02) continue;
                    for (int k = 0; k < 3; ++k) c[k] /= d;
                    double wo[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
                    double ol = sqrt(dot3(wo, wo));
                    for (int k = 0; k < 3; ++k) wo[k] /= ol;
                    double want = L * cap_ggx(c, asin(r / d), wo, cases[i].alpha, 96);
                    double v = px[4 * (y * W + x)];
                    worst = fmax(worst, fabs(v - want));
                    errSum += fabs(v - want);
                    peak = fmax(peak, want);
                    sum += v - want, sum2 += (v - want) * (v - want), wantSum += want;
                    ++checked;
                }
            assert_true(checked > W * H / 20);
            if (pass == 0) {
                printf("GGX alpha %.4g under a sphere (r %.2g at height %.2g)%s, LTC pass: %d pixels, largest error %.3g "
                       "of the peak %.4g, mean |error| %.3g of the mean %.4g (bound %.3g of the peak)\n",
                       cases[i].alpha, r, cases[i].height, cases[i].full ? ", full variant" : "", checked, worst / peak,
                       peak, errSum / wantSum, wantSum / checked, cases[i].bound_ltc);
                assert_true(worst <= cases[i].bound_ltc * peak);
            } else {
                double mean = sum / checked, se = sqrt(fmax(sum2 / checked - mean * mean, 0.0) / checked);
                printf("GGX alpha %.4g under a sphere (r %.2g at height %.2g), Monte Carlo pass: mean difference %.3g of "
                       "the mean %.4g: %.2f standard errors\n",
                       cases[i].alpha, r, cases[i].height, mean, wantSum / checked, fabs(mean) / se);
                assert_true(fabs(mean) <= 4.0 * se + 1e-4 * wantSum / checked);
            }
            free(px);
        }
    }
}

// Where the occluder of `shadows` stands between p and the sphere (centre, r): 1 when every ray
// from p to the sphere passes through the occluder's square 0.01 inside its edges (the rays
// along the cone's boundary, 64 of them: the square and the cone's cross-section are convex),
// 0 when none comes within 0.01 of it (nor the centre's), -1 in between (the penumbra).
static int sphere_umbra(const double centre[3], double r, const double p[3])
{
    double c[3] = {centre[0] - p[0], centre[1] - p[1], centre[2] - p[2]};
    double d = sqrt(dot3(c, c));
    for (int k = 0; k < 3; ++k) c[k] /= d;
    double a = asin(r / d);
    double t1[3], t2[3];
    cap_frame(c, t1, t2);
    int inside = 0, outside = occluder_depth(p, c) < -0.01 ? 1 : 0;
    for (int j = 0; j < 64; ++j) {
        double phi = 2.0 * M_PI * j / 64, w[3];
        for (int k = 0; k < 3; ++k) w[k] = cos(a) * c[k] + sin(a) * (cos(phi) * t1[k] + sin(phi) * t2[k]);
        double depth = occluder_depth(p, w);
        inside += depth > 0.01;
        outside += depth < -0.01;
    }
    return inside == 64 ? 1 : outside == 65 ? 0 : -1;
}

// Shadows of a sphere light: the occluder of `shadows` under a sphere (r 0.15 at height 1.5): 0
// in its umbra, the unshadowed closed form where nothing is in the way (the ratio estimator is
// exact at both: every sample agrees), the denoiser off; the penumbra in between (both kinds
// must be there, and the penumbra wider than a point light's edge).
// The occluder of `shadows` under lights[0] (with shadows, the denoiser off), checked where
// umbra(p) says the light is wholly hidden (0) or wholly seen (want(p)); the penumbra (umbra -1)
// is counted, not checked. `what` names the light in the message.
typedef int (*umbra_fn)(const void *light, const double p[3]);
typedef double (*want_fn)(const void *light, const double p[3]);
static void check_shadows(rtpbr_context *ctx, const rtpbr_light_desc lights[4], const void *light, umbra_fn umbra_of,
                          want_fn want_of, const char *what)
{
    rtpbr_gpu_scene *scene = occluder_scene(ctx, lights);
    rtpbr_renderer *r2 = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *px = test_render_radiance(
        r2, scene, &(rtpbr_render_desc){.shadows = RTPBR_SHADOWS_ON, .shadow_denoiser = RTPBR_SHADOW_DENOISER_OFF}, W, H);
    int umbra = 0, lit = 0, penumbra = 0;
    double worst = 0.0, peak = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double e[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
            double el = sqrt(dot3(e, e));
            for (int k = 0; k < 3; ++k) e[k] /= el;
            if (occluder_depth(p, e) > -0.05) continue; // the camera sees the occluder
            int kind = umbra_of(light, p);
            if (kind < 0) {
                ++penumbra;
                continue;
            }
            double want = kind == 1 ? 0.0 : want_of(light, p);
            peak = fmax(peak, want);
            worst = fmax(worst, fabs(px[4 * (y * W + x)] - want));
            umbra += kind == 1;
            lit += kind == 0;
        }
    printf("%s shadows: %d pixels in the umbra, %d lit, %d in the penumbra; largest error %.3g of the peak %.4g\n", what,
           umbra, lit, penumbra, worst / peak, peak);
    assert_true(umbra > 50 && lit > W * H / 3 && penumbra > 100);
    assert_true(worst <= 1e-3 * peak);
    free(px);
    rtpbr_renderer_destroy(r2);
    rtpbr_gpu_scene_destroy(scene);
}

// The sphere of sphere_shadow: centre xyz, radius, intensity.
static int sphere_umbra_of(const void *light, const double p[3])
{
    const double *s = light;
    return sphere_umbra(s, s[3], p);
}
static double sphere_want_of(const void *light, const double p[3])
{
    const double *s = light;
    bool skip;
    return sphere_want(s, s[3], s[4], 0.0, p, &skip);
}

static void sphere_shadow(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double sphere[5] = {-1.0, 0.5, 1.5, 0.15, 2.0}; // centre, r, I
    rtpbr_light_desc lights[4] = {{.type = RTPBR_LIGHT_POINT, .position = {-1.0f, 0.5f, 1.5f}, .radius = (float)sphere[3],
                                   .emission = {(float)sphere[4], (float)sphere[4], (float)sphere[4]}}};
    for (int l = 1; l < 4; ++l)
        lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
    check_shadows(ctx, lights, sphere, sphere_umbra_of, sphere_want_of, "sphere");
}

// Disk lights (RTPBR_LIGHT_DISK; issue 30). The expected radiance at p is a double-precision
// quadrature over the disk itself: the midpoint rule on n x n cells of equal area (rings by
// sqrt, angles uniform) of L f(wo, w) max(N.w, 0) cos_l / d^2 dA, cos_l the disk's cosine toward
// p (0 behind a one-sided disk), f 0.8 / pi (Lambert) or ggx_single at alpha. Pixels within 0.05
// of the disk are skipped (the quadrature's cells are then too coarse).
typedef struct disk_case {
    double centre[3], normal[3], radius; // normal unit, toward the emitting side
    bool two_sided;
    double radius2, axis[3]; // an ellipse (RTPBR_LIGHT_DISK's disk_radius2, disk_axis): radius2 > 0,
                             // radius along axis (unit, in the plane); 0: a circle
} disk_case;

// The disk's half-axes: r1 t1 and r2 t2, t1 x t2 = the normal (cap_frame's for a circle).
static void disk_axes(const disk_case *c, double t1[3], double t2[3], double *r1, double *r2)
{
    *r1 = c->radius;
    *r2 = c->radius2 > 0.0 ? c->radius2 : c->radius;
    if (!(c->radius2 > 0.0)) {
        cap_frame(c->normal, t1, t2);
        return;
    }
    const double *n = c->normal;
    for (int k = 0; k < 3; ++k) t1[k] = c->axis[k];
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

static double disk_want(const disk_case *c, double L, double alpha, const double p[3], int n, bool *skip)
{
    double t1[3], t2[3], r1, r2;
    disk_axes(c, t1, t2, &r1, &r2);
    double wo[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
    double ol = sqrt(dot3(wo, wo));
    for (int k = 0; k < 3; ++k) wo[k] /= ol;
    // (an ellipse: the disk's cells stretched by r1, r2, still of equal area)
    double cell = M_PI * r1 * r2 / ((double)n * n), sum = 0.0, nearest = 1e30;
    for (int i = 0; i < n; ++i) {
        double rho = sqrt((i + 0.5) / n);
        for (int j = 0; j < n; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / n, y[3], w[3];
            for (int k = 0; k < 3; ++k)
                y[k] = c->centre[k] + rho * (r1 * cos(phi) * t1[k] + r2 * sin(phi) * t2[k]) - p[k];
            double d2 = dot3(y, y), d = sqrt(d2);
            nearest = fmin(nearest, d);
            for (int k = 0; k < 3; ++k) w[k] = y[k] / d;
            double cosL = -dot3(c->normal, w);
            cosL = c->two_sided ? fabs(cosL) : fmax(cosL, 0.0);
            if (w[2] <= 0.0 || cosL <= 0.0) continue;
            double f = alpha > 0.0 ? ggx_single(wo, w, alpha) : 0.8 / M_PI;
            sum += f * w[2] * cosL / d2;
        }
    }
    *skip = nearest < 0.05;
    return L * sum * cell;
}

// The light desc of a disk case: the disk, or (octagon) the regular octagon of its area that
// the loader gave for it before (circumradius r sqrt(pi / (2 sqrt 2))), with the same radiance.
static rtpbr_light_desc disk_desc(const disk_case *c, double L, bool octagon)
{
    rtpbr_light_desc d = {.type = RTPBR_LIGHT_DISK, .radius = (float)c->radius, .two_sided = c->two_sided,
                          .emission = {(float)L, (float)L, (float)L}, .disk_radius2 = (float)c->radius2};
    for (int k = 0; k < 3; ++k)
        d.position[k] = (float)c->centre[k], d.direction[k] = (float)c->normal[k], d.disk_axis[k] = (float)c->axis[k];
    if (octagon) { // (an ellipse's: the octagon stretched along its axes, the loader's)
        double t1[3], t2[3], r1, r2, R = sqrt(M_PI / (2.0 * sqrt(2.0)));
        disk_axes(c, t1, t2, &r1, &r2); // t1 x t2 = the normal: counter-clockwise seen from the front
        d = (rtpbr_light_desc){.vertex_count = 8, .two_sided = c->two_sided, .emission = {(float)L, (float)L, (float)L}};
        for (int v = 0; v < 8; ++v)
            for (int k = 0; k < 3; ++k)
                d.vertices[v][k] = (float)(c->centre[k] + R * (r1 * cos(v * M_PI / 4.0) * t1[k] +
                                                               r2 * sin(v * M_PI / 4.0) * t2[k]));
    }
    return d;
}

// A render of the plane against the expected values of plane_wants: the largest and mean
// absolute errors, the mean signed error and its standard error.
typedef struct plane_errors {
    double worst, peak, errSum, sum, sum2, wantSum;
    int checked;
} plane_errors;
typedef double (*plane_want_fn)(const void *arg, const double p[3], bool *skip);
// want(p) at every step-th pixel (from offset) on the plane, W x H, NAN where not checked (the
// caller frees it): computed once, compared with each render.
static double *plane_wants(int offset, int step, plane_want_fn want_of, const void *arg)
{
    double *wants = malloc(sizeof(double) * W * H);
    assert_non_null(wants);
    for (int i = 0; i < W * H; ++i) wants[i] = NAN;
    for (int y = offset; y < H; y += step)
        for (int x = offset; x < W; x += step) {
            double p[3];
            bool skip;
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double want = want_of(arg, p, &skip);
            if (!skip) wants[y * W + x] = want;
        }
    return wants;
}
static plane_errors measure_plane(const float *px, const double *wants)
{
    plane_errors e = {0};
    for (int i = 0; i < W * H; ++i) {
        double want = wants[i];
        if (isnan(want)) continue;
        double v = px[4 * i];
        e.worst = fmax(e.worst, fabs(v - want));
        e.peak = fmax(e.peak, want);
        e.errSum += fabs(v - want);
        e.sum += v - want, e.sum2 += (v - want) * (v - want), e.wantSum += want;
        ++e.checked;
    }
    return e;
}
// The Monte Carlo pass's mean error within 4 standard errors (+ tolerance x the mean).
static void check_mc_mean(const plane_errors *e, double tolerance, const char *what)
{
    double mean = e->sum / e->checked, se = sqrt(fmax(e->sum2 / e->checked - mean * mean, 0.0) / e->checked);
    printf("%s, Monte Carlo pass: mean difference %.3g of the mean %.4g: %.2f standard errors\n", what, mean,
           e->wantSum / e->checked, fabs(mean) / se);
    assert_true(fabs(mean) <= 4.0 * se + tolerance * e->wantSum / e->checked);
}

// disk_want's arguments.
typedef struct disk_want_args {
    const struct disk_case *disk;
    double L, alpha;
    int n;
} disk_want_args;
static double disk_want_of_args(const void *arg, const double p[3], bool *skip)
{
    const disk_want_args *a = arg;
    return disk_want(a->disk, a->L, a->alpha, p, a->n, skip);
}

static const disk_case disk_cases[] = {
    {{-0.4, 0.5, 1.0}, {0.0, 0.0, -1.0}, 0.4, false, 0.0, {0.0, 0.0, 0.0}},            // facing the plane
    {{0.3, 0.0, 0.6}, {0.6, 0.0, -0.8}, 0.35, false, 0.0, {0.0, 0.0, 0.0}},            // tilted
    {{0.2, 0.3, 0.15}, {0.0, 0.8, -0.6}, 0.4, true, 0.0, {0.0, 0.0, 0.0}},             // two-sided, the plane cuts it
    // ellipses (disk_radius2): facing the plane, tilted, two-sided and cut by the plane
    {{-0.4, 0.5, 1.0}, {0.0, 0.0, -1.0}, 0.6, false, 0.2, {0.8, 0.6, 0.0}},
    {{0.3, 0.0, 0.6}, {0.6, 0.0, -0.8}, 0.2, false, 0.45, {0.8, 0.0, 0.6}},
    {{0.2, 0.3, 0.15}, {0.0, 0.8, -0.6}, 0.6, true, 0.25, {1.0, 0.0, 0.0}},
};

// A Lambertian plane under each disk case: the LTC pass (exact but for float rounding: the
// disk's cone is a closed form; where the horizon cuts it, its clipped 12-gon) and the octagon
// it replaces, against the disk's quadrature; the Monte Carlo pass's mean within 4 standard
// errors. The disk must beat the octagon.
static void disk_lambert(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0;
    const double bound[] = {2e-4, 2e-4, 1e-3, 2e-4, 5e-4, 1e-3}; // of the peak; measured 4.9e-5, 5.4e-5,
                                               // 5.3e-4 (the quadrature's own error is about 5e-5); the
                                               // ellipses 5.4e-5, 2.4e-4 (the same with 160^2 cells: the
                                               // elliptic cone in float, seen obliquely), 8.6e-4
    // The quadrature against a closed form: under the centre of an ellipse (half-axes a, b) that
    // faces the plane from height h, the Lambert form factor is ab / sqrt((a^2 + h^2)(b^2 + h^2))
    // (the disk's r^2 / (r^2 + h^2) when a = b: int of R(phi)^2 / (h^2 + R(phi)^2) dphi / 2 pi with
    // 1 / R^2 = cos^2 / a^2 + sin^2 / b^2 is 1 / sqrt((1 + h^2 / a^2)(1 + h^2 / b^2))).
    {
        const disk_case *c = &disk_cases[3];
        double a = c->radius, b = c->radius2, h = c->centre[2], p[3] = {c->centre[0], c->centre[1], 0.0};
        bool skip;
        double closed = 0.8 * L * a * b / sqrt((a * a + h * h) * (b * b + h * h));
        double quad = disk_want(c, L, 0.0, p, 256, &skip);
        printf("ellipse under its centre: quadrature %.6f, closed form %.6f\n", quad, closed);
        assert_true(fabs(quad - closed) <= 1e-4 * closed);
    }
    for (size_t ci = 0; ci < sizeof disk_cases / sizeof disk_cases[0]; ++ci) {
        const disk_case *c = &disk_cases[ci];
        double errs[2] = {0, 0}, means[2] = {0, 0}, peak = 0.0;
        double *wants = plane_wants(0, 2, disk_want_of_args, &(disk_want_args){c, L, 0.0, 64});
        // the disk (LTC), the octagon (LTC), the disk (Monte Carlo), the disk on a BLEND plane of
        // alpha 1 (the forward pass, LTC)
        for (int kind = 0; kind < 4; ++kind) {
            rtpbr_light_desc lights[4] = {disk_desc(c, L, kind == 1)};
            for (int l = 1; l < 4; ++l)
                lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
            rtpbr_render_desc desc = kind == 2 ? (rtpbr_render_desc){.mc_samples = 16, .mc_seed = 5} : (rtpbr_render_desc){0};
            rtpbr_material_desc material = test_lambert_material;
            if (kind == 3) material.alpha_mode = RTPBR_ALPHA_BLEND, material.alpha = 1.0f;
            float *px = render_plane(ctx, &material, lights, &desc);
            plane_errors e = measure_plane(px, wants);
            double worst = e.worst;
            int checked = e.checked;
            peak = fmax(peak, e.peak);
            assert_true(checked > W * H / 10);
            if (kind == 3) {
                // (the forward pass is a full variant: where the horizon cuts the disk, the cap of
                // its vector, measured 0.0178; for the 0.6 x 0.25 ellipse 0.0362: a round cap
                // stands for an elongated shape)
                printf("disk %zu, BLEND (forward pass): largest error %.3g of the peak\n", ci, worst / peak);
                assert_true(worst / peak <= (c->two_sided ? (c->radius2 > 0.0 ? 0.05 : 0.025) : bound[ci]));
            } else if (kind < 2) {
                errs[kind] = worst / peak;
                means[kind] = e.errSum / e.wantSum;
                printf("disk %zu (r %.2g, %.2g)%s, %s: %d pixels, largest error %.3g of the peak %.4g, mean |error| %.3g of "
                       "the mean\n", ci, c->radius, c->radius2 > 0.0 ? c->radius2 : c->radius, c->two_sided ? ", two-sided, cut by the plane" : "",
                       kind ? "its octagon" : "the disk, LTC pass", checked, worst / peak, peak, means[kind]);
            } else {
                char what[64];
                snprintf(what, sizeof what, "disk %zu", ci);
                check_mc_mean(&e, 1e-4, what);
            }
            free(px);
        }
        free(wants);
        assert_true(errs[0] <= bound[ci]);
        // The disk beats the octagon it replaces, on average and at its worst pixel (where the
        // horizon cuts it: 5.3e-4 of the peak against the octagon's 7.8e-3; with the lobes'
        // 12-gon for its diffuse vector it was 9.0e-3)
        assert_true(means[0] < means[1]);
        assert_true(errs[0] < errs[1]);
    }
}

// A GGX metal plane (F = 1, multiple scattering off) under the disks: the LTC pass's error is
// the LTC fit's (stated, measured), the Monte Carlo pass's mean within 4 standard errors.
static void disk_ggx(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0;
    const struct {
        double roughness, alpha, bound_ltc;
        size_t disk;
        bool full; // a full-variant material (anisotropy 1e-4: alpha_t = alpha + 6e-9)
    } cases[] = {
        {0.625, 0.390625, 0.02, 0, false}, // measured 0.0142
        {0.25, 0.0625, 0.005, 0, false},   // 0.0025
        {0.25, 0.0625, 0.004, 1, false},   // 0.0015
        {0.25, 0.0625, 0.02, 2, false},    // 0.0139: the horizon cuts it (its 12-gon, clipped)
        {0.25, 0.0625, 0.005, 0, true},    // 0.0025
        {0.25, 0.0625, 0.02, 2, true},     // 0.0142: the cap of its vector (the full variant's proxy)
        // ellipses (disk_radius2)
        {0.625, 0.390625, 0.02, 3, false}, // 0.0151
        {0.25, 0.0625, 0.004, 4, false},   // 0.0020
        {0.25, 0.0625, 0.045, 5, false},   // 0.0312: the horizon cuts it (its 12-gon, clipped)
        {0.25, 0.0625, 0.005, 3, true},    // 0.0023
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const disk_case *c = &disk_cases[cases[i].disk];
        const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f,
                                           .roughness = (float)cases[i].roughness,
                                           .anisotropy_strength = cases[i].full ? 1e-4f : 0.0f};
        rtpbr_light_desc lights[4] = {disk_desc(c, L, false)};
        for (int l = 1; l < 4; ++l)
            lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
        const rtpbr_render_desc descs[2] = {{.multiscatter = RTPBR_MULTISCATTER_OFF},
                                            {.multiscatter = RTPBR_MULTISCATTER_OFF, .mc_samples = 64, .mc_seed = 9}};
        double *wants = plane_wants(1, 3, disk_want_of_args, &(disk_want_args){c, L, cases[i].alpha, 128});
        for (int pass = 0; pass < 2; ++pass) {
            if (pass == 1 && cases[i].full) continue; // (the Monte Carlo pass has no variants)
            float *px = render_plane(ctx, &metal, lights, &descs[pass]);
            plane_errors e = measure_plane(px, wants);
            assert_true(e.checked > W * H / 20);
            char what[96];
            snprintf(what, sizeof what, "GGX alpha %.4g under disk %zu%s", cases[i].alpha, cases[i].disk,
                     cases[i].full ? ", full variant" : "");
            if (pass == 0) {
                printf("%s, LTC pass: %d pixels, largest error %.3g of the peak %.4g, mean |error| %.3g of the mean %.4g "
                       "(bound %.3g of the peak)\n", what, e.checked, e.worst / e.peak, e.peak, e.errSum / e.wantSum,
                       e.wantSum / e.checked, cases[i].bound_ltc);
                assert_true(e.worst <= cases[i].bound_ltc * e.peak);
            } else {
                check_mc_mean(&e, 1e-4, what);
            }
            free(px);
        }
        free(wants);
    }
}

// Where the occluder of `shadows` stands between p and disk c (wholly above the occluder): 1
// when every ray from p to the disk's rim (64 of them) passes through the occluder's square 0.01
// inside its edges (the rays to the disk fill the cone over its rim, whose cross-section at the
// occluder's height is convex, as the square), 0 when none comes within 0.01 of it (nor the
// centre's), -1 in between (the penumbra).
static int disk_umbra(const disk_case *c, const double p[3])
{
    double t1[3], t2[3], r1, r2;
    disk_axes(c, t1, t2, &r1, &r2);
    double toCentre[3] = {c->centre[0] - p[0], c->centre[1] - p[1], c->centre[2] - p[2]};
    double cl = sqrt(dot3(toCentre, toCentre));
    for (int k = 0; k < 3; ++k) toCentre[k] /= cl;
    int inside = 0, outside = occluder_depth(p, toCentre) < -0.01 ? 1 : 0;
    for (int j = 0; j < 64; ++j) {
        double phi = 2.0 * M_PI * j / 64, w[3];
        for (int k = 0; k < 3; ++k) w[k] = c->centre[k] + r1 * cos(phi) * t1[k] + r2 * sin(phi) * t2[k] - p[k];
        double wl = sqrt(dot3(w, w));
        for (int k = 0; k < 3; ++k) w[k] /= wl;
        double depth = occluder_depth(p, w);
        inside += depth > 0.01;
        outside += depth < -0.01;
    }
    return inside == 64 ? 1 : outside == 65 ? 0 : -1;
}

// Shadows of a disk light (r 0.2 at height 1.5, facing down), as sphere_shadow's: 0 in the
// umbra, the disk's quadrature where nothing is in the way, the denoiser off.
static const double disk_shadow_L = 5.0;
static int disk_umbra_of(const void *light, const double p[3]) { return disk_umbra(light, p); }
static double disk_want_of(const void *light, const double p[3])
{
    bool skip;
    return disk_want(light, disk_shadow_L, 0.0, p, 32, &skip);
}

static void disk_shadow(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const disk_case c = {{-1.0, 0.5, 1.5}, {0.0, 0.0, -1.0}, 0.2, false, 0.0, {0.0, 0.0, 0.0}};
    rtpbr_light_desc lights[4] = {disk_desc(&c, disk_shadow_L, false)};
    for (int l = 1; l < 4; ++l)
        lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
    check_shadows(ctx, lights, &c, disk_umbra_of, disk_want_of, "disk");
}

// Bad disks are refused with a message: a zero, negative, NaN or too large radius, a zero or NaN
// normal, a NaN centre, negative emission, an ellipse's bad second half-axis or axis; an unknown
// type.
static void bad_disks(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const rtpbr_light_desc bad[] = {
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = -1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = NAN, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1e20f, .emission = {1, 1, 1}}, // pi r^2: no float
        {.type = RTPBR_LIGHT_DISK, .radius = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, NAN, -1}, .radius = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .position = {NAN, 0, 0}, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {-1, 1, 1}},
        // ellipses: a negative or NaN second half-axis, an axis zero, NaN or along the normal
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}, .disk_radius2 = -0.5f,
         .disk_axis = {1, 0, 0}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}, .disk_radius2 = NAN,
         .disk_axis = {1, 0, 0}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}, .disk_radius2 = 0.5f},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}, .disk_radius2 = 0.5f,
         .disk_axis = {NAN, 0, 0}},
        {.type = RTPBR_LIGHT_DISK, .direction = {0, 0, -1}, .radius = 1.0f, .emission = {1, 1, 1}, .disk_radius2 = 0.5f,
         .disk_axis = {0, 0, 3}},
        {.type = (rtpbr_light_type)6, .emission = {1, 1, 1}}, // (5: RTPBR_LIGHT_TUBE)
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        rtpbr_result result = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.lights = &bad[i], .light_count = 1}, &scene);
        if (result != RTPBR_ERROR_INVALID_ARGUMENT) fail_msg("bad disk %zu: result %d", i, (int)result);
        assert_null(scene);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        test_env_shared_case(lambert_plane),
        test_env_shared_case(each_light_counts),
        test_env_shared_case(ggx_plane),
        test_env_shared_case(anisotropic_plane),
        test_env_shared_case(shadows),
        test_env_shared_case(bad_lights),
        test_env_shared_case(sun_disk),
        test_env_shared_case(sphere_light),
        test_env_shared_case(sphere_ggx),
        test_env_shared_case(sphere_shadow),
        test_env_shared_case(disk_lambert),
        test_env_shared_case(disk_ggx),
        test_env_shared_case(disk_shadow),
        test_env_shared_case(bad_disks),
    };
    return test_env_group(tests);
}
