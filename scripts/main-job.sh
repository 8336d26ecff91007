#!/usr/bin/env bash
# The main job: what rtpbr renders today. Writes into out/.
set -euo pipefail
builddir=${1:-build}
mkdir -p out
"$builddir/tools/brdfplot/rtpbr-brdfplot" -o out/brdf-spheres.png
echo "main job: wrote out/brdf-spheres.png"
