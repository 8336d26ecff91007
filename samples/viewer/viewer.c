// rtpbr-viewer: an interactive area-light viewer. A GLFW window whose Vulkan device the viewer
// creates itself (rtpbr runs embedded in it and records into the swapchain images), an orbit
// camera, Dear ImGui panels (ui.cpp) over the image, editable area (polygons, disks) and
// punctual (KHR_lights_punctual) lights and materials (updated in the engine scene in place), the
// engine's technique toggles, per-pass GPU times, a split view and the live HDR-FLIP against
// an oracle reference image, screenshots.
//   usage: rtpbr-viewer [SCENE.gltf] [--reference REF.exr] [--width W] [--height H] [--no-ui]
//                       [--frames N [--screenshot OUT.png] [--radiance OUT.exr]] [--keys KEYS]
//                       [--validation]
// --keys replays key presses before the first frame (scripted screenshots): upper-case
// letters, digits, [ ] - = as themselves; l r u d = arrow keys, p n = PgUp PgDn, t = Tab,
// h = Home.
#include "app.h"
#include "reference.h"
#include "ui.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// Every key handle_key() takes, named as it is in `--help` (tests/cli checks the two agree).
static const char *const help_text =
    "rtpbr-viewer controls (the panels do the same with the mouse)\n"
    "  mouse: left drag orbit, right drag pan, wheel zoom, left click: select a light or surface\n"
    "  Home            back to the scene's camera\n"
    "  Tab             select the next light (area lights, then punctual lights)\n"
    "  1 / 2 / 3       the keys below move / rotate / scale the light (mode 1 at start;\n"
    "                  a disk's scale is its radius);\n"
    "                  a punctual light: its position / direction (a tube's axis too) / range\n"
    "  Left / Right    along (about) world X -/+\n"
    "  Up / Down       along (about) world Z -/+\n"
    "  PgDn / PgUp     along (about) world Y -/+\n"
    "  [ / ]           polygon light vertex count -/+ (3..8); a spot light: outer cone -/+\n"
    "                  2 degrees\n"
    "  C               next light colour\n"
    "  - / =           light intensity -/+ (x 1.25)\n"
    "  T               light one-/two-sided (area lights: polygons, disks)\n"
    "  I               add a light 1 m above the orbit target: quad, disk, sphere, spot,\n"
    "                  point, directional, tube, ellipse, screen (a quad showing a test card)\n"
    "                  in turn (selected; the panel adds each kind too)\n"
    "  X               remove the selected light\n"
    "  M               select the next material\n"
    "  7 / 8           material roughness -/+\n"
    "  9 / 0           material metallic -/+\n"
    "  K               Kulla-Conty energy compensation on/off\n"
    "  N               NDF GGX / Beckmann\n"
    "  R               lighting pass LTC / Monte Carlo\n"
    "  L               says that the LTC sphere proxy is a build-time shaderlib flag only\n"
    "  E / D           exposure +/- half a stop\n"
    "  O               next tone-mapping operator\n"
    "  S               split view against --reference\n"
    "  F               live HDR-FLIP heat map (with --reference)\n"
    "  U               panels on/off\n"
    "  P               screenshot to rtpbr-viewer-NNN.png\n"
    "  H               this help\n"
    "  Esc             quit\n";

static const char *const usage_text =
    "usage: rtpbr-viewer [SCENE.gltf] [--reference REF.exr] [--width W] [--height H] [--no-ui]\n"
    "                    [--frames N [--screenshot OUT.png] [--radiance OUT.exr]] [--keys KEYS]\n"
    "                    [--validation]\n"
    "An interactive area-light viewer (GLFW window, Vulkan). SCENE.gltf defaults to the bundled\n"
    "showcase scene.\n"
    "  --reference REF.exr  an oracle image of the same view and size: split view and live FLIP\n"
    "  --width W            window width (1..16384; default 960)\n"
    "  --height H           window height (1..16384; default 720)\n"
    "  --no-ui              no panels (image tests compare the scene alone)\n"
    "  --frames N           render N frames, then exit\n"
    "  --screenshot OUT.png with --frames: the last frame as presented\n"
    "  --radiance OUT.exr   with --frames: the last frame's linear radiance (float RGB)\n"
    "  --keys KEYS          replay key presses before the first frame: upper-case letters, digits,\n"
    "                       [ ] - = as themselves; l r u d arrows, p n PgUp/PgDn, t Tab, h Home\n"
    "  --validation         Khronos validation layer; any warning or error makes the exit status 1\n"
    "  -h, --help           this text\n";

static void on_log(rtpbr_log_level level, const char *message, void *user)
{
    if (level <= RTPBR_LOG_WARNING) {
        fprintf(stderr, "rtpbr: %s\n", message);
        if (level == RTPBR_LOG_ERROR) ((app *)user)->engine_errors++;
    }
}

static void camera_position(const app *a, float out[3])
{
    out[0] = a->target[0] + a->distance * cosf(a->pitch) * sinf(a->yaw);
    out[1] = a->target[1] + a->distance * sinf(a->pitch);
    out[2] = a->target[2] + a->distance * cosf(a->pitch) * cosf(a->yaw);
}

