#!/usr/bin/env python3
"""rtpbr-sample-host's command line: --help lists every option and exits 0; the bundled room
renders with validation into a PNG and a PFM of the right size; bad input (a missing file, a
malformed mesh file, more lights than the host's light set holds, a bad option) gets a clear
message on stderr and exit status 1 (2 for the command line), never a crash.
usage: sample_host_cli.py RTPBR_SAMPLE_HOST ROOM_MESH OUT_DIR"""
import os
import struct
import subprocess
import sys

exe, room, out = sys.argv[1], sys.argv[2], os.path.join(sys.argv[3], "sample-host-cli")
os.makedirs(out, exist_ok=True)
failures = []


def run(*args):
    p = subprocess.run([exe, *args], capture_output=True, text=True, timeout=240)
    return p.returncode, p.stdout, p.stderr


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


rc, so, se = run("--help")
check(rc == 0, "--help exits 0")
for option in ("-o", "--hdr", "--exposure", "--camera", "--validation", "--help"):
    check(option in so, f"--help lists {option}")

png, pfm = os.path.join(out, "room.png"), os.path.join(out, "room.pfm")
for f in (png, pfm):
    if os.path.exists(f):
        os.remove(f)
rc, so, se = run(room, "-o", png, "--hdr", pfm, "--validation")
check(rc == 0 and "validation" not in se, f"the bundled room renders with validation clean (rc {rc}: {se.strip()})")
if rc == 0:
    with open(png, "rb") as f:
        head = f.read(24)
    check(head[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", head[16:24]) == (640, 480), "a 640 x 480 PNG")
    with open(pfm, "rb") as f:
        data = f.read()
    header = b"PF\n640 480\n-1.0\n"
    check(data.startswith(header) and len(data) == len(header) + 640 * 480 * 12, "a 640 x 480 RGB PFM")
rc, so, se = run(room, "-o", os.path.join(out, "room-reversed-z.png"), "--camera", "reversed-z", "--validation")
check(rc == 0 and "validation" not in se, f"the room renders with a reversed-Z camera, validation clean (rc {rc})")


def write(name, text):
    path = os.path.join(out, name)
    with open(path, "w") as f:
        f.write(text)
    return path


good = "camera 0 1 3  0 1 0  60\nmaterial m 0.5 0.5 0.5 0 0.5\nquad m -1 0 1  1 0 1  1 0 -1  -1 0 -1\n"
light = "light 1 1 1  -1 2 -1  1 2 -1  1 2 1  -1 2 1\n"
cases = [
    ("a missing file", [os.path.join(out, "no-such.mesh")], 1, "cannot open"),
    ("a malformed line", [write("bad.mesh", good + "quad m 1 2 3\n")], 1, "bad.mesh:4: quad takes"),
    ("an unknown material", [write("bad2.mesh", good + "tri x 0 0 0  1 0 0  0 0 1\n")], 1, "unknown material 'x'"),
    ("too many lights", [write("many.mesh", good + light * 65)], 1, "too many lights (at most 64)"),
    ("a light rtpbr refuses (not planar)",
     [write("warped.mesh", good + "light 1 1 1  -1 2 -1  1 2 -1  1 3 1  -1 2 1\n"), "-o", os.path.join(out, "x.png")],
     1, "rtpbr_light_set_update"),
    ("an unknown option", ["--frobnicate"], 2, "unexpected argument '--frobnicate'"),
    ("a bad exposure", ["--exposure", "bright"], 2, "--exposure"),
    ("a bad camera mode", ["--camera", "ortho"], 2, "--camera: 'ortho'"),
]
for what, args, want, message in cases:
    rc, so, se = run(*args)
    check(rc == want and message in se, f"{what}: exit {want} and '{message}' (got {rc}: {se.strip()[:200]})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
