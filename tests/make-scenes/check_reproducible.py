#!/usr/bin/env python3
"""Regenerates the bundled scenes into a temporary folder and compares them byte for byte
with the committed ones (each scene's .gltf, .bin and the pictures it references): the
committed scenes are what the description says."""
import filecmp
import json
import subprocess
import sys
import tempfile
import os

make_scenes, committed, names = sys.argv[1], sys.argv[2], sys.argv[3:]
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, make_scenes, "--out", tmp], check=True, stderr=subprocess.DEVNULL)
    bad = []
    for n in names:
        with open(os.path.join(tmp, n + ".gltf")) as f:
            images = [i["uri"] for i in json.load(f).get("images", [])]
        for name in [n + ".gltf", n + ".bin"] + images:
            a, b = os.path.join(tmp, name), os.path.join(committed, name)
            if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                bad.append(name)
    if bad:
        print("stale or missing bundled scenes (run tools/make-scenes/make_scenes.py):", " ".join(bad))
        sys.exit(1)
    print("%d scenes match their description" % len(names))
