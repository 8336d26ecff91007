#!/usr/bin/env bash
# The main job: what rtpbr renders today. Writes into out/.
set -euo pipefail
builddir=${1:-build}
mkdir -p out
"$builddir/tools/brdfplot/rtpbr-brdfplot" -o out/brdf-spheres.png
echo "main job: wrote out/brdf-spheres.png"
# The engine (librtpbr, Vulkan; lavapipe when there is no GPU) on the default scene:
# linear radiance (EXR, what the oracle is compared with) and the tone-mapped PNG.
if [[ -x "$builddir/samples/headless/rtpbr-render" ]]; then
  for ext in exr png; do
    "$builddir/samples/headless/rtpbr-render" samples/scenes/quad_light.gltf -o "out/engine-quad_light.$ext"
  done
fi
