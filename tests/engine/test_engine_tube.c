#define _DEFAULT_SOURCE // M_PI
// Engine: tube (capsule) lights, RTPBR_LIGHT_TUBE (issue 30), against a double-precision
// quadrature over the capsule's visible surface, computed here independently of the shader
// library: Lo(p) = L int_visible f(wo, w) (N.w) cos_y / d^2 dA over the cylinder (radius r,
// length len) and its two hemispherical caps, a surface point y (outward normal n) counted where
// it faces p (the capsule is convex: dot(n, p - y) > 0) and lies above p's horizon.
// A Lambertian plane (f = 0.8 / pi) and a GGX metal plane (single scattering, F = 1) under a
// tube in the LTC pass, the Monte Carlo pass (mean within 4 standard errors) and the forward
// pass; a tube the plane cuts (no light from below it); a tube of length 0 against the sphere
// light of the same radius and radiance; no pixel above the radiance x albedo; shadows (umbra 0,
// lit pixels as without shadows); bad tubes refused.
#include <stdlib.h>

#include "engine_test.h"

enum { W = 120, H = 90 };

static const rtpbr_camera_desc camera = {.position = {0.3f, -0.2f, 3.0f}, .target = {0.2f, 0.0f, 0.0f}, .yfov = 1.2f,
                                         .znear = 0.1f, .zfar = 100.0f};

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Smith's height-correlated GGX (isotropic) times D over 4 N.L N.V (F = 1).
static double ggx_lambda(const double w[3], double a)
{
    double t2 = (w[0] * w[0] + w[1] * w[1]) / (w[2] * w[2]);
    return (-1.0 + sqrt(1.0 + a * a * t2)) / 2.0;
}
static double ggx_single(const double wo[3], const double wi[3], double alpha)
{
    double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    double hl = sqrt(dot3(h, h));
    for (int k = 0; k < 3; ++k) h[k] /= hl;
    double q = (h[0] * h[0] + h[1] * h[1]) / (alpha * alpha) + h[2] * h[2];
    double D = 1.0 / (M_PI * alpha * alpha * q * q);
    return D / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha)) / (4.0 * wo[2] * wi[2]);
}

typedef struct tube_case {
    double centre[3], axis[3], length, radius; // axis unit
} tube_case;

static const tube_case tube_cases[] = {
    {{-0.3, 0.4, 0.8}, {0.957826, 0.287348, 0.0}, 1.2, 0.12},      // level, above the plane
    {{0.4, -0.2, 0.6}, {0.303046, 0.505076, 0.808122}, 0.8, 0.15}, // tilted
    {{0.2, 0.3, 0.0}, {0.890871, -0.445435, 0.089087}, 1.0, 0.2},  // half below the plane: it cuts it
};

// An orthonormal t1, t2 across unit a.
static void across(const double a[3], double t1[3], double t2[3])
{
    double h[3] = {fabs(a[2]) < 0.9 ? 0.0 : 1.0, 0.0, fabs(a[2]) < 0.9 ? 1.0 : 0.0};
    t1[0] = h[1] * a[2] - h[2] * a[1], t1[1] = h[2] * a[0] - h[0] * a[2], t1[2] = h[0] * a[1] - h[1] * a[0];
    double l = sqrt(dot3(t1, t1));
    for (int k = 0; k < 3; ++k) t1[k] /= l;
    t2[0] = a[1] * t1[2] - a[2] * t1[1], t2[1] = a[2] * t1[0] - a[0] * t1[2], t2[2] = a[0] * t1[1] - a[1] * t1[0];
}

// One surface cell: point y, outward normal nrm, area dA; its term added to *sum.
static void add_cell(const double y[3], const double nrm[3], double dA, const double p[3], const double wo[3],
                     double alpha, double *sum, double *nearest)
{
    double w[3] = {y[0] - p[0], y[1] - p[1], y[2] - p[2]};
    double d2 = dot3(w, w), d = sqrt(d2);
    *nearest = fmin(*nearest, d);
    for (int k = 0; k < 3; ++k) w[k] /= d;
    double cosY = -dot3(nrm, w); // > 0: the cell faces p
    if (w[2] <= 0.0 || cosY <= 0.0) return;
    double f = alpha > 0.0 ? ggx_single(wo, w, alpha) : 0.8 / M_PI;
    *sum += f * w[2] * cosY / d2 * dA;
}

