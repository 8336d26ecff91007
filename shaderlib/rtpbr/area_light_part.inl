// rtpbr shader library, internal: the body of one light's evaluation, included by
// area_light.h (after its #defines) once for each kind of light, so that every function made
// from it carries only its own shape's lobes into the compiler. Do not include it yourself.
//   RTPBR_AREA_LIGHT_PART_FN    the function's name
//   RTPBR_AREA_LIGHT_PART_KIND  what it lights, and how its lobes are walked:
//     RTPBR_AREA_LIGHT_KIND_ANY      a polygon, a sphere, a disk or a textured quad, by the
//                                    run-time flags sphereLight (, diskLight, texturedLight):
//                                    AreaLight_SimpleShapeLobe (AreaLight_AddSimpleShape)
//     RTPBR_AREA_LIGHT_KIND_POLYGON  a polygon (, textured where texturedLight): AreaLight_Lobe
//                                    (AreaLight_AddPolygonShape)
//     RTPBR_AREA_LIGHT_KIND_ROUND    a sphere (, a disk where diskLight): AreaLight_SphereLobe
//                                    (AreaLight_AddRoundShape)
//     RTPBR_AREA_LIGHT_KIND_TUBE     one part of a tube light, tubePart
//                                    (RTPBR_AREA_LIGHT_TUBE_QUAD, _END1, _END2):
//                                    AreaLight_TubePartLobe (AreaLight_AddTubePart)
// Both, and this file's own macros, are #undef'd at its end.
// Why (docs/performance.md, "Pipeline compile time"): the drivers inline every call before
// they fold its constant arguments, and their first passes over the inlined function cost
// more than linearly in its size. With one function for every kind, each of its four lobes'
// calls carried every shape's walk (a tube's part, a sphere, a disk, a polygon) into them.

#if !defined(RTPBR_AREA_LIGHT_PART_FN) || !defined(RTPBR_AREA_LIGHT_PART_KIND)
#error "area_light_part.inl is area_light.h's: include rtpbr/area_light.h"
#endif
#define RTPBR_AREA_LIGHT_PART_IS(kind) (RTPBR_AREA_LIGHT_PART_KIND == RTPBR_AREA_LIGHT_KIND_##kind)
#if RTPBR_AREA_LIGHT_PART_IS(TUBE)
#define RTPBR_AREA_LIGHT_PART_LOBE(lobeMinv, lobeInvMass, lobeF, lobeFl) AreaLight_TubePartLobe(i, tubePart, P, px.frame, lobeMinv, lobeInvMass, lobeF, lobeFl)
#elif RTPBR_AREA_LIGHT_PART_IS(POLYGON)
#define RTPBR_AREA_LIGHT_PART_LOBE(lobeMinv, lobeInvMass, lobeF, lobeFl) AreaLight_Lobe(i, P, px.frame, lobeMinv, lobeInvMass, lobeF, lobeFl)
#elif RTPBR_AREA_LIGHT_PART_IS(ROUND)
#define RTPBR_AREA_LIGHT_PART_LOBE(lobeMinv, lobeInvMass, lobeF, lobeFl) \
    AreaLight_SphereLobe(i, P, px.frame, lobeMinv, lobeInvMass, lobeF, lobeFl RTPBR_AREA_LIGHT_DISK_ARG(diskLight))
#else
#define RTPBR_AREA_LIGHT_PART_LOBE(lobeMinv, lobeInvMass, lobeF, lobeFl) \
    AreaLight_SimpleShapeLobe(i, P, px.frame, lobeMinv, lobeInvMass, lobeF, lobeFl, sphereLight RTPBR_AREA_LIGHT_DISK_ARG(diskLight))
#endif

