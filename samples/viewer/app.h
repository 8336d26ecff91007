// The viewer's state, shared by its C main loop (viewer.c) and its Dear ImGui panels (ui.cpp).
#ifndef RTPBR_VIEWER_APP_H
#define RTPBR_VIEWER_APP_H

#include "flip_live.h"
#include "scene_edit.h"
#include "window.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum viewer_overlay {
    VIEWER_OVERLAY_NONE = 0,
    VIEWER_OVERLAY_SPLIT,    // right half: the reference, tone-mapped like the engine
    VIEWER_OVERLAY_HEATMAP,  // the whole view: the live HDR-FLIP error map (magma)
} viewer_overlay;

typedef struct app {
    viewer_window win;
    struct viewer_ui *ui;     // NULL with --no-ui
    bool ui_hidden;           // U: panels off for now
    rtpbr_context *ctx;
    viewer_scene scene;
    rtpbr_gpu_scene *gpu;
    rtpbr_renderer *renderer;
    uint32_t renderer_w, renderer_h;
    // Edits waiting for the engine scene (applied in place between frames).
    bool lights_dirty, materials_dirty;
    // Orbit camera: position = target + distance (cos p sin y, sin p, cos p cos y).
    float target[3], yaw, pitch, distance, yfov;
    float home_target[3], home_yaw, home_pitch, home_distance;
    int drag; // 0 none, 1 orbit, 2 pan
    double mouse_x, mouse_y, press_x, press_y;
    // Techniques and display.
    rtpbr_ndf ndf;
    bool multiscatter_off;
    bool monte_carlo;         // the Monte Carlo reference pass instead of LTC
    int mc_samples;           // per pixel and light, with monte_carlo
    rtpbr_tonemap tonemap;
    float exposure;
    // Selection and key edits.
    int mode; // 0 move, 1 rotate, 2 scale
    uint32_t light, material, colour_index; // light: area lights first, then punctual
    int new_light_kind;       // what I adds next (viewer_new_light's kinds, cycled)
    bool light_selected;      // the last click or Tab/M chose a light (else a material)
    // Reference image and live FLIP.
    float *reference;
    int reference_w, reference_h;
    viewer_overlay overlay;
    bool overlay_dirty;
    viewer_flip *flip;
    uint64_t view_generation; // bumped by every change of what the engine draws
    uint64_t flip_shown;      // the FLIP generation drawn into the heat-map overlay
    uint64_t flip_submitted;  // the generation last handed to the FLIP worker
    // Status.
    double frame_ms, last_title;
    double steady_ms_sum; // frames after the first (which builds pipelines), for the summary
    long steady_frames;
    rtpbr_timings timings;
    double ui_ms;             // CPU time of building the panels (their GPU time: win.ui_gpu_ms)
    double steady_ui_cpu_sum, steady_ui_gpu_sum; // over the frames of steady_ms_sum
    bool screenshot_request;
    unsigned screenshot_counter;
    uint32_t engine_errors;
    const char *notice;
} app;

// The selected light (a->light, the engine's numbering: viewer_scene_light_total): an area
// light (a polygon or a disk), or else a punctual light; NULL when it is of the other kind (or
// there is none).
static inline viewer_light *app_area_light(app *a)
{
    return a->light < a->scene.light_count ? &a->scene.lights[a->light] : NULL;
}
static inline viewer_punctual *app_punctual_light(app *a)
{
    uint32_t i = a->light - a->scene.light_count;
    return a->light >= a->scene.light_count && i < a->scene.punctual_count ? &a->scene.punctual[i] : NULL;
}

// What the panels call after editing the app (they set fields directly, then say so). Inline
// here, so that the panels (ui.cpp) and the app (viewer.c) do not call each other in a circle.
// Anything the engine draws (bumps view_generation).
static inline void app_changed(app *a) { a->view_generation++; }

// The selected area light's shape, placement, colour or sides; a punctual light's colour,
// intensity, position, direction, range or cones.
static inline void app_light_edited(app *a)
{
    a->lights_dirty = true;
    a->light_selected = true;
    app_changed(a);
}

// Adds a light of viewer_new_light's kind 1 m above the orbit target and selects it; removes
// the selected light. The engine scene is re-uploaded before the next frame.
static inline bool app_add_light(app *a, int kind)
{
    float at[3] = {a->target[0], a->target[1] + 1.0f, a->target[2]};
    viewer_light l;
    viewer_punctual p;
    bool area = viewer_new_light(kind, at, &l, &p);
    if (area ? !viewer_scene_add_light(&a->scene, &l) : !viewer_scene_add_punctual(&a->scene, &p)) return false;
    a->light = area ? a->scene.light_count - 1 : viewer_scene_light_total(&a->scene) - 1;
    app_light_edited(a);
    return true;
}
static inline bool app_remove_light(app *a)
{
    if (!viewer_scene_remove_light(&a->scene, a->light)) return false;
    uint32_t total = viewer_scene_light_total(&a->scene);
    if (a->light >= total) a->light = total ? total - 1 : 0;
    app_light_edited(a);
    return true;
}

// The selected material.
static inline void app_material_edited(app *a)
{
    a->materials_dirty = true;
    a->light_selected = false;
    app_changed(a);
}

#ifdef __cplusplus
}
#endif

#endif
