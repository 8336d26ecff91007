// The G-buffer pass's per-draw push constants (fields declared once, in rtpbr_shared.h:
// RTPBR_DRAW_FIELDS; C: rtpbr_shader_draw). Include after rtpbr_shared.h.
layout(push_constant, std430) uniform Draw {
    RTPBR_DRAW_FIELDS(RTPBR_SHARED_FIELD, Draw)
} draw;
