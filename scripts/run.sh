#!/usr/bin/env bash
# One entry point for a fresh machine: installs what is missing, configures and builds, then
#   run.sh main   renders the bundled area-light scene (engine and oracle, when built) and
#                 writes the comparison into out/
#   run.sh test   runs every test suite
# Both are idempotent: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-main}
builddir=${RTPBR_BUILDDIR:-build}

case "$what" in main|test) ;; *)
  echo "usage: $0 main|test [meson setup options]" >&2
  exit 2
esac

bash scripts/setup.sh "$what"
if [[ ! -f "$builddir/build.ninja" ]]; then
  meson setup "$builddir" "${@:2}"
fi

case "$what" in
  main)
    # Only the programs the main job runs (and what they are made of: the engine library, its
    # shaders, the tables), not the tests and benchmarks: issue 31. A missing one (a feature
    # turned off at setup) is left out; scripts/main-job.sh says what it could not run.
    targets=()
    for t in tools/brdfplot/rtpbr-brdfplot tools/render/rtpbr-render oracle/rtpbr-oracle \
             tools/imgdiff/rtpbr-diff; do
      ninja -C "$builddir" -t query "$t" >/dev/null 2>&1 && targets+=("$t")
    done
    ninja -C "$builddir" "${targets[@]}"
    exec bash scripts/main-job.sh "$builddir"
    ;;
  test)
    ninja -C "$builddir"
    meson test -C "$builddir" --print-errorlogs --num-processes "$(nproc)"
    ;;
  *)
    echo "usage: $0 main|test [meson setup options]" >&2
    exit 2
    ;;
esac
