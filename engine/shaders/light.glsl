// A polygonal light as the passes read it from their lights buffer (fields declared once, in
// rtpbr_shared.h: RTPBR_LIGHT_FIELDS; C: rtpbr_shader_light). Include after rtpbr_shared.h.
struct Light {
    RTPBR_LIGHT_FIELDS(RTPBR_SHARED_FIELD, Light)
};
