#!/usr/bin/env bash
# One consumer of rtpbr, outside the source tree (suite 'consumers', tests/consumers/meson.build):
#   consumer.sh KIND SRC BUILD PREFIX LIBDIR
# KIND pkgconfig | cmake | shaders: a fresh DESTDIR install of BUILD into a temporary directory,
#   then the "Install and use" snippets of docs/library.md for KIND, run verbatim in a temporary
#   directory holding host.c / shade.cpp / host.frag / host.hlsl, with the environment pointing at the
#   staged prefix (PKG_CONFIG_PATH + PKG_CONFIG_SYSROOT_DIR, CMAKE_PREFIX_PATH, LD_LIBRARY_PATH).
# KIND meson: the same without an install; RTPBR_SRC = SRC (its committed HEAD is cloned).
# KIND programs: the installed programs of a validation run work from the staged prefix.
# KIND tables: the installed raw tables agree with the installed EXR images (check_tables.py).
# KIND slang: the installed headers through a second HLSL compiler, Slang's slangc (installed
#   by scripts/setup.sh into .deps/); exit 77 (skipped) when it is not there.
set -euo pipefail
kind=$1 src=$2 build=$3 prefix=$4 libdir=$5
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rtpbr-consumer-$kind.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/work"
cp "$here/host.c" "$here/shade.cpp" "$here/host.frag" "$here/host.hlsl" "$tmp/work/"

if [[ $kind != meson ]]; then
  meson install -C "$build" --no-rebuild --quiet --destdir "$tmp/dest" >/dev/null
  staged="$tmp/dest$prefix"
  export PKG_CONFIG_PATH="$staged/$libdir/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$tmp/dest"
  export CMAKE_PREFIX_PATH="$staged" LD_LIBRARY_PATH="$staged/$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  echo "consumer $kind: installed into $staged ($(du -sh "$staged" | cut -f1))"
fi

if [[ $kind == programs ]]; then
  # The installed programs of a validation run, from the staged prefix alone: each answers
  # --help; rtpbr-render renders an installed scene; rtpbr-validate finds the programs, its
  # thresholds and the scenes (an unknown scene name stops it right after those checks).
  cd "$tmp/work"
  for p in rtpbr-render rtpbr-oracle rtpbr-diff rtpbr-validate; do
    "$staged/bin/$p" --help >/dev/null
  done
  "$staged/bin/rtpbr-render" "$staged/share/rtpbr/samples/scenes/quad_light.gltf" -o quad.png \
    --width 32 --height 24 --validation
  [[ -s quad.png ]]
  if "$staged/bin/rtpbr-validate" --scenes no_such_scene >validate.log 2>&1 ||
     ! grep -q "unknown scene 'no_such_scene' (thresholds.json lists quad_light" validate.log; then
    cat validate.log
    echo "consumer programs: the installed rtpbr-validate did not find its programs, thresholds or scenes"
    exit 1
  fi
  for scene in $(python3 -c 'import json, sys; print(" ".join(json.load(open(sys.argv[1]))["scenes"]))' \
                 "$staged/share/rtpbr/tools/validate/thresholds.json"); do
    [[ -f "$staged/share/rtpbr/samples/scenes/$scene.gltf" ]]
  done
  echo "consumer programs: ok"
  exit 0
fi

if [[ $kind == tables ]]; then
  # The installed raw tables against the installed EXR images (check_tables.py).
  python3 "$here/check_tables.py" "$staged/share/rtpbr/luts" "$(command -v oiiotool)"
  exit
fi

if [[ $kind == slang ]]; then
  slangc="$src/.deps/slangc"
  if [[ ! -x $slangc ]]; then
    echo "consumer slang: $slangc not installed (scripts/setup.sh installs it from PyPI); skipped"
    exit 77
  fi
  # -O0: slangc's optimiser is spirv-opt, which it does not find here; the front end and the
  # SPIR-V emission are what is checked. (Debian 12's spirv-val predates Slang's source id.)
  "$slangc" "$tmp/work/host.hlsl" -I "$staged/include" -target spirv -O0 -entry main -stage fragment \
    -o "$tmp/work/host.slang.spv"
  [[ -s "$tmp/work/host.slang.spv" ]]
  echo "consumer slang: host.hlsl with the installed headers compiled by slangc $("$slangc" -v 2>&1)"
  exit 0
fi

# The snippets: a fenced block right after "<!-- consumer KIND: file PATH -->" is written to
# PATH, one after "<!-- consumer KIND: run -->" is run, in the order of the page.
python3 - "$src/docs/library.md" "$kind" "$tmp/work" <<'PY'
import re, sys
page, kind, work = sys.argv[1:]
text = open(page).read()
blocks = re.findall(r"<!-- consumer (\w+): (file (\S+)|run) -->\n```\w*\n(.*?)```", text, re.S)
runs = []
for k, what, path, body in blocks:
    if k != kind:
        continue
    if what == "run":
        runs.append(body)
    else:
        open(work + "/" + path, "w").write(body)
if not runs:
    sys.exit("consumer %s: %s has no '<!-- consumer %s: run -->' snippet" % (kind, page, kind))
open(work + "/snippet.sh", "w").write("\n".join(runs))
PY
echo "consumer $kind: running the docs/library.md snippet:"
sed 's/^/  | /' "$tmp/work/snippet.sh"
cd "$tmp/work"
RTPBR_SRC="$src" bash -euo pipefail snippet.sh
if [[ $kind == shaders ]]; then
  spirv-val host.frag.spv && spirv-val host.hlsl.spv
fi
echo "consumer $kind: ok"
