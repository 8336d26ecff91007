#!/bin/bash
# Fit time of rtpbr-ltcfit (issue 19). Runs each given binary REPEATS times, the binaries
# alternating (so both see the same load), at --size SIZE with --threads THREADS into a scratch
# directory, and prints each run's wall and process CPU time (user + system, all threads), the
# medians and, with two binaries, the ratio of the medians (BIN over BIN_BEFORE) and whether
# their last runs wrote the same header (speed-ups meant to keep the tables must).
#
#   bench/ltcfit_time.sh [-s SIZE] [-t THREADS] [-r REPEATS] BIN [BIN_BEFORE]
#
# On a shared machine the wall time is inflated by other work; the CPU time is the number to
# compare (wall on T free cores is about CPU / T plus the serial start of each lobe).
set -euo pipefail
usage="usage: $0 [-s SIZE] [-t THREADS] [-r REPEATS] BIN [BIN_BEFORE]
  -s SIZE     table cells per side (default 24)
  -t THREADS  threads of each fit (default 2)
  -r REPEATS  runs of each binary (default 3)
  -h, --help  this text"
[ "${1:-}" = --help ] && { echo "$usage"; exit 0; }
size=24 threads=2 repeats=3
while getopts "hs:t:r:" o; do
    case $o in
        h) echo "$usage"; exit 0 ;;
        s) size=$OPTARG ;;
        t) threads=$OPTARG ;;
        r) repeats=$OPTARG ;;
        *) echo "$usage" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "$usage" >&2
    exit 2
fi
for b in "$@"; do
    [ -x "$b" ] || { echo "$0: $b is not an executable" >&2; exit 1; }
done
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
declare -a walls cpus
for ((r = 0; r < repeats; r++)); do
    i=0
    for b in "$@"; do
        out="$scratch/bin$i"
        mkdir -p "$out"
        start=$(date +%s.%N)
        # the child's user + system time, from bash's `time` keyword
        cpu=$( { TIMEFORMAT='%U %S'; time "$b" --out "$out" --size "$size" --threads "$threads" >/dev/null 2>"$out/log"; } 2>&1 | awk '{ print $1 + $2 }')
        wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
        printf 'run %d, %s: wall %.1f s, CPU %.1f s\n' "$r" "$b" "$wall" "$cpu"
        walls[$i]+="$wall "
        cpus[$i]+="$cpu "
        i=$((i + 1))
    done
done
i=0
for b in "$@"; do
    mw=$(echo "${walls[$i]}" | tr ' ' '\n' | grep . | median)
    mc=$(echo "${cpus[$i]}" | tr ' ' '\n' | grep . | median)
    printf '%s: median wall %.1f s, median CPU %.1f s (size %d, %d threads, %d runs)\n' "$b" "$mw" "$mc" "$size" "$threads" "$repeats"
    eval "mw$i=$mw mc$i=$mc"
    i=$((i + 1))
done
if [ $# -eq 2 ]; then
    printf 'ratio (%s / %s): wall %.2f, CPU %.2f\n' "$1" "$2" "$(awk -v a="$mw0" -v b="$mw1" 'BEGIN { print a / b }')" \
        "$(awk -v a="$mc0" -v b="$mc1" 'BEGIN { print a / b }')"
    if cmp -s "$scratch/bin0/rtpbr_ltc_tables.h" "$scratch/bin1/rtpbr_ltc_tables.h"; then
        echo "tables: byte-identical"
    else
        echo "tables: DIFFER"
    fi
fi
