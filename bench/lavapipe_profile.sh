#!/usr/bin/env bash
# What the lighting pass's code does on lavapipe, by instruction class (issue 32): samples
# rtpbr-bench-engine's frames with perf, copies the compiled shader most samples fall in out of
# the running process (gdb: llvmpipe's JIT code has no file or symbols), disassembles it
# (objdump) and prints, over that code's hot part (the 1 KiB blocks that each hold at least
# 0.5 % of its samples: on a light-heavy scene, mostly the light loop), how many instructions of
# each class it has (static counts, not executions: callgrind's are lavapipe_instructions.sh's)
# and each class's share of the samples. Steadier than times: a frame's time moves by 10-20 %
# between runs on the shared 2-core machine, these counts by a few per cent (bench/README.md,
# "Where a light's instructions go on lavapipe"). A sample is counted against
# the instruction before its address (an instruction is sampled when the next one is waiting
# for it); the static counts do not depend on that.
#   bench/lavapipe_profile.sh BUILD_DIR [--scene NAME] [--lights N] [--size WxH] [--lib DIR] [--seconds S]
set -euo pipefail
help() {
  cat <<EOT
usage: $0 BUILD_DIR [--scene NAME] [--lights N] [--size WxH] [--lib DIR] [--seconds S]
The lighting shader's hot code on lavapipe by instruction class: BUILD_DIR's rtpbr-bench-engine
renders --scene (default floor) with --lights lights (default 16) at --size (default 640x480)
frame after frame; perf samples it for --seconds (default 6) after 8 s of warm-up; the code of
the shader with the most samples is copied out with gdb and disassembled with objdump.
  --lib DIR      the engine library's directory (LD_LIBRARY_PATH; default BUILD_DIR/engine)
Prints, for its hot part (1 KiB blocks with at least 0.5 % of its samples each), the
instructions by class (floating-point arithmetic; division and square root; lane extracts and
inserts, llvmpipe's loads at an index that differs between SIMD lanes; moves to and from the
stack, spills; integer vector; compares and masks; blends; gathers; other) and each class's
share of the samples.
Needs perf (Debian linux-perf), gdb and objdump (binutils), and permission to trace the process.
EOT
}
usage() {
  echo "usage: $0 BUILD_DIR [--scene NAME] [--lights N] [--size WxH] [--lib DIR] [--seconds S] (--help)" >&2
  exit 2
}
case ${1:-} in
-h | --help) help; exit 0 ;;
'' | -*) usage ;;
esac
build=$1
shift
scene=floor lights=16 size=640x480 lib=$build/engine seconds=6
while [[ $# -gt 0 ]]; do
  [[ $1 == -h || $1 == --help ]] && { help; exit 0; }
  [[ $# -ge 2 ]] || usage
  case $1 in
  --scene) scene=$2 ;;
  --lights) lights=$2 ;;
  --size) size=$2 ;;
  --lib) lib=$2 ;;
  --seconds) seconds=$2 ;;
  *) usage ;;
  esac
  shift 2
done
[[ $lights =~ ^[0-9]+$ && $size =~ ^[0-9]+x[0-9]+$ && $seconds =~ ^[0-9]+$ ]] || usage
bench=$build/bench/rtpbr-bench-engine
[[ -x $bench ]] || { echo "$0: no $bench (build first)" >&2; exit 2; }
[[ -d $lib ]] || { echo "$0: no library directory $lib" >&2; exit 2; }
for tool in perf gdb objdump python3; do
  command -v $tool >/dev/null || { echo "$0: needs $tool (Debian: linux-perf, gdb, binutils, python3)" >&2; exit 2; }
