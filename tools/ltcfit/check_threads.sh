#!/bin/bash
# The fit does not depend on the thread count or scheduling (issue 19: three lobes share one
# pool, a row waiting only for its own first-column cell): rtpbr-ltcfit at size 8 (--quick)
# with 1 and with 3 threads must write the same header, byte for byte, and EXRs with the same
# pixels (idiff with zero tolerance; the files differ in their creation date).
#   check_threads.sh RTPBR_LTCFIT
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: $0 RTPBR_LTCFIT" >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for t in 1 3; do
    mkdir "$dir/t$t"
    "$1" --out "$dir/t$t" --size 8 --quick --threads "$t" 2>"$dir/t$t.log" || { cat "$dir/t$t.log" >&2; exit 1; }
done
status=0
if ! cmp -s "$dir/t1/rtpbr_ltc_tables.h" "$dir/t3/rtpbr_ltc_tables.h"; then
    echo "FAIL: rtpbr_ltc_tables.h differs between 1 and 3 threads" >&2
    status=1
fi
for f in ltc_ggx_1 ltc_ggx_2 ltc_beckmann_1 ltc_beckmann_2 ltc_disney_diffuse_1 ltc_disney_diffuse_2; do
    if ! idiff -fail 0 -warn 0 "$dir/t1/$f.exr" "$dir/t3/$f.exr" >"$dir/idiff.log" 2>&1; then
        cat "$dir/idiff.log" >&2
        echo "FAIL: $f.exr differs between 1 and 3 threads" >&2
        status=1
    fi
done
[ $status -eq 0 ] && echo "1 and 3 threads: the same tables"
exit $status
