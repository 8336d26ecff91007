// The per-frame uniform block (C mirror: rtpbr_shader_frame in engine/src/internal.h).
layout(set = 0, binding = RTPBR_FRAME_BINDING, std140) uniform Frame {
    mat4 view_proj;       // clip from world
    mat4 inv_view_proj;   // world from clip
    vec4 camera_position; // xyz
    vec4 background;      // rgb radiance
    uvec2 size;           // render width, height
    uint light_count;
    float cull_form_factor; // per-tile light culling threshold (cull.comp); < 0: off
    uint tiles_x;           // lighting tiles per row
    uint tile_capacity;     // tiles in the frame: the length of each class's tile list
    uint shadow_light_count; // lights with a shadow ratio (shadow_ratio.glsl); 0: shadows off
    uint pad0;
} frame;