// The expected radiance at p toward the camera (n x n cells on the cylinder and on each cap);
// skip where p is within 0.05 of the capsule (or inside it).
static double tube_want(const tube_case *c, double L, double alpha, const double p[3], int n, bool *skip)
{
    double t1[3], t2[3], r = c->radius, len = c->length;
    across(c->axis, t1, t2);
    double wo[3] = {camera.position[0] - p[0], camera.position[1] - p[1], camera.position[2] - p[2]};
    double ol = sqrt(dot3(wo, wo));
    for (int k = 0; k < 3; ++k) wo[k] /= ol;
    double sum = 0.0, nearest = 1e30;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / n, cp = cos(phi), sp = sin(phi), nrm[3], y[3];
            // the cylinder: height s, area r dphi ds
            double s = ((i + 0.5) / n - 0.5) * len;
            for (int k = 0; k < 3; ++k) {
                nrm[k] = cp * t1[k] + sp * t2[k];
                y[k] = c->centre[k] + s * c->axis[k] + r * nrm[k];
            }
            if (len > 0.0) add_cell(y, nrm, r * (2.0 * M_PI / n) * (len / n), p, wo, alpha, &sum, &nearest);
            // the caps: z uniform in [0, 1] is uniform by area on a hemisphere (Archimedes),
            // each cell 2 pi r^2 / n^2
            double z = (i + 0.5) / n, q = sqrt(1.0 - z * z);
            for (int e = -1; e <= 1; e += 2) {
                for (int k = 0; k < 3; ++k) {
                    nrm[k] = q * (cp * t1[k] + sp * t2[k]) + e * z * c->axis[k];
                    y[k] = c->centre[k] + e * 0.5 * len * c->axis[k] + r * nrm[k];
                }
                add_cell(y, nrm, 2.0 * M_PI * r * r / ((double)n * n), p, wo, alpha, &sum, &nearest);
            }
        }
    // p's distance from the segment
    double v[3] = {p[0] - c->centre[0], p[1] - c->centre[1], p[2] - c->centre[2]};
    double h = fmax(-0.5 * len, fmin(0.5 * len, dot3(v, c->axis)));
    for (int k = 0; k < 3; ++k) v[k] -= h * c->axis[k];
    *skip = nearest < 0.05 || sqrt(dot3(v, v)) < r + 0.05;
    return L * sum;
}

static rtpbr_light_desc tube_desc(const tube_case *c, double L)
{
    rtpbr_light_desc d = {.type = RTPBR_LIGHT_TUBE, .radius = (float)c->radius, .length = (float)c->length,
                          .emission = {(float)L, (float)L, (float)L}};
    for (int k = 0; k < 3; ++k) d.position[k] = (float)c->centre[k], d.direction[k] = (float)(2.0 * c->axis[k]);
    return d;
}

static const float plane_normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static const float plane_tangents[16] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
// The plane z = 0 under lights[0] (lights 1..3 dark directional lights), rendered W x H.
static float *render_plane(rtpbr_context *ctx, const rtpbr_material_desc *material, const rtpbr_light_desc *light,
                           const rtpbr_render_desc *desc)
{
    float plane[12];
    square_positions(4.0f, 0.0f, plane);
    rtpbr_mesh_desc mesh = {.positions = plane, .normals = plane_normals, .tangents = plane_tangents,
                            .indices = square_indices, .vertex_count = 4, .index_count = 6};
    rtpbr_light_desc lights[4] = {*light};
    for (int l = 1; l < 4; ++l)
        lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
    rtpbr_gpu_scene *scene = test_mesh_scene(ctx, &mesh, material, lights, 4, &camera);
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *px = test_render_radiance(r, scene, desc, W, H);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    return px;
}

