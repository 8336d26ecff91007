#!/usr/bin/env python3
"""The energy bound on every pixel (issue 28): no surface that does not emit reflects more than
the brightest radiance that reaches it (albedo <= 1), so no pixel of a render may exceed the
brightest emitter's radiance. rtpbr-render measures it on each image it writes (its
--stats-json: the largest pixel / the brightest emitter, the mean of that ratio, non-finite
pixels); this test renders each scene given

  - with the LTC lighting pass, with and without Kulla-Conty, at 1x and 2x supersampling
    (160x120), and with it at 640x480: every pixel <= 1.01 x the brightest emitter;
  - with the Monte Carlo lighting pass (--mc-samples 256), with and without Kulla-Conty: the
    bound holds in expectation, so on the image's mean (<= 1.01); on single pixels a 256-sample
    estimate crosses it where the expectation sits on it (a mirror reflection of a light:
    NormalTangentTest 1.038, the furnace 1.2), so each pixel is held only against a blow-up
    (<= 1.25, MC_PIXEL_GUARD; the furnace, whose every pixel is on the bound, by its mean alone).

A scene with punctual lights (KHR_lights_punctual) has no such bound (rtpbr-render's stats say
"bounded": false): given one, this test fails and says so rather than check a wrong bound.

The furnace (white conductors, albedo 1 with Kulla-Conty, inside an emitting box) is the scene
whose every pixel is at the bound. Its LTC pixels reached 1.04 with Kulla-Conty and 1.02 without
while the point correction of ltc_corrections.h corrected each light on its own (over the box's many lights
the corrected shares of the lobe summed past 1); shade_lights now scales the specular lobe back
where they do (1.007 at 320x240), and the furnace is held to the same 1.01 as every scene.
Before the fix of the tables' normalisation (ltc.md) this test failed on showcase (5.8e7),
polygon_lights and khr_materials.

usage: energy_bound.py RTPBR_RENDER OUT_DIR SCENE.gltf [SCENE.gltf ...]
"""
import json
import os
import subprocess
import sys

LIMIT = 1.01
# Scene-specific limits of the LTC pass, with the reason (none today; see above).
LTC_LIMIT = {}
# Scenes whose Monte Carlo pixels are held by the image's mean alone (every pixel on the bound).
MC_MEAN_ONLY = {"furnace"}
MC_SAMPLES = "256"
# A single Monte Carlo pixel against a blow-up only (see above).
MC_PIXEL_GUARD = 1.25
# The LTC pass once more at this size. ClearCoatTest lit by its own labels (radiance 1) reached
# 4.904 at 640x480 (1593 pixels over the bound) and nothing at 320x240 and below: its coat
# (roughness 0.03) over a normal-mapped base, at NoV = 0, read the GGX table's last row, then
# singular (shaderlib/luts/ltc.md). Its lit wrapper hides it: there the bound is the 12-nit key
# light's.
LARGE = (640, 480)


def render(exe, scene, out_dir, tag, flags, width, height):
    name = os.path.splitext(os.path.basename(scene))[0]
    stats = os.path.join(out_dir, "%s-%s.json" % (name, tag))
    cmd = [exe, scene, "-o", os.path.join(out_dir, "%s-%s.exr" % (name, tag)), "--width", str(width),
           "--height", str(height), "--stats-json", stats, "--validation"] + flags
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if p.returncode != 0:
        return None, "rtpbr-render failed (%d): %s" % (p.returncode, p.stderr.strip())
    with open(stats) as f:
        return json.load(f), None


def main(argv):
    if len(argv) < 4:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    exe, out_dir, scenes = argv[1], argv[2], argv[3:]
    os.makedirs(out_dir, exist_ok=True)
    failures = 0
    checks = 0
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        ltc_limit = LTC_LIMIT.get(name, LIMIT)
        cases = []
        for ms, ms_tag in ((["--no-multiscatter"], "nokc"), ([], "kc")):
            for ss in ("1", "2"):
                cases.append(("ltc-%s-ss%s" % (ms_tag, ss), ms + ["--supersample", ss], 160, 120, "max", ltc_limit))
            # and at 640x480 (LARGE), with Kulla-Conty (the default): thin features (silhouettes
            # of normal-mapped smooth coats) that 160x120 never samples
            if ms_tag == "kc":
                cases.append(("ltc-kc-large", ms, LARGE[0], LARGE[1], "max", ltc_limit))
            cases.append(("mc-%s" % ms_tag, ms + ["--mc-samples", MC_SAMPLES], 64, 48, "mean", LIMIT))
            if name not in MC_MEAN_ONLY:
                cases.append(("mc-%s" % ms_tag, ms + ["--mc-samples", MC_SAMPLES], 64, 48, "max", MC_PIXEL_GUARD))
        done = {}
        for tag, flags, w, h, what, limit in cases:
            if tag not in done:
                done[tag] = render(exe, scene, out_dir, tag, flags, w, h)
            stats, error = done[tag]
            checks += 1
            if error:
                print("FAIL %s %s: %s" % (name, tag, error))
                failures += 1
                continue
            if not stats.get("bounded", True):
                print("FAIL %s %s: the scene has punctual lights (KHR_lights_punctual), so no energy bound exists "
                      "(a delta light's irradiance I / d^2 has no upper limit): nothing to check; this test takes "
                      "scenes lit by area lights and emissive materials only" % (name, tag))
                failures += 1
                continue
            value = stats["max_ratio"] if what == "max" else stats["mean_ratio"]
            ok = value <= limit and stats["non_finite"] == 0 and stats["brightest_emitter"] > 0
            failures += 0 if ok else 1
            print("%s %s %s: %s ratio %.4f (limit %.2f; largest at (%d, %d); brightest 0.01%% of pixels hold %.2f%% "
                  "of the energy; %d not finite; brightest emitter %.4g)"
                  % ("ok  " if ok else "FAIL", name, tag, what, value, limit, stats["max_x"], stats["max_y"],
                     100 * stats["top_share"], stats["non_finite"], stats["brightest_emitter"]))
    print("%d passed, %d failed" % (checks - failures, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
