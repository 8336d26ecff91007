// A rasterised surface's material at a fragment, shared by the G-buffer pass (gbuffer.frag)
// and the forward pass of BLEND surfaces (forward.frag): the inputs gbuffer.vert writes, the
// material's textures (descriptor set 1, one set per material), and fragment_material, which
// samples every texture first, in uniform control flow, where the implicit derivatives that
// pick the mip level are defined (texture coordinates come from the vertex shader: computing
// them here from storage-buffer loads broke the derivatives on lavapipe).
// Include after rtpbr_shared.h, rtpbr/material.h, frame.glsl and material.glsl.

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec3 in_world;
layout(location = 2) in vec4 in_uv_base_color_metallic_roughness; // each slot's (gbuffer.vert)
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_uv_emission_normal;
layout(location = 5) in vec4 in_uv_clearcoat; // clearcoat, clearcoat roughness
layout(location = 6) in vec4 in_uv_sheen;     // sheen colour, sheen roughness
layout(location = 7) in vec4 in_uv_specular;  // specular, specular colour

// The material's textures, name##_texture at its slot's binding (rtpbr_shared.h); a slot
// without a texture holds a 1x1 white one.
#define DECLARE_TEXTURE(unused_a, unused_b, name, slot) layout(set = 1, binding = slot) uniform sampler2D name##_texture;
RTPBR_MATERIAL_TEXTURE_SLOTS(DECLARE_TEXTURE, 0, 0)

struct FragmentMaterial {
    vec3 baseColor;          // factor x texture
    float alpha;             // glTF coverage: the material's alpha x the base colour texture's
    float metallic;
    float roughness;         // perceptual, floored as the material resolve does
    vec3 normal;             // shading normal (world, unit), on the side the camera sees
    vec3 anisotropyDirection; // world, unit; zero: none (no tangents)
    vec3 emission;           // emitted radiance toward the camera
};

// The texture slots this pipeline samples (RTPBR_SPEC_GBUFFER_TEXTURES, rtpbr_shared.h): all by
// default (the forward pass); the G-buffer pass compiles out those its material leaves white.
layout(constant_id = RTPBR_SPEC_GBUFFER_TEXTURES) const uint gbuffer_texture_slots = RTPBR_GBUFFER_TEXTURES_ALL;
#define GBUFFER_SLOT(binding) ((gbuffer_texture_slots & (1u << (binding))) != 0u)

FragmentMaterial fragment_material(Material m)
{
    // A slot left out reads as the white stand-in would (1x1, 255 in every channel: exactly 1).
    vec4 base_color_texel = vec4(1.0), metallic_roughness_texel = vec4(1.0), emission_texel = vec4(1.0),
         normal_texel = vec4(1.0);
    if (GBUFFER_SLOT(RTPBR_BINDING_TEXTURE_BASE_COLOR))
        base_color_texel = texture(base_color_texture, in_uv_base_color_metallic_roughness.xy);
    if (GBUFFER_SLOT(RTPBR_BINDING_TEXTURE_METALLIC_ROUGHNESS))
        metallic_roughness_texel = texture(metallic_roughness_texture, in_uv_base_color_metallic_roughness.zw);
    if (GBUFFER_SLOT(RTPBR_BINDING_TEXTURE_EMISSION))
        emission_texel = texture(emission_texture, in_uv_emission_normal.xy);
    if (GBUFFER_SLOT(RTPBR_BINDING_TEXTURE_NORMAL))
        normal_texel = texture(normal_texture, in_uv_emission_normal.zw);
    FragmentMaterial f;
    vec3 n = normalize(in_normal);
    // Every surface reflects on the side the camera sees; it emits there only if that is its
    // front side or the material is double-sided.
    bool back = dot(n, frame.camera_position.xyz - in_world) < 0.0;
    // glTF normal textures: tangent-space normal (x, y scaled by normalTexture.scale) in the
    // frame (T, B = w N x T, N) of the interpolated vertex tangent.
    // (a material with the flag has the normal slot: rtpbr_gbuffer_material_slots)
    if (GBUFFER_SLOT(RTPBR_BINDING_TEXTURE_NORMAL) && (m.flags & RTPBR_MATERIAL_FLAG_NORMAL_MAPPED) != 0u &&
        dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
        vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
        vec3 b = (in_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
        vec3 ts = normal_texel.xyz * 2.0 - 1.0;
        ts.xy *= m.normal_scale;
        n = normalize(t * ts.x + b * ts.y + n * ts.z);
    }
    // The anisotropy direction (KHR_materials_anisotropy; Disney: the tangent): the tangent
    // made orthogonal to the shading normal, rotated toward the bitangent. Zero without tangents.
    f.anisotropyDirection = vec3(0.0);
    if (dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
        vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
        if (dot(t, t) > 1e-12) {
            t = normalize(t);
            vec3 b = (in_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
            float rotation = m.anisotropy_rotation;
            f.anisotropyDirection = t * cos(rotation) + b * sin(rotation);
        }
    }
    f.normal = back ? -n : n;
    f.emission = back && (m.flags & RTPBR_MATERIAL_FLAG_DOUBLE_SIDED) == 0u ? vec3(0.0) : m.emission * emission_texel.rgb;
    // glTF: textures multiply the factors; metallic-roughness holds roughness in g, metallic in b.
    // The roughness floor of the shader library's material resolve (material.h), applied here
    // so that the lighting passes read the G-buffer's roughness as the resolve would.
    f.roughness = Material_PerceptualRoughness(m.roughness * metallic_roughness_texel.g);
    f.metallic = rtpbr_saturate(m.metallic * metallic_roughness_texel.b);
    f.baseColor = m.base_color * base_color_texel.rgb;
    f.alpha = m.alpha * base_color_texel.a;
    return f;
}
