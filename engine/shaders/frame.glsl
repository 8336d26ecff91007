// The per-frame uniform block (fields declared once, in rtpbr_shared.h).
layout(set = 0, binding = RTPBR_FRAME_BINDING, std140) uniform Frame {
    RTPBR_FRAME_FIELDS(RTPBR_SHARED_FIELD, Frame)
} frame;
