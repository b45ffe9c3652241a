#!/usr/bin/env bash
# After a failed ctest run: each failed test's name and the last lines of its
# output, from the build's Testing/Temporary/LastTest.log. Printed last, so a
# CI log cut to its beginning and end still shows why each test failed.
# usage: scripts/ci-failures.sh [BUILD_DIR] [LINES]
set -uo pipefail
build=${1:-build/release}
lines=${2:-40}
failed="$build/Testing/Temporary/LastTestsFailed.log"
log="$build/Testing/Temporary/LastTest.log"
[ -s "$failed" ] || { echo "ci-failures: no failed tests recorded in $failed"; exit 0; }
[ -f "$log" ] || { echo "ci-failures: no $log"; exit 0; }
while IFS=: read -r _ name; do
  echo "==== $name: the last $lines lines of its output"
  # The block between "N/M Test: NAME" and its "<end of output>".
  awk -v name="$name" '
    $0 ~ /^[0-9]+\/[0-9]+ Test: / { sub(/^[0-9]+\/[0-9]+ Test: /, ""); inside = ($0 == name); next }
    inside && /^<end of output>/ { inside = 0 }
    inside' "$log" | tail -n "$lines"
done <"$failed"
