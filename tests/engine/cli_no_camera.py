#!/usr/bin/env python3
"""rtpbr-render on a scene without a camera (issue 31): it renders from its default camera and
says so on stderr (a newcomer's own glTF often has none); a scene with a camera gets no such
warning.

usage: cli_no_camera.py RTPBR_RENDER SCENE_DIR OUT_DIR
"""
import json
import os
import shutil
import subprocess
import sys

WARNING = "has no camera"


def render(exe, scene, out):
    p = subprocess.run([exe, scene, "-o", out, "--width", "32", "--height", "24"], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True)
    return p.returncode, p.stderr


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    exe, scene_dir, out_dir = argv[1:]
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(scene_dir, "quad_light.gltf")) as f:
        doc = json.load(f)
    doc.pop("cameras", None)
    for node in doc.get("nodes", []):
        node.pop("camera", None)
    scene = os.path.join(out_dir, "no_camera.gltf")
    with open(scene, "w") as f:
        json.dump(doc, f)
    for buffer in doc.get("buffers", []):
        uri = buffer.get("uri", "")
        if uri and not uri.startswith("data:"):
            shutil.copy(os.path.join(scene_dir, uri), os.path.join(out_dir, uri))
    failures = 0
    rc, err = render(exe, scene, os.path.join(out_dir, "no_camera.png"))
    if rc != 0 or WARNING not in err:
        print("FAIL no camera: exit %d, stderr: %s" % (rc, err.strip()))
        failures += 1
    else:
        print("ok   no camera: rendered, warned")
    rc, err = render(exe, os.path.join(scene_dir, "quad_light.gltf"), os.path.join(out_dir, "camera.png"))
    if rc != 0 or WARNING in err:
        print("FAIL with a camera: exit %d, stderr: %s" % (rc, err.strip()))
        failures += 1
    else:
        print("ok   with a camera: no warning")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
