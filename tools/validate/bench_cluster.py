#!/usr/bin/env python3
"""Measures rtpbr-oracle-cluster against one rtpbr-oracle process on this machine: wall time of
one process (all cores) and of a Dask LocalCluster of N single-threaded workers on 127.0.0.1,
interleaved, medians of --repeats; the CPU seconds each used (all processes: client, scheduler,
workers, oracles, merge), which a loaded machine changes far less than wall time; the per-task
overhead (task wall time minus the oracle's own render time: process start, scene load, BVH and
albedo tables, accumulator write/read); and the whole pipeline's cost per task, wall and CPU,
from the same render cut into few and into many tasks.

    bench_cluster.py [--build BUILD] [--scene room] [--workers 2] [--repeats 3]
                     [-- rtpbr-oracle options (default: --width 320 --height 240 --spp 256 --direct-only)]

Every cluster image is checked byte for byte against the one-process image. A shared machine
makes single timings noisy: compare medians, and read the load average printed with them.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import rtpbr_oracle_cluster as oc  # noqa: E402


def main():
    argv = sys.argv[1:]
    own, oracle_args = (argv[:argv.index("--")], argv[argv.index("--") + 1:]) if "--" in argv else (argv, [])
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scene", default="room")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(own)
    oc.ensure_dask(os.path.abspath(__file__), argv)
    import distributed
    import psutil
    oracle_args = oracle_args or ["--width", "320", "--height", "240", "--spp", "256", "--seed", "1", "--direct-only"]
    oracle = os.path.join(args.build, "oracle", "rtpbr-oracle")
    scene = os.path.join(ROOT, "samples", "scenes", args.scene + ".gltf")
    tmp = tempfile.mkdtemp(prefix="rtpbr-bench-cluster-")
    ref = os.path.join(tmp, "one.exr")
    w, h = int(oc.option_value(oracle_args, "--width")), int(oc.option_value(oracle_args, "--height"))
    spp = int(oc.option_value(oracle_args, "--spp"))
    work = w * h * (spp - max(1, spp // 64))
    one, one_cpu, clus, clus_cpu, few, many, overheads = [], [], [], [], [], [], []

    def cpu_seconds(client):
        # This process (client and the in-process scheduler) and its waited children (merges,
        # the one-process oracle), plus each worker process and its waited children (oracles).
        total = 0.0
        for p in [psutil.Process()] + [psutil.Process(pid) for pid in client.run(os.getpid).values()]:
            t = p.cpu_times()
            total += t.user + t.system + t.children_user + t.children_system
        return total

    with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        for rep in range(args.repeats):
            c0, t0 = cpu_seconds(client), time.time()
            subprocess.run([oracle, scene, "-o", ref, "--quiet"] + oracle_args, check=True)
            one.append(time.time() - t0)
            one_cpu.append(cpu_seconds(client) - c0)
            for label, tasks, sink in (("few", 4 * args.workers, few), ("many", 16 * args.workers, many)):
                out = os.path.join(tmp, "cluster.exr")
                c0 = cpu_seconds(client)
                st = oc.render(client, scene, oracle, oracle_args, out, task_samples=-(-work // tasks), task_threads=1)
                sink.append((st["seconds"], st["tasks"], cpu_seconds(client) - c0))
                overheads.append(st["overhead_seconds_median"])
                with open(ref, "rb") as a, open(out, "rb") as b:
                    if a.read() != b.read():
                        print("cluster image differs from the one-process image", file=sys.stderr)
                        return 1
            clus.append(few[-1][0])
            clus_cpu.append(few[-1][2])
            print("repeat %d: one process %.1f s (%.1f CPU s), cluster %d tasks %.1f s (%.1f CPU s), %d tasks %.1f s "
                  "(%.1f CPU s) (load %.2f)" % (rep + 1, one[-1], one_cpu[-1], few[-1][1], few[-1][0], few[-1][2],
                                                many[-1][1], many[-1][0], many[-1][2], os.getloadavg()[0]), flush=True)
    med = statistics.median
    per_task = [(m[0] - f[0]) / (m[1] - f[1]) for f, m in zip(few, many)]
    per_task_cpu = [(m[2] - f[2]) / (m[1] - f[1]) for f, m in zip(few, many)]
    result = {"scene": args.scene, "oracle_args": oracle_args, "workers": args.workers, "repeats": args.repeats,
              "one_process_s": round(med(one), 2), "cluster_s": round(med(clus), 2),
              "speedup": round(med(one) / med(clus), 3), "one_process_cpu_s": round(med(one_cpu), 2),
              "cluster_cpu_s": round(med(clus_cpu), 2), "cpu_ratio": round(med(clus_cpu) / med(one_cpu), 3),
              "pipeline_cpu_s_per_extra_task": round(med(per_task_cpu), 3), "tasks_few": few[0][1], "tasks_many": many[0][1],
              "pipeline_s_per_extra_task": round(med(per_task), 3),
              "task_overhead_s_median": round(med(overheads), 3), "cpu_count": os.cpu_count()}
    print(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
