#!/usr/bin/env python3
"""rtpbr-validate: renders each bundled scene with the engine (rtpbr-render) and with the
oracle (rtpbr-oracle), compares them with rtpbr-diff (HDR-FLIP, RMSE, relMSE, PSNR) and
writes a report: REPORT/index.html (images side by side, heat maps, numbers), summary.json
and summary.md. Exits 1 when a scene exceeds its thresholds (thresholds.json, under version
control), 2 on errors (a tool missing or failing).

    rtpbr_validate.py [--build BUILD] [--thresholds FILE] [--out REPORT] [--quick]
                      [--scenes NAME ...] [--cache DIR] [--no-cache]

Oracle images are cached by a hash of the scene files, the oracle's options and the oracle
binary itself (its version), so a second run re-renders only what changed.
"""
import argparse
import hashlib
import html
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def log(msg):
    print("rtpbr-validate: " + msg, file=sys.stderr, flush=True)


def find_tool(build, name, subdirs):
    for sub in subdirs:
        p = os.path.join(build, sub, name)
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    for dirpath, _, files in os.walk(build):
        if name in files and os.access(os.path.join(dirpath, name), os.X_OK):
            return os.path.join(dirpath, name)
    return None


def file_hash(paths):
    h = hashlib.sha256()
    for p in paths:
        with open(p, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
    return h.hexdigest()


def scene_files(gltf):
    files = [gltf]
    with open(gltf) as f:
        doc = json.load(f)
    for b in doc.get("buffers", []) + doc.get("images", []):
        uri = b.get("uri", "")
        if uri and not uri.startswith("data:"):
            files.append(os.path.join(os.path.dirname(gltf), uri))
    return files


def run(cmd, what):
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0 and what != "diff":
        log("%s failed (exit %d): %s\n%s" % (what, p.returncode, " ".join(cmd), p.stderr.strip()[-2000:]))
        raise SystemExit(2)
    return p, time.time() - t0


def to_png(oiiotool, exr, png, exposure):
    # The same display transform for engine and oracle images: exposure, clamp, sRGB.
    cmd = [oiiotool, exr, "--ch", "R,G,B", "--mulc", str(exposure), "--clamp:min=0:max=1",
           "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o", png]
    run(cmd, "oiiotool")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--thresholds", default=os.path.join(HERE, "thresholds.json"))
    ap.add_argument("--out", default=os.path.join(ROOT, "report"))
    ap.add_argument("--quick", action="store_true", help="small images and few samples (CI)")
    ap.add_argument("--scenes", nargs="*")
    ap.add_argument("--cache", default=None, help="oracle cache (default BUILD/validate-cache)")
    ap.add_argument("--no-cache", action="store_true")
    args = ap.parse_args(argv)

    with open(args.thresholds) as f:
        config = json.load(f)
    mode = "quick" if args.quick else "full"
    settings = dict(config["defaults"])
    settings.update(config.get(mode, {}))

    render = find_tool(args.build, "rtpbr-render", ["samples/headless", "engine"])
    oracle = find_tool(args.build, "rtpbr-oracle", ["oracle"])
    diff = find_tool(args.build, "rtpbr-diff", ["tools/imgdiff"])
    oiiotool = shutil.which("oiiotool")
    missing = [n for n, p in [("rtpbr-render", render), ("rtpbr-oracle", oracle), ("rtpbr-diff", diff),
                              ("oiiotool", oiiotool)] if not p]
    if missing:
        log("missing tools: %s (build with `ninja -C %s`; oiiotool comes from openimageio-tools)"
            % (", ".join(missing), args.build))
        return 2

    cache = args.cache or os.path.join(args.build, "validate-cache")
    os.makedirs(cache, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    oracle_version = file_hash([oracle])[:16]

    names = args.scenes or list(config["scenes"].keys())
    results = []
    failed = False
    for k, name in enumerate(names):
        if name not in config["scenes"]:
            log("unknown scene %r (thresholds.json lists %s)" % (name, ", ".join(config["scenes"])))
            return 2
        sc = dict(settings)
        sc.update({k: v for k, v in config["scenes"][name].items() if k not in ("quick", "full")})
        sc.update(config["scenes"][name].get(mode, {}))
        if "max_mean" not in sc or "max_p95" not in sc:
            log("thresholds.json: scene %s has no max_mean/max_p95 for mode %s" % (name, mode))
            return 2
        gltf = os.path.join(ROOT, "samples", "scenes", name + ".gltf")
        if not os.path.isfile(gltf):
            log("scene file %s missing" % gltf)
            return 2
        outdir = os.path.join(args.out, name)
        os.makedirs(outdir, exist_ok=True)
        w, h = str(sc["width"]), str(sc["height"])
        log("[%d/%d] %s: engine %sx%s" % (k + 1, len(names), name, w, h))
        engine_exr = os.path.join(outdir, "engine.exr")
        _, t_engine = run([render, gltf, "-o", engine_exr, "--width", w, "--height", h, "--camera", "0"]
                          + list(sc.get("engine_flags", [])), "rtpbr-render")

        oracle_args = ["--width", w, "--height", h, "--camera", "0", "--spp", str(sc["spp"]),
                       "--seed", str(sc.get("seed", 1))] + list(sc.get("oracle_flags", []))
        key = hashlib.sha256((file_hash(scene_files(gltf)) + " ".join(oracle_args) + oracle_version).encode()).hexdigest()[:24]
        cached = os.path.join(cache, "%s-%s.exr" % (name, key))
        oracle_exr = os.path.join(outdir, "oracle.exr")
        t_oracle = 0.0
        if os.path.isfile(cached) and not args.no_cache:
            log("[%d/%d] %s: oracle from cache" % (k + 1, len(names), name))
        else:
            log("[%d/%d] %s: oracle %s spp (this is the slow part)" % (k + 1, len(names), name, sc["spp"]))
            _, t_oracle = run([oracle, gltf, "-o", cached + ".tmp.exr", "--quiet"] + oracle_args, "rtpbr-oracle")
            os.replace(cached + ".tmp.exr", cached)
        shutil.copyfile(cached, oracle_exr)

        heat = os.path.join(outdir, "flip.png")
        dcmd = [diff, oracle_exr, engine_exr, "--hdr", "--heatmap", heat, "--json",
                "--max-mean", str(sc["max_mean"]), "--max-p95", str(sc["max_p95"])]
        p, _ = run(dcmd, "diff")
        if p.returncode not in (0, 1):
            log("rtpbr-diff failed (exit %d): %s" % (p.returncode, p.stderr.strip()))
            return 2
        metrics = json.loads(p.stdout)
        ok = p.returncode == 0
        failed = failed or not ok
        exposure = float(sc.get("display_exposure", 1.0))
        to_png(oiiotool, engine_exr, os.path.join(outdir, "engine.png"), exposure)
        to_png(oiiotool, oracle_exr, os.path.join(outdir, "oracle.png"), exposure)
        results.append({"scene": name, "ok": ok, "max_mean": sc["max_mean"], "max_p95": sc["max_p95"],
                        "width": sc["width"], "height": sc["height"], "spp": sc["spp"],
                        "oracle_flags": sc.get("oracle_flags", []), "engine_flags": sc.get("engine_flags", []),
                        "note": sc.get("note", ""),
                        "engine_seconds": round(t_engine, 2), "oracle_seconds": round(t_oracle, 2),
                        "metrics": metrics})
        log("[%d/%d] %s: HDR-FLIP mean %.4f p95 %.4f (limits %.3f / %.3f) %s"
            % (k + 1, len(names), name, metrics["mean"], metrics["p95"], sc["max_mean"], sc["max_p95"],
               "ok" if ok else "EXCEEDED"))

    write_report(args.out, results, mode)
    log("report: %s" % os.path.join(args.out, "index.html"))
    return 1 if failed else 0


def write_report(out, results, mode):
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump({"mode": mode, "scenes": results}, f, indent=1)
    cols = ["scene", "HDR-FLIP mean", "median", "p95", "p99", "max", "RMSE", "relMSE", "limits (mean / p95)", "result"]
    md = ["# rtpbr validation (%s)" % mode, "", "| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    rows_html = []
    for r in results:
        m = r["metrics"]
        vals = [r["scene"], "%.4f" % m["mean"], "%.4f" % m["median"], "%.4f" % m["p95"], "%.4f" % m["p99"],
                "%.4f" % m["max"], "%.4g" % m["rmse"], "%.4g" % m["relmse"],
                "%.3f / %.3f" % (r["max_mean"], r["max_p95"]), "ok" if r["ok"] else "EXCEEDED"]
        md.append("| " + " | ".join(vals) + " |")
        rows_html.append("<tr class='%s'>%s</tr>" % ("ok" if r["ok"] else "bad", "".join("<td>%s</td>" % html.escape(v) for v in vals)))
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    sections = []
    for r in results:
        s = html.escape(r["scene"])
        sections.append(
            "<h2 id='%s'>%s</h2><p>%s</p><p>oracle: %s spp, flags <code>%s</code>; %dx%d; HDR-FLIP mean <b>%.4f</b>, "
            "p95 %.4f (limits %.3f / %.3f)</p><div class='row'><figure><img src='%s/engine.png'><figcaption>engine "
            "(LTC)</figcaption></figure><figure><img src='%s/oracle.png'><figcaption>oracle (path traced)</figcaption>"
            "</figure><figure><img src='%s/flip.png'><figcaption>HDR-FLIP error (magma)</figcaption></figure></div>"
            % (s, s, html.escape(r["note"]), r["spp"], html.escape(" ".join(r["oracle_flags"])), r["width"], r["height"],
               r["metrics"]["mean"], r["metrics"]["p95"], r["max_mean"], r["max_p95"], s, s, s))
    page = """<!doctype html><meta charset="utf-8"><title>rtpbr validation</title>
<style>body{font-family:sans-serif;margin:2em;background:#fafafa}table{border-collapse:collapse}
td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}tr.bad td{background:#fdd}
.row{display:flex;gap:12px}figure{margin:0}img{max-width:100%%;image-rendering:pixelated}</style>
<h1>rtpbr validation: engine against oracle (%s)</h1>
<table><tr>%s</tr>%s</table>%s""" % (mode, "".join("<th>%s</th>" % c for c in cols), "".join(rows_html), "".join(sections))
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write(page)


if __name__ == "__main__":
    sys.exit(main())
