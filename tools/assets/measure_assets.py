#!/usr/bin/env python3
"""Renders every lit asset (samples/assets/<Name>/<Name>.lit.gltf) with the engine
(rtpbr-render) and the oracle (rtpbr-oracle), and prints one Markdown table: whether each
program loads it, the engine's process time, HDR-FLIP (rtpbr-diff --hdr) of the engine
against the oracle, and the energy-bound figures of both images.

    measure_assets.py --build BUILD [--out DIR] [--width 320 --height 240] [--spp 64]
                      [--only NAME ...]

Figures:
  engine s      wall-clock seconds of the whole rtpbr-render process (load, pipeline
                creation, upload, one frame, readback, write); rtpbr-render prints no frame
                time, so this bounds the frame time from above. cpu s: the process's CPU time.
  L_light       the brightest emitter radiance of the file: max over EXT_lights_area lights
                of color x intensity, and over materials of emissiveFactor x
                KHR_materials_emissive_strength. None ("no bound") for a file whose nodes carry
                KHR_lights_punctual lights that shine: a delta light's irradiance I / d^2 has no upper
                limit, so no radiance bounds its pixels (and max / L is not given).
  max / L       the largest pixel radiance (max over RGB) divided by L_light. A surface that
                does not emit cannot exceed 1 (issue 28); the lights are out of frame in
                every spec, and the assets' own emissive surfaces emit at most L_light.
  > 1.01 L      pixels whose radiance exceeds 1.01 L_light (the oracle's, from its noise only).
  top 0.01 %    share of the image's energy (sum of RGB) held by its brightest 0.01 % pixels.

Needs numpy (Debian python3-numpy) and oiiotool (reads the EXR images).
Images and PNG previews are left in OUT (default /tmp/rtpbr-assets).
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time

try:
    import numpy as np
except ImportError:  # --help works without it; main() says it is missing
    np = None

HERE = os.path.dirname(os.path.abspath(__file__))
ASSETS = os.path.normpath(os.path.join(HERE, "..", "..", "samples", "assets"))


def read_exr(path):
    """Linear RGB of an EXR as an (h, w, 3) float array, through oiiotool --dumpdata."""
    text = subprocess.run(["oiiotool", "--info", "--dumpdata", path], check=True, capture_output=True,
                          text=True).stdout
    rows = [line.split(":", 1) for line in text.splitlines() if line.strip().startswith("Pixel (")]
    w = h = 0
    values = []
    for coord, rgb in rows:
        x, y = coord.strip()[len("Pixel ("):-1].split(",")
        w, h = max(w, int(x) + 1), max(h, int(y) + 1)
        values.append([float(v) for v in rgb.split()[:3]])
    return np.array(values, dtype=np.float64).reshape(h, w, 3)


def brightest_emitter(gltf_path):
    with open(gltf_path, encoding="utf-8") as f:
        doc = json.load(f)
    punctual = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    for node in doc.get("nodes", []):
        i = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light", -1)
        if 0 <= i < len(punctual) and punctual[i].get("intensity", 1.0) * max(punctual[i].get("color", [1, 1, 1])) > 0:
            return None  # a shining punctual light: no energy bound
    best = 0.0
    for light in doc.get("extensions", {}).get("EXT_lights_area", {}).get("lights", []):
        color = light.get("color", [1.0, 1.0, 1.0])
        best = max(best, max(color) * light.get("intensity", 1000.0))
    for m in doc.get("materials", []):
        strength = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        best = max(best, max(m.get("emissiveFactor", [0.0, 0.0, 0.0])) * strength)
    return best


def energy_figures(img, light):
    peak = float(np.nanmax(img)) if img.size else 0.0
    energy = np.nan_to_num(img).sum(axis=2).ravel()
    k = max(1, int(round(energy.size * 1e-4)))
    top = np.sort(energy)[-k:].sum()
    total = energy.sum()
    figures = {"max": peak, "top_share": float(top / total) if total > 0 else 0.0, "nan": int(np.isnan(img).sum())}
    if light is not None:  # else no bound (punctual lights): no ratio
        figures["over"] = int((np.nan_to_num(img).max(axis=2) > 1.01 * light).sum())
        figures["ratio"] = peak / light if light > 0 else float("inf")
    return figures


def timed(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return p, wall, cpu


def first_message(p):
    lines = [l for l in (p.stderr + p.stdout).splitlines() if l.strip()]
    errors = [l for l in lines if "error" in l.lower()]
    return (errors or lines or [""])[-1]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="a meson build folder with the engine and oracle")
    ap.add_argument("--out", default="/tmp/rtpbr-assets")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--spp", type=int, default=64, help="oracle samples per pixel")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--json", help="also write the figures here")
    args = ap.parse_args(argv)
    if np is None:
        sys.exit("measure_assets.py: needs numpy (python3-numpy)")
    render = os.path.join(args.build, "tools", "render", "rtpbr-render")
    oracle = os.path.join(args.build, "oracle", "rtpbr-oracle")
    diff = os.path.join(args.build, "tools", "imgdiff", "rtpbr-diff")
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(ASSETS, "lights.json"), encoding="utf-8") as f:
        names = sorted(json.load(f)["assets"])
    size = ["--width", str(args.width), "--height", str(args.height)]
    results = {}
    for name in names:
        if args.only and name not in args.only:
            continue
        lit = os.path.join(ASSETS, name, name + ".lit.gltf")
        light = brightest_emitter(lit)
        r = {"L_light": light}
        eng = os.path.join(args.out, name + ".engine.exr")
        orc = os.path.join(args.out, name + ".oracle.exr")
        p, wall, cpu = timed([render, lit, "-o", eng] + size)
        r["engine"] = {"exit": p.returncode, "wall_s": wall, "cpu_s": cpu, "message": first_message(p),
                       "warnings": [l for l in p.stderr.splitlines() if "warn" in l.lower()]}
        if p.returncode == 0:
            r["engine"].update(energy_figures(read_exr(eng), light))
            subprocess.run([render, lit, "-o", eng[:-4] + ".png"] + size, capture_output=True)
        p, wall, cpu = timed([oracle, lit, "-o", orc, "--spp", str(args.spp), "--quiet",
                              "--preview", orc[:-4] + ".png"] + size)
        r["oracle"] = {"exit": p.returncode, "wall_s": wall, "cpu_s": cpu, "message": first_message(p)}
        if p.returncode == 0:
            r["oracle"].update(energy_figures(read_exr(orc), light))
        if r["engine"]["exit"] == 0 and r["oracle"]["exit"] == 0:
            d = subprocess.run([diff, orc, eng, "--hdr", "--json", "--heatmap",
                                os.path.join(args.out, name + ".flip.png")], capture_output=True, text=True)
            try:
                r["flip"] = json.loads(d.stdout)
            except ValueError:
                r["flip"] = None
        results[name] = r
        print("measured", name, file=sys.stderr, flush=True)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(results, f, indent=1)

    def cell(side, key, fmt):
        return fmt % side[key] if key in side else "—"

    print("| asset | engine | oracle | engine s (cpu s) | HDR-FLIP mean | L_light | engine max / L | "
          "oracle max / L | engine > 1.01 L | oracle > 1.01 L | engine top 0.01 % | oracle top 0.01 % |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, r in results.items():
        e, o = r["engine"], r["oracle"]
        flip = r.get("flip") or {}
        mean = flip.get("mean", flip.get("flip_mean"))
        print("| %s | %s | %s | %.2f (%.2f) | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            name, "loads" if e["exit"] == 0 else "refused (exit %d)" % e["exit"],
            "loads" if o["exit"] == 0 else "refused (exit %d)" % o["exit"], e["wall_s"], e["cpu_s"],
            "%.4f" % mean if isinstance(mean, (int, float)) else "—",
            "no bound" if r["L_light"] is None else "%g" % r["L_light"],
            cell(e, "ratio", "%.3g"), cell(o, "ratio", "%.3g"), cell(e, "over", "%d"), cell(o, "over", "%d"),
            cell(e, "top_share", "%.3g"), cell(o, "top_share", "%.3g")))
    for name, r in results.items():
        for side in ("engine", "oracle"):
            if r[side]["exit"] != 0:
                print("\n%s, %s: %s" % (name, side, r[side]["message"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
