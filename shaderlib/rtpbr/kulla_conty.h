// rtpbr shader library: Kulla-Conty multiple-scattering energy compensation.
//
// Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks" (SIGGRAPH course
// "Physically Based Shading in Theory and Practice"). A single-scattering microfacet BRDF
// f_ss with F = 1 reflects the directional albedo E(mu) < 1; the missing energy is given back
// by a second lobe, separable in the two cosines,
//     f_ms(mu_o, mu_i) = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)),
//     E_avg = 2 int_0^1 E(mu) mu dmu,
// whose albedo is exactly 1 - E(mu_o), so that f_ss + f_ms passes the white furnace test.
// With Fresnel the lobe is coloured by F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),
// F_avg = 2 int_0^1 F(mu) mu dmu (the geometric series of the bounces after the first).
//
// Tables (shaderlib/luts/, see luts/kulla_conty.md and rtpbr_kc_tables.h) are computed by
// tools/lutgen from this library's own BRDF for each NDF / Smith variant:
//   E(mu, r)            2D, KC_LUT_SIZE x KC_LUT_SIZE      (u: mu axis, v: perceptual roughness)
//   E_avg(r)            1D, KC_LUT_SIZE
//   E_F(mu, r, eta)     3D, KC_LUT_SIZE^2 x KC_LUT_SIZE_ETA: albedo of f_ss with the exact
//                       dielectric Fresnel (for the dielectric-over-diffuse layer)
//   E_F_avg(r, eta)     2D, KC_LUT_SIZE x KC_LUT_SIZE_ETA
// Every axis stores its values at the texel centres, node i at axis value i / (N - 1), so a
// bilinear (trilinear) fetch with clamp-to-edge at the coordinates KC_TableCoord* returns
// the linear interpolation of the nodes. The library never samples: the caller fetches the
// table values in its own language and passes them in.
//
// Conventions: NoV = mu_o, NoL = mu_i; perceptual roughness r in [0, 1], alpha = r^2
// (ndf.h). f values do not include the cosine NoL.
#ifndef RTPBR_KULLA_CONTY_H
#define RTPBR_KULLA_CONTY_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "microfacet.h"

RTPBR_NAMESPACE_BEGIN

// ---- table coordinates ---------------------------------------------------------------------

RTPBR_CONST float KC_LUT_SIZE = 32.0f;     // nodes along mu and along r
RTPBR_CONST float KC_LUT_SIZE_ETA = 16.0f; // nodes along the dielectric IOR axis
// The IOR axis is s = sqrt(F0) = (eta - 1) / (eta + 1), linear on [0, KC_ETA_AXIS_MAX];
// 0.5 is eta = 3 (F0 = 0.25), above every common dielectric; larger eta clamp to it.
RTPBR_CONST float KC_ETA_AXIS_MAX = 0.5f;

// The mu axis is x = sqrt(mu): the albedo changes fastest at grazing angles, where the
// square root spreads the nodes (the linear-interpolation error is in kulla_conty.md).
RTPBR_FN float KC_MuAxis(float mu) {
    return sqrt(mu > 0.0f ? min(mu, 1.0f) : 0.0f); // NaN -> 0
}

// The IOR axis value in [0, 1] of a relative IOR eta (> 1: light arrives from the thinner
// medium); eta <= 1 (or NaN) gives 0, where the layer reflects nothing. (eta - 1) / (eta + 1)
// is written 1 - 2 / (eta + 1) so that an infinite eta gives 1, not inf / inf.
RTPBR_FN float KC_EtaAxis(float eta) {
    float e = eta > 1.0f ? eta : 1.0f;
    return rtpbr_saturate((1.0f - 2.0f / (e + 1.0f)) / KC_ETA_AXIS_MAX);
}

// Texel-centre coordinate of axis value x in [0, 1] on an N-node axis: node i at i / (N - 1).
RTPBR_FN float KC_AxisCoord(float x, float n) {
    float c = x > 0.0f ? min(x, 1.0f) : 0.0f; // NaN -> 0
    return (c * (n - 1.0f) + 0.5f) / n;
}

// uv of E(mu, r) (and of the mu-r slices of E_F): u along mu, v along perceptual roughness.
RTPBR_FN rtpbr_float2 KC_TableCoord(float NoV, float perceptualRoughness) {
    return rtpbr_float2(KC_AxisCoord(KC_MuAxis(NoV), KC_LUT_SIZE),
                  KC_AxisCoord(perceptualRoughness, KC_LUT_SIZE));
}