// The scene's first camera if it has one (looking at the point nearest the scene's centre
// along its view ray), else a view of the whole bounding box.
static void camera_home(app *a)
{
    const rtpbr_gltf_scene *s = a->scene.loaded;
    float center[3], extent = 0.0f;
    for (int c = 0; c < 3; ++c) {
        center[c] = 0.5f * (s->bounds_min[c] + s->bounds_max[c]);
        extent = fmaxf(extent, s->bounds_max[c] - s->bounds_min[c]);
    }
    a->yfov = 0.7853982f;
    if (s->camera_count > 0) {
        const rtpbr_gltf_camera *cam = &s->cameras[0];
        float to_center[3] = {center[0] - cam->position[0], center[1] - cam->position[1], center[2] - cam->position[2]};
        float d = to_center[0] * cam->forward[0] + to_center[1] * cam->forward[1] + to_center[2] * cam->forward[2];
        a->distance = d > 0.1f ? d : fmaxf(extent, 1.0f);
        for (int c = 0; c < 3; ++c) a->target[c] = cam->position[c] + a->distance * cam->forward[c];
        a->pitch = asinf(fmaxf(-1.0f, fminf(1.0f, -cam->forward[1])));
        a->yaw = atan2f(-cam->forward[0], -cam->forward[2]);
        if (cam->yfov > 0.0f) a->yfov = cam->yfov;
    } else {
        memcpy(a->target, center, sizeof center);
        a->distance = fmaxf(extent, 1e-3f) / tanf(0.5f * a->yfov);
        a->yaw = 0.0f;
        a->pitch = 0.3f;
    }
    memcpy(a->home_target, a->target, sizeof a->target);
    a->home_yaw = a->yaw, a->home_pitch = a->pitch, a->home_distance = a->distance;
}

// The tone curves of rtpbr.h (rtpbr_tonemap), for the reference in the split view.
static float tone_map(rtpbr_tonemap op, float x)
{
    float y;
    if (op == RTPBR_TONEMAP_REINHARD) y = x / (1.0f + x);
    else if (op == RTPBR_TONEMAP_LINEAR) y = x;
    else y = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f); // Narkowicz 2015 (ACES)
    return y < 0.0f ? 0.0f : (y > 1.0f ? 1.0f : y);
}

static uint8_t srgb_encode(float x) // IEC 61966-2-1
{
    float y = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)(y * 255.0f + 0.5f);
}

// The overlay buffer: for the split view the reference, scaled to the window (nearest texel)
// and tone-mapped like the engine's image, with a white line at the split; for the heat map
// the latest FLIP error map.
static void fill_overlay(app *a)
{
    uint8_t *dst = viewer_window_overlay(&a->win);
    uint32_t w = a->win.extent.width, h = a->win.extent.height;
    bool bgra = viewer_window_bgra(&a->win);
    a->overlay_dirty = false;
    if (a->overlay == VIEWER_OVERLAY_HEATMAP) {
        double mean;
        bool busy;
        a->flip_shown = viewer_flip_result(a->flip, &mean, &busy);
        viewer_flip_heatmap(a->flip, dst, (int)w, (int)h, bgra);
        return;
    }
    float scale = powf(2.0f, a->exposure);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            size_t sx = (size_t)x * a->reference_w / w, sy = (size_t)y * a->reference_h / h;
            const float *p = a->reference + 4 * (sy * a->reference_w + sx);
            uint8_t *o = dst + 4 * ((size_t)y * w + x);
            uint8_t r = srgb_encode(tone_map(a->tonemap, p[0] * scale)),
                    g = srgb_encode(tone_map(a->tonemap, p[1] * scale)),
                    b = srgb_encode(tone_map(a->tonemap, p[2] * scale));
            if (x == w / 2) r = g = b = 255;
            o[0] = bgra ? b : r, o[1] = g, o[2] = bgra ? r : b, o[3] = 255;
        }
}

static const char *const tonemap_names[] = {"ACES", "ACES", "Reinhard", "linear"};

