#!/bin/sh
# The layout checks of rtpbr_shared.h (RTPBR_SHARED_CHECK_LAYOUT) can fail: a correct struct
# compiles, and each misplaced member or size fails the C compiler with the check's message.
# Usage: test_layout_check.sh SHARED_HEADER_DIR LAYOUTS_C CC [CC ARGUMENTS...]
set -u
include=$1
source=$2
shift 2
compile() { "$@" -std=c11 -fsyntax-only -I"$include" "$source" 2>&1; }

if ! out=$(compile "$@" -DLAYOUT_CASE=0); then
    echo "FAIL: the correctly laid out struct does not compile:"
    echo "$out"
    exit 1
fi
echo "ok: case 0 (correct layout) compiles"

status=0
for spec in \
    "1|layout_under_test.colour: not where std140/std430 put a VEC4" \
    "2|layout_under_test.normal: not where std140/std430 put a VEC3" \
    "3|layout_under_test.size: not where std140/std430 put a UVEC2" \
    "4|layout_under_test: size is not a multiple of 16 bytes"; do
    n=${spec%%|*}
    message=${spec#*|}
    if out=$(compile "$@" -DLAYOUT_CASE="$n"); then
        echo "FAIL: case $n compiled; expected: $message"
        status=1
    elif ! printf '%s\n' "$out" | grep -qF "$message"; then
        echo "FAIL: case $n failed without the message '$message':"
        printf '%s\n' "$out"
        status=1
    else
        echo "ok: case $n fails with '$message'"
    fi
done
exit $status