// u of the 1D table E_avg(r).
RTPBR_FN float KC_TableCoordAvg(float perceptualRoughness) {
    return KC_AxisCoord(perceptualRoughness, KC_LUT_SIZE);
}

// uvw of the 3D table E_F(mu, r, eta) (w along the IOR axis).
RTPBR_FN rtpbr_float3 KC_TableCoord3D(float NoV, float perceptualRoughness, float eta) {
    return rtpbr_float3(KC_TableCoord(NoV, perceptualRoughness),
                  KC_AxisCoord(KC_EtaAxis(eta), KC_LUT_SIZE_ETA));
}

// uv of the 2D table E_F_avg(r, eta): u along perceptual roughness, v along the IOR axis.
RTPBR_FN rtpbr_float2 KC_TableCoordAvg2D(float perceptualRoughness, float eta) {
    return rtpbr_float2(KC_AxisCoord(perceptualRoughness, KC_LUT_SIZE),
                  KC_AxisCoord(KC_EtaAxis(eta), KC_LUT_SIZE_ETA));
}

// ---- average Fresnel F_avg = 2 int_0^1 F(mu) mu dmu ------------------------------------------

// Schlick's Fresnel in closed form: 2 int_0^1 (1 - mu)^5 mu dmu = 2 B(2, 6) = 1/21, so
// F_avg = f0 + (f90 - f0) / 21 (Kulla & Conty 2017 give (20 f0 + 1) / 21 for f90 = 1).
RTPBR_FN rtpbr_float3 F_Avg_Schlick(rtpbr_float3 f0, float f90) {
    return f0 + (RTPBR_F3(f90) - f0) * (1.0f / 21.0f);
}

// One node of the F_avg quadrature: mu = t^2 (dmu = 2 t dt) turns 2 int F(mu) mu dmu into
// 4 int_0^1 F(t^2) t^3 dt; the nodes and weights are 6-point Gauss-Legendre on [0, 1], the
// weight already multiplied by 4 t^3.
RTPBR_FN rtpbr_float3 F_Avg_ConductorNode(rtpbr_float3 eta, rtpbr_float3 k, float t, float w) {
    return (w * 4.0f * t * t * t) * F_Conductor(t * t, eta, k);
}

// Average of the exact conductor Fresnel (complex IOR eta + i k, per channel), by a fixed
// 6-point Gauss-Legendre quadrature in t = sqrt(mu); with k = 0 it is the dielectric F_avg.
// Absolute error < 5e-5 for eta in [0.05, 4], k in [0, 10] with eta >= 1 or k >= 1 (every
// metal in the visible range; tests/shaderlib/kc). The kink of total internal reflection (eta < 1 and
// k -> 0, not a conductor) is not resolved: up to 0.18 there.
RTPBR_FN rtpbr_float3 F_Avg_Conductor(rtpbr_float3 eta, rtpbr_float3 k) {
    rtpbr_float3 s = F_Avg_ConductorNode(eta, k, 0.033765242898424f, 0.085662246189585f);
    s += F_Avg_ConductorNode(eta, k, 0.169395306766868f, 0.180380786524069f);
    s += F_Avg_ConductorNode(eta, k, 0.380690406958402f, 0.233956967286346f);
    s += F_Avg_ConductorNode(eta, k, 0.619309593041598f, 0.233956967286346f);
    s += F_Avg_ConductorNode(eta, k, 0.830604693233132f, 0.180380786524069f);
    s += F_Avg_ConductorNode(eta, k, 0.966234757101576f, 0.085662246189585f);
    // NaN (from NaN input) -> 0, per channel.
    return rtpbr_float3(min(rtpbr_pos(s.x), 1.0f), min(rtpbr_pos(s.y), 1.0f), min(rtpbr_pos(s.z), 1.0f));
}

// Average of the exact dielectric Fresnel seen from the outside (eta > 1).
RTPBR_FN float F_Avg_Dielectric(float eta) {
    float e = eta > 1.0f ? min(eta, 1e3f) : 1.0f;
    return F_Avg_Conductor(RTPBR_F3(e), RTPBR_F3(0.0f)).x;
}

