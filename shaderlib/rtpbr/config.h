// rtpbr shader library: model selection flags.
//
// Define any of these before including an rtpbr header to pick a model; each has a default.
// The functions of every model are always compiled (tests and the oracle call them by name);
// the flags choose what the generic entry points (D_Microfacet, V_Microfacet, F_Microfacet,
// BRDF_Specular, ...) use.
//
//   RTPBR_NDF          RTPBR_NDF_GGX (default) | RTPBR_NDF_BECKMANN | RTPBR_NDF_GTR
//                      GTR uses RTPBR_GTR_GAMMA (default 2, which is GGX).
//   RTPBR_SMITH        RTPBR_SMITH_HEIGHT_CORRELATED (default) | RTPBR_SMITH_SEPARABLE
//                      How G2 combines the two directions (Heitz 2014, "Understanding the
//                      Masking-Shadowing Function in Microfacet-Based BRDFs", sec. 5).
//   RTPBR_SMITH_FAST   0 (default): exact Lambda. 1: the usual fast approximations:
//                      GGX  - Hammon 2017 ("PBR Diffuse Lighting for GGX+Smith Microsurfaces")
//                             approximation of the height-correlated visibility;
//                      Beckmann - Walter et al. 2007 rational approximation of G1.
//   RTPBR_FRESNEL      RTPBR_FRESNEL_SCHLICK (default) | RTPBR_FRESNEL_DIELECTRIC
//                      | RTPBR_FRESNEL_CONDUCTOR
//   RTPBR_MULTISCATTER 0 | 1 (default): Kulla-Conty energy compensation (kulla_conty.h).
//   RTPBR_DIFFUSE      RTPBR_DIFFUSE_LAMBERT (default) | RTPBR_DIFFUSE_BURLEY
//   RTPBR_KC_SHAPE     1 (default) | 0: the multiple-scattering lobe of BRDF_SpecularMS and of
//                      the engine's lights: shaped toward the single-scattering lobe at low
//                      roughness (KC_LobeShaped) or Kulla-Conty's separable lobe (KC_Lobe).
//   RTPBR_LTC_POINT_CORRECTION 1 (default) | 0: callers of the point correction
//                      (ltc_corrections.h, LTC_PointFactor; the engine's lighting pass) apply
//                      it to the isotropic microfacet lobe of polygonal lights.
//   RTPBR_LTC_STREAK   1 (default) | 0: callers of the streak estimate (ltc_corrections.h,
//                      LTC_StreakEnd; the engine's lighting pass) mix it into that lobe's
//                      result on the mirror side near the horizon (GGX only; with the point
//                      correction).
//
// Roughness convention: materials carry perceptual roughness r in [0, 1]; the NDFs take
// alpha = r * r (Burley 2012). alpha is clamped below at RTPBR_MIN_ALPHA so that every term
// stays finite in 32-bit float; RTPBR_MIN_ALPHA defaults to 1e-3 (perceptual ~0.032), where
// D_GGX peaks at 1/(pi alpha^2) ~ 3.2e5.
#ifndef RTPBR_CONFIG_H
#define RTPBR_CONFIG_H

#define RTPBR_NDF_GGX 1
#define RTPBR_NDF_BECKMANN 2
#define RTPBR_NDF_GTR 3

#define RTPBR_SMITH_HEIGHT_CORRELATED 1
#define RTPBR_SMITH_SEPARABLE 2

#define RTPBR_FRESNEL_SCHLICK 1
#define RTPBR_FRESNEL_DIELECTRIC 2
#define RTPBR_FRESNEL_CONDUCTOR 3

#define RTPBR_DIFFUSE_LAMBERT 1
#define RTPBR_DIFFUSE_BURLEY 2

#ifndef RTPBR_NDF
#define RTPBR_NDF RTPBR_NDF_GGX
#endif
#ifndef RTPBR_GTR_GAMMA
#define RTPBR_GTR_GAMMA 2.0f
#endif
#ifndef RTPBR_SMITH
#define RTPBR_SMITH RTPBR_SMITH_HEIGHT_CORRELATED
#endif
#ifndef RTPBR_SMITH_FAST
#define RTPBR_SMITH_FAST 0
#endif
#ifndef RTPBR_FRESNEL
#define RTPBR_FRESNEL RTPBR_FRESNEL_SCHLICK
#endif
#ifndef RTPBR_MULTISCATTER
#define RTPBR_MULTISCATTER 1
#endif
#ifndef RTPBR_DIFFUSE
#define RTPBR_DIFFUSE RTPBR_DIFFUSE_LAMBERT
#endif
#ifndef RTPBR_LTC_POINT_CORRECTION
#define RTPBR_LTC_POINT_CORRECTION 1
#endif
#ifndef RTPBR_KC_SHAPE
#define RTPBR_KC_SHAPE 1
#endif
#ifndef RTPBR_LTC_STREAK
#define RTPBR_LTC_STREAK 1
#endif
#ifndef RTPBR_MIN_ALPHA
#define RTPBR_MIN_ALPHA 1e-3f
#endif

// The LTC tables a host's Host_TableLtc1 / Host_TableLtc2 hand to area_light.h (its host
// bridge): the specular lobe's (rtpbr_ltc_ggx_*, or _beckmann_* with RTPBR_NDF_BECKMANN),
// Burley's diffuse (rtpbr_ltc_disney_diffuse_*) and KHR sheen's (rtpbr_ltc_sheen_*). Defined
// here, before the host's hooks that test them.
#define RTPBR_TABLE_LTC_SPECULAR 0
#define RTPBR_TABLE_LTC_DISNEY_DIFFUSE 1
#define RTPBR_TABLE_LTC_SHEEN 2

#endif // RTPBR_CONFIG_H
