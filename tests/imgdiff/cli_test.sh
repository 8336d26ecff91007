#!/usr/bin/env bash
# Command-line tests of rtpbr-diff: exit codes, error messages, JSON output, heat map.
# usage: cli_test.sh CASE RTPBR_DIFF MAKE_IMAGES PYTHON3 WORKDIR
# The input images are generated at run time into WORKDIR by MAKE_IMAGES.
set -u
case_name=$1 tool=$(realpath "$2") make_images=$(realpath "$3") python=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"$make_images" . || { echo "FAIL: make_images"; exit 1; }

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect CODE ARGS...: runs the tool, keeps stdout/stderr in out.txt/err.txt, checks the exit code.
expect() {
    local want=$1; shift
    "$tool" "$@" >out.txt 2>err.txt
    local got=$?
    [[ $got -eq $want ]] || fail "rtpbr-diff $* exited $got, expected $want; stderr: $(cat err.txt)"
    if [[ $want -ne 0 ]]; then
        [[ $(wc -l <err.txt) -eq 1 ]] || fail "rtpbr-diff $* should print one stderr line, got: $(cat err.txt)"
    fi
}

# json_check FILE PYTHON_EXPR: loads the JSON object as d and asserts the expression.
json_check() {
    "$python" -c 'import json, sys
d = json.load(open(sys.argv[1]))
keys = ["mean", "median", "p95", "p99", "max", "rmse", "relmse", "psnr", "width", "height", "mode", "ppd"]
missing = [k for k in keys if k not in d]
assert not missing, "missing keys %s" % missing
assert eval(sys.argv[2]), "failed: %s on %s" % (sys.argv[2], d)' "$1" "$2" || fail "JSON check '$2'"
}

case $case_name in
exit-codes)
    expect 0 ref.png ref_copy.png --max-mean 0 --max-p95 0
    expect 0 ref.png slight.png --max-mean 0.5 --max-p95 0.9
    expect 0 ref.png strong.png
    expect 1 ref.png strong.png --max-mean 0.01
    grep -q "exceeds --max-mean" err.txt || fail "threshold message: $(cat err.txt)"
    expect 1 ref.png strong.png --max-p95 0.01
    grep -q "exceeds --max-p95" err.txt || fail "threshold message: $(cat err.txt)"
    expect 1 ref.png slight.png --max-mean 0.5 --max-p95 0.0001
    expect 0 ref.exr test.exr --hdr --max-mean 1
    expect 1 ref.exr test.exr --hdr --max-mean 0.0001
    expect 0 --help
    ;;
errors)
    expect 2 missing.png ref.png
    grep -q "missing.png" err.txt || fail "missing file not named: $(cat err.txt)"
    expect 2 ref.png missing.png
    expect 2 not_an_image.png ref.png
    head -c 2000 strong.png >truncated.png
    LSAN_OPTIONS=${IMGDIFF_TRUNCATED_PNG_LSAN:-} expect 2 truncated.png strong.png
    head -c 300 ref.exr >truncated.exr
    expect 2 ref.exr truncated.exr
    expect 2 ref.png small.png
    grep -q "size mismatch" err.txt || fail "size mismatch message: $(cat err.txt)"
    expect 2 ref.png
    expect 2
    expect 2 ref.png ref.png --bogus
    expect 2 ref.png ref.png --ppd abc
    expect 2 ref.png ref.png --ppd 0
    expect 2 ref.png ref.png --ppd nan
    expect 2 ref.png ref.png --max-mean
    expect 2 ref.png ref.png --max-mean -1
    expect 2 ref.png ref.png --heatmap no/such/dir/heat.png
    ;;
json)
    expect 0 ref.png ref_copy.png --json
    json_check out.txt 'd["mean"] == 0 and d["max"] == 0 and d["psnr"] is None and d["rmse"] == 0'
    expect 0 ref.png slight.png --json
    json_check out.txt 'd["width"] == 64 and d["height"] == 48 and d["mode"] == "ldr-flip" and d["ppd"] == 67'
    json_check out.txt '0 < d["median"] <= d["p95"] <= d["p99"] <= d["max"] <= 1 and 0 < d["mean"] < 1'
    cp out.txt slight.json
    expect 0 ref.png strong.png --json --ppd 30
    json_check out.txt 'd["ppd"] == 30 and d["psnr"] > 0'
    expect 0 ref.png strong.png --json
    cp out.txt strong.json
    "$python" -c 'import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert a["mean"] < b["mean"] and a["rmse"] < b["rmse"] and a["psnr"] > b["psnr"], (a, b)' slight.json strong.json ||
        fail "stronger noise should give larger errors"
    expect 0 ref.exr test.exr --hdr --json
    json_check out.txt 'd["mode"] == "hdr-flip" and d["exposure_count"] >= 2 and 0 < d["mean"] < 1'
    ;;
memory)
    # PNGs whose IHDR claims 8000 x 8000 (within the pixel limit) over one tiny IDAT: the need,
    # 7.63 GiB at 128 bytes a pixel, is counted from the headers and refused before any pixel
    # is read; without the check rtpbr-diff reads both (and fails on the data, or runs).
    "$python" -c 'import struct, sys, zlib
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 8000, 8000, 8, 2, 0, 0, 0))
open(sys.argv[1], "wb").write(png + chunk(b"IDAT", zlib.compress(b"\0" * 64)) + chunk(b"IEND", b""))' big.png ||
        fail "cannot write big.png"
    expect 2 big.png big.png --memory-limit 1024
    grep -q "comparing two 8000x8000 images needs 7.63 GiB of memory" err.txt || fail "memory message: $(cat err.txt)"
    expect 0 ref.png ref_copy.png --memory-limit 1  # 64 x 48 x 128 bytes fit in 1 MiB
    expect 2 ref.png ref_copy.png --memory-limit 0
    expect 2 ref.png ref_copy.png --memory-limit 1.5
    ;;
heatmap)
    expect 0 ref.png strong.png --heatmap heat.png
    [[ -s heat.png ]] || fail "heat map not written"
    expect 0 heat.png heat.png --json
    json_check out.txt 'd["width"] == 64 and d["height"] == 48'
    expect 0 ref.png ref_copy.png --heatmap zero.png
    # No error maps to magma's first entry (0.001462, 0.000466, 0.013866) -> sRGB bytes (0, 0, 4).
    expect 0 zero.png zero.png --json
    ;;
*)
    echo "unknown case '$case_name'"
    exit 1
    ;;
esac

if [[ $failures -ne 0 ]]; then
    echo "$failures check(s) failed"
    exit 1
fi
echo "cli $case_name: all checks passed"
