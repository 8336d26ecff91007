// The viewer's editable copy of a glTF scene: loaded once with the rtpbr scene loader, edited
// (lights, materials) and kept in step with the engine scene in place: materials with
// rtpbr_gpu_scene_set_material, an area light's emissive surface (its polygon, or a disk's fan)
// with rtpbr_gpu_scene_set_transform (moves, turns and scales are affine maps of the uploaded
// surface), the lights (polygons, disks and KHR_lights_punctual) with
// rtpbr_gpu_scene_set_lights. Only a new vertex count re-uploads the scene.
#ifndef RTPBR_VIEWER_SCENE_EDIT_H
#define RTPBR_VIEWER_SCENE_EDIT_H

#include <rtpbr/rtpbr.h>
#include <rtpbr/rtpbr_gltf.h>
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

// An area light: a convex polygon (type RTPBR_LIGHT_POLYGON, zero) or a disk
// (RTPBR_LIGHT_DISK: centre, normal, radius; an EXT_lights_area disk is this disk, not the
// loader's octagon). Either is drawn as an emissive surface, so it is seen and can be picked.
typedef struct viewer_light {
    rtpbr_light_type type;  // RTPBR_LIGHT_POLYGON or RTPBR_LIGHT_DISK
    float vertices[RTPBR_MAX_POLYGON_VERTICES][3]; // polygon: convex, counter-clockwise seen from the front
    uint32_t vertex_count;  // polygon: 3..8; disk: 0
    float center[3];        // disk: its centre
    float normal[3];        // disk: unit, toward the side it emits on
    float radius;           // disk: > 0 (VIEWER_MIN_DISK_RADIUS .. VIEWER_MAX_DISK_RADIUS after an edit);
                            // an ellipse's half-axis along `axis`
    float radius2;          // disk: 0 a circle; > 0 an ellipse (rtpbr_light_desc.disk_radius2), its
                            // half-axis across `axis` (in the same range after an edit)
    float axis[3];          // ellipse: unit, in its plane, the direction of the half-axis `radius`
    float color[3];     // max component 1
    float intensity;    // radiance = color * intensity
    bool two_sided;
    uint32_t emission_texture; // polygon of 4 vertices: rtpbr_light_desc's (a screen: radiance =
    float emission_uv[3][2];   // color * intensity * the texture); dropped when it is reshaped.
                               // VIEWER_TEST_CARD: the viewer's own picture (VIEWER_NEW_SCREEN)
    int32_t material;   // the emissive material it came from (its surface), -1: none
    // World-from-uploaded map of the edits since the last upload (column-major): the light's
    // emissive mesh is drawn with it, so moves need no new geometry.
    float transform[16];
    bool reshaped;      // the vertex count changed: the polygon mesh must be re-uploaded
} viewer_light;

// A disk is drawn as a regular polygon of this many vertices inscribed in it (the engine shades
// the disk itself); its radius stays in [MIN, MAX] under the viewer's scaling (the engine asks
// for a radius above 1e-6 of the centre's coordinates).
#define VIEWER_DISK_SEGMENTS 48
#define VIEWER_MIN_DISK_RADIUS 1e-3f
#define VIEWER_MAX_DISK_RADIUS 100.0f

// viewer_light.emission_texture of a screen showing the viewer's own picture (colour bars over
// a grey ramp, VIEWER_TEST_CARD_WIDTH x _HEIGHT sRGB texels, viewer_test_card), which the
// upload appends to the scene's textures when a light shows it.
#define VIEWER_TEST_CARD UINT32_MAX
#define VIEWER_TEST_CARD_WIDTH 64
#define VIEWER_TEST_CARD_HEIGHT 36
void viewer_test_card(uint8_t rgba[VIEWER_TEST_CARD_WIDTH * VIEWER_TEST_CARD_HEIGHT * 4]);

// A KHR_lights_punctual light (rtpbr_light_desc's point, spot and directional lights): no
// geometry, nothing drawn; only its light is seen.
typedef struct viewer_punctual {
    rtpbr_light_type type;  // RTPBR_LIGHT_POINT, RTPBR_LIGHT_SPOT or RTPBR_LIGHT_DIRECTIONAL
    float position[3];      // point, spot: world space
    float direction[3];     // spot, directional: unit, the way the light travels
    float color[3];         // max component 1
    float intensity;        // emission = color * intensity: candela (point, spot), lux (directional)
    float range;            // point, spot: where the light ends; 0: infinite
    float inner_cone_angle; // spot: radians, 0 <= inner < outer <= pi/2
    float outer_cone_angle;
    float angular_diameter; // directional: the disk's, radians (rtpbr_light_desc's); 0: a true direction
    float radius;           // point: the sphere's (rtpbr_light_desc's); 0: a true point
    float length;           // point with a radius: > 0 a capsule, the engine's
                            // RTPBR_LIGHT_TUBE (rtpbr_gltf_punctual_light's length); 0: a sphere
    float axis[3];          // its axis, unit (the loader's; a new tube's +X)
} viewer_punctual;