// F_avg of the Fresnel model selected by RTPBR_FRESNEL.
RTPBR_FN rtpbr_float3 F_Avg_Microfacet(FresnelParams p) {
#if RTPBR_FRESNEL == RTPBR_FRESNEL_DIELECTRIC
    return RTPBR_F3(F_Avg_Dielectric(p.eta.x));
#elif RTPBR_FRESNEL == RTPBR_FRESNEL_CONDUCTOR
    return F_Avg_Conductor(p.eta, p.k);
#else
    return F_Avg_Schlick(p.f0, p.f90);
#endif
}

// ---- the multiple-scattering lobe ----------------------------------------------------------

// Kulla & Conty 2017: the colour of the multiple-scattering lobe,
// F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)). (The total energy of all bounces is
// F_avg E_avg / (1 - F_avg (1 - E_avg)); the bounces after the first carry one more F_avg
// and the uncoloured lobe's average albedo 1 - E_avg is divided out.) 1 when F_avg = 1.
RTPBR_FN rtpbr_float3 KC_FmsColor(rtpbr_float3 Favg, float Eavg) {
    // Clamped to [0, 1] with NaN -> 0 (saturate keeps NaN on some targets).
    rtpbr_float3 f = rtpbr_float3(min(rtpbr_pos(Favg.x), 1.0f), min(rtpbr_pos(Favg.y), 1.0f), min(rtpbr_pos(Favg.z), 1.0f));
    float e = min(rtpbr_pos(Eavg), 1.0f);
    return f * f * e / max(RTPBR_F3(1.0f) - f * (1.0f - e), RTPBR_F3(1e-6f));
}

// Kulla & Conty 2017: f_ms = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)), with F = 1.
// Eo = E(NoV), Ei = E(NoL), Eavg = E_avg from the tables. Never negative (table values above
// 1, as the fast visibility approximations can give, count as 1); 0 when E_avg = 1.
RTPBR_FN float KC_Lobe(float Eo, float Ei, float Eavg) {
    float a = rtpbr_pos(1.0f - Eo);
    float b = rtpbr_pos(1.0f - Ei);
    float d = rtpbr_pos(1.0f - Eavg);
    return d > 1e-6f ? a * b / (RTPBR_PI * d) : 0.0f;
}

// ---- the shaped multiple-scattering lobe (issue 19, fifth round; RTPBR_KC_SHAPE) -------------
//
// The separable lobe above has the right energy for every view but not the right direction:
// on the Smith microsurface (the random walk of Heitz et al. 2016, the oracle's) the light
// scattered twice or more leaves close to the single-scattering lobe at low roughness and
// spreads out only as the roughness grows; seen at grazing angles, the separable lobe sends
// 2.5-4.5 times the walk's multiple scattering back toward a light on the viewer's side (r 0.35,
// shaderlib/luts/kulla_conty.md). The shaped lobe blends the separable lobe with the
// single-scattering lobe's own shape at the same energy (the latter is the shape of Turquin
// 2019's compensation):
//     f_ms = (1 - E(mu_o)) [beta f_ss(F = 1) / E(mu_o) + (1 - beta) (1 - E(mu_i)) / (pi (1 - E_avg))]
// whose cosine-weighted integral over mu_i is 1 - E(mu_o) for every view, as the separable
// lobe's, so white furnaces stay exact; it is not reciprocal. beta = KC_ShapeWeight(r, mu_o).

// beta of the shaped lobe at perceptual roughness r and view cosine mu_o:
// min(1, exp(-3 (r - 0.2))) (1 - mu_o^4), fitted by rtpbr-kc-shape to the walk's multiple
// scattering of GGX (F = 1) over r 0.2-1 and mu_o 0.05-1 (the roughness term: the optimum
// per roughness, 1 up to r 0.2, 0.73 at 0.3, 0.44 at 0.5, 0.22 at 0.7; the view term: near
// normal incidence the walk's multiple scattering is broad, as the separable lobe). NaN -> 0
// (the separable lobe).
RTPBR_FN float KC_ShapeWeight(float perceptualRoughness, float NoV) {
    float r = perceptualRoughness;
    float b = r > 0.2f ? exp(-3.0f * min(r - 0.2f, 10.0f)) : (r <= 0.2f ? 1.0f : 0.0f);
    float m = NoV > 0.0f ? min(NoV, 1.0f) : 0.0f; // NaN -> 0
    float m2 = m * m;
    return b * (1.0f - m2 * m2);
}

