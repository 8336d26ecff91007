#!/bin/sh
# The cost of the viewer's Dear ImGui panels (issue 21: at most 5 % of the frame time at
# 960 x 720 on lavapipe). Runs rtpbr-viewer on the showcase scene REPEATS times with the
# panels and REPEATS times with --no-ui, interleaved, FRAMES frames each, and prints each run's
# mean frame time (frames after the first) and the panels' own cost measured inside the run:
# CPU time of building them and GPU time of their render pass (two timestamps around it).
#   usage: bench/viewer_overlay.sh BUILD [REPEATS [FRAMES]]
set -eu
usage="usage: $0 BUILD [REPEATS [FRAMES]]
The frame time of rtpbr-viewer (BUILD/samples/viewer) on the showcase scene with its panels
and with --no-ui, REPEATS runs each (default 3) of FRAMES frames (default 4), under xvfb-run.
  -h, --help  this text"
case ${1:-} in
-h | --help) echo "$usage"; exit 0 ;;
'' | -*) echo "$usage" >&2; exit 2 ;;
esac
build=$1 repeats=${2:-3} frames=${3:-4}
scene=$(dirname "$0")/../samples/scenes/showcase.gltf
export VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
run() {
    xvfb-run -a -s "-screen 0 1024x768x24" "$build/samples/viewer/rtpbr-viewer" "$scene" \
        --width 960 --height 720 --frames "$frames" "$@" |
        sed -n -e 's/^rtpbr-viewer: \([0-9.]*\) ms per frame.*/frame_ms \1/p' \
               -e 's/^rtpbr-viewer: panels \([0-9.]*\) ms CPU + \([0-9.]*\) ms GPU.*/panels_ms \1 \2/p'
}
i=0
while [ "$i" -lt "$repeats" ]; do
    echo "run $i panels: $(run | tr '\n' ' ')"
    echo "run $i no-ui:  $(run --no-ui | tr '\n' ' ')"
    i=$((i + 1))
done