typedef struct viewer_scene {
    rtpbr_gltf_scene *loaded;
    rtpbr_material_desc *materials; // one per loaded material (edited in place)
    uint32_t material_count;
    viewer_light *lights;           // the area lights: polygons and disks, in the loader's order
    uint32_t light_count;
    viewer_punctual *punctual;      // the loaded scene's punctual lights, in its order
    uint32_t punctual_count;
    bool *primitive_is_light;       // primitives replaced by the lights' own polygons
    bool lights_restructured;       // a light was added or removed: the scene must be re-uploaded
    uint32_t light_mesh_base;       // engine mesh index of light 0's surface (last upload)
} viewer_scene;

// Area and punctual lights together: the viewer numbers them as the engine does, the area
// lights first.
static inline uint32_t viewer_scene_light_total(const viewer_scene *s) { return s->light_count + s->punctual_count; }

// Loads a glTF file; false with the loader's message on stderr.
bool viewer_scene_load(viewer_scene *s, const char *path);
// Loaded light i (i < in->light_count) as the viewer edits it: rtpbr_gpu_scene_from_loaded's
// light (a disk or an ellipse as itself, a screen's texture and coordinates, the emission as
// colour x intensity), its material, an identity transform.
void viewer_light_from_loaded(const rtpbr_gltf_scene *in, uint32_t i, viewer_light *v);
void viewer_scene_destroy(viewer_scene *s);
// Builds the engine scene: every non-emissive primitive with its (edited) material, and every
// area light both as a light (a polygon or a disk) and as an emissive mesh (its polygon, a
// disk's fan of VIEWER_DISK_SEGMENTS triangles), so that it is seen. Materials are the scene's
// (engine index i = loader material i), then one per light (the light's surface: its source
// material with the light's emission). The engine's lights are the area lights, then the
// punctual lights (rtpbr_gpu_scene_from_loaded's order and kinds: a scene without edits is
// lit as rtpbr-render lights the file). Resets the lights' transforms to the identity (the
// surfaces are uploaded where they are).
rtpbr_result viewer_scene_upload(viewer_scene *s, rtpbr_context *ctx, rtpbr_gpu_scene **out);
// In-place updates of an uploaded scene (no frame may be pending): material i; area light i's
// surface material and mesh transform, and all the lights; every area light's surface and
// transform, and all the lights (after any light edit, punctual lights' too).
rtpbr_result viewer_scene_update_material(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t material);
rtpbr_result viewer_scene_update_light(const viewer_scene *s, rtpbr_gpu_scene *gpu, uint32_t light);
rtpbr_result viewer_scene_update_lights(const viewer_scene *s, rtpbr_gpu_scene *gpu);
// Every light as the engine gets it (upload and updates): viewer_scene_light_total descs, the
// area lights (RTPBR_LIGHT_POLYGON with the vertices; RTPBR_LIGHT_DISK with position = centre,
// direction = normal, radius), then the punctual lights.
void viewer_scene_light_descs(const viewer_scene *s, rtpbr_light_desc *out);
// Adds an area light (its own surface: a rough black material with its emission; material
// and transform are set here) or a punctual light at the end of its kind, or removes light
// `index` in the viewer's numbering (area lights first; an area light's surface goes with
// it). False when out of memory or index is out of range. Each makes
// viewer_scene_needs_upload true (the engine scene's light and mesh counts change).
bool viewer_scene_add_light(viewer_scene *s, const viewer_light *light);
bool viewer_scene_add_punctual(viewer_scene *s, const viewer_punctual *light);
bool viewer_scene_remove_light(viewer_scene *s, uint32_t index);
// The new lights the viewer's Insert key (I) adds, in this order: a 0.5 m square quad facing
// down (radiance 4), a disk facing down of the quad's area and radiance (so of its power:
// radius 0.5 / sqrt(pi) m), a sphere (radius 0.1 m), a spot pointing down, a point, a
// directional light, a tube (a capsule along +X: radius 0.05 m, length 0.8 m, 2 cd), an
// ellipse facing down (half-axes 0.4 m along +X and 0.2 m, radiance 4), a screen (a 0.8 x
// 0.45 m quad facing down showing the viewer's test card, VIEWER_TEST_CARD, radiance 4 x the
// picture); all but the directional light centred at `at`.
typedef enum viewer_new_light_kind {
    VIEWER_NEW_QUAD, VIEWER_NEW_DISK, VIEWER_NEW_SPHERE, VIEWER_NEW_SPOT, VIEWER_NEW_POINT, VIEWER_NEW_DIRECTIONAL,
    VIEWER_NEW_TUBE, VIEWER_NEW_ELLIPSE, VIEWER_NEW_SCREEN, VIEWER_NEW_LIGHT_KINDS
} viewer_new_light_kind;
const char *viewer_new_light_name(int kind);
// Fills *light (the quad, the disk, the ellipse, the screen) or *punctual (the others); returns
// true for an area light.
bool viewer_new_light(int kind, const float at[3], viewer_light *light, viewer_punctual *punctual);