// The shaped lobe (F = 1) for one pair of directions: fss1 = f_ss(wo, wi) with F = 1 (D V),
// Eo, Ei, Eavg as for KC_Lobe, beta = KC_ShapeWeight. Eo <= 0 or NaN inputs: the separable
// part alone.
RTPBR_FN float KC_LobeShaped(float Eo, float Ei, float Eavg, float fss1, float beta) {
    float b = beta > 0.0f ? min(beta, 1.0f) : 0.0f; // NaN -> 0
    float ss = Eo > 1e-4f && fss1 > 0.0f && fss1 < 3.0e38f ? rtpbr_pos(1.0f - Eo) * fss1 / Eo : 0.0f; // +Inf -> 0
    return b * ss + (1.0f - b) * KC_Lobe(Eo, Ei, Eavg);
}

// The compensated specular BRDF f_ss + F_ms f_ms of the models picked by RTPBR_NDF,
// RTPBR_SMITH, RTPBR_FRESNEL; without RTPBR_MULTISCATTER only f_ss. f_ms is the shaped lobe
// (KC_LobeShaped, not reciprocal) unless RTPBR_KC_SHAPE is 0 (the separable KC_Lobe). Eo, Ei, Eavg are the
// fetched E(NoV, r), E(NoL, r), E_avg(r) of the same NDF / Smith variant; Favg =
// F_Avg_Microfacet(fresnel) (constant per material: hoist it).
RTPBR_FN rtpbr_float3 BRDF_SpecularMS(float NoV, float NoL, float NoH, float VoH, float alpha,
                                FresnelParams fresnel, float Eo, float Ei, float Eavg,
                                rtpbr_float3 Favg) {
    rtpbr_float3 fss = BRDF_Specular(NoV, NoL, NoH, VoH, alpha, fresnel);
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return fss;
    // A 0 / 1 factor rather than an #if around the term keeps every parameter used (no
    // unused-parameter warnings in C++) and is folded by every compiler.
#if RTPBR_MULTISCATTER
    float msOn = 1.0f;
#else
    float msOn = 0.0f;
#endif
#if RTPBR_KC_SHAPE
    float ms = KC_LobeShaped(Eo, Ei, Eavg, D_Microfacet(NoH, alpha) * V_Microfacet(NoV, NoL, alpha),
                             KC_ShapeWeight(sqrt(max(alpha, 0.0f)), NoV));
#else
    float ms = KC_Lobe(Eo, Ei, Eavg);
#endif
    return fss + (msOn * ms) * KC_FmsColor(Favg, Eavg);
}

// ---- dielectric specular over a diffuse base -----------------------------------------------
//
// Kulla & Conty 2017, "energy conservation" of a dielectric coating over a diffuse base: the
// base sees only the energy the (compensated) specular layer did not reflect, and its lobe has
// the same separable form as f_ms:
//     f_d = rho (1 - E_s(mu_o)) (1 - E_s(mu_i)) / (pi (1 - E_s_avg)),
// so with rho = 1 the total albedo is exactly E_s(mu_o) + (1 - E_s(mu_o)) = 1.
// E_s is the albedo of the compensated specular with the exact dielectric Fresnel:
//     E_s(mu) = E_F(mu) + F_ms (1 - E(mu)),  E_s_avg = E_F_avg + F_ms (1 - E_avg),
// with E_F, E_F_avg from the dielectric tables and F_ms = KC_FmsColor(F_Avg_Dielectric(eta),
// E_avg).

// Albedo of the compensated dielectric specular (EF = E_F(mu, r, eta), E = E(mu, r); or the
// averages E_F_avg, E_avg for the average albedo). Fms is a scalar: dielectrics are grey.
RTPBR_FN float KC_SpecularAlbedoDielectric(float EF, float E, float Fms) {
    return rtpbr_saturate(EF + Fms * rtpbr_pos(1.0f - E));
}

// The diffuse base's energy-conserving lobe (per unit base colour): (1 - Eso)(1 - Esi) /
// (pi (1 - Es_avg)), from the specular layer albedos of KC_SpecularAlbedoDielectric.
RTPBR_FN float Fd_KullaContyLayered(float Eso, float Esi, float EsAvg) {
    return KC_Lobe(Eso, Esi, EsAvg);
}

