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

bash scripts/setup.sh
if [[ ! -f "$builddir/build.ninja" ]]; then
  meson setup "$builddir" "${@:2}"
fi
ninja -C "$builddir"

case "$what" in
  main)
    exec bash scripts/main-job.sh "$builddir"
    ;;
  test)
    meson test -C "$builddir" --print-errorlogs --num-processes "$(nproc)"
    ;;
  *)
    echo "usage: $0 main|test [meson setup options]" >&2
    exit 2
    ;;
esac
