#!/usr/bin/env python3
"""rtpbr-validate: renders each bundled scene with the engine (rtpbr-render) and with the
oracle (rtpbr-oracle), compares them with rtpbr-diff (HDR-FLIP, RMSE, relMSE, PSNR) and
writes a report: REPORT/index.html (images side by side, heat maps, numbers), summary.json
and summary.md. Exits 1 when a scene exceeds its thresholds (thresholds.json, under version
control), 2 on errors (a tool missing or failing).

    rtpbr_validate.py [--build BUILD] [--thresholds FILE] [--out REPORT] [--quick]
                      [--scenes NAME ...] [--cache DIR] [--no-cache]
                      [--scheduler tcp://HOST:PORT | --local-workers N | --jobqueue slurm ...]

Oracle images are cached by a hash of the scene files, the oracle's options and the oracle
binary itself (its version), so a second run re-renders only what changed. With a cluster
option the oracle references are rendered on Dask distributed (rtpbr_oracle_cluster.py: tasks
of image bands x sample ranges, merged bit for bit into the image one process writes), into the
same cache; the report says where each reference was rendered (tasks, workers, retries).
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

import rtpbr_oracle_cluster as oracle_cluster

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


# The page shows results; why each limit is what it is (the measurements behind it, their
# history) stays beside the limit, in the scene's note.
LIMITS_LINE = ("Limits: tools/validate/thresholds.json (each limit is at most 1.2 x the latest measurement; the scene's note there "
               "records the measurements).")


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


def scene_descriptions():
    """What each bundled scene shows (tools/make-scenes/scenes.json; absent when installed)."""
    path = os.path.join(ROOT, "tools", "make-scenes", "scenes.json")
    if not os.path.isfile(path):
        return {}
    with open(path) as f:
        return {name: s.get("description", "") for name, s in json.load(f)["scenes"].items()}


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
    oracle_cluster.add_cluster_arguments(ap)
    raw_argv = sys.argv[1:] if argv is None else argv
    args = ap.parse_args(argv)
    on_cluster = bool(args.scheduler or args.local_workers or args.jobqueue)
    try:
        if on_cluster:
            oracle_cluster.ensure_dask(os.path.abspath(__file__), raw_argv)
        return validate(args, on_cluster)
    except oracle_cluster.ClusterError as e:
        log(str(e))
        return 2
    finally:
        if _cluster_state["client"] is not None:
            _cluster_state["client"].close()
        if _cluster_state["cluster"] is not None:
            _cluster_state["cluster"].close()


_cluster_state = {"client": None, "cluster": None}


def cluster_client(args):
    """The Dask client, connected on first use (a run whose references are all cached needs none)."""
    if _cluster_state["client"] is None:
        log("connecting to %s" % oracle_cluster.cluster_description(args.scheduler, args.local_workers,
                                                                     args.jobqueue, args.jobs))
        _cluster_state["client"], _cluster_state["cluster"] = oracle_cluster.connect(
            args.scheduler, args.local_workers, args.jobqueue, args.jobs, args.jobqueue_option)
    return _cluster_state["client"]


def validate(args, on_cluster):

    with open(args.thresholds) as f:
        config = json.load(f)
    mode = "quick" if args.quick else "full"
    settings = dict(config["defaults"])
    settings.update(config.get(mode, {}))

    render = find_tool(args.build, "rtpbr-render", ["tools/render", "engine"])
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

    # Bundled scenes (samples/scenes/NAME.gltf) and real assets (the public models lit by
    # tools/assets/light_assets.py: asset_file), each with its thresholds.
    entries = dict((n, ("scene", c)) for n, c in config["scenes"].items())
    entries.update((n, ("asset", c)) for n, c in config.get("assets", {}).items())
    names = args.scenes or list(entries.keys())
    descriptions = scene_descriptions()
    results = []
    failed = False
    for k, name in enumerate(names):
        if name not in entries:
            log("unknown scene %r (thresholds.json lists %s)" % (name, ", ".join(entries)))
            return 2
        kind, entry = entries[name]
        sc = dict(settings)
        sc.update({k: v for k, v in entry.items() if k not in ("quick", "full")})
        sc.update(entry.get(mode, {}))
        if "max_mean" not in sc or "max_p95" not in sc:
            log("thresholds.json: scene %s has no max_mean/max_p95 for mode %s" % (name, mode))
            return 2
        if kind == "asset":
            gltf = asset_file(name)
        else:
            gltf = os.path.join(ROOT, "samples", "scenes", name + ".gltf")
        if not os.path.isfile(gltf):
            log("scene file %s missing" % gltf)
            return 2
        outdir = os.path.join(args.out, name)
        os.makedirs(outdir, exist_ok=True)
        w, h = str(sc["width"]), str(sc["height"])
        log("[%d/%d] %s: engine %sx%s" % (k + 1, len(names), name, w, h))
        engine_exr = os.path.join(outdir, "engine.exr")
        engine_stats = os.path.join(outdir, "engine-energy.json")
        _, t_engine = run([render, gltf, "-o", engine_exr, "--width", w, "--height", h, "--camera", "0",
                           "--stats-json", engine_stats] + list(sc.get("engine_flags", [])), "rtpbr-render")
        with open(engine_stats) as f:
            energy = json.load(f)
        brightest = energy["brightest_emitter"]
        # A scene with punctual lights has no energy bound (rtpbr_common/energy.hpp): none is checked.
        bounded = energy.get("bounded", True)
        if not bounded:
            log("[%d/%d] %s: %s" % (k + 1, len(names), name, NO_BOUND))

        oracle_args = ["--width", w, "--height", h, "--camera", "0", "--spp", str(sc["spp"]),
                       "--seed", str(sc.get("seed", 1))] + list(sc.get("oracle_flags", []))
        key = hashlib.sha256((file_hash(scene_files(gltf)) + " ".join(oracle_args) + oracle_version).encode()).hexdigest()[:24]
        cached = os.path.join(cache, "%s-%s.exr" % (name, key))
        oracle_exr = os.path.join(outdir, "oracle.exr")
        t_oracle = 0.0
        # How the cached image was rendered, beside it (one process or a cluster run).
        how_path = cached[:-len(".exr")] + ".json"
        if os.path.isfile(cached) and not args.no_cache:
            log("[%d/%d] %s: oracle from cache" % (k + 1, len(names), name))
            how = {"where": "local"}
            if os.path.isfile(how_path):
                with open(how_path) as f:
                    how = json.load(f)
            how["cached"] = True
        elif on_cluster:
            log("[%d/%d] %s: oracle %s spp on the cluster" % (k + 1, len(names), name, sc["spp"]))
            t0 = time.time()
            stats = oracle_cluster.render(cluster_client(args), gltf, oracle, oracle_args, cached + ".tmp.exr",
                                          args.task_seconds, args.task_samples, args.task_threads,
                                          args.worker_oracle, args.shared_scene,
                                          lambda msg: log("[%d/%d] %s" % (k + 1, len(names), msg)), name)
            t_oracle = time.time() - t0
            how = {"where": "cluster", "cluster": oracle_cluster.cluster_description(
                args.scheduler, args.local_workers, args.jobqueue, args.jobs)}
            how.update({key: stats[key] for key in ("tasks", "workers", "retries", "seconds",
                                                   "task_seconds_median", "overhead_seconds_median")})
            os.replace(cached + ".tmp.exr", cached)
            with open(how_path, "w") as f:
                json.dump(how, f, indent=1)
            how["cached"] = False
        else:
            log("[%d/%d] %s: oracle %s spp (this is the slow part)" % (k + 1, len(names), name, sc["spp"]))
            _, t_oracle = run([oracle, gltf, "-o", cached + ".tmp.exr", "--quiet"] + oracle_args, "rtpbr-oracle")
            os.replace(cached + ".tmp.exr", cached)
            how = {"where": "local", "seconds": round(t_oracle, 2)}
            with open(how_path, "w") as f:
                json.dump(how, f, indent=1)
            how["cached"] = False
        shutil.copyfile(cached, oracle_exr)

        heat = os.path.join(outdir, "flip.png")
        # The energy bound (issue 28): no pixel of the engine above max_ratio (1.01 unless the
        # scene says why) x the brightest emitter; the oracle's figure is reported (its noise
        # can cross the bound), not gated.
        max_ratio = float(sc.get("max_ratio", 1.01))
        dcmd = [diff, oracle_exr, engine_exr, "--hdr", "--heatmap", heat, "--json",
                "--max-mean", str(sc["max_mean"]), "--max-p95", str(sc["max_p95"])]
        if brightest > 0:
            dcmd += ["--bound", repr(brightest), "--max-ratio", repr(max_ratio)]
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
        results.append({"scene": name, "kind": kind, "ok": ok, "max_mean": sc["max_mean"], "max_p95": sc["max_p95"],
                        "max_ratio": max_ratio, "bounded": bounded,
                        "width": sc["width"], "height": sc["height"], "spp": sc["spp"],
                        "oracle_flags": sc.get("oracle_flags", []), "engine_flags": sc.get("engine_flags", []),
                        "description": descriptions.get(name, "") if kind == "scene" else "",
                        "engine_seconds": round(t_engine, 2), "oracle_seconds": round(t_oracle, 2),
                        "oracle_args": oracle_args, "oracle_render": how, "metrics": metrics})
        log("[%d/%d] %s: HDR-FLIP mean %.4f p95 %.4f (limits %.3f / %.3f); largest pixel / brightest emitter: "
            "%s %s"
            % (k + 1, len(names), name, metrics["mean"], metrics["p95"], sc["max_mean"], sc["max_p95"],
               bound_text(results[-1]), "ok" if ok else "EXCEEDED"))

    write_report(args.out, results, mode)
    log("report: %s" % os.path.join(args.out, "index.html"))
    return 1 if failed else 0


def asset_file(name):
    """The wrapper an 'assets' entry of thresholds.json names: NAME is the asset lit by its area
    lights, samples/assets/NAME/NAME.lit.gltf; NAME.punctual the same asset lit by its
    KHR_lights_punctual lights, samples/assets/NAME/NAME.punctual.gltf (samples/assets/lights.json)."""
    asset, dot, variant = name.partition(".")
    return os.path.join(ROOT, "samples", "assets", asset, "%s.%s.gltf" % (asset, variant if dot else "lit"))


def ratio_text(energy):
    return "%.4g" % energy["max_ratio"] if energy else "-"


NO_BOUND = ("no energy bound: the scene has punctual lights (KHR_lights_punctual), whose irradiance I / d^2 has "
            "no upper limit")


def bound_text(r, bold=lambda t: t):
    """A result's largest pixel / brightest emitter, engine and oracle, with the limit."""
    if not r.get("bounded", True):
        return "none (punctual lights)"
    bound = r["metrics"].get("bound", {})
    return "engine %s, oracle %s (limit %.2f)" % (bold(ratio_text(bound.get("test"))),
                                                  ratio_text(bound.get("reference")), r["max_ratio"])


