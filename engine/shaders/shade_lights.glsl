// Reflected radiance from polygonal lights at a surface point (shade_lights), the per-light
// loop shared by the LTC lighting pass (lighting.comp) and the forward pass of BLEND surfaces
// (forward.frag): the LTC tables, one pass over a light's edges per lobe (light_lobe), the
// point correction and the streak estimate. All BRDF and polygon-integration math comes from
// the shader library (shaderlib/rtpbr); this file only fetches, loops and sums.
// Include after shading.glsl (and, in the lighting pass, lighting_common.glsl), with
// RTPBR_LIGHTING_FULL set and a shadow_factor(uint light, ivec2 pixel) defined.

layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_1) uniform sampler2D lut_ltc_ggx_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_2) uniform sampler2D lut_ltc_ggx_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_1) uniform sampler2D lut_ltc_beckmann_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_2) uniform sampler2D lut_ltc_beckmann_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_1) uniform sampler2D lut_ltc_disney_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_2) uniform sampler2D lut_ltc_disney_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_1) uniform sampler2D lut_ltc_sheen_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_2) uniform sampler2D lut_ltc_sheen_2;

// The LTC tables of the NDF this variant is built for.
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define LUT_LTC_1 lut_ltc_beckmann_1
#define LUT_LTC_2 lut_ltc_beckmann_2
#else
#define LUT_LTC_1 lut_ltc_ggx_1
#define LUT_LTC_2 lut_ltc_ggx_2
#endif

// One pass over light i's edges (vectors from P in the LTC frame): the horizon clip, then the
// LTC lobe minv; returns its form factor, the clipped polygon's vector form factor F (up to
// its sign) and the lobe's own vector form factor Fl (LTC_LobeEndVector; callers that do not
// read it leave its x, y to dead-code elimination). The basic variant integrates its one LTC
// lobe in this pass; the full variant runs a pass per lobe the material has, so that one
// lobe's clip state is live at a time (registers: the lobes' states together spilled on RDNA3).
float light_lobe(uint i, vec3 P, mat3 ltcFrame, mat3 minv, out vec3 F, out vec3 Fl)
{
    LtcClipper horizon = LTC_ClipperBegin();
    LtcLobe lobe = LTC_LobeBegin(minv);
    F = vec3(0.0f);
#ifdef RTPBR_STATS_FIXED_LIGHTS
    const uint count = 4u;
#else
    uint count = lights[i].vertex_count;
#endif
    vec3 first = rtpbr_mul(ltcFrame, lights[i].vertices[0].xyz - P);
    vec3 a = first;
    [[unroll]] for (uint k = 1u; k <= count + 1u; ++k) {
        LtcSegment seg;
        vec3 b = a;
        if (k <= count) {
            b = k < count ? rtpbr_mul(ltcFrame, lights[i].vertices[k].xyz - P) : first;
            seg = LTC_ClipEdge(horizon, a, b);
        } else {
            seg = LTC_ClipClose(horizon);
        }
        if (seg.valid) {
            F += LTC_EdgeIntegral(LTC_SafeNormalize(seg.a), LTC_SafeNormalize(seg.b));
            LTC_LobeEdge(lobe, seg.a, seg.b);
        }
        a = b;
    }
    Fl = LTC_LobeEndVector(lobe);
    return LTC_LobeEnd(lobe);
}

