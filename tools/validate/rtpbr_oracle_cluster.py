#!/usr/bin/env python3
"""rtpbr-oracle-cluster: renders one oracle reference on a Dask distributed cluster and writes
the EXR that `rtpbr-oracle SCENE -o OUT.exr OPTIONS` writes on one machine, bit for bit.

    rtpbr_oracle_cluster.py SCENE.gltf -o OUT.exr (--scheduler tcp://HOST:PORT | --local-workers N
                            | --jobqueue slurm|pbs|sge|lsf [--jobs N] [--jobqueue-option KEY=VALUE ...])
                            [--oracle PATH] [--worker-oracle PATH] [--task-seconds S | --task-samples N]
                            [--task-threads T] [--shared-scene] [--stats-json FILE] [--quiet]
                            -- [rtpbr-oracle options: --width W --height H --spp N --seed S ...]

How the render is cut: a probe task renders sample 0..p (p = 1, or fewer than 1/64 of the samples)
of the whole image; its timing (the oracle's own samples/s, without its start-up) sizes the
other tasks: bands of full image rows x sample ranges of about --task-seconds each (default 30).
Each task runs `rtpbr-oracle --region 0:Y0:W:Y1 --sample-range A:B -o part.acc` on a worker and
returns the band's rows of the accumulator (fixed-point sums, see oracle/README.md). The client
puts the disjoint bands of one sample range into one accumulator file (a byte copy: adding a
band to zeros is exact), then `rtpbr-oracle --merge` sums the sample ranges into the EXR. The
oracle's 128-bit fixed-point sums are associative, so the image equals the single-process render
byte for byte (tests/cluster).

Workers need an rtpbr-oracle binary (--worker-oracle, default: the client's path, so a shared
build directory or the same install prefix on every node; the task refuses a binary whose
SHA-256 differs from the client's, which would not give the same image) and the scene: by
default each run ships the scene's bytes (.gltf/.glb and the buffers and images it refers to)
as one Dask task the render tasks depend on, written once per worker into its scratch
directory; --shared-scene passes the path instead (a file system every worker sees).

Faults: a worker that dies mid-task costs time only: the scheduler reruns its tasks elsewhere
(Dask's allowed-failures, 3 by default) and the image is the same. An oracle killed by a signal
on a live worker is resubmitted up to 3 times. An oracle that exits with an error (bad scene,
bad option) fails the run at once with the oracle's message; the other tasks are cancelled.
Exit status: 0 done, 1 the oracle refused the scene or a task failed, 2 usage or cluster errors.
"""
import argparse
import hashlib
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import urllib.parse
import uuid

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
VENV_PYTHON = os.path.join(ROOT, ".deps", "venv", "bin", "python3")

# The accumulator file (oracle/README.md): "RTPBRAC1", uint32 width, height, uint64 seed,
# settings hash, non-finite count, clamped count; uint32 samples[w*h]; int128 sum[3*w*h];
# double sumSquares[3*w*h]. Host byte order, little-endian.
ACC_MAGIC = b"RTPBRAC1"
ACC_HEADER = "<8sIIQQQQ"  # a format, not a struct.Struct: tasks are pickled by value
ACC_HEADER_SIZE = struct.calcsize(ACC_HEADER)
TRANSIENT_RESUBMITS = 3
WORKER_WAIT_SECONDS = float(os.environ.get("RTPBR_CLUSTER_WORKER_WAIT", "1800"))


class ClusterError(Exception):
    """A failure of the run: message for the user, exit status."""

    def __init__(self, message, status=1):
        super().__init__(message)
        self.status = status


def ensure_dask(script, argv):
    """Imports distributed, re-running the script under the project's venv (.deps/venv, made
    by scripts/setup.sh) when the current Python lacks it."""
    try:
        import distributed  # noqa: F401
        return
    except ImportError:
        pass
    if os.path.isfile(VENV_PYTHON) and os.path.realpath(sys.executable) != os.path.realpath(VENV_PYTHON):
        os.execv(VENV_PYTHON, [VENV_PYTHON, script] + list(argv))
    raise ClusterError("the Dask packages are not installed (run scripts/setup.sh: it makes %s)" % VENV_PYTHON, 2)


