#!/bin/sh
# The viewer's live HDR-FLIP equals `rtpbr-diff --hdr` on the same two images within 0.001:
# the oracle renders the showcase scene from its camera at the viewer's size, the viewer
# computes the FLIP of its last frame against it and writes that frame's radiance, and
# rtpbr-diff compares the two files.
#   usage: live_flip.sh RTPBR_ORACLE RTPBR_VIEWER RTPBR_DIFF XVFB_RUN SCENE OUTDIR
set -eu
oracle=$1 viewer=$2 diff=$3 xvfb=$4 scene=$5 out=$6
mkdir -p "$out"
"$oracle" "$scene" -o "$out/flip_reference.exr" --width 160 --height 120 --spp 16 --seed 1 --quiet
"$xvfb" -a -s "-screen 0 1024x768x24" "$viewer" "$scene" --reference "$out/flip_reference.exr" \
    --width 160 --height 120 --frames 2 --no-ui --radiance "$out/flip_view.exr" --validation > "$out/flip_viewer.log"
cat "$out/flip_viewer.log"
live=$(sed -n 's/^rtpbr-viewer: HDR-FLIP mean \([0-9.]*\) against.*/\1/p' "$out/flip_viewer.log")
"$diff" "$out/flip_reference.exr" "$out/flip_view.exr" --hdr --json > "$out/flip_diff.json"
cat "$out/flip_diff.json"
python3 - "$live" "$out/flip_diff.json" <<'PY'
import json, sys
live = float(sys.argv[1])
ref = json.load(open(sys.argv[2]))
mean = ref["mean"]
print("live %.6f, rtpbr-diff --hdr %.6f" % (live, mean))
assert mean > 0.01, "the two images should differ (engine against oracle)"
assert abs(live - mean) <= 0.001, "live FLIP %.6f differs from rtpbr-diff's %.6f" % (live, mean)
PY