typedef struct plane_errors {
    double worst, peak, errSum, sum, sum2, wantSum, most;
    int checked;
} plane_errors;
// tube_want at every step-th pixel (from offset) on the plane, NAN where not checked.
static double *plane_wants(int offset, int step, const tube_case *c, double L, double alpha, int n)
{
    double *wants = malloc(sizeof(double) * W * H);
    assert_non_null(wants);
    for (int i = 0; i < W * H; ++i) wants[i] = NAN;
    for (int y = offset; y < H; y += step)
        for (int x = offset; x < W; x += step) {
            double p[3];
            bool skip;
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double want = tube_want(c, L, alpha, p, n, &skip);
            if (!skip) wants[y * W + x] = want;
        }
    return wants;
}
static plane_errors measure_plane(const float *px, const double *wants)
{
    plane_errors e = {0};
    for (int i = 0; i < W * H; ++i) {
        if (isfinite(px[4 * i])) e.most = fmax(e.most, px[4 * i]);
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

// The quadrature against a closed form: a sphere (length 0) of radius r at height h over p,
// Lambert: its form factor r^2 / h^2 (the cap it subtends, wholly above the horizon).
static void quadrature_check(void **state)
{
    (void)state;
    const tube_case sphere = {{0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, 0.0, 0.3};
    const double p[3] = {0.0, 0.0, 0.0};
    bool skip;
    double quad = tube_want(&sphere, 1.0, 0.0, p, 256, &skip), closed = 0.8 * 0.3 * 0.3;
    printf("sphere over p: quadrature %.7f, closed form %.7f\n", quad, closed);
    assert_true(fabs(quad - closed) <= 1e-4 * closed);
}

// A Lambertian plane under each tube: the LTC pass, the Monte Carlo pass and the forward pass
// (a BLEND plane of alpha 1) against the quadrature; nothing above L x 0.8 anywhere.
static void tube_lambert(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0;
    // Of the peak (the LTC and the forward pass alike): measured 4.16e-3, 3.22e-2 (the tilted tube's
    // low end, a radius or two from the plane: ltc_lines.h's ends), 4.50e-2 (cut by the plane),
    // held at about 1.5x. The library's decomposition, not the engine: the Monte Carlo pass, over
    // the capsule itself, agrees with the quadrature within 2.1 standard errors.
    const double bound[] = {6.5e-3, 5e-2, 7e-2};
    const double bound_forward[] = {6.5e-3, 5e-2, 7e-2};
    for (size_t ci = 0; ci < sizeof tube_cases / sizeof tube_cases[0]; ++ci) {
        const tube_case *c = &tube_cases[ci];
        rtpbr_light_desc light = tube_desc(c, L);
        double *wants = plane_wants(0, 2, c, L, 0.0, 64);
        for (int kind = 0; kind < 3; ++kind) { // LTC, Monte Carlo, forward
            rtpbr_render_desc desc = kind == 1 ? (rtpbr_render_desc){.mc_samples = 16, .mc_seed = 5} : (rtpbr_render_desc){0};
            rtpbr_material_desc material = test_lambert_material;
            if (kind == 2) material.alpha_mode = RTPBR_ALPHA_BLEND, material.alpha = 1.0f;
            float *px = render_plane(ctx, &material, &light, &desc);
            plane_errors e = measure_plane(px, wants);
            assert_true(e.checked > W * H / 10);
            char what[64];
            snprintf(what, sizeof what, "tube %zu (L %.2g, r %.2g)", ci, c->length, c->radius);
            if (kind == 1) {
                check_mc_mean(&e, 1e-4, what);
            } else {
                printf("%s, %s: %d pixels, largest error %.3g of the peak %.4g, mean |error| %.3g of the mean; "
                       "brightest pixel %.4g (L x albedo %.4g)\n",
                       what, kind ? "forward pass" : "LTC pass", e.checked, e.worst / e.peak, e.peak,
                       e.errSum / e.wantSum, e.most, 0.8 * L);
                assert_true(e.worst <= (kind ? bound_forward[ci] : bound[ci]) * e.peak);
                assert_true(e.most <= 0.8 * L * (1.0 + 1e-3));
            }
            free(px);
        }
        free(wants);
    }
}

// A GGX metal plane (F = 1, multiple scattering off): the LTC pass's error is the LTC fit's
// (stated, measured), the Monte Carlo pass's mean within 4 standard errors.
static void tube_ggx(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0;
    const struct {
        double roughness, alpha, bound_ltc;
        size_t tube;
    } cases[] = {
        // measured with the tube's parts lit as three lights (area_light.h's AreaLight_AddTube;
        // summed in one lobe, the branch wip/tubeeng2: 0.0242, 0.129, 0.156, 0.142)
        {0.625, 0.390625, 0.036, 0}, // measured 0.0224
        {0.25, 0.0625, 0.2, 0},      // 0.130: a glossy lobe sees the cylinder as its flat quad
        {0.25, 0.0625, 0.16, 1},     // 0.105
        {0.25, 0.0625, 0.2, 2},      // 0.132 (cut by the plane; the library: 0.198 across the horizon)
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const tube_case *c = &tube_cases[cases[i].tube];
        const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f,
                                           .roughness = (float)cases[i].roughness};
        rtpbr_light_desc light = tube_desc(c, L);
        const rtpbr_render_desc descs[2] = {{.multiscatter = RTPBR_MULTISCATTER_OFF},
                                            {.multiscatter = RTPBR_MULTISCATTER_OFF, .mc_samples = 64, .mc_seed = 9}};
        double *wants = plane_wants(1, 3, c, L, cases[i].alpha, 128);
        for (int pass = 0; pass < 2; ++pass) {
            float *px = render_plane(ctx, &metal, &light, &descs[pass]);
            plane_errors e = measure_plane(px, wants);
            assert_true(e.checked > W * H / 20);
            char what[96];
            snprintf(what, sizeof what, "GGX alpha %.4g under tube %zu", cases[i].alpha, cases[i].tube);
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

// A tube of length 0 is the sphere light of its radius and radiance (a point light of radius
// r and intensity L pi r^2): the same pixels within 1e-5 of the peak (Lambert and GGX).
static void zero_length(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0, r = 0.25;
    rtpbr_light_desc tube = {.type = RTPBR_LIGHT_TUBE, .position = {-0.2f, 0.3f, 0.7f}, .direction = {0.3f, 1.0f, 0.2f},
                             .radius = (float)r, .emission = {(float)L, (float)L, (float)L}};
    rtpbr_light_desc sphere = {.type = RTPBR_LIGHT_POINT, .position = {-0.2f, 0.3f, 0.7f}, .radius = (float)r};
    for (int k = 0; k < 3; ++k) sphere.emission[k] = (float)(L * M_PI * r * r);
    const rtpbr_material_desc metal = {.base_color = {1.0f, 1.0f, 1.0f}, .metallic = 1.0f, .roughness = 0.4f};
    const rtpbr_material_desc *materials[2] = {&test_lambert_material, &metal};
    for (int m = 0; m < 2; ++m) {
        float *a = render_plane(ctx, materials[m], &tube, &(rtpbr_render_desc){0});
        float *b = render_plane(ctx, materials[m], &sphere, &(rtpbr_render_desc){0});
        double worst = 0.0, peak = 0.0;
        for (int i = 0; i < W * H; ++i)
            for (int k = 0; k < 3; ++k) {
                worst = fmax(worst, fabs((double)a[4 * i + k] - b[4 * i + k]));
                peak = fmax(peak, b[4 * i + k]);
            }
        printf("length 0 against the sphere, %s: largest difference %.3g of the peak %.4g\n", m ? "GGX" : "Lambert",
               worst / peak, peak);
        assert_true(peak > 0.0);
        assert_true(worst <= 1e-5 * peak);
        free(a);
        free(b);
    }
}

// Shadows: a square occluder (facing down, at z = 0.8) under a small tube. Where every ray from p
// to the capsule's surface (a grid of 16 x 16 cells on each part) passes 0.01 inside the square,
// p is in the umbra: 0; where none comes within 0.01 of it, the shadowed render equals the
// unshadowed one (the ratio estimator is exact where every sample agrees); the penumbra between
// is counted. The denoiser off, the default 4 samples: sampled uniformly over the whole capsule,
// 1 of the 358 umbra pixels drew only points facing away (no estimate: ratio 1, lit); with the
// cylinder's far half mirrored to its near half (shadow.comp), none.
static const double occluder_z = 0.8, occluder_min[2] = {-1.4, 0.1}, occluder_max[2] = {-0.6, 0.9};
static double occluder_depth(const double p[3], const double L[3])
{
    if (!(L[2] > 0.0)) return -1.0;
    double t = (occluder_z - p[2]) / L[2];
    double q[2] = {p[0] + t * L[0], p[1] + t * L[1]};
    double inside = 1e30;
    for (int k = 0; k < 2; ++k) inside = fmin(inside, fmin(q[k] - occluder_min[k], occluder_max[k] - q[k]));
    return inside;
}
static int tube_umbra(const tube_case *c, const double p[3])
{
    enum { n = 16 };
    double t1[3], t2[3];
    across(c->axis, t1, t2);
    int inside = 0, outside = 0, count = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int part = 0; part < 3; ++part) { // the cylinder, the caps
                double phi = (j + 0.5) * 2.0 * M_PI / n, z = (i + 0.5) / n, q = sqrt(1.0 - z * z), y[3];
                for (int k = 0; k < 3; ++k) {
                    double nrm = part == 0 ? cos(phi) * t1[k] + sin(phi) * t2[k]
                                           : q * (cos(phi) * t1[k] + sin(phi) * t2[k]) + (part == 1 ? -z : z) * c->axis[k];
                    double s = part == 0 ? (z - 0.5) * c->length : (part == 1 ? -0.5 : 0.5) * c->length;
                    y[k] = c->centre[k] + s * c->axis[k] + c->radius * nrm - p[k];
                }
                double d = sqrt(dot3(y, y));
                for (int k = 0; k < 3; ++k) y[k] /= d;
                double depth = occluder_depth(p, y);
                inside += depth > 0.01;
                outside += depth < -0.01;
                ++count;
            }
    return inside == count ? 1 : outside == count ? 0 : -1;
}

static void tube_shadow(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const tube_case c = {{-1.0, 0.5, 1.5}, {0.8, 0.6, 0.0}, 0.3, 0.08};
    rtpbr_light_desc lights[4] = {tube_desc(&c, 3.0)};
    for (int l = 1; l < 4; ++l)
        lights[l] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .angular_diameter = -1.0f};
    float plane[12];
    float occluder[12] = {(float)occluder_min[0], (float)occluder_min[1], (float)occluder_z,
                          (float)occluder_max[0], (float)occluder_min[1], (float)occluder_z,
                          (float)occluder_max[0], (float)occluder_max[1], (float)occluder_z,
                          (float)occluder_min[0], (float)occluder_max[1], (float)occluder_z};
    static const uint32_t down[6] = {0, 2, 1, 0, 3, 2};
    rtpbr_mesh_desc meshes[2] = {test_square_mesh(4.0f, 0.0f, plane),
                                 {.positions = occluder, .indices = down, .vertex_count = 4, .index_count = 6}};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = 2,
                                                                     .materials = &test_lambert_material, .material_count = 1,
                                                                     .lights = lights, .light_count = 4, .cameras = &camera,
                                                                     .camera_count = 1});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *on = test_render_radiance(
        r, scene, &(rtpbr_render_desc){.shadows = RTPBR_SHADOWS_ON, .shadow_denoiser = RTPBR_SHADOW_DENOISER_OFF}, W, H);
    float *off = test_render_radiance(r, scene, &(rtpbr_render_desc){.shadows = RTPBR_SHADOWS_OFF}, W, H);
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
            int kind = tube_umbra(&c, p);
            if (kind < 0) {
                ++penumbra;
                continue;
            }
            int i = y * W + x;
            double want = kind == 1 ? 0.0 : off[4 * i];
            peak = fmax(peak, off[4 * i]);
            worst = fmax(worst, fabs(on[4 * i] - want));
            umbra += kind == 1;
            lit += kind == 0;
        }
    printf("tube shadows: %d pixels in the umbra, %d lit, %d in the penumbra; largest error %.3g of the peak %.4g\n",
           umbra, lit, penumbra, worst / peak, peak);
    assert_true(umbra > 50 && lit > W * H / 3 && penumbra > 100);
    assert_true(worst <= 1e-3 * peak);
    free(on);
    free(off);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// A tube with a range (issue 30): its radiance windowed by W = clamp(1 - (d / range)^4, 0, 1),
// d the distance from its centre (KHR_lights_punctual's window, as a sphere's from its centre;
// the oracle's capsules alike). Tube 0 with range 1.5 m over the Lambertian plane: the LTC pass
// against the quadrature times W (within tube_lambert's bound for that tube: the window only
// scales the reference), the Monte Carlo pass's mean within 4 standard errors, and every pixel
// beyond the range exactly 0 (the window; the cull drops those tiles). Without the range the
// same pixels are lit (so the window is what darkens them).
static void tube_range(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const double L = 3.0, range = 1.5;
    const tube_case *c = &tube_cases[0];
    rtpbr_light_desc light = tube_desc(c, L);
    light.range = (float)range;
    double *wants = plane_wants(0, 2, c, L, 0.0, 64);
    int beyond = 0, beyond_lit = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) {
                wants[y * W + x] = NAN;
                continue;
            }
            double v[3] = {p[0] - c->centre[0], p[1] - c->centre[1], p[2] - c->centre[2]};
            double q = dot3(v, v) / (range * range), window = fmin(fmax(1.0 - q * q, 0.0), 1.0);
            if (!isnan(wants[y * W + x])) wants[y * W + x] *= window;
            if (window == 0.0) wants[y * W + x] = -1.0; // beyond the range: checked apart
        }
    float *unwindowed = NULL;
    for (int kind = 0; kind < 3; ++kind) { // LTC, Monte Carlo, LTC without the range
        rtpbr_render_desc desc = kind == 1 ? (rtpbr_render_desc){.mc_samples = 16, .mc_seed = 7} : (rtpbr_render_desc){0};
        rtpbr_light_desc l = light;
        if (kind == 2) l.range = 0.0f;
        float *px = render_plane(ctx, &test_lambert_material, &l, &desc);
        if (kind == 2) {
            unwindowed = px;
            break;
        }
        double *checked = malloc(sizeof(double) * W * H);
        assert_non_null(checked);
        for (int i = 0; i < W * H; ++i) {
            checked[i] = wants[i] < 0.0 ? NAN : wants[i];
            if (wants[i] < 0.0 && kind == 0) ++beyond, beyond_lit += px[4 * i] != 0.0f;
        }
        plane_errors e = measure_plane(px, checked);
        assert_true(e.checked > W * H / 20);
        if (kind == 1) {
            check_mc_mean(&e, 1e-4, "tube 0 with range 1.5");
        } else {
            printf("tube 0 with range 1.5, LTC pass: %d pixels, largest error %.3g of the peak %.4g; %d pixels beyond "
                   "the range, %d of them not 0\n", e.checked, e.worst / e.peak, e.peak, beyond, beyond_lit);
            assert_true(e.worst <= 6.5e-3 * e.peak);
        }
        for (int i = 0; i < W * H && kind == 1; ++i)
            if (wants[i] < 0.0) assert_true(px[4 * i] == 0.0f);
        free(checked);
        free(px);
    }
    assert_true(beyond > W * H / 10);
    assert_int_equal(beyond_lit, 0);
    int lit_without = 0;
    for (int i = 0; i < W * H; ++i) lit_without += wants[i] < 0.0 && unwindowed[4 * i] > 0.0f;
    printf("tube 0 without its range: %d of those %d pixels lit\n", lit_without, beyond);
    assert_true(lit_without > beyond / 2);
    free(unwindowed);
    free(wants);
}

