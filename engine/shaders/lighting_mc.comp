#version 450
#extension GL_GOOGLE_include_directive : require
// Brute-force Monte Carlo lighting pass: the reference lighting.comp is measured against in
// bench/ (rtpbr_render_desc.mc_samples). Same G-buffer, lights, materials, descriptor set and
// output as lighting.comp; the same direct-lighting integral (no visibility) of the same
// material model (lighting.comp's shade_lights: metallic-roughness with the Kulla-Conty
// dielectric-over-diffuse layering and KHR clearcoat, or Disney), estimated by sampling
// instead of LTC: every lobe is evaluated per sample direction by the shader library
// (surface.h's Surface_Evaluate: BRDF_Specular, KC_Lobe with E, E_F fetched at the sample's
// NoL, BRDF_DisneyDiffuse / _Sheen / _Clearcoat with the true GTR1 coat), where lighting.comp integrates LTC fits and
// evaluates the separable lobes at one representative direction per polygon. Like
// lighting.comp it shades anisotropic lobes isotropically at sqrt(alpha_t alpha_b) (the
// G-buffer has no tangent).
// Per pixel and light, mc.samples directions, each drawn from the mixture
//   pdf(w) = (1 - pBrdf) pdf_light(w) + pBrdf pdf_vndf(w)
// (one-sample MIS with the balance heuristic; Veach & Guibas 1995, "Optimally Combining
// Sampling Techniques for Monte Carlo Rendering"): pdf_light is uniform area sampling of the
// polygon (fan triangles picked by area) converted to solid angle, d^2 / (|cos_light| A);
// pdf_vndf reflects a visible normal of the main specular lobe (Heitz 2018 / Dupuy & Benyoub
// 2023 for GGX, Heitz & d'Eon 2014 for Beckmann; shaderlib sampling.h). pBrdf = 0.5 Fs /
// (Fs + Fd), Fs, Fd the largest channel of the specular lobe's average Fresnel and of the
// diffuse colour: 0 for a surface without specular (pure light sampling), 1/2 for a metal.
// Punctual lights (point, spot, directional: shaderlib punctual.h) are exact, as in
// lighting.comp: their BRDF times N.L times their intensity's factor, with no sample. A sphere
// light (a point light with a radius) is sampled uniformly in the cone it subtends (pdf
// 1 / (2 pi (1 - cos of its half-angle))), and a BRDF direction hits it when inside that cone;
// its radiance is windowed by its range at the distance from its centre.
// A tube (capsule) light: as a polygon, its surface's points uniform by area (pdf d^2 /
// (cos_light A), A = 4 pi r^2 + 2 pi r L), cos_light by the point's own normal (> 0 only: the
// convex capsule hides the rest), and a BRDF direction meets it at the ray's first hit; its
// radiance is windowed by its range at the distance from its centre, as a sphere's.
// No per-tile culling: every light is summed at every pixel (lights behind a one-sided light's
// plane are skipped per pixel, where the integrand is 0). The host splits the pass into
// dispatches over ranges of lights and samples (lavapipe ends every loop of a shader run after
// 65535 iterations in all; engine/src/passes/lighting_mc.c): each adds its partial sums,
// already divided by the total sample count, to the radiance image. Kept flat (no nested early returns:
// lavapipe's gallivm limits control-flow nesting, see tests/shaderlib/gpu/kernel.h).
#include "rtpbr_shared.h"
#define RTPBR_RADIANCE_ACCESS // read and written: the dispatches after the first add to it
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "rtpbr/punctual.h"
#include "material.glsl"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_TILE_SIZE, local_size_y = RTPBR_TILE_SIZE) in;

// C mirror: rtpbr_shader_mc (engine/src/internal.h).
layout(push_constant, std430) uniform McParams {
    RTPBR_MC_FIELDS(RTPBR_SHARED_FIELD, McParams)
} mc;