static void update_title(app *a)
{
    char title[512];
    int n = snprintf(title, sizeof title, "rtpbr viewer | %.1f ms | %s, %s, Kulla-Conty %s | EV %+.1f %s",
                     a->frame_ms, a->monte_carlo ? "Monte Carlo" : "LTC",
                     a->ndf == RTPBR_NDF_BECKMANN_MODEL ? "Beckmann" : "GGX", a->multiscatter_off ? "off" : "on",
                     a->exposure, tonemap_names[a->tonemap]);
    if (viewer_scene_light_total(&a->scene) > 0 && n > 0 && (size_t)n < sizeof title) {
        static const char *const modes[] = {"move", "rotate", "scale"};
        n += snprintf(title + n, sizeof title - n, " | light %u/%u [%s]", a->light + 1,
                      viewer_scene_light_total(&a->scene), modes[a->mode]);
        const viewer_light *l = app_area_light(a);
        const viewer_punctual *p = app_punctual_light(a);
        if (l && l->type == RTPBR_LIGHT_DISK && n > 0 && (size_t)n < sizeof title)
            n += snprintf(title + n, sizeof title - n, " %s r=%.2f x %.2f I=%.2f %s", viewer_light_kind(l), l->radius,
                          viewer_light_radius2(l), l->intensity, l->two_sided ? "two-sided" : "one-sided");
        else if (l && n > 0 && (size_t)n < sizeof title)
            n += snprintf(title + n, sizeof title - n, " %u-gon%s I=%.2f %s", l->vertex_count,
                          l->emission_texture ? " screen" : "", l->intensity,
                          l->two_sided ? "two-sided" : "one-sided");
        else if (p && n > 0 && (size_t)n < sizeof title)
            n += snprintf(title + n, sizeof title - n, " %s I=%.2f %s", viewer_punctual_kind(p), p->intensity,
                          p->type == RTPBR_LIGHT_DIRECTIONAL ? "lux" : "cd");
        if (p && p->range > 0.0f && p->type != RTPBR_LIGHT_DIRECTIONAL && n > 0 && (size_t)n < sizeof title)
            n += snprintf(title + n, sizeof title - n, " range %.2f", p->range);
    }
    if (a->scene.material_count > 0 && n > 0 && (size_t)n < sizeof title) {
        const rtpbr_material_desc *m = &a->scene.materials[a->material];
        n += snprintf(title + n, sizeof title - n, " | material %u/%u r=%.2f m=%.2f", a->material + 1,
                      a->scene.material_count, m->roughness, m->metallic);
    }
    if (a->overlay == VIEWER_OVERLAY_SPLIT && n > 0 && (size_t)n < sizeof title)
        n += snprintf(title + n, sizeof title - n, " | right: reference");
    if (a->flip && n > 0 && (size_t)n < sizeof title) {
        double mean;
        bool busy;
        if (viewer_flip_result(a->flip, &mean, &busy))
            n += snprintf(title + n, sizeof title - n, " | HDR-FLIP %.4f", mean);
    }
    if (a->notice && n > 0 && (size_t)n < sizeof title) snprintf(title + n, sizeof title - n, " | %s", a->notice);
    glfwSetWindowTitle(a->win.glfw, title);
}

// The arrow keys' edit of a punctual light: its position, direction or range (what it has).
static void edit_punctual(app *a, viewer_punctual *p, int axis, float sign)
{
    if (a->mode == 0 && p->type != RTPBR_LIGHT_DIRECTIONAL) {
        p->position[axis] += 0.1f * sign;
    } else if (a->mode == 1 && p->type != RTPBR_LIGHT_POINT) {
        viewer_punctual_rotate(p, axis, sign * 0.0872665f); // 5 degrees
    } else if (a->mode == 2 && p->type != RTPBR_LIGHT_DIRECTIONAL && p->range > 0.0f) {
        p->range *= sign > 0.0f ? 1.1f : 1.0f / 1.1f;
    } else {
        a->notice = a->mode == 0   ? "a directional light has no position"
                    : a->mode == 1 ? "a point light has no direction"
                                   : "scale: a point or spot light's finite range (the panel sets one)";
        return;
    }
    viewer_punctual_clamp(p);
    app_light_edited(a);
}

static void edit_light(app *a, int key)
{
    // Arrows: X and Z; PgUp/PgDn: Y (world axes).
    int axis = key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT ? 0 : (key == GLFW_KEY_UP || key == GLFW_KEY_DOWN ? 2 : 1);
    float sign = key == GLFW_KEY_RIGHT || key == GLFW_KEY_DOWN || key == GLFW_KEY_PAGE_UP ? 1.0f : -1.0f;
    viewer_punctual *p = app_punctual_light(a);
    if (p) {
        edit_punctual(a, p, axis, sign);
        return;
    }
    viewer_light *l = app_area_light(a);
    if (!l) return;
    if (a->mode == 0) {
        float d[3] = {0.0f, 0.0f, 0.0f};
        d[axis] = 0.1f * sign;
        viewer_light_translate(l, d);
    } else if (a->mode == 1) {
        viewer_light_rotate(l, axis, sign * 0.0872665f); // 5 degrees
    } else {
        viewer_light_scale(l, sign > 0.0f ? 1.1f : 1.0f / 1.1f);
    }
    app_light_edited(a);
}

static void set_overlay(app *a, viewer_overlay overlay)
{
    a->overlay = a->overlay == overlay ? VIEWER_OVERLAY_NONE : overlay;
    a->overlay_dirty = true;
}