def share_text(energy):
    return "%.3g %%" % (100 * energy["top_share"]) if energy else "-"


def describe_render(how):
    """One line on how an oracle reference was rendered, for the report."""
    if how.get("where") == "cluster":
        text = ("on %s: %d tasks on %d workers, %d retries, %.1f s (median task %.1f s, of which %.1f s outside "
                "the render)" % (how.get("cluster", "a Dask cluster"), how["tasks"], how["workers"], how["retries"],
                                 how["seconds"], how.get("task_seconds_median") or 0.0,
                                 how.get("overhead_seconds_median") or 0.0))
    else:
        text = "in one process" + (", %.1f s" % how["seconds"] if "seconds" in how else "")
    return ("from the cache (rendered %s)" if how.get("cached") else "rendered %s") % text


def rendering_summary(results):
    renders = [r["oracle_render"] for r in results]
    fresh = [h for h in renders if not h.get("cached")]
    on_cluster = [h for h in fresh if h.get("where") == "cluster"]
    return {"references": len(renders), "from_cache": len(renders) - len(fresh),
            "in_one_process": len(fresh) - len(on_cluster), "on_cluster": len(on_cluster),
            "cluster": on_cluster[0]["cluster"] if on_cluster else None,
            "tasks": sum(h["tasks"] for h in on_cluster), "workers": max([h["workers"] for h in on_cluster] or [0]),
            "retries": sum(h["retries"] for h in on_cluster)}


