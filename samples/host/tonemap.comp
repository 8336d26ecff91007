#version 450
// rtpbr-sample-host's own tone mapping: rtpbr's linear radiance (the lighting pass's HDR
// output) scaled by 2^exposure, Reinhard on luminance, sRGB-encoded into an RGBA8 image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D ldr;
layout(push_constant) uniform Tonemap {
    float scale; // 2^exposure
    uint width, height;
    uint swap_rb; // 1: stored as B, G, R, A (copied as bytes into a BGRA swapchain image)
} tm;

// The sRGB transfer function (IEC 61966-2-1).
vec3 srgb_encode(vec3 c)
{
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main()
{
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= tm.width || p.y >= tm.height) return;
    vec3 c = max(imageLoad(hdr, ivec2(p)).rgb * tm.scale, vec3(0.0));
    float l = dot(c, vec3(0.2126, 0.7152, 0.0722)); // Rec. 709 luminance
    c *= 1.0 / (1.0 + l);                             // Reinhard on luminance: L / (1 + L)
    c = srgb_encode(clamp(c, 0.0, 1.0));
    imageStore(ldr, ivec2(p), vec4(tm.swap_rb != 0u ? c.bgr : c, 1.0));
}