// (sphereLight: lit through a sphere's paths below, a sphere, a disk or a tube's part. Where
// the kind fixes it, a variable all the same, not a const: glslang folds a const in its front
// end, and lavapipe's code then differed from AreaLight_AddSimpleShape's with the same flags
// by 2 ulps in places)
#if RTPBR_AREA_LIGHT_PART_IS(TUBE)
RTPBR_FN void RTPBR_AREA_LIGHT_PART_FN(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                       rtpbr_float3 N, uint i, uint tubePart) {
    bool sphereLight = true;
#if RTPBR_AREA_LIGHT_TEXTURED
    bool texturedLight = false;
#endif
#elif RTPBR_AREA_LIGHT_PART_IS(POLYGON)
RTPBR_FN void RTPBR_AREA_LIGHT_PART_FN(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                       rtpbr_float3 N, uint i RTPBR_AREA_LIGHT_TEXTURE_PARAM) {
    bool sphereLight = false;
#elif RTPBR_AREA_LIGHT_PART_IS(ROUND)
RTPBR_FN void RTPBR_AREA_LIGHT_PART_FN(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                       rtpbr_float3 N, uint i RTPBR_AREA_LIGHT_DISK_PARAM) {
    bool sphereLight = true;
#if RTPBR_AREA_LIGHT_TEXTURED
    bool texturedLight = false;
#endif
#else
RTPBR_FN void RTPBR_AREA_LIGHT_PART_FN(AreaLightPixel px, RTPBR_INOUT(AreaLightSum) acc, ShadingSurface s, rtpbr_float3 P,
                                       rtpbr_float3 N, uint i, bool sphereLight RTPBR_AREA_LIGHT_DISK_PARAM
                                           RTPBR_AREA_LIGHT_TEXTURE_PARAM) {
#endif
    // P on the light's plane sees it edge-on; behind a one-sided light, nothing; a light
    // whose bounding sphere is below the horizon, nothing. A sphere light: below the horizon
    // or beyond its range, nothing.
    rtpbr_float4 sphere = Host_LightSphere(i);
    float window = 1.0f; // a sphere light's range window (a tube's part: its weight)
#if RTPBR_AREA_LIGHT_PART_IS(TUBE)
    // A tube light's part: the tube wholly below the horizon (both ends' centres more than the
    // radius below it), nothing; a part of weight 0 (AreaLight_TubePartWeight), nothing; the
    // window is the part's weight (the radiance's scale), times the range window with
    // RTPBR_AREA_LIGHT_TUBE_RANGE (beyond the range, nothing). From here on
    // it is lit as a sphere is, its lobes by AreaLight_TubePartLobe.
    {
        RTPBR_UNUSED(sphere); // (read, unused: AreaLight_AddTube's Host_LightSphere)
        rtpbr_float4 end1 = Host_LightTube(i, 0u), end2 = Host_LightTube(i, 1u);
        if (!(max(dot(N, rtpbr_float3(end1.x, end1.y, end1.z) - P), dot(N, rtpbr_float3(end2.x, end2.y, end2.z) - P)) > -end1.w))
            return;
        window = AreaLight_TubePartWeight(i, tubePart, P);
#if RTPBR_AREA_LIGHT_TUBE_RANGE
        rtpbr_float3 toCentre = 0.5f * (rtpbr_float3(end1.x, end1.y, end1.z) + rtpbr_float3(end2.x, end2.y, end2.z)) - P;
        window *= Punctual_RangeWindow(dot(toCentre, toCentre), Host_LightTubeInvRange2(i));
#endif
        if (!(window > 0.0f))
            return;
    }
#else
#if RTPBR_AREA_LIGHT_DISKS && !RTPBR_AREA_LIGHT_PART_IS(POLYGON)
    // A disk light: P on its plane sees it edge-on; behind a one-sided disk, nothing; wholly
    // below the horizon (its centre's height less sqrt((N.u)^2 + (N.v)^2), the ellipse's
    // half-extent along N), nothing; a zero or NaN axis, nothing. From here on it is lit as a
    // sphere's disk is (sphereLight: AreaLight_SphereLobe, every choice below alike).
    if (diskLight) {
#if RTPBR_AREA_LIGHT_PART_IS(ANY)
        sphereLight = true;
#endif
        rtpbr_float3 toCentre = rtpbr_float3(sphere.x, sphere.y, sphere.z) - P;
        rtpbr_float3 du = Host_LightDiskAxis(i, 0u), dv = Host_LightDiskAxis(i, 1u);
        rtpbr_float3 dn = cross(du, dv); // toward the emitting side
        float side = -dot(dn, toCentre); // > 0: the front
        float Nu = dot(N, du), Nv = dot(N, dv);
        if (!(abs(side) > 1e-7f * length(dn) * sqrt(max(dot(du, du), dot(dv, dv)))) ||
            (!Host_LightTwoSided(i) && side < 0.0f) || !(dot(N, toCentre) + sqrt(Nu * Nu + Nv * Nv) > 0.0f))
            return;
    } else
#endif
    if (sphereLight) {
#if RTPBR_AREA_LIGHT_SPHERES
        rtpbr_float3 toCentre = rtpbr_float3(sphere.x, sphere.y, sphere.z) - P;
        window = Punctual_RangeWindow(dot(toCentre, toCentre), Host_LightPosition(i).w);
        if (dot(N, toCentre) < -sphere.w || !(window > 0.0f))
            return;
#endif
    } else {
        rtpbr_float4 plane = Host_LightPlane(i);
        float side = dot(rtpbr_float3(plane.x, plane.y, plane.z), P) + plane.w; // > 0: the front (emitting) side
        bool twoSided = Host_LightTwoSided(i);
        if (abs(side) <= 1e-7f * sphere.w || (!twoSided && side < 0.0f) || dot(N, rtpbr_float3(sphere.x, sphere.y, sphere.z) - P) < -sphere.w)
            return;
    }
#endif
#if !RTPBR_AREA_LIGHT_FULL
    // (latency: docs/performance.md, 8) fetched before the walk, which hides its latency
    rtpbr_float3 visibility = Host_LightVisibility(i);
#endif
#if RTPBR_AREA_LIGHT_STREAK
    // (registers: docs/performance.md, 3)
    // (a sphere light is no candidate: the estimate walks a polygon's edges)
    rtpbr_float3 toBound = rtpbr_float3(sphere.x, sphere.y, sphere.z) - P;
    bool streakSized = RTPBR_AREA_LIGHT_STREAK_ON != 0 && !sphereLight && !RTPBR_AREA_LIGHT_TEXTURED_FLAG && LTC_StreakCandidateSquared(sphere.w, dot(toBound, toBound), s.tableRoughness * s.tableRoughness, s.NoV);
#endif
    rtpbr_float3 F, Fl;
    float specularFF = RTPBR_AREA_LIGHT_PART_LOBE(px.specularMinv, px.specularInvMass, F, Fl);
    // A textured quad's emission where each lobe looks (ltc_textured.h: the point where the
    // lobe's vector form factor meets the quad, read from the chain prefiltered to the lobe's
    // footprint): texS for the specular lobe and its multiple scattering, read here (Fl is the
    // specular lobe's), texD, at the Lambert vector's point, for the diffuse lobe, read after
    // the point correction. The full evaluation reads one texel for every lobe of the base
    // after their walks, at the point of the unclipped quad's Lambert vector
    // (AreaLight_TexturedQuadLambert: registers, a colour live through its lobes' walks spilled
    // on gfx1100; a glossy base lobe's reflection of the texture is then as blurred as the
    // diffuse lobe's, and the point of a quad the horizon cuts is its whole quad's), and one for
    // the coat at the coat lobe's own point, after its walk.
#if !RTPBR_AREA_LIGHT_FULL
    rtpbr_float3 texS = RTPBR_F3(1.0f);
#if RTPBR_AREA_LIGHT_TEXTURED
    if (texturedLight) {
        rtpbr_float3 v0 = Host_LightVertex(i, 0u);
        texS = Host_LightTexture(i, LTC_TextureLookup(px.frame, P, v0, Host_LightVertex(i, 1u) - v0,
                                                      Host_LightVertex(i, 3u) - v0, px.specularMinv, Fl));
    }
#endif
#endif
    F = F.z < 0.0f ? -F : F;
    float ff = min(F.z, 1.0f);
    if (!(ff > 0.0f)) return;
    float lenF = length(F);
#if !RTPBR_AREA_LIGHT_FULL
    // The representative direction of the polygon: its vector form factor's. The cosine-weighted
    // mean of each albedo over the polygon (KC_PolygonMeanE): the table read here, before the
    // point correction, which hides its latency (docs/performance.md, 8; the full evaluation
    // reads it after, where it is at its register limit).
    rtpbr_float3 lRep = F / lenF;
    float muRep = rtpbr_saturate(lRep.z);
    rtpbr_float2 eRep = Host_TableE_EF(muRep, s.tableRoughness, s.eta);
#endif
#if RTPBR_LTC_POINT_CORRECTION
    rtpbr_float4 pointLtc1 = AreaLight_IsotropicLtc1(px.specularMinv);
#if RTPBR_AREA_LIGHT_FULL
    // (registers: docs/performance.md, 2 and 25) The lobe's vector Fl from the walk above (a
    // second walk for it, which the full variant took until issue 32, gave the same value), only
    // where the fade leaves anything to correct (at a form factor of 0.5 or more the factor is
    // within (16 - 1) x 0.5^16 = 2.3e-4 of 1, and a light holding half of the LTC's mass lies
    // mostly outside its tail: the tail estimate is skipped with it); the norm fetched again
    // (the same texel). Not for a sphere light (nor a disk or a tube's part): with it the spheres'
    // full variant spills (docs/performance.md, 12 and 25).
    if (px.pointOn && specularFF < 0.5f && !sphereLight) {
        float norm = Host_TableLtc2(RTPBR_TABLE_LTC_SPECULAR, LTC_LutCoord(s.NoV, s.tableRoughness)).x;
        specularFF = AreaLight_SpecularCorrected(Fl, pointLtc1, LTC_InverseHorizonMass(px.specularMinv), norm, s.NoV, s.tableRoughness, specularFF, F, ff, lenF);
    }
#else
#if RTPBR_AREA_LIGHT_INV_MASS_PER_POINT
    float pointInvMass = px.specularInvMass;
#else
    float pointInvMass = LTC_InverseHorizonMass(px.specularMinv);
#endif
    specularFF = AreaLight_SpecularCorrected(Fl, pointLtc1, pointInvMass, px.pointNorm, s.NoV, s.tableRoughness, specularFF, F, ff, lenF);
#if RTPBR_AREA_LIGHT_STREAK
    // the streak estimate's candidate (after the loop): the first light it applies to and
    // whose size can give it any trust (LTC_StreakCandidate)
    if (px.pointOn && streakSized && acc.streakLight == RTPBR_AREA_LIGHT_NONE && LTC_StreakWeight(px.vLocal, F) > 0.0f) {
        acc.streakLight = i;
        acc.streakFF = specularFF;
    }
#endif
#endif
#endif
#if RTPBR_AREA_LIGHT_FULL
    // The representative direction of the polygon: its vector form factor's.
    rtpbr_float3 lRep = F / lenF;
    float muRep = rtpbr_saturate(lRep.z);
    // The cosine-weighted mean of each albedo over the polygon (KC_PolygonMeanE).
    rtpbr_float2 eRep = Host_TableE_EF(muRep, s.tableRoughness, s.eta);
#endif
    float Erep = KC_PolygonMeanE(eRep.x, s.Eavg, lenF);
    rtpbr_float3 texD = RTPBR_F3(1.0f);
#if RTPBR_AREA_LIGHT_TEXTURED && !RTPBR_AREA_LIGHT_FULL
    if (texturedLight) {
        rtpbr_float3 v0 = Host_LightVertex(i, 0u);
        texD = Host_LightTexture(i, LTC_TextureLookup(px.frame, P, v0, Host_LightVertex(i, 1u) - v0,
                                                      Host_LightVertex(i, 3u) - v0, LTC_InverseMatrix(LTC_Identity()), lRep));
    }
#endif
#if RTPBR_AREA_LIGHT_FULL
    rtpbr_float3 texS = texD; // (ones: the base's texel multiplies lo after its lobes' walks)
#endif

    // (with RTPBR_KC_SHAPE: KC_PolygonLobeShaped, its two parts folded into specularScale and
    // msColor by AreaLight_Begin)
    rtpbr_float3 lo = texS * (px.specularScale * specularFF +
                              px.msColor * (px.msScale * (rtpbr_pos(1.0f - Erep) * rtpbr_pos(ff)))); // KC_PolygonLobe(s.Eo, Erep, s.Eavg, ff)
    rtpbr_float3 unusedF, unusedFl;
    rtpbr_float3 base;
#if RTPBR_AREA_LIGHT_FULL
    if (s.disney) {
        float LoH = rtpbr_saturate(dot(lRep, normalize(lRep + px.vLocal)));
        // the material's parameters from AreaLight_Begin's shared registers (the rest unread)
        DisneyMaterial dm = s.dm;
        dm.roughness = px.baseParams.x;
        dm.metallic = px.baseParams.y;
        dm.sheen = px.baseParams.w;
        dm.baseColor = rtpbr_float3(px.baseColors.x, px.baseColors.y, px.baseColors.z);
        dm.sheenTint = px.baseColors.w;
        dm.subsurface = 1.0f; // the subsurface shape alone
        base = px.baseScale * RTPBR_AREA_LIGHT_PART_LOBE(LTC_InverseMatrix(px.ltc1b), -1.0f, unusedF, unusedFl) +
               (px.baseParams.z * Disney_DiffuseLobe(dm, s.NoV, muRep, LoH) + Disney_SheenLobe(dm, LoH)) *
                   (RTPBR_PI * ff);
    } else
#endif
    {
#if RTPBR_AREA_LIGHT_FULL
        float specularWeight = px.baseParams.x, EFavg = px.baseParams.y, FmsDielectric = px.baseParams.z;
#else
        float specularWeight = s.specularWeight, EFavg = s.EFavg, FmsDielectric = s.FmsDielectric;
#endif
        float EFrep = specularWeight > 0.0f ? KC_PolygonMeanE(eRep.y, EFavg, lenF) : 0.0f;
        float Esrep = specularWeight * KC_SpecularAlbedoDielectric(EFrep, Erep, FmsDielectric);
        base = px.baseScale * (rtpbr_pos(1.0f - Esrep) * rtpbr_pos(ff)); // KC_PolygonLobe(s.Eso, Esrep, s.EsAvg, ff)
    }
    lo += texD * base;
#if RTPBR_AREA_LIGHT_FULL
    if (s.sheen && !s.disney) { // (as AreaLight_Begin)
#if RTPBR_AREA_LIGHT_SHEEN_REFETCH
        // (registers) AreaLight_Begin's row, read again: the same coordinates, the same texel
        rtpbr_float4 ltc1s = Host_TableLtc1(RTPBR_TABLE_LTC_SHEEN, LTC_LutCoord(s.NoV, px.baseParams.w));
#else
        rtpbr_float4 ltc1s = px.ltc1b;
#endif
        // (the sheen's parameters from AreaLight_Begin's shared registers)
        lo = lo * Sheen_AlbedoScaling(rtpbr_float3(px.baseColors.x, px.baseColors.y, px.baseColors.z), px.baseColors.w,
                                      Host_TableSheenE(muRep, px.baseParams.w)) +
             texD * px.sheenScale * RTPBR_AREA_LIGHT_PART_LOBE(LTC_InverseMatrix(ltc1s), -1.0f, unusedF, unusedFl);
    }
    lo *= s.baseAttenuation;
#if RTPBR_AREA_LIGHT_TEXTURED
    if (texturedLight)
        lo *= AreaLight_TexturedQuadLambert(i, P, px.frame);
#endif
    if (px.coated) {
        rtpbr_float3 coatFl;
        rtpbr_float3 coat = texS * (px.coatScale * RTPBR_AREA_LIGHT_PART_LOBE(LTC_InverseMatrix(px.ltc1c), -1.0f, unusedF, coatFl) +
              s.msCoat * KC_PolygonLobe(s.Eoc, KC_PolygonMeanE(Host_TableE(muRep, s.coatRoughness), s.Eavgc, lenF), s.Eavgc, ff));
#if RTPBR_AREA_LIGHT_TEXTURED
        // the coat, often the sharpest lobe: its own point and footprint
        if (texturedLight) {
            rtpbr_float3 v0 = Host_LightVertex(i, 0u);
            coat *= Host_LightTexture(i, LTC_TextureLookup(px.frame, P, v0, Host_LightVertex(i, 1u) - v0,
                                                           Host_LightVertex(i, 3u) - v0, LTC_InverseMatrix(px.ltc1c), coatFl));
        }
#endif
        lo += coat;
    }
#endif
#if RTPBR_LTC_POINT_CORRECTION && !RTPBR_AREA_LIGHT_FULL
    acc.specularMass += specularFF;
#endif
#if RTPBR_AREA_LIGHT_FULL
    rtpbr_float3 visibility = Host_LightVisibility(i);
#endif
    if (sphereLight)
        visibility *= window;
    acc.sum += Host_LightRadiance(i) * lo * visibility;
}

#undef RTPBR_AREA_LIGHT_PART_LOBE
#undef RTPBR_AREA_LIGHT_PART_FN
#undef RTPBR_AREA_LIGHT_PART_KIND
#undef RTPBR_AREA_LIGHT_PART_IS
