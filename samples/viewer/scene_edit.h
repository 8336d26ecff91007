// The viewer's editable copy of a glTF scene: loaded once with the rtpbr scene loader, edited
// (lights, materials), and re-uploaded to the engine as a whole after each edit (the engine
// API has rtpbr_gpu_scene_set_lights but nothing to change materials or emissive geometry).
#ifndef RTPBR_VIEWER_SCENE_EDIT_H
#define RTPBR_VIEWER_SCENE_EDIT_H

#include <rtpbr/rtpbr.h>
#include <rtpbr/rtpbr_scene.h>
#include <stdbool.h>

typedef struct viewer_light {
    float vertices[RTPBR_MAX_POLYGON_VERTICES][3]; // convex, counter-clockwise seen from the front
    uint32_t vertex_count;
    float color[3];     // max component 1
    float intensity;    // radiance = color * intensity
    bool two_sided;
    int32_t material;   // the emissive material it came from (its surface), -1: none
} viewer_light;

typedef struct viewer_scene {
    rtpbr_scene *loaded;
    rtpbr_material_desc *materials; // one per loaded material (edited in place)
    uint32_t material_count;
    viewer_light *lights;
    uint32_t light_count;
    bool *primitive_is_light;       // primitives replaced by the lights' own polygons
} viewer_scene;

// Loads a glTF file; false with the loader's message on stderr.
bool viewer_scene_load(viewer_scene *s, const char *path);
void viewer_scene_destroy(viewer_scene *s);
// Builds the engine scene: every non-emissive primitive with its (edited) material, and every
// light both as a polygonal light and as an emissive polygon mesh, so that it is seen.
rtpbr_result viewer_scene_upload(const viewer_scene *s, rtpbr_context *ctx, rtpbr_gpu_scene **out);

// Edits of one light, about its centre (vertex mean).
void viewer_light_center(const viewer_light *l, float out[3]);
void viewer_light_normal(const viewer_light *l, float out[3]);
void viewer_light_translate(viewer_light *l, const float d[3]);
void viewer_light_rotate(viewer_light *l, int axis, float radians); // about a world axis 0..2
void viewer_light_scale(viewer_light *l, float factor);
// A regular polygon of n (3..8) vertices with the light's centre, normal and mean radius.
void viewer_light_set_vertex_count(viewer_light *l, uint32_t n);

#endif
