#!/usr/bin/env bash
# Renames the shader library's portability vocabulary to its prefixed names (issue 15: in GLSL
# and HLSL the library defines no unprefixed name, so a host shader keeps its own float3, lerp,
# saturate, ...), in every shader source of this repository, and removes the unprefixed block
# of shaderlib/rtpbr/lang.h. Mechanical and idempotent: run it again after merging code that
# still uses the old names (a second run changes nothing). Also usable on your own shaders:
#   tools/rename_shaderlib_vocab.sh [FILE ...]     (default: this repository's shader sources)
#
#   float2 float3 float4 float3x3 -> rtpbr_float2 ...    lerp saturate rsqrt atan2 -> rtpbr_...
#   sq safe_sqrt -> rtpbr_sq rtpbr_safe_sqrt
# In *.hlsl files (HLSL hosts) only sq and safe_sqrt are renamed: the others are HLSL's own
# types and intrinsics there. C++ sources are not touched: rtpbr::float3, rtpbr::lerp, ... stay
# as aliases in namespace rtpbr.
set -euo pipefail
cd "$(dirname "$0")/.."

all_names='float2|float3|float4|float3x3|lerp|saturate|rsqrt|atan2|sq|safe_sqrt'
hlsl_names='sq|safe_sqrt'

files=("$@")
if ((${#files[@]} == 0)); then
  # The library's headers (lang.h defines the vocabulary: only its old block goes), the
  # engine's shaders, the shader-include sample, and the shader sources of the tests (kernels
  # shared by GLSL, HLSL and C++ included).
  mapfile -t files < <(
    { ls shaderlib/rtpbr/*.h | grep -v '/lang\.h$'
      ls engine/shaders/*.glsl engine/shaders/*.comp engine/shaders/*.frag engine/shaders/*.vert 2>/dev/null
      ls samples/shader-include/* 2>/dev/null
      find tests tools oracle bench -type f \( -name '*.glsl' -o -name '*.comp' -o -name '*.frag' \
           -o -name '*.vert' -o -name '*.hlsl' -o -name '*.inc' \) 2>/dev/null
      ls tests/shaderlib/gpu/kernel.h tests/shaderlib/gpu/kernel_cases.h 2>/dev/null
    } | grep -v '^tests/consumers/' | sort -u)
  # lang.h: drop the block of unprefixed names (BEGIN ... END unprefixed vocabulary).
  sed -i '/^\/\/ BEGIN unprefixed vocabulary/,/^\/\/ END unprefixed vocabulary/d' shaderlib/rtpbr/lang.h
fi

for f in "${files[@]}"; do
  case "$f" in
    *.hlsl) names=$hlsl_names ;;
    *) names=$all_names ;;
  esac
  # Code only (the part of a line before //: comments keep the math's own words). Whole
  # identifiers only, so rtpbr_float3 (already renamed) is left alone and a second run changes
  # nothing; a leading "." or "->" keeps struct members (v.sq) untouched.
  NAMES="$names" perl -pi -e 'my ($code, $comment) = split m{(?=//)}, $_, 2;
    $code =~ s/(?<![A-Za-z0-9_.>])($ENV{NAMES})\b/rtpbr_$1/g;
    $_ = $code . ($comment // "");' "$f"
done
