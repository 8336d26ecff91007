#!/bin/sh
# Copy-paste test of the shader library: copy shaderlib/rtpbr/ ALONE into an empty folder
# (as a user would), compile samples/shader-include's GLSL and HLSL fragment shaders against
# that copy for several model flag sets, and validate the SPIR-V with spirv-val.
# usage: shader_include.sh GLSLANG SPIRV_VAL SOURCE_ROOT
set -eu
glslang=$1; spirv_val=$2; root=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/include"
cp -R "$root/shaderlib/rtpbr" "$work/include/rtpbr"
cp "$root/samples/shader-include/quad_light.frag" "$root/samples/shader-include/quad_light.hlsl" "$work/"
failed=0
for flags in "" \
             "-DRTPBR_MULTISCATTER=0" \
             "-DRTPBR_NDF=RTPBR_NDF_BECKMANN" \
             "-DRTPBR_LTC_CLIPLESS=1" \
             "-DRTPBR_NDF=RTPBR_NDF_BECKMANN -DRTPBR_LTC_CLIPLESS=1 -DRTPBR_MULTISCATTER=0"; do
    # shellcheck disable=SC2086 # flags is a word list on purpose
    if ! "$glslang" -V -I"$work/include" $flags -o "$work/glsl.spv" "$work/quad_light.frag" \
         || ! "$spirv_val" "$work/glsl.spv"; then
        echo "FAIL: GLSL with flags '$flags'"; failed=1
    fi
    # shellcheck disable=SC2086
    if ! "$glslang" -V -D -e main -S frag -I"$work/include" $flags -o "$work/hlsl.spv" "$work/quad_light.hlsl" \
         || ! "$spirv_val" "$work/hlsl.spv"; then
        echo "FAIL: HLSL with flags '$flags'"; failed=1
    fi
done
[ $failed -eq 0 ] && echo "GLSL and HLSL compile and validate against a bare copy of shaderlib/rtpbr/"
exit $failed