// True when an edit needs viewer_scene_upload (a polygon's vertex count changed, a light was
// added or removed).
bool viewer_scene_needs_upload(const viewer_scene *s);

// The nearest surface hit by the ray origin + t dir (t > 0): a light (*light >= 0, *material
// -1) or a primitive (*material its material, *light -1). False if nothing is hit.
bool viewer_scene_pick(const viewer_scene *s, const float origin[3], const float dir[3], int32_t *light,
                       int32_t *material);

// Edits of one area light, about its centre (a polygon's vertex mean, a disk's centre). A disk
// moves its centre, turns its normal (an ellipse its axis too) and scales its radius (an
// ellipse both half-axes; kept within VIEWER_MIN_DISK_RADIUS .. VIEWER_MAX_DISK_RADIUS: the
// factor applied is the one that keeps them there).
void viewer_light_center(const viewer_light *l, float out[3]);
void viewer_light_normal(const viewer_light *l, float out[3]);
void viewer_light_translate(viewer_light *l, const float d[3]);
void viewer_light_rotate(viewer_light *l, int axis, float radians); // about a world axis 0..2
void viewer_light_scale(viewer_light *l, float factor);
// A disk's half-axis across its axis set to r2 (clamped to VIEWER_MIN_DISK_RADIUS ..
// VIEWER_MAX_DISK_RADIUS; a circle becomes an ellipse whose axis is the first of its drawn
// outline's frame; r2 equal to the radius, a circle again): its surface is stretched across
// the axis. Polygons: nothing.
void viewer_light_set_radius2(viewer_light *l, float r2);
// "polygon", "screen" (a textured quad), "disk" or "ellipse".
const char *viewer_light_kind(const viewer_light *l);
// A polygon's mean distance of its vertices from the centre; a disk's radius (an ellipse's
// half-axis along its axis).
float viewer_light_radius(const viewer_light *l);
// A disk's half-axis across its axis (its radius for a circle); 0 for polygons.
float viewer_light_radius2(const viewer_light *l);
// A regular polygon of n (3..8) vertices with the light's centre, normal and mean radius. A
// disk has no vertices: it stays as it is.
void viewer_light_set_vertex_count(viewer_light *l, uint32_t n);

// "point", "spot", "directional" or "tube" (a point with a radius and a length).
const char *viewer_punctual_kind(const viewer_punctual *p);
// A punctual light the engine shades as a tube (RTPBR_LIGHT_TUBE): a point with a radius
// and a length (with a range too: windowed at the distance from its centre, as the loader maps
// it).
bool viewer_punctual_is_tube(const viewer_punctual *p);
// Edits of one punctual light. Its direction (and a tube's axis) turned about a world axis 0..2
// (the sense of viewer_light_rotate); as two angles: direction = (cos e sin a, sin e, cos e cos a), azimuth a
// about +Y from +Z toward +X, elevation e above the horizon (negative: down).
void viewer_punctual_rotate(viewer_punctual *p, int axis, float radians);
void viewer_punctual_angles(const viewer_punctual *p, float *azimuth, float *elevation);
void viewer_punctual_set_angles(viewer_punctual *p, float azimuth, float elevation);
// After an edit: values the engine accepts (intensity and range >= 0, a unit direction, a
// spot's cones 0 <= inner < outer <= pi/2 with outer at least VIEWER_MIN_CONE; radius and
// length in [0, 100], NaN 0; a unit axis, +X for none).
#define VIEWER_MIN_CONE 0.01f
void viewer_punctual_clamp(viewer_punctual *p);

#ifdef __cplusplus
}
#endif

#endif
