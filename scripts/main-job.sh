#!/usr/bin/env bash
# The main job: renders the bundled area-light scene (samples/scenes/quad_light.gltf) with the
# engine (LTC, Kulla-Conty) and with the oracle (path traced), compares them with HDR-FLIP and
# writes the report into report/ (index.html, summary.json, summary.md), plus a plot of the
# shader library's BRDFs into out/.
set -euo pipefail
builddir=${1:-build}
mkdir -p out
"$builddir/tools/brdfplot/rtpbr-brdfplot" -o out/brdf-spheres.png
echo "main job: wrote out/brdf-spheres.png"
# The engine (librtpbr, Vulkan; lavapipe when there is no GPU) on the default scene:
# linear radiance (EXR, what the oracle is compared with) and the tone-mapped PNG.
if [[ -x "$builddir/tools/render/rtpbr-render" ]]; then
  for ext in exr png; do
    "$builddir/tools/render/rtpbr-render" samples/scenes/quad_light.gltf -o "out/engine-quad_light.$ext" \
      --supersample 2
  done
fi
if [[ -x "$builddir/tools/render/rtpbr-render" && -x "$builddir/oracle/rtpbr-oracle" ]]; then
  python3 tools/validate/rtpbr_validate.py --build "$builddir" --out report --scenes quad_light
  echo "main job: engine against oracle on quad_light: report/index.html (summary in report/summary.md)"
else
  echo "main job: the engine or the oracle is not built (see meson's summary); only the BRDF plot was made" >&2
fi
