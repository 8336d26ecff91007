#!/usr/bin/env bash
# Shader instructions per pixel on lavapipe, counted, not timed (issue 32): rtpbr-render renders
# SCENE under valgrind's callgrind at two sizes; the instructions executed in the code llvmpipe
# compiled (its shaders: callgrind's object "???", the only code without a file) differ between
# them by the per-pixel work of every pass (G-buffer, lighting, tone mapping), which this prints
# divided by the difference in pixels. The compile, the scene's load and the fixed per-frame
# work cancel. On a shared 2-core machine a frame's time moves by 10-20 % between runs (one
# library's lighting pass: 126 to 175 ms in four runs of one scene); this count repeats to
# 1e-4 for the same library, Mesa and scene, so that a change of 1 % can be seen. What it does
# not see: an instruction's cost (a gather, a division or a texel read counts 1) and memory.
# Under valgrind the CPU has no AVX-512, so llvmpipe's code is its AVX2 code whatever the
# machine. The driver's own functions (libvulkan_lvp: its threads wait by spinning, which varies
# from run to run) are not counted.
#   bench/lavapipe_instructions.sh BUILD_DIR SCENE.gltf [--lib DIR]... [--sizes WxH,WxH] [-- RENDER_FLAGS]
# --lib DIR: the engine library's directory (LD_LIBRARY_PATH; default BUILD_DIR/engine), repeatable:
# each is counted and compared with the first (an A/B with one rtpbr-render). Each size runs in
# its own valgrind, both at once (2 cores); about 100 s per library for a bundled scene.
set -euo pipefail
help() {
  cat <<EOT
usage: $0 BUILD_DIR SCENE.gltf [--lib DIR]... [--sizes WxH,WxH] [-- RENDER_FLAGS]
lavapipe's shader instructions per pixel for SCENE, counted by valgrind's callgrind (not timed):
BUILD_DIR's rtpbr-render at two sizes, the difference of the instructions executed in the
driver's compiled shaders over the difference of the pixels (the compile and the per-frame work
cancel). Repeats to about 1e-4; an instruction's cost and memory are not seen.
  --lib DIR      the engine library's directory (LD_LIBRARY_PATH; default BUILD_DIR/engine);
                 repeatable: each counted, the ratio against the first printed
  --sizes S,L    the two sizes WxH (default 64x48,320x240)
  -- FLAGS       the rest goes to rtpbr-render (e.g. -- --shadows)
  -h, --help     this text
Needs valgrind (Debian package valgrind); about 100 s per library (two valgrinds at once).
EOT
}
usage() {
  echo "usage: $0 BUILD_DIR SCENE.gltf [--lib DIR]... [--sizes WxH,WxH] [-- RENDER_FLAGS] (--help)" >&2
  exit 2
}
case ${1:-} in
-h | --help) help; exit 0 ;;
-*) usage ;;
esac
[[ $# -ge 2 ]] || usage
build=$1 scene=$2
shift 2
libs=() sizes=64x48,320x240 flags=()
while [[ $# -gt 0 ]]; do
  case $1 in
  --lib) [[ $# -ge 2 ]] || usage; libs+=("$2"); shift 2 ;;
  --sizes) [[ $# -ge 2 ]] || usage; sizes=$2; shift 2 ;;
  --) shift; flags=("$@"); break ;;
  -h | --help) help; exit 0 ;;
  *) usage ;;
  esac
done
[[ ${#libs[@]} -gt 0 ]] || libs=("$build/engine")
for lib in "${libs[@]}"; do
  [[ -d $lib ]] || { echo "$0: no library directory $lib" >&2; exit 2; }
done
small=${sizes%,*} large=${sizes#*,}
[[ $small =~ ^[0-9]+x[0-9]+$ && $large =~ ^[0-9]+x[0-9]+$ ]] || { echo "$0: --sizes takes WxH,WxH" >&2; exit 2; }
render=$build/tools/render/rtpbr-render
[[ -x $render ]] || { echo "$0: no $render (build first)" >&2; exit 2; }
[[ -f $scene ]] || { echo "$0: no scene $scene" >&2; exit 2; }
for tool in valgrind callgrind_annotate; do
  command -v $tool >/dev/null || { echo "$0: needs $tool (Debian package valgrind)" >&2; exit 2; }
done
pixels() { local s=$1; echo $(( ${s%x*} * ${s#*x} )); }
dpx=$(( $(pixels "$large") - $(pixels "$small") ))
[[ $dpx -gt 0 ]] || { echo "$0: the second size must have more pixels" >&2; exit 2; }
icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
[[ -n ${VK_ICD_FILENAMES:-} || ! -f $icd ]] || export VK_ICD_FILENAMES=$icd
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The JIT's instructions of one callgrind profile: the functions of object "???".
jit_instructions() {
  callgrind_annotate --inclusive=no --threshold=100 "$1" 2>/dev/null |
    awk '/\[\?\?\?\] *$/ {gsub(",", "", $1); s += $1} END {printf "%d\n", s}'
}

echo "# $(basename "$scene"), ${flags[*]:-default flags}: llvmpipe's shader instructions per pixel ($large - $small)"
echo "| library | instructions per pixel | against the first |"
echo "|---|---:|---:|"
first=
for n in "${!libs[@]}"; do
  lib=${libs[$n]}
  pids=()
  for s in "$small" "$large"; do
    LD_LIBRARY_PATH=$lib valgrind --tool=callgrind --callgrind-out-file="$work/$n-$s.cg" \
      "$render" "$scene" -o "$work/$n-$s.png" --width "${s%x*}" --height "${s#*x}" "${flags[@]}" \
      >"$work/$n-$s.log" 2>&1 &
    pids+=($!)
  done
  for p in "${pids[@]}"; do
    wait "$p" || { echo "$0: rtpbr-render failed under valgrind ($lib):" >&2; tail -5 "$work"/$n-*.log >&2; exit 1; }
  done
  a=$(jit_instructions "$work/$n-$small.cg") b=$(jit_instructions "$work/$n-$large.cg")
  per=$(awk -v a="$a" -v b="$b" -v d="$dpx" 'BEGIN {printf "%.1f", (b - a) / d}')
  [[ -n $first ]] || first=$per
  ratio=$(awk -v p="$per" -v f="$first" 'BEGIN {printf "%.4f", (f > 0 ? p / f : 0)}')
  echo "| $lib | $per | $ratio |"
done
