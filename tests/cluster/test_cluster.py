#!/usr/bin/env python3
"""Oracle references on a Dask cluster (suite 'cluster'): a LocalCluster of 2 worker processes
on 127.0.0.1 only, driven through the command lines (rtpbr_validate.py and
rtpbr_oracle_cluster.py with --scheduler tcp://127.0.0.1:PORT).

    test_cluster.py equal|kill|bad-scene --build BUILD

equal      rtpbr-validate --quick on two bundled scenes with the references cut into bands x
           sample ranges: each reference EXR equals the one `rtpbr-oracle` writes in one
           process, byte for byte; a second run without the cluster takes both from the cache.
kill       one worker process is killed (SIGKILL) while its oracle runs: the run still ends,
           reports the rerun, leaves no orphan oracle, and the image is byte-identical.
bad-scene  a scene whose buffer is cut short fails the run quickly with the oracle's own
           message (the one `rtpbr-oracle` prints in one process), each task started once.
plan       (no cluster) the cut covers every (row, sample) after the probe exactly once, for
           many image sizes, sample counts and task sizes, in bands of at least 16 rows.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
VALIDATE = os.path.join(ROOT, "tools", "validate", "rtpbr_validate.py")
CLUSTER_CLI = os.path.join(ROOT, "tools", "validate", "rtpbr_oracle_cluster.py")
VENV_PYTHON = os.path.join(ROOT, ".deps", "venv", "bin", "python3")
SCENES = os.path.join(ROOT, "samples", "scenes")

try:
    import distributed
    import psutil
except ImportError:
    if os.path.isfile(VENV_PYTHON) and os.path.realpath(sys.executable) != os.path.realpath(VENV_PYTHON):
        os.execv(VENV_PYTHON, [VENV_PYTHON] + sys.argv)
    print("test_cluster: the Dask packages are missing: run scripts/setup.sh (it makes %s)" % VENV_PYTHON,
          file=sys.stderr)
    sys.exit(1)

failures = []


def check(cond, what):
    print("%s: %s" % ("ok" if cond else "FAIL", what), flush=True)
    if not cond:
        failures.append(what)
    return cond


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def local_cluster():
    # Loopback only; no dashboard. Nannies restart a killed worker, as a deployment's would.
    return distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                    dashboard_address=None, scheduler_port=0)


def oracle_alone(oracle, scene, out, args):
    p = subprocess.run([oracle, scene, "-o", out, "--quiet"] + list(args), stderr=subprocess.PIPE, text=True)
    return p.returncode, p.stderr


def test_equal(build, oracle, tmp):
    out, cache = os.path.join(tmp, "report"), os.path.join(tmp, "cache")
    scenes = ["quad_light", "room"]
    with local_cluster() as cluster:
        # 120000 pixel-samples per task: the 128 x 96 x 63 samples after the probe become
        # 6 bands x 2 sample ranges, so both kinds of cut are merged.
        cmd = [sys.executable, VALIDATE, "--build", build, "--quick", "--scenes"] + scenes + [
            "--out", out, "--cache", cache, "--scheduler", cluster.scheduler_address,
            "--task-threads", "1", "--task-samples", "120000"]
        p = subprocess.run(cmd, stderr=subprocess.PIPE, text=True)
        sys.stderr.write(p.stderr[-3000:])
    if not check(p.returncode == 0, "rtpbr-validate on the cluster exits 0 (got %d)" % p.returncode):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    check(summary["oracle_rendering"]["on_cluster"] == 2, "summary.json: both references rendered on the cluster")
    for r in summary["scenes"]:
        how = r["oracle_render"]
        check(how["where"] == "cluster" and how["tasks"] == 13 and how["workers"] >= 1 and how["retries"] == 0,
              "%s: rendered on the cluster in %s tasks on %s workers, %s retries"
              % (r["scene"], how.get("tasks"), how.get("workers"), how.get("retries")))
        ref = os.path.join(tmp, r["scene"] + "-one-process.exr")
        status, err = oracle_alone(oracle, os.path.join(SCENES, r["scene"] + ".gltf"), ref, r["oracle_args"])
        check(status == 0, "%s: single-process oracle renders (%s)" % (r["scene"], err.strip()))
        check(same_bytes(ref, os.path.join(out, r["scene"], "oracle.exr")),
              "%s: cluster EXR == single-process EXR, byte for byte" % r["scene"])
    with open(os.path.join(out, "index.html")) as f:
        page = f.read()
    check("on Dask scheduler tcp://127.0.0.1:" in page and " tasks on " in page and " retries" in page,
          "index.html says how the references were rendered")
    saved = {r["scene"]: open(os.path.join(out, r["scene"], "oracle.exr"), "rb").read() for r in summary["scenes"]}

    # The same cache without a cluster: nothing is rendered again.
    p = subprocess.run([sys.executable, VALIDATE, "--build", build, "--quick", "--scenes"] + scenes +
                       ["--out", out, "--cache", cache], stderr=subprocess.PIPE, text=True)
    check(p.returncode == 0, "rtpbr-validate without a cluster exits 0")
    with open(os.path.join(out, "summary.json")) as f:
        again = json.load(f)
    check(again["oracle_rendering"]["from_cache"] == 2, "a run without the cluster takes both references from the cache")
    for r in again["scenes"]:
        check(r["oracle_render"].get("cached") and r["oracle_render"]["where"] == "cluster",
              "%s: the report says: from the cache, rendered on the cluster" % r["scene"])
        check(open(os.path.join(out, r["scene"], "oracle.exr"), "rb").read() == saved[r["scene"]],
              "%s: cached reference unchanged" % r["scene"])


def test_kill(build, oracle, tmp):
    scene = os.path.join(SCENES, "room.gltf")
    args = ["--width", "96", "--height", "72", "--spp", "256", "--seed", "3", "--direct-only"]
    out, stats_path = os.path.join(tmp, "cluster.exr"), os.path.join(tmp, "stats.json")
    with local_cluster() as cluster, distributed.Client(cluster) as client:
        cmd = [sys.executable, CLUSTER_CLI, scene, "-o", out, "--oracle", oracle, "--scheduler",
               cluster.scheduler_address, "--task-threads", "1", "--task-samples", "200000",
               "--stats-json", stats_path, "--"] + args
        proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True)
        lines = []
        reader = threading.Thread(target=lambda: lines.extend(iter(proc.stderr.readline, "")), daemon=True)
        reader.start()
        victim = orphan = None
        deadline = time.time() + 120
        while victim is None and proc.poll() is None and time.time() < deadline:
            if any("tasks (" in ln for ln in lines):  # the probe is done, the band tasks are out
                for addr, pid in client.run(os.getpid).items():
                    kids = [c for c in psutil.Process(pid).children() if c.name() == "rtpbr-oracle"]
                    if kids:
                        victim, orphan = (addr, pid), kids[0]
                        os.kill(pid, signal.SIGKILL)
                        break
            time.sleep(0.05)
        check(victim is not None, "a worker was killed while its rtpbr-oracle was running (%s)" % (victim,))
        try:
            status = proc.wait(timeout=300)
        except subprocess.TimeoutExpired:
            proc.kill()
            status = None
        reader.join()
        sys.stderr.write("".join(lines[-12:]))
        if orphan is not None:
            try:
                orphan.wait(timeout=10)
                gone = True
            except psutil.TimeoutExpired:
                gone = False
                orphan.kill()
            check(gone, "the killed worker's rtpbr-oracle died with it")
    if not check(status == 0, "the cluster run ends with status 0 after the kill (got %s)" % status):
        return
    with open(stats_path) as f:
        stats = json.load(f)
    check(stats["retries"] >= 1, "the statistics count the rerun (retries %d)" % stats["retries"])
    ref = os.path.join(tmp, "one-process.exr")
    status, err = oracle_alone(oracle, scene, ref, args)
    check(status == 0, "single-process oracle renders (%s)" % err.strip())
    check(same_bytes(ref, out), "EXR after a killed worker == single-process EXR, byte for byte")


def test_bad_scene(build, oracle, tmp):
    # quad_light with its buffer cut to half: valid JSON, a buffer shorter than its byteLength.
    scene_dir = os.path.join(tmp, "bad")
    os.makedirs(scene_dir)
    shutil.copy(os.path.join(SCENES, "quad_light.gltf"), scene_dir)
    with open(os.path.join(SCENES, "quad_light.bin"), "rb") as f:
        data = f.read()
    with open(os.path.join(scene_dir, "quad_light.bin"), "wb") as f:
        f.write(data[:len(data) // 2])
    scene = os.path.join(scene_dir, "quad_light.gltf")
    args = ["--width", "64", "--height", "48", "--spp", "64"]
    status_alone, message_alone = oracle_alone(oracle, scene, os.path.join(tmp, "alone.exr"), args)
    message_alone = message_alone.strip()
    check(status_alone == 1 and message_alone.startswith("rtpbr-oracle: "),
          "the oracle alone refuses the scene: %s" % message_alone)
    with local_cluster() as cluster, distributed.Client(cluster) as client:
        t0 = time.time()
        p = subprocess.run([sys.executable, CLUSTER_CLI, scene, "-o", os.path.join(tmp, "bad.exr"), "--oracle", oracle,
                            "--scheduler", cluster.scheduler_address, "--task-threads", "1", "--"] + args,
                           stderr=subprocess.PIPE, text=True, timeout=300)
        seconds = time.time() - t0
        starts = [ev for _, ev in client.get_events("rtpbr-oracle-start")]
        workers = client.run(os.getpid)
    sys.stderr.write(p.stderr[-2000:])
    check(p.returncode == 1, "the cluster run fails with status 1 (got %d)" % p.returncode)
    check(message_alone in p.stderr.splitlines()[-1], "the failure is the oracle's message, %r" % message_alone)
    check("Traceback" not in p.stderr, "no Python traceback")
    keys = [ev["key"] for ev in starts]
    check(len(keys) == len(set(keys)) and len(keys) >= 1, "no task was retried (%d starts of %d tasks)"
          % (len(keys), len(set(keys))))
    check(len(workers) == 2, "both workers are still alive")
    check(not os.path.exists(os.path.join(tmp, "bad.exr")), "no image written")
    print("bad scene: failed after %.1f s" % seconds)


def test_plan(build, oracle, tmp):
    sys.path.insert(0, os.path.dirname(CLUSTER_CLI))
    import rtpbr_oracle_cluster as oc
    import random
    rng = random.Random(7)
    bad = []
    for _ in range(300):
        w, h, spp = rng.randint(1, 400), rng.randint(1, 300), rng.randint(1, 600)
        first = max(1, spp // 64)
        task_samples, workers = rng.choice([1, 1000, 50000, 10 ** 9]), rng.randint(1, 8)
        pieces = oc.plan(w, h, spp, first, task_samples, workers)
        cover = {}
        for (y0, y1), (a, b) in pieces:
            for y in range(y0, y1):
                cover.setdefault(y, []).append((a, b))
        ok = spp == first and not pieces or all(sorted(cover.get(y, [])) and
                                                 sorted(cover[y])[0][0] == first and sorted(cover[y])[-1][1] == spp and
                                                 all(p[1] == q[0] for p, q in zip(sorted(cover[y]), sorted(cover[y])[1:]))
                                                 for y in range(h))
        ok = ok and all(y1 - y0 >= 16 or h < 32 for (y0, y1), _ in pieces)
        if not ok:
            bad.append((w, h, spp, task_samples, workers))
    check(not bad, "plans cover rows x samples exactly once (failures: %s)" % bad[:3])
    pieces = oc.plan(128, 96, 64, 1, 120000, 2)
    check(len(pieces) == 12 and len({p[1] for p in pieces}) == 2, "128x96x63 at 120000 per task: 6 bands x 2 ranges")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("test", choices=["equal", "kill", "bad-scene", "plan"])
    ap.add_argument("--build", required=True)
    args = ap.parse_args()
    oracle = os.path.join(args.build, "oracle", "rtpbr-oracle")
    if not os.access(oracle, os.X_OK):
        print("test_cluster: no %s" % oracle, file=sys.stderr)
        return 1
    tmp = tempfile.mkdtemp(prefix="rtpbr-cluster-test-")
    try:
        {"equal": test_equal, "kill": test_kill, "bad-scene": test_bad_scene,
         "plan": test_plan}[args.test](args.build, oracle, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print("test_cluster %s: %d checks failed" % (args.test, len(failures)), file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