static void handle_key(app *a, int key)
{
    viewer_light *l = app_area_light(a);
    viewer_punctual *p = app_punctual_light(a);
    uint32_t light_total = viewer_scene_light_total(&a->scene);
    rtpbr_material_desc *m = a->scene.material_count ? &a->scene.materials[a->material] : NULL;
    static const float colours[][3] = {{1, 1, 1}, {1, 0.85f, 0.7f}, {0.7f, 0.85f, 1}, {1, 0.2f, 0.1f},
                                       {0.2f, 1, 0.3f}, {0.2f, 0.4f, 1}};
    a->notice = NULL;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(a->win.glfw, GLFW_TRUE); break;
    case GLFW_KEY_H: fputs(help_text, stdout); break;
    case GLFW_KEY_HOME:
        memcpy(a->target, a->home_target, sizeof a->target);
        a->yaw = a->home_yaw, a->pitch = a->home_pitch, a->distance = a->home_distance;
        app_changed(a);
        break;
    case GLFW_KEY_TAB:
        if (light_total) a->light = (a->light + 1) % light_total, a->light_selected = true;
        break;
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: a->mode = key - GLFW_KEY_1; break;
    case GLFW_KEY_LEFT: case GLFW_KEY_RIGHT: case GLFW_KEY_UP: case GLFW_KEY_DOWN:
    case GLFW_KEY_PAGE_UP: case GLFW_KEY_PAGE_DOWN: edit_light(a, key); break;
    case GLFW_KEY_LEFT_BRACKET: case GLFW_KEY_RIGHT_BRACKET:
        if (l && l->type == RTPBR_LIGHT_DISK) {
            a->notice = "a disk has no vertices (scale, 3, sets its radius)";
        } else if (l) {
            viewer_light_set_vertex_count(l, l->vertex_count + (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1));
            app_light_edited(a);
        }
        if (p && p->type == RTPBR_LIGHT_SPOT) { // 2 degrees; the inner cone stays inside
            p->outer_cone_angle += key == GLFW_KEY_RIGHT_BRACKET ? 0.0349066f : -0.0349066f;
            viewer_punctual_clamp(p);
            app_light_edited(a);
        }
        break;
    case GLFW_KEY_C:
        if (l || p) a->colour_index = (a->colour_index + 1) % 6;
        if (l || p) memcpy(l ? l->color : p->color, colours[a->colour_index], sizeof colours[0]), app_light_edited(a);
        break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_MINUS:
        if (l) l->intensity *= key == GLFW_KEY_EQUAL ? 1.25f : 0.8f, app_light_edited(a);
        if (p) p->intensity *= key == GLFW_KEY_EQUAL ? 1.25f : 0.8f, app_light_edited(a);
        break;
    case GLFW_KEY_T: if (l) l->two_sided = !l->two_sided, app_light_edited(a); break;
    case GLFW_KEY_I:
        static const char *const added[VIEWER_NEW_LIGHT_KINDS] = {
            [VIEWER_NEW_QUAD] = "added a quad light", [VIEWER_NEW_DISK] = "added a disk light",
            [VIEWER_NEW_SPHERE] = "added a sphere light", [VIEWER_NEW_SPOT] = "added a spot light",
            [VIEWER_NEW_POINT] = "added a point light", [VIEWER_NEW_DIRECTIONAL] = "added a directional light",
            [VIEWER_NEW_TUBE] = "added a tube light", [VIEWER_NEW_ELLIPSE] = "added an ellipse light",
            [VIEWER_NEW_SCREEN] = "added a screen (a textured quad light)"};
        a->notice = app_add_light(a, a->new_light_kind) ? added[a->new_light_kind] : "out of memory";
        a->new_light_kind = (a->new_light_kind + 1) % VIEWER_NEW_LIGHT_KINDS;
        break;
    case GLFW_KEY_X: if (!app_remove_light(a)) a->notice = "no light to remove"; break;
    case GLFW_KEY_M:
        if (a->scene.material_count)
            a->material = (a->material + 1) % a->scene.material_count, a->light_selected = false;
        break;
    case GLFW_KEY_7: case GLFW_KEY_8:
        if (m) m->roughness = fminf(1.0f, fmaxf(0.0f, m->roughness + (key == GLFW_KEY_8 ? 0.05f : -0.05f)));
        if (m) app_material_edited(a);
        break;
    case GLFW_KEY_9: case GLFW_KEY_0:
        if (m) m->metallic = fminf(1.0f, fmaxf(0.0f, m->metallic + (key == GLFW_KEY_0 ? 0.1f : -0.1f)));
        if (m) app_material_edited(a);
        break;
    case GLFW_KEY_K: a->multiscatter_off = !a->multiscatter_off, app_changed(a); break;
    case GLFW_KEY_N:
        a->ndf = a->ndf == RTPBR_NDF_BECKMANN_MODEL ? RTPBR_NDF_GGX_MODEL : RTPBR_NDF_BECKMANN_MODEL;
        app_changed(a);
        break;
    case GLFW_KEY_R: a->monte_carlo = !a->monte_carlo, app_changed(a); break;
    case GLFW_KEY_L: a->notice = "the engine API has no run-time LTC sphere-proxy variant"; break;
    case GLFW_KEY_E: case GLFW_KEY_D:
        a->exposure += key == GLFW_KEY_E ? 0.5f : -0.5f;
        a->overlay_dirty = true;
        app_changed(a);
        break;
    case GLFW_KEY_O:
        a->tonemap = a->tonemap == RTPBR_TONEMAP_LINEAR || a->tonemap == RTPBR_TONEMAP_DEFAULT
                         ? (a->tonemap == RTPBR_TONEMAP_DEFAULT ? RTPBR_TONEMAP_REINHARD : RTPBR_TONEMAP_ACES)
                         : (rtpbr_tonemap)(a->tonemap + 1);
        a->overlay_dirty = true;
        app_changed(a);
        break;
    case GLFW_KEY_S:
        if (a->reference) set_overlay(a, VIEWER_OVERLAY_SPLIT);
        else a->notice = "no --reference image";
        break;
    case GLFW_KEY_F:
        if (a->flip) set_overlay(a, VIEWER_OVERLAY_HEATMAP);
        else a->notice = "no --reference image";
        break;
    case GLFW_KEY_U: if (a->ui) a->ui_hidden = !a->ui_hidden; break;
    case GLFW_KEY_P: a->screenshot_request = true; break;
    default: break;
    }
    a->last_title = 0.0; // refresh now
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    app *a = glfwGetWindowUserPointer(window);
    if (action == GLFW_RELEASE || viewer_ui_wants_keyboard(a->ui)) return;
    handle_key(a, key);
}

