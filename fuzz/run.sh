#!/usr/bin/env bash
# Runs one fuzzer for a while on the shared machine (fuzz/README.md).
#   fuzz/run.sh BUILD_DIR scene|image|scene_api SECONDS [extra libFuzzer flags]
#   (SECONDS 0 with -runs=N: a fixed number of executions, as .ci/run does)
#   fuzz/run.sh BUILD_DIR image-leaks 0     (replays the image corpus with leak checks)
# Corpus (kept between runs): BUILD_DIR/fuzz/corpus-NAME, seeded from make_seeds.py output;
# crashes, leaks, timeouts and OOMs: BUILD_DIR/fuzz/findings-NAME/; log: BUILD_DIR/fuzz/NAME.log.
set -euo pipefail
build=$(cd "$1" && pwd); name=$2; seconds=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd); repo=$(dirname "$here")
out=$build/fuzz
[[ -d $out/seeds ]] || python3 "$here/make_seeds.py" "$repo/samples/scenes" "$here/assets" "$out/seeds"
dict=$here/gltf.dict; [[ $name == image ]] && dict=$here/image.dict
max_len=16384  # larger inputs reach no other code, and each costs more (issue 18)
[[ $name == image ]] && max_len=131072
dict_flag=(-dict="$dict"); [[ $name == scene_api ]] && dict_flag=() && max_len=4096
if [[ $name == scene_api ]]; then
  # lavapipe, with the validation layer; both stay mapped so that LeakSanitizer can name the
  # third-party leaks (fuzz/lsan_scene_api.supp).
  export VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
  preload=""
  for lib in libVkLayer_khronos_validation.so libvulkan_lvp.so; do
    [[ -e /usr/lib/x86_64-linux-gnu/$lib ]] && preload="$preload /usr/lib/x86_64-linux-gnu/$lib"
  done
  export LD_PRELOAD="${preload# }"
  export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/lsan_scene_api.supp:print_suppressions=0}
  asan=detect_leaks=1:allocator_may_return_null=0:verify_asan_link_order=0
  mkdir -p "$out/seeds/scene_api"
  # Seeds: byte streams of 16..2048 bytes (fuzz_scene_api.c reads any bytes as descs).
  [[ -n $(ls -A "$out/seeds/scene_api") ]] || python3 -c "
import random, sys
for i in range(8):
    r = random.Random(i)
    open('%s/seed%d' % (sys.argv[1], i), 'wb').write(bytes(r.randrange(256) for _ in range(16 << i)))
" "$out/seeds/scene_api"
fi
# detect_leaks: LeakSanitizer after each input that grew the heap; the suppressions cover
# OpenImageIO's known leak on truncated PNGs (tests/imgdiff/lsan.supp), nothing of ours.
# The image fuzzer runs without leak checks: OpenImageIO's known leak is only recognised with
# the slow unwinder (the library has no frame pointers), which costs 2x. Its corpus is then
# replayed with leak checks:  fuzz/run.sh BUILD_DIR image-leaks 0
[[ $name == scene_api ]] || asan=detect_leaks=1:allocator_may_return_null=0
if [[ $name == image ]]; then asan=detect_leaks=0:allocator_may_return_null=0; fi
if [[ $name == image-leaks ]]; then
  export ASAN_OPTIONS=detect_leaks=1:fast_unwind_on_malloc=0
  export LSAN_OPTIONS=suppressions=$repo/tests/imgdiff/lsan.supp:print_suppressions=0
  nice -n 10 "$out/fuzz_image" -runs=0 -rss_limit_mb=2048 -timeout=10 -close_fd_mask=3 \
    "$out/corpus-image" 2>&1 | tee "$out/image-leaks.log"
  exit "${PIPESTATUS[0]}"
fi
# Kept regression inputs (fuzz/regressions/NAME/: past findings) join the seeds, so that every
# run, .ci/run's included, replays them first.
if [[ -d $here/regressions/$name ]]; then
  mkdir -p "$out/seeds/$name" && cp "$here/regressions/$name"/* "$out/seeds/$name/"
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-$asan}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$repo/tests/imgdiff/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$out/corpus-$name" "$out/findings-$name"
cd "$out/findings-$name"
nice -n 10 "$out/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
  -max_len=$max_len "${dict_flag[@]}" -close_fd_mask=1 -print_final_stats=1 "$@" \
  "$out/corpus-$name" "$out/seeds/$name" 2>&1 | tee "$out/$name.log"
exit "${PIPESTATUS[0]}"
