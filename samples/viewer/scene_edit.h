// The viewer's editable copy of a glTF scene: loaded once with the rtpbr scene loader, edited
// (lights, materials) and kept in step with the engine scene in place: materials with
// rtpbr_gpu_scene_set_material, a light's emissive polygon with rtpbr_gpu_scene_set_transform
// (moves, turns and scales are affine maps of the uploaded polygon), the lights with
// rtpbr_gpu_scene_set_lights. Only a new vertex count re-uploads the scene.
#ifndef RTPBR_VIEWER_SCENE_EDIT_H
#define RTPBR_VIEWER_SCENE_EDIT_H

#include <rtpbr/rtpbr.h>
#include <rtpbr/rtpbr_gltf.h>
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct viewer_light {
    float vertices[RTPBR_MAX_POLYGON_VERTICES][3]; // convex, counter-clockwise seen from the front
    uint32_t vertex_count;
    float color[3];     // max component 1
    float intensity;    // radiance = color * intensity
    bool two_sided;
    int32_t material;   // the emissive material it came from (its surface), -1: none
    // World-from-uploaded map of the edits since the last upload (column-major): the light's
    // emissive mesh is drawn with it, so moves need no new geometry.
    float transform[16];
    bool reshaped;      // the vertex count changed: the polygon mesh must be re-uploaded
} viewer_light;

typedef struct viewer_scene {
    rtpbr_gltf_scene *loaded;
    rtpbr_material_desc *materials; // one per loaded material (edited in place)
    uint32_t material_count;
    viewer_light *lights;
    uint32_t light_count;
    bool *primitive_is_light;       // primitives replaced by the lights' own polygons
    uint32_t light_mesh_base;       // engine mesh index of light 0's polygon (last upload)
} viewer_scene;

// Loads a glTF file; false with the loader's message on stderr.
bool viewer_scene_load(viewer_scene *s, const char *path);
void viewer_scene_destroy(viewer_scene *s);
// Builds the engine scene: every non-emissive primitive with its (edited) material, and every
// light both as a polygonal light and as an emissive polygon mesh, so that it is seen.
// Materials are the scene's (engine index i = loader material i), then one per light (the
// light's surface: its source material with the light's emission). Resets the lights'
// transforms to the identity (the polygons are uploaded where they are).
rtpbr_result viewer_scene_upload(viewer_scene *s, rtpbr_context *ctx, rtpbr_gpu_scene **out);
// In-place updates of an uploaded scene (no frame may be pending): material i, light i's
// surface material and mesh transform, and all the lights' polygons.
rtpbr_result viewer_scene_update_material(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t material);
rtpbr_result viewer_scene_update_light(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t light);
// True when an edit needs viewer_scene_upload (a light's vertex count changed).
bool viewer_scene_needs_upload(const viewer_scene *s);

// The nearest surface hit by the ray origin + t dir (t > 0): a light (*light >= 0, *material
// -1) or a primitive (*material its material, *light -1). False if nothing is hit.
bool viewer_scene_pick(const viewer_scene *s, const float origin[3], const float dir[3], int32_t *light,
                       int32_t *material);

// Edits of one light, about its centre (vertex mean).
void viewer_light_center(const viewer_light *l, float out[3]);
void viewer_light_normal(const viewer_light *l, float out[3]);
void viewer_light_translate(viewer_light *l, const float d[3]);
void viewer_light_rotate(viewer_light *l, int axis, float radians); // about a world axis 0..2
void viewer_light_scale(viewer_light *l, float factor);
// A regular polygon of n (3..8) vertices with the light's centre, normal and mean radius.
void viewer_light_set_vertex_count(viewer_light *l, uint32_t n);

#ifdef __cplusplus
}
#endif

#endif