// Replays --keys (see the top of this file); false for a character with no key.
static bool replay_keys(app *a, const char *keys)
{
    for (const char *c = keys; *c; ++c) {
        int key = 0;
        if ((*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '[' || *c == ']' || *c == '-' || *c == '=')
            key = *c; // GLFW key codes of these are their ASCII codes
        else if (*c == 'l') key = GLFW_KEY_LEFT;
        else if (*c == 'r') key = GLFW_KEY_RIGHT;
        else if (*c == 'u') key = GLFW_KEY_UP;
        else if (*c == 'd') key = GLFW_KEY_DOWN;
        else if (*c == 'p') key = GLFW_KEY_PAGE_UP;
        else if (*c == 'n') key = GLFW_KEY_PAGE_DOWN;
        else if (*c == 't') key = GLFW_KEY_TAB;
        else if (*c == 'h') key = GLFW_KEY_HOME;
        if (!key) {
            fprintf(stderr, "rtpbr-viewer: --keys: no key for '%c'\n", *c);
            return false;
        }
        handle_key(a, key);
    }
    return true;
}

// Selects the light or material under window pixel (x, y): a ray through the pixel of the
// orbit camera (the engine's look-at pinhole, +Y up) against the viewer's own scene copy.
static void pick(app *a, double x, double y)
{
    int ww, wh;
    glfwGetWindowSize(a->win.glfw, &ww, &wh);
    if (ww <= 0 || wh <= 0) return;
    float eye[3], f[3], r[3], u[3];
    camera_position(a, eye);
    for (int c = 0; c < 3; ++c) f[c] = a->target[c] - eye[c];
    float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int c = 0; c < 3; ++c) f[c] /= fl;
    r[0] = -f[2], r[1] = 0.0f, r[2] = f[0]; // f x (0, 1, 0)
    float rl = sqrtf(r[0] * r[0] + r[2] * r[2]);
    if (!(rl > 0.0f)) return;
    r[0] /= rl, r[2] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    float t = tanf(0.5f * a->yfov), aspect = (float)ww / (float)wh;
    float nx = (float)(2.0 * x / ww - 1.0), ny = (float)(2.0 * y / wh - 1.0);
    float dir[3];
    for (int c = 0; c < 3; ++c) dir[c] = f[c] + nx * t * aspect * r[c] - ny * t * u[c];
    int32_t light, material;
    if (!viewer_scene_pick(&a->scene, eye, dir, &light, &material)) return;
    if (light >= 0) a->light = (uint32_t)light, a->light_selected = true;
    else a->material = (uint32_t)material, a->light_selected = false;
    a->last_title = 0.0;
}

static void on_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    app *a = glfwGetWindowUserPointer(window);
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    if (action == GLFW_PRESS) {
        if (viewer_ui_wants_mouse(a->ui)) return;
        a->drag = button == GLFW_MOUSE_BUTTON_LEFT ? 1 : (button == GLFW_MOUSE_BUTTON_RIGHT ? 2 : 0);
        a->mouse_x = a->press_x = x, a->mouse_y = a->press_y = y;
    } else {
        // A left click that did not drag selects what is under it.
        if (a->drag == 1 && fabs(x - a->press_x) < 3.0 && fabs(y - a->press_y) < 3.0) pick(a, x, y);
        a->drag = 0;
    }
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    app *a = glfwGetWindowUserPointer(window);
    float dx = (float)(x - a->mouse_x), dy = (float)(y - a->mouse_y);
    a->mouse_x = x, a->mouse_y = y;
    if (a->drag == 1) {
        a->yaw -= 0.01f * dx;
        a->pitch = fminf(1.55f, fmaxf(-1.55f, a->pitch + 0.01f * dy));
        app_changed(a);
    } else if (a->drag == 2) {
        // Pan in the camera's plane: right = (cos y, 0, -sin y), up ~ world Y.
        float k = 0.002f * a->distance;
        a->target[0] -= k * dx * cosf(a->yaw);
        a->target[2] += k * dx * sinf(a->yaw);
        a->target[1] += k * dy;
        app_changed(a);
    }
}

