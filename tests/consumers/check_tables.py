#!/usr/bin/env python3
"""The installed tables: every raw file share/rtpbr/luts/*.f32 (written from the C headers, the
layout of share/rtpbr/README.md) against the EXR images the generators wrote independently of
the headers, read by oiiotool: each EXR is one variant's slice of its raw file, pixel (x, y)
channel c at element ((y * width + x) * channels + c) of the slice. Values agree to 1e-5
relative (+ 1e-9 absolute: oiiotool prints 9 decimals).

    check_tables.py LUTDIR OIIOTOOL
"""
import os
import re
import struct
import subprocess
import sys

KC_VARIANTS = ["ggx_hc", "ggx_sep", "ggx_fast", "beckmann_hc", "beckmann_sep", "beckmann_fast"]


def read_exr(oiiotool, path):
    out = subprocess.run([oiiotool, "--dumpdata", path], check=True, capture_output=True, text=True).stdout
    m = re.match(r"\S+\s*:\s*(\d+) x\s*(\d+), (\d+) channel", out)
    w, h, c = (int(g) for g in m.groups())
    values = {}
    for pm in re.finditer(r"Pixel \((\d+), (\d+)\): ([^\n]*)", out):
        x, y = int(pm.group(1)), int(pm.group(2))
        values[(x, y)] = [float(v) for v in pm.group(3).split()]
    flat = []
    for y in range(h):
        for x in range(w):
            flat += values[(x, y)]
    assert len(flat) == w * h * c, path
    return flat


def main(lutdir, oiiotool):
    raws = {f[:-4]: f for f in os.listdir(lutdir) if f.endswith(".f32")}
    covered, failures, compared = set(), 0, 0
    for exr in sorted(f for f in os.listdir(lutdir) if f.endswith(".exr")):
        stem = exr[:-4]
        m = re.match(r"kc_(E|Eavg|EF|EFavg)_(\w+)$", stem)
        if m:
            raw, variant = "rtpbr_kc_" + m.group(1), KC_VARIANTS.index(m.group(2))
        else:
            raw, variant = "rtpbr_" + stem, 0
        if raw not in raws:
            print("check_tables: %s has no raw file %s.f32" % (exr, raw))
            failures += 1
            continue
        covered.add(raw)
        data = open(os.path.join(lutdir, raws[raw]), "rb").read()
        image = read_exr(oiiotool, os.path.join(lutdir, exr))
        n = len(image)
        if len(data) % (4 * n):
            print("check_tables: %s: %d bytes is not a whole number of %s images" % (raws[raw], len(data), exr))
            failures += 1
            continue
        raw_slice = struct.unpack("<%df" % n, data[4 * n * variant:4 * n * (variant + 1)])
        # oiiotool prints 9 decimals: an absolute floor of 1e-9 for the smallest values.
        bad = [(i, a, b) for i, (a, b) in enumerate(zip(image, raw_slice))
               if abs(a - b) > 1e-5 * max(abs(a), abs(b)) + 1e-9]
        compared += n
        if bad:
            i, a, b = bad[0]
            print("check_tables: %s differs from %s (variant %d) at %d of %d values, first at element %d: %.9g vs %.9g"
                  % (exr, raws[raw], variant, len(bad), n, i, a, b))
            failures += 1
    missing = sorted(set(raws) - covered - {"rtpbr_sheen_E"})  # the sheen albedo has no EXR
    if missing:
        print("check_tables: raw files without an EXR to check against: " + ", ".join(missing))
        failures += 1
    print("check_tables: %d values of %d raw files agree with the EXR images" % (compared, len(covered)))
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