# ---- scene files --------------------------------------------------------------------------------

def _gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF" and len(data) >= 20:
        (chunk_len, chunk_type) = struct.unpack_from("<II", data, 12)
        if chunk_type != 0x4E4F534A:  # "JSON"
            return None
        data = data[20:20 + chunk_len]
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        return None


def scene_bundle(path):
    """The scene file and the files it refers to by relative URI, as {relative path: bytes}.
    What cannot be read or parsed is left to the oracle on the worker to report (its message is
    the one the user sees); URIs the loader refuses (absolute, '..') are not shipped."""
    main = os.path.basename(path)
    with open(path, "rb") as f:
        files = {main: f.read()}
    doc = _gltf_json(path)
    if isinstance(doc, dict):
        for entry in (doc.get("buffers") or []) + (doc.get("images") or []):
            uri = entry.get("uri") if isinstance(entry, dict) else None
            if not isinstance(uri, str) or not uri or uri.startswith("data:"):
                continue
            rel = urllib.parse.unquote(uri)
            norm = os.path.normpath(rel)
            if os.path.isabs(norm) or norm.startswith("..") or "://" in uri:
                continue
            src = os.path.join(os.path.dirname(path), norm)
            if os.path.isfile(src):
                with open(src, "rb") as f:
                    files[norm] = f.read()
    h = hashlib.sha256()
    for name in sorted(files):
        h.update(name.encode() + b"\0" + hashlib.sha256(files[name]).digest())
    return {"hash": h.hexdigest()[:24], "main": main, "files": files}


def _identity(x):
    return x


def upload_self(client):
    """Sends this module to the scheduler and the workers, present and future (Dask's upload-file
    plugins), so the tasks' functions import there; the name is the file's hash, so a second run
    of the same code replaces the plugin instead of adding one."""
    from distributed.diagnostics.plugin import SchedulerUploadFile, UploadFile
    path = os.path.abspath(__file__)
    with open(path, "rb") as f:
        name = "rtpbr-oracle-cluster-" + hashlib.sha256(f.read()).hexdigest()[:16]
    if client.run_on_scheduler(lambda dask_scheduler: name in dask_scheduler.plugins):
        return
    client.register_plugin(SchedulerUploadFile(path, load=True), name=name)
    client.register_plugin(UploadFile(path, load=True), name=name)


# ---- the task (runs on a worker) ----------------------------------------------------------------

def _set_parent_death_signal():
    # The oracle dies with the worker that started it (Linux prctl PR_SET_PDEATHSIG = 1):
    # a killed worker must not leave an orphan render burning the node's cores.
    try:
        import ctypes
        import signal
        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL), 0, 0, 0)
    except (OSError, AttributeError):
        pass


