#!/usr/bin/env bash
# Renders every bundled scene (samples/scenes) with every option set of rtpbr-render into DIR,
# as EXR, for refactors that must change nothing (issue 29): render before and after, then
#   bench/nothing_moves.sh compare BEFORE_DIR AFTER_DIR
# prints the largest relative difference per image (|a - b| / max(|a|, |b|, 1e-3)) and exits 1
# when one exceeds the tolerance (default 1e-6; --tol X).
#   bench/nothing_moves.sh render BUILD_DIR OUT_DIR [WIDTHxHEIGHT]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
case "${1:-}" in
render)
  build=$2 out=$3 size=${4:-192x144}
  w=${size%x*} h=${size#*x}
  mkdir -p "$out"
  opts=("default:" "beckmann:--ndf beckmann" "nomultiscatter:--no-multiscatter"
        "shadows:--shadows" "mc:--mc-samples 2" "supersample:--supersample 2")
  for scene in "$here"/samples/scenes/*.gltf; do
    name=$(basename "$scene" .gltf)
    for o in "${opts[@]}"; do
      tag=${o%%:*} flags=${o#*:}
      # shellcheck disable=SC2086
      "$build/tools/render/rtpbr-render" "$scene" -o "$out/$name-$tag.exr" --width "$w" --height "$h" \
        $flags > "$out/$name-$tag.log" 2>&1 || { echo "render failed: $name $tag (see $out/$name-$tag.log)" >&2; exit 2; }
    done
  done
  echo "rendered $(ls "$out"/*.exr | wc -l) images into $out"
  ;;
compare)
  a=$2 b=$3 tol=1e-6
  [[ "${4:-}" == --tol ]] && tol=$5
  exec /usr/bin/python3 - "$a" "$b" "$tol" <<'PY'
import os, re, subprocess, sys, tempfile
import numpy as np
a, b, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
def load(path):
    # through FITS (OIIO's float writer that numpy reads without a library): 2880-byte
    # header blocks, then big-endian float32 samples
    with tempfile.TemporaryDirectory() as d:
        fits = os.path.join(d, "x.fits")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "float", "-o", fits], check=True)
        raw = open(fits, "rb").read()
    cards = [raw[i:i + 80].decode("latin-1") for i in range(0, 2880 * 8, 80)]
    end = next(i for i, c in enumerate(cards) if c.startswith("END"))
    start = ((end * 80 + 80 + 2879) // 2880) * 2880
    dims = [int(c.split("=")[1].split("/")[0]) for c in cards[:end] if re.match(r"NAXIS\d", c)]
    return np.frombuffer(raw, dtype=">f4", count=int(np.prod(dims)), offset=start).astype(np.float64)
worst, bad = 0.0, 0
names = sorted(n for n in os.listdir(a) if n.endswith(".exr"))
for n in names:
    pb = os.path.join(b, n)
    if not os.path.exists(pb):
        print(f"{n}: missing in {b}"); bad += 1; continue
    x, y = load(os.path.join(a, n)), load(pb)
    if x.shape != y.shape:
        print(f"{n}: size differs"); bad += 1; continue
    rel = np.abs(x - y) / np.maximum(np.maximum(np.abs(x), np.abs(y)), 1e-3)
    rel[~np.isfinite(rel)] = np.inf
    m = float(rel.max()); worst = max(worst, m)
    frac = float((rel > tol).mean())
    flag = "" if m <= tol else "  <-- exceeds"
    print(f"{n:40s} max rel {m:.3g}  pixels over {tol:g}: {100*frac:.3f} %{flag}")
    bad += m > tol
print(f"{len(names)} images, largest relative difference {worst:.3g}, {bad} over {tol:g}")
sys.exit(1 if bad else 0)
PY
  ;;
*) echo "usage: $0 render BUILD_DIR OUT_DIR [WxH] | compare BEFORE AFTER [--tol X]" >&2; exit 2 ;;
esac
