#!/usr/bin/env python3
"""rtpbr-render on the punctual wrappers of the real assets (samples/assets/<Name>/<Name>.punctual.gltf,
KHR_lights_punctual lights added by tools/assets/light_assets.py; suite 'assets').

Each wrapper is rendered at 160 x 120 with the Vulkan validation layers, with the LTC lighting pass
(with and without --shadows) and the Monte Carlo one (--mc-samples 16); each run must exit 0, count
every light of the wrapper ("N punctual lights"), write no non-finite pixel and light the asset
(largest pixel > 0). No energy bound is checked: a scene with punctual lights has none (its stats say
"bounded": false, and this test requires that they do; tests/energy takes the area-lit wrappers).

usage: render_punctual.py RTPBR_RENDER OUT_DIR NAME.punctual.gltf [NAME.punctual.gltf ...]
"""
import argparse
import json
import os
import subprocess
import sys

MODES = (("ltc", []), ("ltc-shadows", ["--shadows"]), ("mc", ["--mc-samples", "16"]))


def light_count(gltf):
    with open(gltf, encoding="utf-8") as f:
        doc = json.load(f)
    return sum(1 for n in doc.get("nodes", []) if "KHR_lights_punctual" in n.get("extensions", {}))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("render", help="the rtpbr-render executable")
    ap.add_argument("out_dir", help="where the images and their stats go")
    ap.add_argument("scenes", nargs="+", metavar="NAME.punctual.gltf")
    args = ap.parse_args(argv)
    exe, out_dir, scenes = args.render, args.out_dir, args.scenes
    os.makedirs(out_dir, exist_ok=True)
    failures = 0
    for scene in scenes:
        name = os.path.basename(scene)[:-len(".gltf")]
        expected = "%d punctual lights" % light_count(scene)
        for tag, flags in MODES:
            stats_path = os.path.join(out_dir, "%s-%s.json" % (name, tag))
            cmd = [exe, scene, "-o", os.path.join(out_dir, "%s-%s.exr" % (name, tag)), "--width", "160",
                   "--height", "120", "--validation", "--stats-json", stats_path] + flags
            p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
            problems = []
            if p.returncode != 0:
                problems.append("exit %d: %s" % (p.returncode, p.stderr.strip()[-600:]))
            else:
                if expected not in p.stdout:
                    problems.append("rtpbr-render does not report %s" % expected)
                with open(stats_path) as f:
                    stats = json.load(f)
                if stats.get("bounded", True):
                    problems.append("stats say the scene is bounded (it has punctual lights)")
                if stats["non_finite"] != 0:
                    problems.append("%d pixels not finite" % stats["non_finite"])
                if not stats["largest"] > 0.0:
                    problems.append("the image is black")
            failures += 1 if problems else 0
            print("%s %s %s: %s" % ("FAIL" if problems else "ok  ", name, tag,
                                    "; ".join(problems) if problems else "largest pixel %.4g" % stats["largest"]))
    print("%d passed, %d failed" % (len(scenes) * len(MODES) - failures, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
