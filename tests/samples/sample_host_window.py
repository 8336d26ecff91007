#!/usr/bin/env python3
"""rtpbr-sample-host --window (issue 33) under Xvfb: the frame shown in the window is the headless
frame, pixel for pixel (the headless frame is held against rtpbr_render by test_sample_host), with
the same --keys edits, with both camera modes; the keys do what they say (a light made brighter
brightens the image); the animation runs clean; validation with synchronization validation is
clean in every window run; bad window options exit 2 with a message.
usage: sample_host_window.py RTPBR_SAMPLE_HOST XVFB_RUN OUT_DIR"""
import os
import struct
import subprocess
import sys
import zlib

exe, xvfb, out = sys.argv[1], sys.argv[2], os.path.join(sys.argv[3], "sample-host-window")
os.makedirs(out, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(*args, window=False):
    cmd = ([xvfb, "-a", "-s", "-screen 0 1024x768x24"] if window else []) + [exe, *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    return p.returncode, p.stdout, p.stderr


def read_png(path):
    """(width, height, RGBA rows) of an 8-bit RGBA PNG (what stb_image_write writes): zlib and the
    five PNG row filters (PNG spec, section 9)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour == 6, f"{path}: not 8-bit RGBA"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), 4 * w, [], bytearray(4 * w)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - 4] if x >= 4 else 0
            b, c = prev[x], prev[x - 4] if x >= 4 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, rows


def differing(a, b):
    """Pixels that differ between two decoded images (None: different sizes)."""
    if a[:2] != b[:2]:
        return None
    return sum(1 for ra, rb in zip(a[2], b[2]) for x in range(0, len(ra), 4) if ra[x:x + 3] != rb[x:x + 3])


def mean_rgb(img):
    w, h, rows = img
    return sum(sum(r[x] for x in range(len(r)) if x % 4 != 3) for r in rows) / (3.0 * w * h)


keys = "t=====Crrrpu"  # the second light: 1.25^5 brighter, warm, moved +X 0.3, +Y 0.1, -Z 0.1
cases = {}
for name, args in (("plain", []), ("keys", ["--keys", keys]),
                   ("reversed-z", ["--keys", keys, "--camera", "reversed-z"])):
    head, win = os.path.join(out, f"{name}-headless.png"), os.path.join(out, f"{name}-window.png")
    for f in (head, win):
        if os.path.exists(f):
            os.remove(f)
    rc, so, se = run(*args, "-o", head, "--validation")
    check(rc == 0 and "validation" not in se, f"{name}: headless frame, validation clean (rc {rc}: {se.strip()[:300]})")
    rc, so, se = run(*args, "--window", "--frames", "3", "--screenshot", win, "--validation", window=True)
    check(rc == 0 and "validation" not in se and "in a window" in so,
          f"{name}: 3 frames in a window, validation with synchronization validation clean (rc {rc}: {se.strip()[:300]})")
    if os.path.exists(head) and os.path.exists(win):
        a, b = read_png(head), read_png(win)
        d = differing(a, b)
        check(d == 0, f"{name}: the window shows the headless frame pixel for pixel ({a[0]}x{a[1]}; {d} pixels differ)")
        cases[name] = a

if "plain" in cases and "keys" in cases:
    d = differing(cases["plain"], cases["keys"])
    m0, m1 = mean_rgb(cases["plain"]), mean_rgb(cases["keys"])
    check(d is not None and d > 10000, f"the keys change the frame ({d} pixels)")
    check(m1 > 1.2 * m0, f"a light 3x brighter brightens the room (mean {m0:.1f} -> {m1:.1f} of 255)")

anim = os.path.join(out, "animated-window.png")
rc, so, se = run("--keys", "A", "--window", "--frames", "4", "--screenshot", anim, "--validation", window=True)
check(rc == 0 and "validation" not in se, f"the animation (A) runs clean in a window (rc {rc}: {se.strip()[:300]})")
if rc == 0 and "plain" in cases:
    d = differing(cases["plain"], read_png(anim))
    check(d is not None and d > 1000, f"the animated lights moved ({d} pixels differ after 4 frames)")

for what, args, message in [
        ("--frames without --window", ["--frames", "3"], "are for --window"),
        ("--screenshot without --frames", ["--window", "--screenshot", os.path.join(out, "x.png")], "needs --frames"),
        ("a bad --frames", ["--window", "--frames", "0"], "--frames: '0'"),
        ("a character that is no key", ["--keys", "tx"], "no key for 'x'")]:
    rc, so, se = run(*args)
    check(rc == 2 and message in se, f"{what}: exit 2 and '{message}' (got {rc}: {se.strip()[:200]})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