static void bad_tubes(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const rtpbr_light_desc bad[] = {
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .length = 1.0f, .emission = {1, 1, 1}},                  // radius 0
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = -1.0f, .length = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = NAN, .length = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 1e19f, .length = 1.0f, .emission = {1, 1, 1}}, // area: no float
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 1.0f, .length = 3e38f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = -1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = NAN, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = INFINITY, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .radius = 0.1f, .length = 1.0f, .emission = {1, 1, 1}}, // a zero axis
        {.type = RTPBR_LIGHT_TUBE, .direction = {0, NAN, 1}, .radius = 0.1f, .length = 1.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .position = {NAN, 0, 0}, .direction = {1, 0, 0}, .radius = 0.1f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = 1.0f, .emission = {-1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = 1.0f, .emission = {NAN, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = 1.0f, .range = -2.0f, .emission = {1, 1, 1}},
        {.type = RTPBR_LIGHT_TUBE, .direction = {1, 0, 0}, .radius = 0.1f, .length = 1.0f, .range = NAN, .emission = {1, 1, 1}},
        {.type = (rtpbr_light_type)6, .emission = {1, 1, 1}},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        rtpbr_result result = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.lights = &bad[i], .light_count = 1}, &scene);
        if (result != RTPBR_ERROR_INVALID_ARGUMENT) fail_msg("bad tube %zu: result %d", i, (int)result);
        assert_null(scene);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(quadrature_check),
        test_env_shared_case(zero_length),
        test_env_shared_case(bad_tubes),
        test_env_shared_case(tube_lambert),
        test_env_shared_case(tube_ggx),
        test_env_shared_case(tube_shadow),
        test_env_shared_case(tube_range),
    };
    return test_env_group(tests);
}