def write_report(out, results, mode):
    rendering = rendering_summary(results)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump({"mode": mode, "oracle_rendering": rendering, "scenes": results}, f, indent=1)
    how_line = ("Oracle references: %d rendered in one process, %d on %s (%d tasks, up to %d workers, %d retries), "
                "%d from the cache." % (rendering["in_one_process"], rendering["on_cluster"],
                                        rendering["cluster"] or "a cluster", rendering["tasks"], rendering["workers"],
                                        rendering["retries"], rendering["from_cache"]))
    cols = ["scene", "HDR-FLIP mean", "median", "p95", "p99", "max", "RMSE", "relMSE", "limits (mean / p95)",
            "largest / brightest emitter", "brightest 0.01 % hold (engine)", "result"]
    md = ["# rtpbr validation (%s)" % mode, "", how_line + " " + LIMITS_LINE, "",
          "Largest / brightest emitter: the largest pixel of the image over the brightest emitter's "
          "radiance; no surface reflects more than reaches it, so above 1.01 the engine fails (the "
          "oracle's noise may cross it: reported only). A scene with punctual lights has no such bound "
          "(none is checked).", "",
          "| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    rows_html = []
    for r in results:
        m = r["metrics"]
        bound = m.get("bound", {})
        vals = [r["scene"] + (" (asset)" if r.get("kind") == "asset" else ""), "%.4f" % m["mean"],
                "%.4f" % m["median"], "%.4f" % m["p95"], "%.4f" % m["p99"],
                "%.4f" % m["max"], "%.4g" % m["rmse"], "%.4g" % m["relmse"],
                "%.3f / %.3f" % (r["max_mean"], r["max_p95"]),
                bound_text(r), share_text(bound.get("test")), "ok" if r["ok"] else "EXCEEDED"]
        md.append("| " + " | ".join(vals) + " |")
        rows_html.append("<tr class='%s'>%s</tr>" % ("ok" if r["ok"] else "bad", "".join("<td>%s</td>" % html.escape(v) for v in vals)))
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    sections = []
    for kind in ("scene", "asset"):
        chosen = [r for r in results if r.get("kind", "scene") == kind]
        if kind == "asset" and chosen:
            sections.append("<h2 id='assets'>Real assets</h2><p>Public Khronos glTF sample models (samples/assets, "
                            "licences beside each), lit by the added lights of samples/assets/lights.json "
                            "(tools/assets/light_assets.py): NAME by its area lights, NAME.punctual by its "
                            "KHR_lights_punctual lights.</p>")
        for r in chosen:
            s = html.escape(r["scene"])
            bound = r["metrics"].get("bound", {})
            sections.append(
                "<h%d id='%s'>%s</h%d><p>%s</p><p>oracle: %s spp, flags <code>%s</code>; %dx%d; HDR-FLIP mean <b>%.4f</b>, "
                "p95 %.4f (limits %.3f / %.3f); largest pixel / brightest emitter: %s; "
                "the brightest 0.01 %% of the engine's pixels hold %s of its energy</p>"
                "<p class='how'>oracle reference %s</p><div class='row'><figure><img src='%s/engine.png'><figcaption>engine "
                "(LTC)</figcaption></figure><figure><img src='%s/oracle.png'><figcaption>oracle (path traced)</figcaption>"
                "</figure><figure><img src='%s/flip.png'><figcaption>HDR-FLIP error (magma)</figcaption></figure></div>"
                % (2 if kind == "scene" else 3, s, s, 2 if kind == "scene" else 3, html.escape(r["description"]), r["spp"],
                   html.escape(" ".join(r["oracle_flags"])), r["width"], r["height"],
                   r["metrics"]["mean"], r["metrics"]["p95"], r["max_mean"], r["max_p95"],
                   bound_text(r, lambda t: "<b>%s</b>" % t), share_text(bound.get("test")),
                   html.escape(describe_render(r["oracle_render"])), s, s, s))
    page = """<!doctype html><meta charset="utf-8"><title>rtpbr validation</title>
<style>body{font-family:sans-serif;margin:2em;background:#fafafa}table{border-collapse:collapse}
td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}tr.bad td{background:#fdd}
.row{display:flex;gap:12px}figure{margin:0}img{max-width:100%%;image-rendering:pixelated}</style>
<h1>rtpbr validation: engine against oracle (%s)</h1>
<p>%s %s</p>
<table><tr>%s</tr>%s</table>%s""" % (mode, html.escape(how_line), html.escape(LIMITS_LINE), "".join("<th>%s</th>" % c for c in cols),
                                     "".join(rows_html), "".join(sections))
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write(page)


if __name__ == "__main__":
    sys.exit(main())
