// The material record of the G-buffer and lighting passes. C mirror: rtpbr_shader_material
// (engine/src/internal.h), written by convert_material (engine/src/scene.c).
struct Material {
    vec4 base_color_metallic;
    vec4 emission_roughness;
    vec4 specular_color_ior;
    vec4 specular; // x: specular factor, y: double-sided, z: normal-mapped, w: normal scale
    vec4 coat;     // x: clearcoat, y: clearcoat perceptual roughness, z: model, w: anisotropy
    vec4 disney0;  // Disney: subsurface, specular, specular_tint, sheen
    vec4 disney1;  // Disney: sheen_tint, clearcoat, clearcoat_gloss, anisotropic
    vec4 sheen;    // KHR sheen: colour rgb, perceptual roughness
    vec4 anisotropy; // x: KHR anisotropy rotation (radians, from the tangent toward the bitangent)
};