def render_task(scene, oracle, oracle_hash, args, band, sample_range, threads, key):
    """Runs one oracle piece: rows band = (Y0, Y1, image width) or None for the whole image,
    samples sample_range = (A, B). Returns the band's accumulator rows, or {"error": ...} when the
    oracle failed (permanent: exit status >= 1; transient: killed by a signal)."""
    import distributed
    t0 = time.time()
    try:
        worker = distributed.get_worker()
        worker.log_event("rtpbr-oracle-start", {"key": key, "worker": worker.address})
        address, scratch = worker.address, worker.local_directory
    except ValueError:  # not on a worker (direct call)
        address, scratch = "local", tempfile.gettempdir()
    if not (os.path.isfile(oracle) and os.access(oracle, os.X_OK)):
        return {"error": "worker %s: no rtpbr-oracle at %s (--worker-oracle)" % (address, oracle), "permanent": True}
    h = hashlib.sha256()
    with open(oracle, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    if h.hexdigest() != oracle_hash:
        return {"error": "worker %s: %s is not the client's rtpbr-oracle (SHA-256 differs); the image would not "
                         "be the same" % (address, oracle), "permanent": True}
    if isinstance(scene, dict):  # shipped bytes: written once per worker, atomically
        scene_dir = os.path.join(scratch, "rtpbr-scenes", scene["hash"])
        if not os.path.isdir(scene_dir):
            os.makedirs(os.path.dirname(scene_dir), exist_ok=True)
            tmp = tempfile.mkdtemp(dir=os.path.dirname(scene_dir))
            for name, data in scene["files"].items():
                os.makedirs(os.path.dirname(os.path.join(tmp, name)) or tmp, exist_ok=True)
                with open(os.path.join(tmp, name), "wb") as f:
                    f.write(data)
            try:
                os.rename(tmp, scene_dir)
            except OSError:  # another task of this worker was first
                shutil.rmtree(tmp, ignore_errors=True)
        scene_path = os.path.join(scene_dir, scene["main"])
    else:
        scene_path = scene
    with tempfile.TemporaryDirectory(dir=scratch) as tmp:
        out = os.path.join(tmp, "part.acc")
        cmd = [oracle, scene_path, "-o", out, "--sample-range", "%d:%d" % sample_range]
        if band is not None:
            cmd += ["--region", "0:%d:%d:%d" % (band[0], band[2], band[1])]
        if threads:
            cmd += ["--threads", str(threads)]
        cmd += list(args)
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           preexec_fn=_set_parent_death_signal)
        if p.returncode != 0:
            lines = [ln for ln in p.stderr.strip().splitlines() if ln.startswith("rtpbr-oracle:")]
            msg = "\n".join(lines[-5:]) or p.stderr.strip()[-2000:] or "no message"
            if p.returncode < 0:
                return {"error": "worker %s: rtpbr-oracle killed by signal %d" % (address, -p.returncode),
                        "permanent": False}
            if isinstance(scene, dict):  # name the files as the client knows them
                msg = msg.replace(scene_dir + os.sep, "\0")
            return {"error": msg, "permanent": True, "status": p.returncode}
        render_seconds = None
        for ln in p.stderr.splitlines():  # "rtpbr-oracle: WxH, N samples in S s (...)"
            if " samples in " in ln:
                try:
                    render_seconds = float(ln.split(" samples in ")[1].split("s")[0])
                except ValueError:
                    pass
        with open(out, "rb") as f:
            data = f.read()
    magic, w, hgt, seed, settings, nonfinite, clamped = struct.unpack_from(ACC_HEADER, data, 0)
    npix = w * hgt
    if magic != ACC_MAGIC or len(data) != ACC_HEADER_SIZE + npix * (4 + 48 + 24):
        return {"error": "worker %s: the oracle wrote an accumulator this client does not read" % address,
                "permanent": True}
    y0, y1 = (band[0], band[1]) if band is not None else (0, hgt)
    o_samples = ACC_HEADER_SIZE
    o_sum = o_samples + 4 * npix
    o_sq = o_sum + 48 * npix
    return {"width": w, "height": hgt, "seed": seed, "settings": settings, "nonfinite": nonfinite,
            "clamped": clamped, "rows": (y0, y1),
            "samples": data[o_samples + 4 * w * y0:o_samples + 4 * w * y1],
            "sum": data[o_sum + 48 * w * y0:o_sum + 48 * w * y1],
            "sumsq": data[o_sq + 24 * w * y0:o_sq + 24 * w * y1],
            "worker": address, "seconds": time.time() - t0, "render_seconds": render_seconds}


# ---- planning -----------------------------------------------------------------------------------