// The whole dielectric-over-diffuse BRDF: exact-dielectric specular f_ss + its F_ms f_ms
// compensation + the base. EFo/EFi/EFavg: E_F(NoV), E_F(NoL), E_F_avg at (r, eta);
// Eo/Ei/Eavg: the F = 1 tables E(NoV), E(NoL), E_avg at r. Without RTPBR_MULTISCATTER the
// specular is f_ss alone and E_s = E_F. Specular and base share the NDF / Smith variant.
RTPBR_FN rtpbr_float3 BRDF_DielectricOverDiffuse(float NoV, float NoL, float NoH, float VoH,
                                           float alpha, float eta, rtpbr_float3 baseColor,
                                           float EFo, float EFi, float EFavg,
                                           float Eo, float Ei, float Eavg) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return RTPBR_F3(0.0f);
    float fss = D_Microfacet(NoH, alpha) * V_Microfacet(NoV, NoL, alpha) * F_Dielectric(VoH, eta);
#if RTPBR_MULTISCATTER
    float Fms = KC_FmsColor(RTPBR_F3(F_Avg_Dielectric(eta)), Eavg).x;
#else
    float Fms = 0.0f;
#endif
    float spec = fss + Fms * KC_Lobe(Eo, Ei, Eavg);
    float Eso = KC_SpecularAlbedoDielectric(EFo, Eo, Fms);
    float Esi = KC_SpecularAlbedoDielectric(EFi, Ei, Fms);
    float EsAvg = KC_SpecularAlbedoDielectric(EFavg, Eavg, Fms);
    return RTPBR_F3(spec) + baseColor * Fd_KullaContyLayered(Eso, Esi, EsAvg);
}

// ---- polygonal lights ------------------------------------------------------------------------
//
// f_ms is separable, so over a polygon P (unit radiance) it integrates to
//     int_P f_ms cos dw = (1 - E(mu_o)) / (pi (1 - E_avg)) int_P (1 - E(mu_i)) mu_i dw.
// The remaining integral is approximated by the cosine-weighted integral of the polygon,
// pi * formFactor (formFactor = (1/pi) int_P mu_i dw, what LTC / Lambert's polygon formula
// give for the clipped polygon), times 1 - E at a representative direction: the direction of
// the polygon's vector form factor (the "average direction" LTC code computes), whose cosine
// mu_rep to the normal selects Erep = E(mu_rep, r). Error measured in tests/shaderlib/kc (kulla_conty.md).

// The E of the representative direction, widened with the polygon's size (ours): with |F| the
// length of the vector form factor (sin^2 of the angular radius for a sphere cap; 1 for the
// whole hemisphere) the cosine-weighted mean of E over the polygon is taken as
// rtpbr_lerp(E(mu_rep), E_avg, |F|). It is exact at both ends (a vanishing polygon; the whole
// hemisphere, whose mean is E_avg by definition) and, for a cap around the normal, wherever
// E is linear in mu^2 in between. Measured against quadrature in tests/shaderlib/kc.
RTPBR_FN float KC_PolygonMeanE(float Erep, float Eavg, float lengthF) {
    float t = lengthF > 0.0f ? min(lengthF, 1.0f) : 0.0f; // NaN -> 0
    return rtpbr_lerp(Erep, Eavg, t);
}

// Integral over a polygon of the uncoloured f_ms times cos (for unit radiance).
// Multiply by KC_FmsColor (or, for the layered base, use E_s values and multiply by rho).
RTPBR_FN float KC_PolygonLobe(float Eo, float Erep, float Eavg, float formFactor) {
    float d = rtpbr_pos(1.0f - Eavg);
    if (!(d > 1e-6f))
        return 0.0f;
    return rtpbr_pos(1.0f - Eo) * rtpbr_pos(1.0f - Erep) * rtpbr_pos(formFactor) / d;
}

// The shaped lobe over a polygon (unit radiance): beta (1 - Eo) ssFormFactor + (1 - beta)
// KC_PolygonLobe, ssFormFactor = the polygon's form factor under the single-scattering lobe
// normalised to 1 over the hemisphere (what the specular LTC integral gives: the integral of
// f_ss(F = 1) cos / E(mu_o)).
RTPBR_FN float KC_PolygonLobeShaped(float Eo, float Erep, float Eavg, float formFactor, float ssFormFactor, float beta) {
    float b = beta > 0.0f ? min(beta, 1.0f) : 0.0f; // NaN -> 0
    float ss = ssFormFactor > 0.0f && ssFormFactor < 3.0e38f ? rtpbr_pos(1.0f - Eo) * ssFormFactor : 0.0f; // +Inf -> 0
    return b * ss + (1.0f - b) * KC_PolygonLobe(Eo, Erep, Eavg, formFactor);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_KULLA_CONTY_H
