#!/bin/bash
# error_budget.sh: splits a scene's engine-against-oracle HDR-FLIP into the LTC's part and the
# Kulla-Conty multiple-scattering part (issue 19, round 3; results in shaderlib/luts/ltc.md).
#
#   tools/validate/error_budget.sh [BUILD] [SCENE] [OUTDIR]
#     BUILD   build directory (default build), SCENE a bundled scene name (default quad_light),
#     OUTDIR  where the images and FLIP maps go (default BUILD/error-budget/SCENE).
#   Environment: WIDTH, HEIGHT, SPP (oracle, defaults 320, 240, 512: the full validation's
#   settings), MC (engine Monte Carlo samples per pixel and light, default 2048).
#
# Renders, with the validation's options (engine --supersample 2; oracle --direct-only
# --no-shadows, seed 1):
#   O   oracle, multiple-scattering walk          Oss oracle --single-scatter
#   E   engine, LTC + KC_PolygonLobe              Ess engine --no-multiscatter
#   M   engine --mc-samples: the true BRDF with KC_Lobe per sample direction
#   Mss engine --mc-samples --no-multiscatter
# and compares with O (HDR-FLIP mean / p95, heat maps beside them):
#   E                    the engine as validated
#   Ess + (O - Oss)      only the LTC's single-scattering error (multiple scattering exact)
#   Mss + (E - Ess)      only the engine's Kulla-Conty polygon lobe's error (single scattering exact)
#   M                    the Kulla-Conty lobe evaluated per direction (no polygon approximation)
#   Mss + (O - Oss)      neither (the noise floor of these composites)
#   Mss against Oss      the engine's single scattering without LTC (should be noise only)
# Composites are built with oiiotool (negative values clamped to 0). Slow: the oracle twice
# and the Monte Carlo pass twice (about 4 minutes on the 2 shared cores of 2026-12-01 at the defaults).
set -euo pipefail
case ${1:-} in
-h | --help) sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; echo "  -h, --help  this text"; exit 0 ;;
-*) echo "usage: $0 [BUILD] [SCENE] [OUTDIR] (-h, --help: what it does)" >&2; exit 2 ;;
esac
BUILD=${1:-build}
SCENE=${2:-quad_light}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT=${3:-$BUILD/error-budget/$SCENE}
W=${WIDTH:-320}; H=${HEIGHT:-240}; SPP=${SPP:-512}; MC=${MC:-2048}
GLTF=$ROOT/samples/scenes/$SCENE.gltf
RENDER=$BUILD/tools/render/rtpbr-render
ORACLE=$BUILD/oracle/rtpbr-oracle
DIFF=$BUILD/tools/imgdiff/rtpbr-diff
for t in "$RENDER" "$ORACLE" "$DIFF"; do
    [ -x "$t" ] || { echo "error_budget: $t not built (ninja -C $BUILD)" >&2; exit 2; }
done
command -v oiiotool >/dev/null || { echo "error_budget: oiiotool missing (openimageio-tools)" >&2; exit 2; }
[ -f "$GLTF" ] || { echo "error_budget: no scene $GLTF" >&2; exit 2; }
mkdir -p "$OUT"

E=(--width "$W" --height "$H" --camera 0 --supersample 2)
O=(--width "$W" --height "$H" --camera 0 --spp "$SPP" --seed 1 --no-shadows --direct-only --quiet)
echo "error_budget: $SCENE ${W}x$H, oracle $SPP spp, engine Monte Carlo $MC samples" >&2
"$ORACLE" "$GLTF" -o "$OUT/O.exr" "${O[@]}"
"$ORACLE" "$GLTF" -o "$OUT/Oss.exr" "${O[@]}" --single-scatter
"$RENDER" "$GLTF" -o "$OUT/E.exr" "${E[@]}" >/dev/null
"$RENDER" "$GLTF" -o "$OUT/Ess.exr" "${E[@]}" --no-multiscatter >/dev/null
"$RENDER" "$GLTF" -o "$OUT/M.exr" "${E[@]}" --mc-samples "$MC" >/dev/null
"$RENDER" "$GLTF" -o "$OUT/Mss.exr" "${E[@]}" --mc-samples "$MC" --no-multiscatter >/dev/null

# a + b - c, clamped at 0
combine() { oiiotool "$OUT/$2.exr" "$OUT/$3.exr" --add "$OUT/$4.exr" --sub --clamp:min=0 -o "$OUT/$1.exr"; }
combine ltc_only Ess O Oss
combine kc_only Mss E Ess
combine neither Mss O Oss

flip() { # REF TEST LABEL
    "$DIFF" "$OUT/$1.exr" "$OUT/$2.exr" --hdr --json --heatmap "$OUT/flip_$2.png" |
        python3 -c 'import json, sys; d = json.load(sys.stdin); print("%-48s %.4f / %.4f" % (sys.argv[1], d["mean"], d["p95"]))' "$3"
}
echo "HDR-FLIP against the oracle (mean / p95):"
flip O E "engine (LTC + Kulla-Conty polygon lobe)"
flip O ltc_only "LTC error only (Ess + O - Oss)"
flip O kc_only "Kulla-Conty polygon error only (Mss + E - Ess)"
flip O M "Kulla-Conty per direction (Monte Carlo)"
flip O neither "neither (Mss + O - Oss)"
flip Oss Mss "Monte Carlo single scattering vs Oss"
