// The material record of the G-buffer and lighting passes (fields declared once, in
// rtpbr_shared.h; C mirror rtpbr_shader_material, written by convert_material in scene.c).
struct Material {
    RTPBR_MATERIAL_FIELDS(RTPBR_SHARED_FIELD, Material)
};