#include "lighting_common.glsl"
#include "mc_sampling.glsl"
#include "capsule.glsl"
// The textured quads' emission (rtpbr_shared.h: RTPBR_BINDING_LIGHT_TEXTURES), read unblurred
// (level 0) at the sample's point.
layout(set = 0, binding = RTPBR_BINDING_LIGHT_TEXTURES) uniform sampler2DArray light_textures;
#include "shadow_ratio.glsl"

#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define MC_SAMPLE_VNDF Sample_Beckmann_VNDF
#define MC_PDF_REFLECTION PDF_Beckmann_Reflection
#else
#define MC_SAMPLE_VNDF Sample_GGX_VNDF
#define MC_PDF_REFLECTION PDF_GGX_Reflection
#endif

// Reflected radiance from this dispatch's lights at P: samples mc.first_sample ..
// + mc.sample_count - 1 of the mc.samples directions per light of the estimate.
vec3 shade_lights_mc(vec3 P, vec3 N, vec3 V, ShadingSurface s, uvec2 pixel)
{
    // Local frame z = N, x along the anisotropy direction (alpha_t) when there is one, else
    // toward V (as LTC_Frame); NoV clamped as the LTC table lookup.
    bool anisotropic = s.anisoK > 1.0f;
    vec3 T = (anisotropic ? s.anisoDir : V) - N * dot(N, anisotropic ? s.anisoDir : V);
    float tl2 = dot(T, T);
    vec3 up = abs(N.z) > 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f);
    T = tl2 > 1e-10f ? T * inversesqrt(tl2) : normalize(cross(up, N));
    vec3 B = cross(N, T);
    float NoV = clamp(dot(N, V), 1e-4f, 1.0f);
    vec2 woTangent = vec2(dot(V, T), dot(V, B));
    float woTangentLength = length(woTangent);
    woTangent = woTangentLength > 0.0f ? woTangent * (sqrt(1.0f - NoV * NoV) / woTangentLength) : vec2(0.0f);
    vec3 wo = vec3(woTangent, NoV);
    // Strategy weights: Schlick's average Fresnel f0 + (f90 - f0) / 21 (Kulla & Conty 2017).
    float fs = Surface_Max3(F_Avg_Schlick(s.f0, s.f90));
    float fd = Surface_Max3(s.diffuseColor);
    float pBrdf = fs > 0.0f ? 0.5f * fs / (fs + fd) : 0.0f;
    vec2 alphaSample = s.alphas; // the specular lobe's (alpha_t along T, alpha_b along B)

    uint samples = max(mc.samples, 1u);
    vec3 sum = vec3(0.0f);
    uint lightEnd = min(mc.first_light + mc.light_count, frame.light_count);
    for (uint i = mc.first_light; i < lightEnd; ++i) {
        // The light's fields are read from the buffer where they are used (no private copy).
        uint count = min(lights[i].vertex_count, uint(RTPBR_SHADER_MAX_POLYGON_VERTICES));
        uint shape = lights[i].shape;
        // A tube: its capsule's points uniform by area (capsule.glsl) and the first point a ray
        // meets (capsule_ray), each one-sided by its own normal (the capsule hides the others).
        bool tubeLight = shape == uint(RTPBR_LIGHT_SHAPE_TUBE);
        bool twoSided = lights[i].two_sided != 0.0f && !tubeLight;
        vec4 plane = lights[i].plane;
        float side = dot(plane.xyz, P) + plane.w;
        // Fan triangles (v0, vk, vk+1), k = 1..count-2: vertices[k].w is the area of those below
        // vk (rtpbr_shared.h, RTPBR_LIGHT_FIELDS); area is the polygon's.
        vec3 v0 = lights[i].vertices[0].xyz;
        float area = lights[i].area;
        // A sphere: the cone it subtends from P (axis sphereAxis, cos of its half-angle
        // cosMax; every direction from inside it, cosMax = -1), sampled uniformly (pdf
        // 1 / (2 pi (1 - cosMax))); a direction hits it exactly when it is inside the cone.
        bool sphereLight = shape == uint(RTPBR_LIGHT_SHAPE_SPHERE);
        vec4 sphere = lights[i].sphere;
        vec3 toCentre = sphere.xyz - P;
        float centre2 = dot(toCentre, toCentre);
        bool insideSphere = centre2 <= sphere.w * sphere.w;
        float sin2Max = insideSphere ? 1.0f : sphere.w * sphere.w / centre2;
        float cosMax = insideSphere ? -1.0f : sqrt(max(1.0f - sin2Max, 0.0f));
        float oneMinusCos = insideSphere ? 2.0f : sin2Max / (1.0f + cosMax);
        vec3 sphereAxis = toCentre * inversesqrt(max(centre2, 1e-30f));
        // A sphere's range window at the distance from its centre; a tube's the same (its record's
        // sphere is centred on it; vertices[3].w its 1 / range^2).
        float window = sphereLight ? Punctual_RangeWindow(centre2, lights[i].vertices[0].w)
                       : tubeLight ? Punctual_RangeWindow(centre2, lights[i].vertices[3].w)
                                   : 1.0f;
        // A disk: as a polygon, its points uniform by area (mc_disk_point, mc_ray_disk).
        bool diskLight = shape == uint(RTPBR_LIGHT_SHAPE_DISK);
        bool lit = ((shape == uint(RTPBR_LIGHT_SHAPE_POLYGON) && count >= 3u || diskLight || tubeLight) && area > 0.0f &&
                    (twoSided ? side != 0.0f : side > 0.0f) && window > 0.0f) ||
                   (sphereLight && window > 0.0f && centre2 > 0.0f);
        uint n = lit ? mc.sample_count : 0u;

        uint rng = mc_seed(pixel, i, mc.seed) * mc.skip_mul + mc.skip_add; // at mc.first_sample
        vec3 lightSum = vec3(0.0f);
        for (uint j = 0u; j < n; ++j) {
            float uStrategy = mc_uniform(rng);
            float uPick = mc_uniform(rng);
            vec2 u = vec2(mc_uniform(rng), mc_uniform(rng));
            bool fromBrdf = uStrategy < pBrdf;

            vec3 wi;
            float t;
            bool hit;
            vec3 lightNormal = plane.xyz; // a tube's: at the point sampled or met
            if (fromBrdf) {
                // Strategy 2: a visible normal of the specular lobe, reflected; does it hit?
                vec3 wiLocal = Reflect_About(wo, MC_SAMPLE_VNDF(wo, alphaSample.x, alphaSample.y, u));
                wi = T * wiLocal.x + B * wiLocal.y + N * wiLocal.z;
                hit = sphereLight ? dot(wi, sphereAxis) >= cosMax
                      : tubeLight ? capsule_ray(P, wi, v0, lights[i].vertices[1].xyz, lights[i].vertices[0].w, t, lightNormal)
                      : diskLight ? mc_ray_disk(P, wi, i, t) : mc_ray_polygon(P, wi, i, count, t);
            } else if (sphereLight) {
                // Strategy 1 for a sphere: a direction uniform in its cone.
                float cosT = 1.0f - u.x * oneMinusCos;
                float sinT = sqrt(max(1.0f - cosT * cosT, 0.0f));
                float phi = 6.28318531f * u.y;
                vec3 a1 = normalize(cross(abs(sphereAxis.z) < 0.9f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f), sphereAxis));
                wi = sphereAxis * cosT + (a1 * cos(phi) + cross(sphereAxis, a1) * sin(phi)) * sinT;
                hit = true;
            } else {
                // Strategy 1: a uniform point on the polygon (fan triangle chosen by area).
                float target = uPick * area;
                uint pick = 1u;
                for (uint k = 2u; k + 1u < count; ++k)
                    if (target >= lights[i].vertices[k].w) pick = k;
                vec3 toLight = (tubeLight ? capsule_point(v0, lights[i].vertices[1].xyz, lights[i].vertices[0].w, u, lightNormal)
                                : diskLight ? mc_disk_point(i, u)
                                          : mc_triangle_point(v0, lights[i].vertices[pick].xyz, lights[i].vertices[pick + 1u].xyz, u)) - P;
                t = length(toLight);
                wi = toLight / max(t, 1e-30f);
                hit = t > 0.0f;
            }
            // The light's front faces -plane.xyz travellers; one-sided lights emit only there.
            float cosLight = -dot(lightNormal, wi);
            hit = hit && (sphereLight || (twoSided ? cosLight != 0.0f : cosLight > 0.0f));
            float pdfLight = hit ? (sphereLight ? 1.0f / (6.28318531f * oneMinusCos) : t * t / (abs(cosLight) * area)) : 0.0f;

            vec3 wiLocal = vec3(dot(wi, T), dot(wi, B), dot(wi, N));
            float pdfBrdf = pBrdf > 0.0f ? MC_PDF_REFLECTION(wo, wiLocal, alphaSample.x, alphaSample.y) : 0.0f;
            float pdf = (1.0f - pBrdf) * pdfLight + pBrdf * pdfBrdf;

            // every lobe of the material (the shader library's, as a punctual light's)
            float NoL = wiLocal.z;
            vec3 f = Surface_Evaluate(s, wo, wiLocal);
            bool valid = hit && NoL > 0.0f && pdf > 0.0f;
            // A textured quad: its texture at (s, t) of the point met, X = v0 + s e1 + t e2.
            uint layer = lights[i].texture;
            if (valid && layer != 0u) {
                vec3 e1 = lights[i].vertices[1].xyz - v0, e2 = lights[i].vertices[3].xyz - v0;
                vec3 r = P + t * wi - v0;
                float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
                float r1 = dot(r, e1), r2 = dot(r, e2), det = a11 * a22 - a12 * a12;
                vec2 st = vec2(a22 * r1 - a12 * r2, a11 * r2 - a12 * r1) / det;
                f *= textureLod(light_textures, vec3(st, float(layer - 1u)), 0.0f).rgb;
            }
            lightSum += valid ? f * (NoL / pdf) : vec3(0.0f);
        }
        vec3 lightTerm = lightSum / float(samples) * window;
        // A punctual light: exact, no sample (added once, by the dispatch of the first samples).
        if (shape != uint(RTPBR_LIGHT_SHAPE_POLYGON) && !sphereLight && !diskLight && !tubeLight) {
            vec4 incident = Punctual_Incident(P, shape, lights[i].vertices[0], lights[i].vertices[1].xyz, lights[i].vertices[2].xy);
            vec3 wiLocal = vec3(dot(incident.xyz, T), dot(incident.xyz, B), dot(incident.xyz, N));
            bool on = mc.first_sample == 0u && wiLocal.z > 0.0f && incident.w > 0.0f;
            lightTerm = on ? Surface_Evaluate(s, wo, wiLocal) * (wiLocal.z * incident.w) : vec3(0.0f);
        }
        sum += lights[i].radiance * lightTerm * shadow_factor(i, ivec2(pixel));
    }
    return sum;
}

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(uvec2(pixel), frame.size));
    float depth = inside ? texelFetch(gbuffer_depth, pixel, 0).r : 1.0f;
    bool surface = depth < 1.0f;
    vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
    vec3 P = world.xyz / world.w;

    bool first = mc.first_light == 0u && mc.first_sample == 0u;
    vec4 result = vec4(frame.background.rgb, 0.0f);
    if (inside && surface) {
        GBufferSurface g = gbuffer_surface(pixel, texelFetch(gbuffer2, pixel, 0));
        vec3 V = normalize(frame.camera_position.xyz - P);
        vec3 N = g.normal;
        // NoV clamped below as the LTC table lookup does.
        ShadingSurface s = surface_terms(g, materials[g.materialIndex], clamp(dot(N, V), 1e-4f, 1.0f));
        vec3 reflected = shade_lights_mc(lifted_point(ndc, depth, P, N), N, V, s, uvec2(pixel));
        result = first ? vec4(g.emission + reflected, 1.0f) : imageLoad(radiance, pixel) + vec4(reflected, 0.0f);
    }
    if (inside && (first || surface)) imageStore(radiance, pixel, result);
}
