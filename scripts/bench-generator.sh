#!/usr/bin/env bash
# Generator benchmark: time to a verified binary 4-orientable field with 4 x 4
# windows at several sizes, and k-ary fields at screen sizes. Prints a Markdown
# table for docs/BENCHMARKS.md. Usage: scripts/bench-generator.sh [BUILD_DIR] [LIMIT_S]
# UMF_BENCH_LARGE=1 adds 93 x 93, 94 x 94 and 110 x 110 (each up to LIMIT_S).
set -euo pipefail
build=${1:-build/release}
limit=${2:-1800}
tool="$build/bin/umf-field"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%Y-%m-%d)"
echo
echo "| field | window | colours | seed | result | seconds |"
echo "|---|---|---|---|---|---|"
run() {  # width height window colors seed
    local start end status
    start=$(date +%s%N)
    set +e
    "$tool" generate --width "$1" --height "$2" --window "$3" --colors "$4" --seed "$5" \
        --time-limit "$limit" --quiet --out "$tmp/f.json" >/dev/null 2>&1
    status=$?
    set -e
    end=$(date +%s%N)
    local result="verified"
    if [ $status -ne 0 ]; then result="not reached in ${limit} s"; else "$tool" verify "$tmp/f.json" >/dev/null; fi
    printf "| %s x %s | %s | %s | %s | %s | %.2f |\n" "$1" "$2" "$3" "$4" "$5" "$result" "$(awk -v a="$start" -v b="$end" 'BEGIN { print (b - a) / 1e9 }')"
}
# The 4 x 4 binary sizes of the method's Table 3 (its largest fields) and the
# screen sizes, three seeds each.
for size in "64 36" "92 92" "110 78" "122 61" "159 53" "120 68"; do
    for seed in 1 2 3; do run $size 4 2 $seed; done
done
# k-ary candidates at screen sizes.
for size in "64 36 4 3" "128 72 4 3" "64 36 3 5"; do
    set -- $size
    run "$1" "$2" "$3" "$4" 1
done
# Beyond: squares past 92 x 92, each with the time limit.
if [ "${UMF_BENCH_LARGE:-0}" = 1 ]; then
    for side in 93 94 110; do run $side $side 4 2 1; done
fi
