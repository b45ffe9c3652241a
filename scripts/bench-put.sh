#!/usr/bin/env bash
# How fast a put carries a file: a headless provider taking every put
# (--puts always), umf-requester put of SIZE_MB random megabytes from a
# straight photo of that provider's screen, over loopback TLS. Prints the
# requester's own hashing, the whole put (hash, aim, ask, upload, the
# provider hashing and storing), and sha256sum on the same file for scale.
# Usage: scripts/bench-put.sh [BUILD] [SIZE_MB] [RUNS]
set -euo pipefail
build=${1:-build/release}
size_mb=${2:-500}
runs=${3:-3}
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
cleanup() { kill $(jobs -p) 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT

head -c "$((size_mb * 1000000))" /dev/urandom >"$work/carried.bin"
"$build/bin/umf-provider" compose --board "$here/tests/web/browser/board/board.json" --screen 1920x1080 \
  --preset kiosk --time 0.75 --out "$work/screen.png" --map "$work/map.json" --config-dir "$work/cfg" >/dev/null 2>&1
: >"$work/provider.log"  # there before the child opens it, so the first read finds it
"$build/bin/umf-provider" --headless --port 0 --no-qr --config-dir "$work/cfg" --puts always \
  --put-dir "$work/received" >>"$work/provider.log" 2>&1 &
url=
for _ in $(seq 100); do url=$(sed -n 's/^pairing URL: //p' "$work/provider.log"); [ -n "$url" ] && break; sleep 0.1; done
[ -n "$url" ] || { echo "no provider"; cat "$work/provider.log"; exit 1; }

now() { date +%s.%N; }
t0=$(now); sha256sum "$work/carried.bin" >/dev/null; t1=$(now)
printf 'sha256sum %d MB: %.2f s\n' "$size_mb" "$(echo "$t1 - $t0" | bc)"
for run in $(seq "$runs"); do
  t0=$(now)
  XDG_CONFIG_HOME="$work/phone" "$build/bin/umf-requester" put "$work/carried.bin" --url "$url" \
    --image "$work/screen.png" >"$work/out.json" 2>"$work/put.log"
  t1=$(now)
  seconds=$(echo "$t1 - $t0" | bc)
  printf 'put %d MB, run %d: %.2f s, %.0f MB/s end to end\n' "$size_mb" "$run" "$seconds" \
    "$(echo "$size_mb / $seconds" | bc -l)"
  grep -q '"ok":true' "$work/out.json" || { cat "$work/out.json" "$work/put.log"; exit 1; }
  cmp -s "$work/carried.bin" "$work/received/$(sed 's/.*"name":"\([^"]*\)".*/\1/' "$work/out.json")" ||
    { echo "the file arrived changed"; exit 1; }
  rm -f "$work/received/"*
done