static void on_scroll(GLFWwindow *window, double dx, double dy)
{
    (void)dx;
    app *a = glfwGetWindowUserPointer(window);
    if (viewer_ui_wants_mouse(a->ui)) return;
    a->distance = fmaxf(0.05f, a->distance * powf(0.9f, (float)dy));
    app_changed(a);
}

static bool record_frame(VkCommandBuffer cmd, VkImage image, VkImageView view, uint32_t index, void *user)
{
    (void)index;
    app *a = user;
    rtpbr_camera_desc camera = {.yfov = a->yfov, .up = {0.0f, 1.0f, 0.0f}};
    camera_position(a, camera.position);
    memcpy(camera.target, a->target, sizeof camera.target);
    rtpbr_render_desc desc = {.camera = &camera, .exposure = a->exposure, .ndf = a->ndf, .tonemap = a->tonemap,
        .multiscatter = a->multiscatter_off ? RTPBR_MULTISCATTER_OFF : RTPBR_MULTISCATTER_ON,
        .mc_samples = a->monte_carlo ? (uint32_t)a->mc_samples : 0u, .mc_seed = (uint32_t)a->view_generation};
    rtpbr_record_desc target = {.command_buffer = cmd, .image = image, .view = view, .format = a->win.format,
        .old_layout = VK_IMAGE_LAYOUT_UNDEFINED, .new_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    rtpbr_result r = rtpbr_record(a->renderer, a->gpu, &desc, &target);
    if (r != RTPBR_SUCCESS) fprintf(stderr, "rtpbr-viewer: rtpbr_record: %s\n", rtpbr_result_string(r));
    return r == RTPBR_SUCCESS;
}

static bool record_ui(VkCommandBuffer cmd, VkImage image, VkImageView view, uint32_t index, void *user)
{
    (void)image, (void)view;
    app *a = user;
    return viewer_ui_record(a->ui, cmd, index);
}

// Keeps the engine scene and renderer in step with edits and the window size.
static bool sync_engine(app *a)
{
    rtpbr_result r = RTPBR_SUCCESS;
    if (!a->gpu || viewer_scene_needs_upload(&a->scene)) {
        rtpbr_gpu_scene_destroy(a->gpu); // the last frame has completed (one frame in flight)
        a->gpu = NULL;
        if ((r = viewer_scene_upload(&a->scene, a->ctx, &a->gpu)) != RTPBR_SUCCESS) {
            fprintf(stderr, "rtpbr-viewer: scene upload: %s\n", rtpbr_result_string(r));
            return false;
        }
        a->lights_dirty = a->materials_dirty = false;
    }
    // In place (the last frame has completed): every material and light, a few host writes.
    for (uint32_t i = 0; a->materials_dirty && i < a->scene.material_count && r == RTPBR_SUCCESS; ++i)
        r = viewer_scene_update_material(&a->scene, a->gpu, i);
    if (a->lights_dirty && r == RTPBR_SUCCESS) r = viewer_scene_update_lights(&a->scene, a->gpu);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "rtpbr-viewer: scene update: %s\n", rtpbr_result_string(r));
        return false;
    }
    a->lights_dirty = a->materials_dirty = false;
    if (!a->renderer || a->renderer_w != a->win.extent.width || a->renderer_h != a->win.extent.height) {
        rtpbr_renderer_destroy(a->renderer);
        a->renderer = NULL;
        rtpbr_renderer_desc desc = {.width = a->win.extent.width, .height = a->win.extent.height, .timings = 1};
        r = rtpbr_renderer_create(a->ctx, &desc, &a->renderer);
        if (r == RTPBR_ERROR_MISSING_FEATURE) { // no timestamps on this queue: no GPU times
            desc.timings = 0;
            r = rtpbr_renderer_create(a->ctx, &desc, &a->renderer);
        }
        if (r != RTPBR_SUCCESS) {
            fprintf(stderr, "rtpbr-viewer: renderer: %s\n", rtpbr_result_string(r));
            return false;
        }
        a->renderer_w = desc.width, a->renderer_h = desc.height;
        a->overlay_dirty = true;
        app_changed(a);
    }
    if (a->overlay == VIEWER_OVERLAY_HEATMAP) {
        double mean;
        bool busy;
        if (viewer_flip_result(a->flip, &mean, &busy) != a->flip_shown) a->overlay_dirty = true;
    }
    if (a->overlay != VIEWER_OVERLAY_NONE && a->overlay_dirty) fill_overlay(a);
    return true;
}

