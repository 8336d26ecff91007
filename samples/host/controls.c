// rtpbr-sample-host's controls (host.h, sh_controls): the edits a key makes to the host's own
// scene. The lights changed here reach rtpbr through rtpbr_light_set_update at the next frame
// (sh_record_frame): no pipeline, descriptor set or buffer is made for an edit.
#include "host.h"

#include <math.h>
#include <string.h>

const char sh_controls_help[] =
    "  mouse: left drag orbit, right drag pan, wheel zoom\n"
    "  Home            back to the mesh file's camera\n"
    "  Tab             select the next light\n"
    "  Left / Right    move the light along world X -/+ (0.1 m)\n"
    "  Up / Down       along world Z -/+\n"
    "  PgDn / PgUp     along world Y -/+\n"
    "  - / =           light radiance -/+ (x 1.25)\n"
    "  C               next light colour (its R + G + B kept)\n"
    "  A               animate every light (a circle and a hue turn per frame) on/off\n"
    "  E / D           exposure +/- half a stop\n"
    "  P               screenshot to rtpbr-sample-host-NNN.png\n"
    "  H               this help\n"
    "  Esc             quit\n";

void sh_controls_init(sh_controls *c, const sh_scene *s, float exposure)
{
    memset(c, 0, sizeof *c);
    c->home = s->camera;
    c->exposure = exposure;
}

static void light_move(sh_light *l, int axis, float step)
{
    for (int k = 0; k < 4; ++k) l->corners[k][axis] += step;
}

// Colours C cycles through (relative R, G, B; the light's R + G + B is kept).
static const float palette[6][3] = {{1.0f, 1.0f, 1.0f}, {1.0f, 0.8f, 0.6f}, {0.6f, 0.8f, 1.0f},
                                    {1.0f, 0.3f, 0.3f}, {0.3f, 1.0f, 0.3f}, {0.3f, 0.3f, 1.0f}};

int sh_controls_key(sh_controls *c, sh_scene *s, char key)
{
    sh_light *l = s->light_count ? &s->lights[c->light % s->light_count] : NULL;
    switch (key) {
    case 't': c->light = s->light_count ? (c->light + 1) % s->light_count : 0; return 0;
    case 'h': s->camera = c->home; return 0;
    case 'E': c->exposure = fminf(30.0f, c->exposure + SH_EXPOSURE_STEP); return 0;
    case 'D': c->exposure = fmaxf(-30.0f, c->exposure - SH_EXPOSURE_STEP); return 0;
    case 'A': c->animate = !c->animate; return 0;
    case 'l': case 'r': case 'u': case 'd': case 'p': case 'n':
        if (l) {
            int axis = key == 'l' || key == 'r' ? 0 : key == 'p' || key == 'n' ? 1 : 2;
            light_move(l, axis, key == 'r' || key == 'd' || key == 'p' ? SH_MOVE_STEP : -SH_MOVE_STEP);
        }
        return 0;
    case '-': case '=':
        if (l)
            for (int i = 0; i < 3; ++i) l->radiance[i] *= key == '=' ? 1.25f : 1.0f / 1.25f;
        return 0;
    case 'C':
        if (l) {
            uint32_t *k = &c->colour[c->light % s->light_count];
            *k = (*k + 1) % 6;
            float sum = l->radiance[0] + l->radiance[1] + l->radiance[2];
            float psum = palette[*k][0] + palette[*k][1] + palette[*k][2];
            for (int i = 0; i < 3; ++i) l->radiance[i] = palette[*k][i] * sum / psum;
        }
        return 0;
    default: return 1;
    }
}

void sh_controls_frame(sh_controls *c, sh_scene *s)
{
    if (!c->animate) return;
    // Each light on a circle of radius 0.25 m in its plane of constant Y (phase by index), and
    // its colour turned about the grey axis by 2 degrees (Rodrigues; R + G + B is kept, a
    // component that would go negative is clipped to 0).
    const float r = 0.25f, dphi = 0.05f, turn = 2.0f * 3.14159265f / 180.0f;
    const float ct = cosf(turn), st = sinf(turn), k = 1.0f / sqrtf(3.0f);
    for (uint32_t i = 0; i < s->light_count; ++i) {
        float phi = (float)c->frame * dphi + (float)i;
        float dx = r * (cosf(phi + dphi) - cosf(phi)), dz = r * (sinf(phi + dphi) - sinf(phi));
        sh_light *l = &s->lights[i];
        light_move(l, 0, dx);
        light_move(l, 2, dz);
        const float *v = l->radiance;
        float g = k * (v[0] + v[1] + v[2]);                                          // k . v
        float x[3] = {k * (v[2] - v[1]), k * (v[0] - v[2]), k * (v[1] - v[0])};     // k x v (k = (1,1,1)/sqrt 3)
        float out[3];
        for (int j = 0; j < 3; ++j) out[j] = fmaxf(0.0f, v[j] * ct + x[j] * st + k * g * (1.0f - ct));
        memcpy(l->radiance, out, sizeof out);
    }
    ++c->frame;
}

// The camera as (distance, yaw, pitch) about its target; yaw about +Y from +Z.
static void to_orbit(const sh_camera *cam, float *distance, float *yaw, float *pitch)
{
    float d[3] = {cam->position[0] - cam->target[0], cam->position[1] - cam->target[1], cam->position[2] - cam->target[2]};
    *distance = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    *yaw = atan2f(d[0], d[2]);
    *pitch = *distance > 0.0f ? asinf(fmaxf(-1.0f, fminf(1.0f, d[1] / *distance))) : 0.0f;
}

static void from_orbit(sh_camera *cam, float distance, float yaw, float pitch)
{
    cam->position[0] = cam->target[0] + distance * cosf(pitch) * sinf(yaw);
    cam->position[1] = cam->target[1] + distance * sinf(pitch);
    cam->position[2] = cam->target[2] + distance * cosf(pitch) * cosf(yaw);
}

void sh_camera_orbit(sh_camera *cam, float dyaw, float dpitch)
{
    float distance, yaw, pitch;
    to_orbit(cam, &distance, &yaw, &pitch);
    from_orbit(cam, distance, yaw + dyaw, fminf(1.55f, fmaxf(-1.55f, pitch + dpitch)));
}

void sh_camera_pan(sh_camera *cam, float right, float up)
{
    float distance, yaw, pitch;
    to_orbit(cam, &distance, &yaw, &pitch);
    // The view's right is (cos yaw, 0, -sin yaw); up is world Y (as the viewer pans).
    float move[3] = {distance * right * cosf(yaw), distance * up, -distance * right * sinf(yaw)};
    for (int i = 0; i < 3; ++i) cam->target[i] += move[i], cam->position[i] += move[i];
}

void sh_camera_zoom(sh_camera *cam, float factor)
{
    float distance, yaw, pitch;
    to_orbit(cam, &distance, &yaw, &pitch);
    from_orbit(cam, fmaxf(0.05f, distance * factor), yaw, pitch);
}