def split(lo, hi, parts):
    """[lo, hi) cut into `parts` contiguous ranges of nearly equal length."""
    n = hi - lo
    return [(lo + n * i // parts, lo + n * (i + 1) // parts) for i in range(parts)]


def plan(width, height, spp, first_sample, task_samples, workers):
    """Bands x sample ranges covering rows [0, height) x samples [first_sample, spp) once, each
    about task_samples pixel-samples. Bands first (a task returns only its rows), down to
    16-row bands (the oracle's tile), then sample ranges."""
    remaining = spp - first_sample
    if remaining <= 0:
        return []
    work = width * height * remaining
    count = max(1, -(-work // max(1, task_samples)), min(workers, height * remaining))
    bands = max(1, min(count, height // 16 or 1))
    ranges = max(1, min(remaining, -(-count // bands)))
    return [(b, r) for r in split(first_sample, spp, ranges) for b in split(0, height, bands)]


def option_value(args, name, default=None):
    for i, a in enumerate(args):
        if a == name and i + 1 < len(args):
            return args[i + 1]
    return default


# ---- connecting ---------------------------------------------------------------------------------

JOBQUEUE_KINDS = {"slurm": "SLURMCluster", "pbs": "PBSCluster", "sge": "SGECluster", "lsf": "LSFCluster"}


def _parse_value(text):
    for conv in (int, float):
        try:
            return conv(text)
        except ValueError:
            pass
    if text.startswith("[") or text.startswith("{"):
        return json.loads(text)
    return text


def connect(scheduler=None, local_workers=0, jobqueue=None, jobs=1, jobqueue_options=()):
    """A distributed.Client and the cluster object it owns (None for --scheduler)."""
    import distributed
    if scheduler:
        try:
            return distributed.Client(scheduler, timeout="30s"), None
        except (OSError, TimeoutError) as e:
            raise ClusterError("cannot reach the Dask scheduler %s: %s" % (scheduler, e), 2)
    if local_workers:
        cluster = distributed.LocalCluster(n_workers=local_workers, threads_per_worker=1, processes=True,
                                           host="127.0.0.1", dashboard_address=None)
        return distributed.Client(cluster), cluster
    if jobqueue:
        kind = JOBQUEUE_KINDS.get(jobqueue.lower())
        if not kind:
            raise ClusterError("--jobqueue: expected one of %s" % ", ".join(JOBQUEUE_KINDS), 2)
        import dask_jobqueue
        kwargs = {}
        for opt in jobqueue_options:
            if "=" not in opt:
                raise ClusterError("--jobqueue-option: expected KEY=VALUE, got %r" % opt, 2)
            k, v = opt.split("=", 1)
            kwargs[k.replace("-", "_")] = _parse_value(v)
        # One worker per job running one task at a time: the oracle's own threads use the job's cores.
        kwargs.setdefault("processes", 1)
        kwargs.setdefault("worker_extra_args", ["--nthreads", "1"])
        cluster = getattr(dask_jobqueue, kind)(**kwargs)
        cluster.scale(jobs=jobs)
        return distributed.Client(cluster), cluster
    raise ClusterError("no cluster: give --scheduler, --local-workers or --jobqueue", 2)


def cluster_description(scheduler=None, local_workers=0, jobqueue=None, jobs=1):
    if scheduler:
        return "Dask scheduler %s" % scheduler
    if local_workers:
        return "Dask LocalCluster (%d worker processes)" % local_workers
    return "dask-jobqueue %s (%d jobs)" % (jobqueue, jobs)


# ---- the render ---------------------------------------------------------------------------------

def _fmt_seconds(s):
    s = int(round(s))
    return "%dm%02ds" % (s // 60, s % 60) if s >= 60 else "%ds" % s


class _Chunk:
    """One sample range's accumulator, assembled from disjoint bands."""

    def __init__(self, first, total_bands):
        self.first = first
        self.left = total_bands
        self.parts = []


def render(client, scene_path, oracle, oracle_args, out_path, task_seconds=30.0, task_samples=None,
           task_threads=0, worker_oracle=None, shared_scene=False, progress=None, name=None):
    """Renders scene_path with `rtpbr-oracle scene -o out_path oracle_args` on the cluster
    behind client; returns the run's statistics (tasks, workers, retries, seconds, per-task
    overhead). Raises ClusterError with the oracle's message on a permanent failure."""
    import distributed
    upload_self(client)
    say = progress or (lambda msg: None)
    name = name or os.path.splitext(os.path.basename(scene_path))[0]
    oracle_args = list(oracle_args)
    for flag in ("-o", "--sample-range", "--region", "--threads", "--stderr-image", "--preview"):
        if flag in oracle_args:
            raise ClusterError("%s is set by rtpbr-oracle-cluster; leave it out of the oracle options" % flag, 2)
    oracle_args = [a for a in oracle_args if a != "--quiet"]
    spp = int(option_value(oracle_args, "--spp", "16"))
    h = hashlib.sha256()
    with open(oracle, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    oracle_hash = h.hexdigest()
    worker_oracle = worker_oracle or oracle
    run_id = uuid.uuid4().hex[:8]
    t_start = time.time()

    if shared_scene:
        scene = os.path.abspath(scene_path)
    else:
        try:
            bundle = scene_bundle(scene_path)
        except OSError as e:
            raise ClusterError("%s: %s" % (scene_path, e.strerror or e), 1)
        # A task, not client.scatter: the scheduler keeps its recipe, so when the worker
        # holding the bytes dies they are made again instead of being lost.
        scene = client.submit(_identity, bundle, key="rtpbr-scene-%s-%s" % (bundle["hash"], run_id))

    stats = {"tasks": 0, "workers": set(), "resubmits": 0, "overheads": [], "task_seconds": []}
    attempts = {}

    def submit(band, srange, idx):
        key = "rtpbr-oracle-%s-%s-%d" % (name, run_id, idx)
        attempts.setdefault(key, 0)
        attempts[key] += 1
        fut = client.submit(render_task, scene, worker_oracle, oracle_hash, oracle_args, band, srange,
                            task_threads, key, key=key + "-%d" % attempts[key], pure=False)
        return fut, (band, srange, idx, key)

    def wait_one(fut):
        try:
            return fut.result()
        except distributed.KilledWorker as e:
            raise ClusterError("%s: task %s killed the workers running it %s times (out of memory?): %s"
                               % (name, fut.key, "several", e), 1)
        except Exception as e:  # noqa: BLE001 (any task exception ends the run with its message)
            raise ClusterError("%s: task %s failed: %s: %s" % (name, fut.key, type(e).__name__, e), 1)

    def check(res, meta):
        if "error" in res:
            if res["permanent"]:
                # The oracle's own message, with the shipped scene's paths as the client's.
                msg = res["error"].replace("\0", os.path.join(os.path.dirname(scene_path), ""))
                raise ClusterError(msg if msg.startswith("rtpbr-oracle:") else "%s: %s" % (scene_path, msg), 1)
            return False
        stats["workers"].add(res["worker"])
        stats["task_seconds"].append(res["seconds"])
        if res["render_seconds"] is not None:
            stats["overheads"].append(res["seconds"] - res["render_seconds"])
        return True

    tmpdir = tempfile.mkdtemp(prefix="rtpbr-oracle-cluster-")
    futures = []
    try:
        # The probe: samples [0, p) of the whole image. It is part of the image, and its speed
        # sizes the other tasks.
        probe_samples = max(1, spp // 64)
        workers_now = len(client.nthreads())
        if not workers_now:  # batch jobs may sit in the queue a while
            say("%s: waiting up to %.0f s for a worker to join" % (name, WORKER_WAIT_SECONDS))
            try:
                client.wait_for_workers(1, timeout=WORKER_WAIT_SECONDS)
            except TimeoutError:
                raise ClusterError("no Dask worker joined within %.0f s" % WORKER_WAIT_SECONDS, 2)
            workers_now = len(client.nthreads())
        say("%s: probe task (samples 0:%d of %d) on %d workers" % (name, probe_samples, spp, workers_now))
        while True:
            fut, meta = submit(None, (0, probe_samples), 0)
            futures = [fut]
            probe = wait_one(fut)
            if check(probe, meta):
                break
            stats["resubmits"] += 1
            if stats["resubmits"] > TRANSIENT_RESUBMITS:
                raise ClusterError("%s: %s (%d times)" % (scene_path, probe["error"], stats["resubmits"]), 1)
        stats["tasks"] += 1
        width, height = probe["width"], probe["height"]
        probe_path = os.path.join(tmpdir, "range-0.acc")
        with open(probe_path, "wb") as f:
            f.write(struct.pack(ACC_HEADER, ACC_MAGIC, width, height, probe["seed"], probe["settings"], probe["nonfinite"],
                                    probe["clamped"]))
            f.write(probe["samples"])
            f.write(probe["sum"])
            f.write(probe["sumsq"])
        if task_samples is None:
            rs = probe["render_seconds"] or probe["seconds"]
            rate = width * height * probe_samples / max(rs, 1e-3)
            task_samples = int(rate * task_seconds)
        workers_now = max(1, len(client.nthreads()))
        pieces = plan(width, height, spp, probe_samples, task_samples, workers_now)
        total = len(pieces) + 1
        work_total = width * height * (spp - probe_samples)
        chunks = {}
        for band, srange in pieces:
            chunks.setdefault(srange, _Chunk(srange[0], 0)).left += 1
        pending = {}
        for i, (band, srange) in enumerate(pieces):
            fut, meta = submit((band[0], band[1], width), srange, i + 1)
            pending[fut] = meta
        futures = list(pending)
        say("%s: %d tasks (%d bands x %d sample ranges after the probe, ~%d pixel-samples each) on %d workers"
            % (name, total, len(pieces) // max(1, len(chunks)) if chunks else 0, len(chunks),
               task_samples, workers_now))
        acc_files = [probe_path]
        work_done = 0
        t_plan = time.time()
        last_report = 0.0
        ac = distributed.as_completed(list(pending))
        for fut in ac:
            meta = pending.pop(fut)
            res = wait_one(fut)
            band, srange, idx, key = meta
            if not check(res, meta):
                stats["resubmits"] += 1
                if attempts[key] > TRANSIENT_RESUBMITS:
                    raise ClusterError("%s: %s (%d times)" % (scene_path, res["error"], attempts[key]), 1)
                say("%s: %s; resubmitting" % (name, res["error"]))
                nfut, nmeta = submit(band, srange, idx)
                pending[nfut] = nmeta
                futures.append(nfut)
                ac.add(nfut)
                continue
            if (res["width"], res["height"], res["seed"], res["settings"]) != (width, height, probe["seed"],
                                                                                 probe["settings"]):
                raise ClusterError("%s: task %s rendered different settings than the probe" % (name, key), 1)
            stats["tasks"] += 1
            chunk = chunks[srange]
            chunk.parts.append(res)
            chunk.left -= 1
            work_done += width * (band[1] - band[0]) * (srange[1] - srange[0])
            if chunk.left == 0:
                path = os.path.join(tmpdir, "range-%d.acc" % srange[0])
                _write_chunk(path, chunk.parts, width, height, probe)
                chunk.parts = []
                acc_files.append(path)
            now = time.time()
            if now - last_report > 2.0 or not pending:
                last_report = now
                left = (now - t_plan) / max(work_done, 1) * (work_total - work_done)
                say("%s: %d/%d tasks done, %d workers, %s left" % (name, stats["tasks"], total,
                                                                   len(client.nthreads()),
                                                                   _fmt_seconds(left)))
        cmd = [oracle, "--merge"] + acc_files + ["-o", out_path]
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            raise ClusterError("%s: rtpbr-oracle --merge failed: %s" % (name, p.stderr.strip()[-2000:]), 1)
    finally:
        for f in futures:
            if not f.done():
                f.cancel()
        shutil.rmtree(tmpdir, ignore_errors=True)

    starts = {}
    try:
        for _, ev in client.get_events("rtpbr-oracle-start"):
            if isinstance(ev, dict) and ev.get("key") in attempts:
                starts[ev["key"]] = starts.get(ev["key"], 0) + 1
    except Exception:  # noqa: BLE001 (the event log is a nicety; the image is done)
        pass
    # A rerun is a task started more than once: its worker died (the scheduler moved it) or its
    # oracle was killed by a signal (resubmitted here).
    reruns = sum(max(0, n - 1) for n in starts.values())
    overheads = sorted(stats["overheads"])
    return {"tasks": stats["tasks"], "workers": len(stats["workers"]), "retries": max(reruns, stats["resubmits"]),
            "seconds": round(time.time() - t_start, 2), "width": width, "height": height, "spp": spp,
            "task_samples": task_samples,
            "task_seconds_median": round(sorted(stats["task_seconds"])[len(stats["task_seconds"]) // 2], 3),
            "overhead_seconds_median": round(overheads[len(overheads) // 2], 3) if overheads else None}


def _write_chunk(path, parts, width, height, probe):
    parts = sorted(parts, key=lambda r: r["rows"][0])
    rows = [r["rows"] for r in parts]
    if rows[0][0] != 0 or rows[-1][1] != height or any(a[1] != b[0] for a, b in zip(rows, rows[1:])):
        raise ClusterError("internal error: bands %s do not tile the image" % rows, 2)
    with open(path, "wb") as f:
        f.write(struct.pack(ACC_HEADER, ACC_MAGIC, width, height, probe["seed"], probe["settings"],
                                sum(r["nonfinite"] for r in parts), sum(r["clamped"] for r in parts)))
        for field in ("samples", "sum", "sumsq"):
            for r in parts:
                f.write(r[field])


# ---- command line -------------------------------------------------------------------------------

def add_cluster_arguments(ap):
    g = ap.add_argument_group("cluster (Dask distributed)")
    g.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://HOST:8786")
    g.add_argument("--local-workers", type=int, default=0,
                   help="start a Dask LocalCluster with N worker processes on 127.0.0.1")
    g.add_argument("--jobqueue", choices=sorted(JOBQUEUE_KINDS), help="start workers as batch jobs (dask-jobqueue)")
    g.add_argument("--jobs", type=int, default=1, help="--jobqueue: number of jobs (one worker each)")
    g.add_argument("--jobqueue-option", action="append", default=[], metavar="KEY=VALUE",
                   help="--jobqueue: keyword of the dask-jobqueue cluster (cores=32, memory=64GB, queue=..., "
                        "walltime=..., account=...); the rest comes from ~/.config/dask/jobqueue.yaml")
    g.add_argument("--task-seconds", type=float, default=30.0, help="target seconds per task (30)")
    g.add_argument("--task-samples", type=int, help="pixel-samples per task (instead of --task-seconds)")
    g.add_argument("--task-threads", type=int, default=0, help="rtpbr-oracle --threads on the workers (all cores)")
    g.add_argument("--worker-oracle", help="rtpbr-oracle path on the workers (the client's)")
    g.add_argument("--shared-scene", action="store_true",
                   help="workers read the scene from its path (shared file system) instead of receiving its bytes")
    return g


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(prog="rtpbr-oracle-cluster", description=__doc__.split("\n\n")[0],
                                 usage="%(prog)s SCENE.gltf -o OUT.exr CLUSTER [options] -- [rtpbr-oracle options]")
    ap.add_argument("scene")
    ap.add_argument("-o", dest="out", required=True)
    ap.add_argument("--oracle", help="rtpbr-oracle on this machine (build/oracle/rtpbr-oracle)")
    ap.add_argument("--stats-json", help="write the run's statistics here")
    ap.add_argument("--quiet", action="store_true")
    add_cluster_arguments(ap)
    own, oracle_args = (argv[:argv.index("--")], argv[argv.index("--") + 1:]) if "--" in argv else (argv, [])
    args = ap.parse_args(own)

    def say(msg):
        if not args.quiet:
            print("rtpbr-oracle-cluster: " + msg, file=sys.stderr, flush=True)

    oracle = args.oracle or os.path.join(ROOT, "build", "oracle", "rtpbr-oracle")
    if not os.access(oracle, os.X_OK):
        print("rtpbr-oracle-cluster: no rtpbr-oracle at %s (--oracle)" % oracle, file=sys.stderr)
        return 2
    client = cluster = None
    try:
        ensure_dask(os.path.abspath(__file__), argv)
        client, cluster = connect(args.scheduler, args.local_workers, args.jobqueue, args.jobs,
                                  args.jobqueue_option)
        stats = render(client, args.scene, oracle, oracle_args, args.out, args.task_seconds, args.task_samples,
                       args.task_threads, args.worker_oracle, args.shared_scene, say)
        stats["cluster"] = cluster_description(args.scheduler, args.local_workers, args.jobqueue, args.jobs)
        say("%s: %d tasks on %d workers, %d retries, %.1fs; wrote %s"
            % (args.scene, stats["tasks"], stats["workers"], stats["retries"], stats["seconds"], args.out))
        if args.stats_json:
            with open(args.stats_json, "w") as f:
                json.dump(stats, f, indent=1)
        return 0
    except ClusterError as e:
        print("rtpbr-oracle-cluster: %s" % e, file=sys.stderr)
        return e.status
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    # Run as the module, not as __main__: the tasks' functions then travel by module name,
    # the same way whether rtpbr-validate or this command line submits them.
    sys.path.insert(0, HERE)
    import rtpbr_oracle_cluster
    sys.exit(rtpbr_oracle_cluster.main())
