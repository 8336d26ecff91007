#!/usr/bin/env python3
"""Regenerates the bundled scenes into a temporary folder and compares them byte for byte
with the committed ones: the committed scenes are what the description says."""
import filecmp
import subprocess
import sys
import tempfile
import os

make_scenes, committed, names = sys.argv[1], sys.argv[2], sys.argv[3:]
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, make_scenes, "--out", tmp], check=True, stderr=subprocess.DEVNULL)
    bad = []
    for n in names:
        for ext in (".gltf", ".bin"):
            a, b = os.path.join(tmp, n + ext), os.path.join(committed, n + ext)
            if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                bad.append(n + ext)
    if bad:
        print("stale or missing bundled scenes (run tools/make-scenes/make_scenes.py):", " ".join(bad))
        sys.exit(1)
    print("%d scenes match their description" % len(names))
