// The smallest host program of an installed rtpbr, built three ways by tests/consumers
// (pkg-config, CMake find_package, meson subproject): renders one 32 x 32 frame headless and
// checks the centre pixel against Lambert's closed-form irradiance of the light (computed
// here, independently of the library), within 1%. Exit 0: pass; 1: wrong pixel; 2: rtpbr error.
//   host [--validation]
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <rtpbr/rtpbr.h>

enum { W = 32, H = 32 };

// Lambert's formula (Lambert 1760; Arvo 1995): the form factor of a polygon seen from x with
// normal n, (1 / 2 pi) |sum_i theta_i (n . g_i)|, g_i the unit normal of the plane through x
// and edge i, theta_i the angle the edge subtends.
static double form_factor(const double x[3], const double n[3], const float (*v)[3], unsigned count)
{
    double sum = 0.0;
    for (unsigned i = 0; i < count; ++i) {
        const float *p = v[i], *q = v[(i + 1) % count];
        double a[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]}, b[3] = {q[0] - x[0], q[1] - x[1], q[2] - x[2]};
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (cl > 0.0)
            sum += atan2(cl, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / cl;
    }
    return fabs(sum) / (2.0 * 3.14159265358979323846);
}

int main(int argc, char **argv)
{
    int validation = argc > 1 && strcmp(argv[1], "--validation") == 0;
    if (rtpbr_version() != RTPBR_VERSION) {
        fprintf(stderr, "host: header version %u.%u.%u, library 0x%x\n", RTPBR_VERSION_MAJOR,
                RTPBR_VERSION_MINOR, RTPBR_VERSION_PATCH, rtpbr_version());
        return 2;
    }
    // A Lambertian plane z = 0 (albedo 0.8, no specular lobe) under a two-sided square light at
    // z = 1, seen straight down from z = 3.
    const float plane[12] = {-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    rtpbr_material_desc material = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 1.0f, .flags = RTPBR_MATERIAL_NO_SPECULAR};
    rtpbr_mesh_desc mesh = {.positions = plane, .indices = indices, .vertex_count = 4, .index_count = 6};
    rtpbr_light_desc light = {.vertices = {{-0.5f, -0.5f, 1.0f}, {0.5f, -0.5f, 1.0f}, {0.5f, 0.5f, 1.0f}, {-0.5f, 0.5f, 1.0f}},
                              .vertex_count = 4, .emission = {3.0f, 2.0f, 1.0f}, .two_sided = 1};
    rtpbr_camera_desc camera = {.position = {0.0f, 0.0f, 3.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f};

    rtpbr_context *ctx = NULL;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_renderer *renderer = NULL;
    static float pixels[W * H * 4];
    rtpbr_result res = rtpbr_context_create(&(rtpbr_context_desc){.validation = validation}, &ctx);
    if (res == RTPBR_SUCCESS)
        res = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                  .materials = &material, .material_count = 1,
                                                                  .lights = &light, .light_count = 1,
                                                                  .cameras = &camera, .camera_count = 1},
                                     &scene);
    if (res == RTPBR_SUCCESS)
        res = rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = W, .height = H}, &renderer);
    if (res == RTPBR_SUCCESS)
        res = rtpbr_render(renderer, scene, &(rtpbr_render_desc){0});
    if (res == RTPBR_SUCCESS)
        res = rtpbr_read_radiance(renderer, pixels, sizeof pixels);
    unsigned messages = ctx ? rtpbr_context_validation_message_count(ctx) : 0;
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    if (res != RTPBR_SUCCESS) {
        fprintf(stderr, "host: %s\n", rtpbr_result_string(res));
        return 2;
    }
    if (messages) {
        fprintf(stderr, "host: %u validation messages\n", messages);
        return 1;
    }

    // Pixel (W/2, H/2) looks through its centre at the plane point (tan(fov/2) * 3 / H, -the same, 0)
    // (the documented pinhole: +Y up, square pixels).
    double step = tan(0.5 * camera.yfov) * 3.0 * 2.0 / H;
    double x[3] = {0.5 * step, -0.5 * step, 0.0}, n[3] = {0.0, 0.0, 1.0};
    double ff = form_factor(x, n, light.vertices, 4);
    const float *got = pixels + 4 * ((H / 2) * W + W / 2);
    int ok = 1;
    for (int c = 0; c < 3; ++c) {
        double expect = 0.8 * light.emission[c] * ff;
        printf("host: channel %d: rendered %.6f, Lambert's formula %.6f\n", c, got[c], expect);
        ok = ok && fabs(got[c] - expect) <= 0.01 * expect;
    }
    printf("host: rtpbr %u.%u.%u %s\n", RTPBR_VERSION_MAJOR, RTPBR_VERSION_MINOR, RTPBR_VERSION_PATCH,
           ok ? "ok" : "WRONG PIXEL");
    return ok ? 0 : 1;
}