// The specular lobe's LTC result ltcFF corrected (ltc.h): the point correction (LTC_PointFactor:
// the true f NoL (F = 1, the lobe the tables were fitted to) at the centre of the part of the
// light the LTC sees, against the LTC's value there, the table's scale norm x its density) or,
// for a light in the LTC's tail, the tail estimate (LTC_PointTail: f at the direction of the
// light's vector form factor F x pi x its form factor ff), whichever is larger
// (LTC_PointCombine); lenF = |F| (LTC_PointWidthRatio).
float specular_corrected(vec3 Fl, vec4 ltc1, float norm, float NoV, float specR, float ltcFF, vec3 F, float ff,
                         float lenF)
{
    // recomputed here rather than kept live through the light loop (registers of the full variant)
    float alpha = Alpha_FromPerceptual(specR);
    vec3 vLocal = vec3(sqrt(max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);
    LtcPoint pt = LTC_LobePoint(Fl, ltc1);
    float NoL = pt.dir.z;
    vec3 h = vLocal + pt.dir;
    float hh = dot(h, h);
    float fCos = NoL > 0.0f && hh > 1e-12f
                     ? D_Microfacet(h.z * inversesqrt(hh), alpha) * V_Microfacet(NoV, NoL, alpha) * NoL
                     : 0.0f;
    float corrected = ltcFF * LTC_PointFactor(fCos, norm * pt.density, ltcFF, LTC_PointWidthRatio(alpha, sqrt(hh), lenF));
    float weight = LTC_PointTailWeight(Fl, ltcFF, ff);
    float tail = 0.0f;
    if (weight > 0.0f) {
        vec3 c = F / lenF;
        vec3 hc = vLocal + c;
        float hc2 = dot(hc, hc);
        float f = c.z > 0.0f && hc2 > 1e-12f ? D_Microfacet(hc.z * inversesqrt(hc2), alpha) * V_Microfacet(NoV, c.z, alpha) : 0.0f;
        tail = LTC_PointTail(f, ff, norm);
    }
    return LTC_PointCombine(corrected, tail, weight);
}

#if RTPBR_LTC_STREAK && RTPBR_NDF == RTPBR_NDF_GGX && !RTPBR_LIGHTING_FULL
#define RTPBR_ENGINE_STREAK 1
#define RTPBR_NO_STREAK 0xffffffffu
// The streak estimate (ltc.h, LTC_StreakEnd) of light i's specular lobe, after the light loop
// (shade_lights): two more passes over its horizon-clipped edges, one for its vector form
// factor F and its elevations, one for the chords through the nodes. Returns the estimate
// (F = 1) and its weight (LTC_StreakWeight x its trust), (-1, 0) for none.
vec3 light_streak(uint i, vec3 P, mat3 ltcFrame, float NoV, float specR)
{
#ifdef RTPBR_STATS_FIXED_LIGHTS
    const uint count = 4u;
#else
    uint count = lights[i].vertex_count;
#endif
    vec3 vLocal = vec3(sqrt(max(1.0f - NoV * NoV, 0.0f)), 0.0f, NoV);
    vec3 F = vec3(0.0f);
    LtcStreak st = LTC_StreakBegin();
    [[dont_unroll]] for (int pass = 0; pass < 2; ++pass) {
        LtcClipper horizon = LTC_ClipperBegin();
        vec3 first = rtpbr_mul(ltcFrame, lights[i].vertices[0].xyz - P);
        vec3 a = first;
        for (uint k = 1u; k <= count + 1u; ++k) {
            LtcSegment seg;
            vec3 b = a;
            if (k <= count) {
                b = k < count ? rtpbr_mul(ltcFrame, lights[i].vertices[k].xyz - P) : first;
                seg = LTC_ClipEdge(horizon, a, b);
            } else {
                seg = LTC_ClipClose(horizon);
            }
            if (seg.valid) {
                if (pass == 0) {
                    F += LTC_EdgeIntegral(LTC_SafeNormalize(seg.a), LTC_SafeNormalize(seg.b));
                    LTC_StreakEdge(st, seg.a, seg.b);
                } else {
                    LTC_StreakChordEdge(st, seg.a, seg.b);
                }
            }
            a = b;
        }
        if (pass == 0)
            LTC_StreakNodes(st, F);
    }
    vec2 e = LTC_StreakEnd(st, vLocal, Alpha_FromPerceptual(specR));
    return vec3(e.x, e.y * LTC_StreakWeight(vLocal, F), LTC_StreakVoH(st, vLocal));
}
#endif

// Reflected radiance from the tile's polygonal lights, for the model of lighting_common.glsl
// (surface_terms). Every lobe's polygon integral comes from the shader library: LTC (Heitz et
// al. 2016, ltc.h) for the specular lobes and Burley's diffuse, the clipped polygon's vector
// form factor for Lambert, Kulla-Conty (kulla_conty.h) for the multiple-scattering lobes and
// the dielectric-over-diffuse layering (the specular lobe's f_ms shaped with RTPBR_KC_SHAPE:
// KC_PolygonLobeShaped, below). Separable lobes (f_ms, the layered base) integrate as
// (1 - E(mu_o)) / (1 - E_avg) times the form factor times 1 - (the cosine-weighted mean of E
// over the polygon), from E at the representative direction (that of the vector form factor
// of the polygon's part above the horizon) widened towards E_avg with the polygon's size
// (KC_PolygonLobe, KC_PolygonMeanE). Disney's subsurface shape and sheen are evaluated at the
// representative direction times pi x the form factor; its GTR1 coat is integrated as GGX at
// the same alpha. Per light and lobe: one pass over the edges (light_lobe). The lights: those
// of the tile's mask (the lighting pass), or with RTPBR_SHADE_ALL_LIGHTS every light of the
// frame (the forward pass: its surfaces are not in the G-buffer the masks were culled by).
// shadow_factor(i, pixel): light i's shadow ratio at the pixel (shadow_ratio.glsl), or 1.
vec3 shade_lights(vec3 P, vec3 N, vec3 V, Surface s, uint tile, ivec2 pixel)
{
    vec2 uv = LTC_LutCoord(s.NoV, s.specR);
    vec4 ltc1 = textureLod(LUT_LTC_1, uv, 0.0f);
    vec4 ltc2 = textureLod(LUT_LTC_2, uv, 0.0f);
    vec3 specularScale = LTC_FresnelScale(ltc2, s.f0, s.f90);
    mat3 ltcFrame = LTC_Frame(N, V);
    mat3 specularMinv = LTC_InverseMatrix(ltc1);
    vec3 vLocal = vec3(sqrt(max(1.0f - s.NoV * s.NoV, 0.0f)), 0.0f, s.NoV);
    // The point correction and tail estimate (specular_corrected) on the isotropic specular lobe: its scale,
    // the table's norm, and in the full variant whether the lobe is isotropic.
    float pointNorm = ltc2.x;
    bool pointOn = RTPBR_LTC_POINT_CORRECTION != 0;
#if RTPBR_LIGHTING_FULL
    bool coated = s.coat > 0.0f;
    vec4 ltc1c = LTC_Identity();
    vec3 coatScale = RTPBR_F3(0.0f);
    if (coated) {
        vec2 uvc = LTC_LutCoord(s.NoV, s.coatR);
        ltc1c = textureLod(LUT_LTC_1, uvc, 0.0f);
        coatScale = s.coat * LTC_FresnelScale(textureLod(LUT_LTC_2, uvc, 0.0f), RTPBR_F3(RTPBR_MATERIAL_COAT_F0), 1.0f);
    }
    // Burley's diffuse (Disney): its LTC fit, column = the material's roughness.
    vec4 ltc1d = LTC_Identity();
    vec3 burleyScale = RTPBR_F3(0.0f);
    DisneyMaterial dss = s.dm; // the subsurface shape alone
    dss.subsurface = 1.0f;
    if (s.disney) {
        vec2 uvd = LTC_LutCoord(s.NoV, s.roughness);
        ltc1d = textureLod(lut_ltc_disney_1, uvd, 0.0f);
        burleyScale = ((1.0f - s.dm.subsurface) * textureLod(lut_ltc_disney_2, uvd, 0.0f).x) * s.diffuseColor;
    }
    // KHR sheen: its LTC fit (sheen.h); the layer below is scaled by the KHR albedo scaling
    // with E_sheen at NoV and at the polygon's representative direction.
    vec4 ltc1s = LTC_Identity();
    vec3 sheenScale = RTPBR_F3(0.0f);
    if (s.sheen) {
        vec2 uvs = LTC_LutCoord(s.NoV, s.sheenR);
        ltc1s = textureLod(lut_ltc_sheen_1, uvs, 0.0f);
        sheenScale = Sheen_LtcScale(textureLod(lut_ltc_sheen_2, uvs, 0.0f), s.sheenColor);
    }
    // The anisotropic stretch about the mirror direction (LTC_AnisotropicInverseMatrix): the
    // anisotropy direction made orthogonal to it; no stretch without one.
    vec3 mirror = vec3(-vLocal.x, 0.0f, vLocal.z);
    vec3 anisoLocal = rtpbr_mul(ltcFrame, s.anisoDir);
    vec3 e1 = anisoLocal - mirror * dot(anisoLocal, mirror);
    float e1Length = length(e1);
    if (s.anisoK > 1.0001f && e1Length > 1e-4f) {
        specularMinv = LTC_AnisotropicInverseMatrix(ltc1, mirror, e1 / e1Length, s.anisoK);
        specularScale *= LTC_AnisotropicAlbedoScale(ltc1, specularMinv);
        pointOn = false; // no point correction for anisotropic lobes
    }
#endif

    // The multiple-scattering lobe: with RTPBR_KC_SHAPE the shaped lobe (kulla_conty.h,
    // KC_PolygonLobeShaped): beta (1 - Eo) x the specular lobe's corrected form factor, which
    // joins the specular term's scale, plus (1 - beta) x the separable lobe (no register is
    // added to the loop: the full variant is at gfx1100's limit).
#if RTPBR_KC_SHAPE
    float kcBeta = KC_ShapeWeight(s.specR, s.NoV);
    specularScale += s.msColor * (kcBeta * rtpbr_pos(1.0f - s.Eo));
    vec3 msColor = s.msColor * (1.0f - kcBeta);
#else
    vec3 msColor = s.msColor;
#endif
    vec3 sum = vec3(0.0f);
#if RTPBR_LTC_POINT_CORRECTION && !RTPBR_LIGHTING_FULL
    // The sum of the specular lobe's corrected results over the lights: the share of the lobe's
    // mass they claim (see the end of the loop).
    float specularMass = 0.0f;
#endif
#ifdef RTPBR_ENGINE_STREAK
    uint streakLight = RTPBR_NO_STREAK;
    float streakFF = 0.0f; // its specular result in the loop
#endif
#ifdef RTPBR_STATS_FIXED_LIGHTS
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i) {
#elif defined(RTPBR_SHADE_ALL_LIGHTS)
    for (uint i = 0u; i < frame.light_count; ++i) {
#else
    uint words = (frame.light_count + 31u) / 32u;
    for (uint word = 0u; word < words; ++word)
    for (uint bits = tile_masks[tile * uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u) {
        uint i = word * 32u + uint(findLSB(bits));
#endif
        // P on the light's plane sees it edge-on; behind a one-sided light, nothing; a light
        // whose bounding sphere is below the horizon, nothing.
        vec4 plane = lights[i].plane;
        vec4 sphere = lights[i].sphere;
        float side = dot(plane.xyz, P) + plane.w; // > 0: the front (emitting) side
        bool twoSided = lights[i].two_sided != 0.0f;
        if (abs(side) <= 1e-7f * sphere.w || (!twoSided && side < 0.0f) || dot(N, sphere.xyz - P) < -sphere.w)
            continue;

#ifdef RTPBR_ENGINE_STREAK
        // (while the bounding sphere is live: a lane mask rather than four registers kept)
        bool streakSized = LTC_StreakCandidate(sphere.w, length(sphere.xyz - P), Alpha_FromPerceptual(s.specR), s.NoV);
#endif
        vec3 F, Fl;
        float specularFF = light_lobe(i, P, ltcFrame, specularMinv, F, Fl);
        F = F.z < 0.0f ? -F : F;
        float ff = min(F.z, 1.0f);
        if (!(ff > 0.0f)) continue;
        float lenF = length(F);
#if RTPBR_LTC_POINT_CORRECTION
        // (isotropic: specularMinv holds ltc1's four entries, LTC_InverseMatrix; read from there
        // so that ltc1 need not stay live in the full variant, whose anisotropic lobes have none)
        vec4 pointLtc1 = vec4(specularMinv[0][0], specularMinv[2][0], specularMinv[0][2], specularMinv[2][2]);
#if RTPBR_LIGHTING_FULL
        // The full variant's registers are at gfx1100's limit: the lobe's vector comes from a
        // second pass over the edges (the same lobe, so the same value), taken only where the
        // fade leaves anything to correct (at a form factor of 0.5 or more the factor is within
        // (16 - 1) x 0.5^16 = 2.3e-4 of 1, and a light holding half of the LTC's mass lies
        // mostly outside its tail: the tail estimate is skipped with it), and the norm is
        // fetched again (the same texel) rather than kept live through the loop.
        if (pointOn && specularFF < 0.5f) {
            vec3 unusedF2;
            light_lobe(i, P, ltcFrame, specularMinv, unusedF2, Fl);
            float norm = textureLod(LUT_LTC_2, LTC_LutCoord(s.NoV, s.specR), 0.0f).x;
            specularFF = specular_corrected(Fl, pointLtc1, norm, s.NoV, s.specR, specularFF, F, ff, lenF);
            // (no streak estimate here: its two passes spill this variant on gfx1100)
        }
#else
        specularFF = specular_corrected(Fl, pointLtc1, pointNorm, s.NoV, s.specR, specularFF, F, ff, lenF);
#ifdef RTPBR_ENGINE_STREAK
        // the streak estimate's candidate (after the loop): the first light it applies to and
        // whose size can give it any trust (LTC_StreakCandidate; the one of largest weight x form
        // factor kept one more register live: 96 VGPRs on navi21)
        if (pointOn && streakSized && streakLight == RTPBR_NO_STREAK && LTC_StreakWeight(vLocal, F) > 0.0f) {
            streakLight = i;
            streakFF = specularFF;
        }
#endif
#endif
#endif
        // The representative direction of the polygon: its vector form factor's.
        vec3 lRep = F / lenF;
        float muRep = rtpbr_saturate(lRep.z);
        // The cosine-weighted mean of each albedo over the polygon (KC_PolygonMeanE).
        vec2 eRep = kc_E_EF(muRep, s.specR, s.eta);
        float Erep = KC_PolygonMeanE(eRep.x, s.Eavg, lenF);

        // (with RTPBR_KC_SHAPE: KC_PolygonLobeShaped, its two parts folded into specularScale and
        // msColor before the loop)
        vec3 lo = specularScale * specularFF + msColor * KC_PolygonLobe(s.Eo, Erep, s.Eavg, ff);
        vec3 unusedF, unusedFl;
        vec3 base;
#if RTPBR_LIGHTING_FULL
        if (s.disney) {
            float LoH = rtpbr_saturate(dot(lRep, normalize(lRep + vLocal)));
            base = burleyScale * light_lobe(i, P, ltcFrame, LTC_InverseMatrix(ltc1d), unusedF, unusedFl) +
                   (s.dm.subsurface * Disney_DiffuseLobe(dss, s.NoV, muRep, LoH) + Disney_SheenLobe(s.dm, LoH)) *
                       (RTPBR_PI * ff);
        } else
#endif
        {
            float EFrep = s.w > 0.0f ? KC_PolygonMeanE(eRep.y, s.EFavg, lenF) : 0.0f;
            float Esrep = s.w * KC_SpecularAlbedoDielectric(EFrep, Erep, s.FmsDielectric);
            base = s.diffuseColor * KC_PolygonLobe(s.Eso, Esrep, s.EsAvg, ff);
        }
        lo += base;
#if RTPBR_LIGHTING_FULL
        if (s.sheen)
            lo = lo * Sheen_AlbedoScaling(s.sheenColor, s.EsheenO, sheen_E(muRep, s.sheenR)) +
                 sheenScale * light_lobe(i, P, ltcFrame, LTC_InverseMatrix(ltc1s), unusedF, unusedFl);
        lo *= s.baseAttenuation;
        if (coated)
            lo += coatScale * light_lobe(i, P, ltcFrame, LTC_InverseMatrix(ltc1c), unusedF, unusedFl) +
                  s.msCoat * KC_PolygonLobe(s.Eoc, KC_PolygonMeanE(kc_E(muRep, s.coatR), s.Eavgc, lenF), s.Eavgc, ff);
#endif
        sum += lights[i].radiance * lo * shadow_factor(i, pixel);
#if RTPBR_LTC_POINT_CORRECTION && !RTPBR_LIGHTING_FULL
        specularMass += specularFF;
#endif
    }
#if RTPBR_LTC_POINT_CORRECTION && !RTPBR_LIGHTING_FULL
    // Energy conservation across lights. Each light's specular result is a share of the lobe's
    // mass (LTC_LobeEnd divides by the horizon's), and over disjoint lights the shares of the
    // true lobe sum to at most 1. The point correction and the tail estimate correct each light
    // on its own, so over many lights that surround the point (the furnace: a box of emitters)
    // their shares summed to 1.02-1.04 and the pixel reflected more than the brightest light.
    // Where the shares sum past 1, the lights' sum is scaled back to a mass of 1. The whole sum,
    // not its specular part alone: keeping that apart cost 8 VGPRs (104 on navi21, over the
    // default variant's budget of 96), so the other lobes lose the same fraction 1 - 1 / mass
    // at such pixels (up to 4 % in the furnace; they occur only where lights surround the
    // point). Not in the full variant: one more register there spills on gfx1100, and its
    // point correction runs only for lights holding under half the lobe's mass.
    if (specularMass > 1.0f) sum *= 1.0f / specularMass;
#endif
#ifdef RTPBR_ENGINE_STREAK
    // The streak estimate (light_streak) for one light per pixel, after the loop (where little
    // else is live: its passes inside the loop raised the basic variant's VGPRs by 16 on
    // navi21): the light's specular term moved toward it by its weight.
    if (streakLight != RTPBR_NO_STREAK) {
        vec3 e = light_streak(streakLight, P, ltcFrame, s.NoV, s.specR);
        // the light's specular term moves from specularScale x streakFF toward F(V.h) x the
        // estimate (Schlick's Fresnel at the streak, the tables' Fresnel model)
        if (e.x >= 0.0f && e.y > 0.0f && pointNorm > 0.0f) {
            // specularScale = the Fresnel scale f0 (ltc2.x - ltc2.y) + f90 ltc2.y
            // (LTC_FresnelScale) + the shaped multiple-scattering lobe's part folded into it
            // before the loop, msColor beta / (1 - beta) (1 - Eo) (msColor being s.msColor
            // (1 - beta)); f0 from there and the table's texel fetched again (s.f0 kept live
            // through the loop cost 8 VGPRs on navi21). Where 1 - beta is too small to split
            // them, the tables' Fresnel scale as it is.
            vec3 next = specularScale * (e.x / pointNorm);
#if RTPBR_KC_SHAPE
            float beta = KC_ShapeWeight(s.specR, s.NoV);
            vec3 msShaped = msColor * (beta / max(1.0f - beta, 1e-3f) * rtpbr_pos(1.0f - s.Eo));
            bool split = 1.0f - beta > 1e-3f;
#else
            vec3 msShaped = vec3(0.0f);
            bool split = true;
#endif
            if (split) {
                vec4 t2 = textureLod(LUT_LTC_2, LTC_LutCoord(s.NoV, s.specR), 0.0f);
                vec3 f0 = (specularScale - msShaped - s.f90 * t2.y) / max(t2.x - t2.y, 1e-6f);
                next = F_Schlick(f0, s.f90, e.z) * e.x + msShaped * (e.x / pointNorm);
            }
            sum += lights[streakLight].radiance * ((next - specularScale * streakFF) * e.y) * shadow_factor(streakLight, pixel);
        }
    }
#endif
    return sum;
}

