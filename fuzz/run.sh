#!/usr/bin/env bash
# Runs one fuzzer for a while on the shared machine (fuzz/README.md).
#   fuzz/run.sh BUILD_DIR scene|image SECONDS [extra libFuzzer flags]
#   fuzz/run.sh BUILD_DIR image-leaks 0     (replays the image corpus with leak checks)
# Corpus (kept between runs): BUILD_DIR/fuzz/corpus-NAME, seeded from make_seeds.py output;
# crashes, leaks, timeouts and OOMs: BUILD_DIR/fuzz/findings-NAME/; log: BUILD_DIR/fuzz/NAME.log.
set -euo pipefail
build=$(cd "$1" && pwd); name=$2; seconds=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd); repo=$(dirname "$here")
out=$build/fuzz
[[ -d $out/seeds ]] || python3 "$here/make_seeds.py" "$repo/samples/scenes" "$here/assets" "$out/seeds"
dict=$here/gltf.dict; [[ $name == image ]] && dict=$here/image.dict
# detect_leaks: LeakSanitizer after each input that grew the heap; the suppressions cover
# OpenImageIO's known leak on truncated PNGs (tests/imgdiff/lsan.supp), nothing of ours.
# The image fuzzer runs without leak checks: OpenImageIO's known leak is only recognised with
# the slow unwinder (the library has no frame pointers), which costs 2x. Its corpus is then
# replayed with leak checks:  fuzz/run.sh BUILD_DIR image-leaks 0
asan=detect_leaks=1:allocator_may_return_null=0
if [[ $name == image ]]; then asan=detect_leaks=0:allocator_may_return_null=0; fi
if [[ $name == image-leaks ]]; then
  export ASAN_OPTIONS=detect_leaks=1:fast_unwind_on_malloc=0
  export LSAN_OPTIONS=suppressions=$repo/tests/imgdiff/lsan.supp:print_suppressions=0
  nice -n 10 "$out/fuzz_image" -runs=0 -rss_limit_mb=2048 -timeout=10 -close_fd_mask=3 \
    "$out/corpus-image" 2>&1 | tee "$out/image-leaks.log"
  exit "${PIPESTATUS[0]}"
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-$asan}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$repo/tests/imgdiff/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$out/corpus-$name" "$out/findings-$name"
cd "$out/findings-$name"
nice -n 10 "$out/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
  -max_len=131072 -dict="$dict" -close_fd_mask=1 -print_final_stats=1 "$@" \
  "$out/corpus-$name" "$out/seeds/$name" 2>&1 | tee "$out/$name.log"
exit "${PIPESTATUS[0]}"