done
icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
[[ -n ${VK_ICD_FILENAMES:-} || ! -f $icd ]] || export VK_ICD_FILENAMES=$icd
work=$(mktemp -d)
pid=
cleanup() { [[ -z $pid ]] || kill "$pid" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT

LD_LIBRARY_PATH=$lib "$bench" --repeat 1000 --sizes "$size" --lights "$lights" --scene "$scene" \
  >"$work/bench.log" 2>&1 &
pid=$!
sleep 8 # (the pipelines' compile and the first frames)
kill -0 "$pid" 2>/dev/null || { echo "$0: rtpbr-bench-engine stopped:" >&2; tail -5 "$work/bench.log" >&2; exit 1; }
perf record -p "$pid" -F 2000 -o "$work/perf.data" -- sleep "$seconds" >"$work/perf.log" 2>&1 ||
  { echo "$0: perf record failed:" >&2; tail -5 "$work/perf.log" >&2; exit 1; }
perf script -i "$work/perf.data" -F ip 2>/dev/null | sort | uniq -c >"$work/ips.txt"
cp "/proc/$pid/maps" "$work/maps"
# the executable anonymous mapping with the most samples (llvmpipe's compiled shaders)
region=$(python3 - "$work/ips.txt" "$work/maps" <<'PY'
import sys
ips = [(int(l.split()[0]), int(l.split()[1], 16)) for l in open(sys.argv[1]) if len(l.split()) == 2]
best, best_n = None, 0
for line in open(sys.argv[2]):
    f = line.split()
    if 'x' not in f[1] or len(f) > 5:  # executable, no file
        continue
    lo, hi = (int(x, 16) for x in f[0].split('-'))
    n = sum(c for c, a in ips if lo <= a < hi)
    if n > best_n:
        best, best_n = (lo, hi), n
if best:
    print(f'{best[0]:x} {best[1]:x}')
PY
)
[[ -n $region ]] || { echo "$0: no samples in compiled code (is the device lavapipe?)" >&2; exit 1; }
read -r lo hi <<<"$region"
gdb -p "$pid" -batch -ex "dump binary memory $work/jit.bin 0x$lo 0x$hi" >"$work/gdb.log" 2>&1 ||
  { echo "$0: gdb could not read the process:" >&2; tail -3 "$work/gdb.log" >&2; exit 1; }
kill "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
pid=
objdump -D -b binary -mi386:x86-64 --adjust-vma="0x$lo" "$work/jit.bin" >"$work/jit.asm"
echo "# $scene, $lights lights, $size, $(basename "$lib"): lavapipe's hottest compiled code by instruction class"
python3 - "$work/ips.txt" "$work/jit.asm" "$lo" "$hi" <<'PY'
import bisect, collections, re, sys
ips = [(int(l.split()[0]), int(l.split()[1], 16)) for l in open(sys.argv[1]) if len(l.split()) == 2]
lo, hi = int(sys.argv[3], 16), int(sys.argv[4], 16)
asm = []
for line in open(sys.argv[2]):
    m = re.match(r'\s*([0-9a-f]+):\s+((?:[0-9a-f]{2} )+)\s*(.*)', line)
    if m and m.group(3).strip():
        asm.append((int(m.group(1), 16), m.group(3).strip()))
addr = [a for a, _ in asm]
total = sum(c for c, _ in ips)
inside = [(c, a) for c, a in ips if lo <= a < hi]
n_in = sum(c for c, _ in inside)

def klass(s):
    op = s.split()[0]
    if op in ('vdivps', 'vsqrtps', 'vdivss', 'vsqrtss', 'vrcpps', 'vrsqrtps'):
        return 'division and root'
    if op.startswith('vmov') and '(%rsp)' in s:
        return 'stack moves (spills)'
    if 'gather' in op:
        return 'gathers'
    if op in ('vpextrd', 'vpinsrd', 'vpextrq', 'vpinsrq', 'vextractps', 'vinsertps', 'vmovd', 'vmovq', 'movslq',
              'vextracti128', 'vinserti128', 'vextractf128', 'vinsertf128', 'vinserti32x4', 'vextracti32x4'):
        return 'lane extracts and inserts'
    if op.startswith(('vblend', 'vpblend')) or '{%k' in s and op.startswith('vmov'):
        return 'blends and masked moves'
    if op.startswith(('vcmp', 'vpcmp', 'vptest', 'k')):
        return 'compares and masks'
    if op.startswith(('vfmadd', 'vfmsub', 'vfnmadd', 'vfnmsub')) or op in (
            'vmulps', 'vaddps', 'vsubps', 'vminps', 'vmaxps', 'vandps', 'vandnps', 'vorps', 'vxorps', 'vroundps'):
        return 'float arithmetic'
    if op.startswith('vmov'):
        return 'register moves'
    if op.startswith('vp') or op.startswith('vcvt'):
        return 'integer vector and conversions'
    return 'scalar and other'

# 1 KiB blocks of the region by samples; the hot ones hold at least 0.5 % of them each (a
# density, not a cumulative share: the loop's blocks hold 2 to 12 % each, the cold ones well
# under 0.5 %, so the set does not move with the sampling's noise at its edge)
blocks = collections.Counter()
for c, a in inside:
    blocks[(a - lo) // 1024] += c
hot = {b for b, c in blocks.items() if c >= 0.005 * n_in}
acc = sum(blocks[b] for b in hot)
static = collections.Counter(klass(s) for a, s in asm if (a - lo) // 1024 in hot)
sampled = collections.Counter()
for c, a in inside:
    i = bisect.bisect_right(addr, a) - 1
    if i >= 1 and (a - lo) // 1024 in hot:
        sampled[klass(asm[i - 1][1])] += c
n_static = sum(static.values())
n_sampled = sum(sampled.values())
print(f'samples: {total}, in this code {n_in} ({100 * n_in / max(total, 1):.1f} %); its hot part: '
      f'{len(hot)} KiB, {n_static} instructions, {100 * acc / max(n_in, 1):.1f} % of its samples')
print('| class | instructions | share | share of the samples |')
print('|---|---:|---:|---:|')
for k, v in static.most_common():
    print(f'| {k} | {v} | {100 * v / n_static:.1f} % | {100 * sampled[k] / max(n_sampled, 1):.1f} % |')
PY