// After a frame has completed: the GPU times, and the radiance for the live FLIP when the
// worker is free and the view changed since its last evaluation.
static void after_frame(app *a, float *radiance)
{
    rtpbr_timings t;
    if (rtpbr_renderer_timings(a->renderer, &t) == RTPBR_SUCCESS && t.valid) a->timings = t;
    if (!a->flip || a->flip_submitted == a->view_generation) return;
    int rw, rh;
    viewer_flip_size(a->flip, &rw, &rh);
    if ((uint32_t)rw != a->renderer_w || (uint32_t)rh != a->renderer_h || !radiance) return;
    double mean;
    bool busy;
    viewer_flip_result(a->flip, &mean, &busy);
    if (busy) return;
    if (rtpbr_read_radiance(a->renderer, radiance, (size_t)rw * rh * 16) == RTPBR_SUCCESS &&
        viewer_flip_submit(a->flip, radiance, rw, rh, a->view_generation))
        a->flip_submitted = a->view_generation;
}

static bool resize(app *a)
{
    if (!viewer_window_resize(&a->win)) return false;
    return !a->ui || a->win.extent.width == 0 || viewer_ui_resize(a->ui, &a->win);
}

int main(int argc, char **argv)
{
    const char *scene_path = RTPBR_VIEWER_DEFAULT_SCENE, *reference_path = NULL, *screenshot_path = NULL;
    const char *radiance_path = NULL, *keys = "";
    long frames = 0, width = 960, height = 720;
    bool validation = false, no_ui = false;
    for (int i = 1; i < argc; ++i) {
        bool has_value = i + 1 < argc;
        if (!strcmp(argv[i], "--reference") && has_value) reference_path = argv[++i];
        else if (!strcmp(argv[i], "--screenshot") && has_value) screenshot_path = argv[++i];
        else if (!strcmp(argv[i], "--radiance") && has_value) radiance_path = argv[++i];
        else if (!strcmp(argv[i], "--frames") && has_value) frames = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--width") && has_value) width = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--height") && has_value) height = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--keys") && has_value) keys = argv[++i];
        else if (!strcmp(argv[i], "--validation")) validation = true;
        else if (!strcmp(argv[i], "--no-ui")) no_ui = true;
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            printf("%s\n%s", usage_text, help_text);
            return 0;
        } else if (argv[i][0] != '-') scene_path = argv[i];
        else {
            fputs(usage_text, stderr);
            return 2;
        }
    }
    if (frames < 0 || width < 1 || height < 1 || width > 16384 || height > 16384 ||
        ((screenshot_path || radiance_path) && frames < 1)) {
        fprintf(stderr, "rtpbr-viewer: --frames must be >= 1 with --screenshot or --radiance; sizes 1..16384\n");
        return 2;
    }
    app *a = calloc(1, sizeof *a);
    if (!a) return 1;
    int status = 1;
    float *radiance = NULL;
    a->mc_samples = 16;
    if (reference_path) {
        if (!(a->reference = viewer_reference_load(reference_path, &a->reference_w, &a->reference_h))) goto done;
        if (!(a->flip = viewer_flip_create(reference_path))) goto done;
        a->overlay = VIEWER_OVERLAY_SPLIT;
    }
    if (!viewer_scene_load(&a->scene, scene_path)) goto done;
    if (!viewer_window_create(&a->win, (int)width, (int)height, validation, false)) goto done;
    glfwSetWindowUserPointer(a->win.glfw, a);
    glfwSetKeyCallback(a->win.glfw, on_key);
    glfwSetMouseButtonCallback(a->win.glfw, on_button);
    glfwSetCursorPosCallback(a->win.glfw, on_cursor);
    glfwSetScrollCallback(a->win.glfw, on_scroll);
    if (!no_ui && !viewer_ui_create(&a->ui, &a->win)) goto done;
    rtpbr_context_desc desc = {.logger = {.func = on_log, .user_data = a},
        .embedded = {.instance = a->win.instance, .physical_device = a->win.physical_device,
                     .device = a->win.device, .queue = a->win.queue, .queue_family_index = a->win.queue_family,
                     .enabled_features = &a->win.features}};
    rtpbr_result r = rtpbr_context_create(&desc, &a->ctx);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "rtpbr-viewer: rtpbr_context_create: %s\n", rtpbr_result_string(r));
        goto done;
    }
    camera_home(a);
    a->light_selected = viewer_scene_light_total(&a->scene) > 0;
    if (!replay_keys(a, keys)) goto done;
    if (!frames) fputs(help_text, stdout);
    bool screenshot_written = false;
    for (long frame = 0; !glfwWindowShouldClose(a->win.glfw) && (!frames || frame < frames);) {
        glfwPollEvents();
        if (a->win.extent.width == 0 || a->win.extent.height == 0) {
            glfwWaitEvents();
            if (!resize(a)) goto done;
            continue;
        }
        if (!sync_engine(a)) goto done;
        if (!radiance || a->renderer_w * a->renderer_h != a->win.extent.width * a->win.extent.height) {
            free(radiance);
            if (!(radiance = malloc((size_t)a->renderer_w * a->renderer_h * 16))) goto done;
        }
        bool shot = a->screenshot_request || (screenshot_path && frame == frames - 1);
        double start = glfwGetTime();
        bool draw_ui = a->ui && !a->ui_hidden;
        if (draw_ui) {
            viewer_ui_build(a->ui, a);
            a->ui_ms = 1000.0 * (glfwGetTime() - start);
            if (!sync_engine(a)) goto done; // the panels' edits, before the frame records
        }
        bool out_of_date = false;
        // The heat map covers the view once there is an error map (until then: the scene).
        int split_x = -1;
        if (a->overlay == VIEWER_OVERLAY_SPLIT) split_x = (int)(a->win.extent.width / 2);
        else if (a->overlay == VIEWER_OVERLAY_HEATMAP && a->flip_shown) split_x = 0;
        if (!viewer_window_frame(&a->win, record_frame, draw_ui ? record_ui : NULL, a, split_x, shot, &out_of_date))
            goto done;
        if (out_of_date) { // the image may not have been shown: resize and draw the frame again
            if (!resize(a)) goto done;
            continue;
        }
        double now = glfwGetTime();
        if (frame > 0) { // the first frame compiles pipelines: not in the frame time
            a->frame_ms = a->frame_ms > 0.0 ? 0.9 * a->frame_ms + 100.0 * (now - start) : 1000.0 * (now - start);
            a->steady_ms_sum += 1000.0 * (now - start), a->steady_frames++;
            if (draw_ui) a->steady_ui_cpu_sum += a->ui_ms, a->steady_ui_gpu_sum += a->win.ui_gpu_ms;
        }
        after_frame(a, radiance);
        if (shot) {
            char name[64];
            const char *path = screenshot_path && frame == frames - 1 ? screenshot_path : name;
            snprintf(name, sizeof name, "rtpbr-viewer-%03u.png", a->screenshot_counter++);
            if (!viewer_window_write_screenshot(&a->win, path)) goto done;
            printf("rtpbr-viewer: wrote %s (%ux%u)\n", path, a->win.extent.width, a->win.extent.height);
            screenshot_written |= path == screenshot_path;
            a->screenshot_request = false;
        }
        if (now - a->last_title > 0.25) update_title(a), a->last_title = now;
        ++frame;
    }
    if (a->steady_frames > 0)
        printf("rtpbr-viewer: %.1f ms per frame (mean of %ld frames after the first) at %ux%u on %s%s\n",
               a->steady_ms_sum / (double)a->steady_frames, a->steady_frames, a->win.extent.width,
               a->win.extent.height, rtpbr_context_device_name(a->ctx), a->ui ? ", panels on" : ", --no-ui");
    if (a->steady_frames > 0 && a->ui)
        printf("rtpbr-viewer: panels %.3f ms CPU + %.3f ms GPU per frame (mean), %.2f%% of the frame time\n",
               a->steady_ui_cpu_sum / (double)a->steady_frames, a->steady_ui_gpu_sum / (double)a->steady_frames,
               100.0 * (a->steady_ui_cpu_sum + a->steady_ui_gpu_sum) / a->steady_ms_sum);
    if (a->timings.valid)
        printf("rtpbr-viewer: GPU time of the last frame: G-buffer %.3f ms, lighting %.3f ms, tone mapping %.3f ms\n",
               a->timings.gbuffer_ms, a->timings.lighting_ms, a->timings.tonemap_ms);
    // Scripted runs: the last frame's radiance, and its HDR-FLIP against the reference.
    bool outputs_ok = true;
    if (frames && (radiance_path || a->flip)) {
        size_t bytes = (size_t)a->renderer_w * a->renderer_h * 16;
        outputs_ok = rtpbr_read_radiance(a->renderer, radiance, bytes) == RTPBR_SUCCESS;
        if (outputs_ok && radiance_path)
            outputs_ok = viewer_write_radiance(radiance_path, radiance, (int)a->renderer_w, (int)a->renderer_h);
        int rw = 0, rh = 0;
        if (a->flip) viewer_flip_size(a->flip, &rw, &rh);
        if (outputs_ok && a->flip && (uint32_t)rw == a->renderer_w && (uint32_t)rh == a->renderer_h) {
            double mean = viewer_flip_mean_now(a->flip, radiance, rw, rh);
            if (mean >= 0.0) printf("rtpbr-viewer: HDR-FLIP mean %.6f against %s\n", mean, reference_path);
            else outputs_ok = false;
        } else if (a->flip) {
            printf("rtpbr-viewer: no HDR-FLIP: the reference is %dx%d, the view %ux%u\n", rw, rh, a->renderer_w,
                   a->renderer_h);
        }
    }
    status = (screenshot_path && !screenshot_written) || a->engine_errors || !outputs_ok ? 1 : 0;
done:
    if (a->win.device) vkDeviceWaitIdle(a->win.device);
    viewer_flip_destroy(a->flip);
    viewer_ui_destroy(a->ui);
    rtpbr_renderer_destroy(a->renderer);
    rtpbr_gpu_scene_destroy(a->gpu);
    rtpbr_context_destroy(a->ctx);
    viewer_window_destroy(&a->win);
    viewer_scene_destroy(&a->scene);
    free(a->reference);
    free(radiance);
    if (a->win.validation_messages) {
        fprintf(stderr, "rtpbr-viewer: %u validation message(s)\n", a->win.validation_messages);
        status = 1;
    }
    free(a);
    return status;
}
