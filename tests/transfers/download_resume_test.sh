#!/bin/bash
# A large grab through a connection that is cut once in the middle: a real
# provider on loopback TLS serves a board whose one tile is SIZE_MB random
# megabytes, umf-requester grabs it from a picture of the screen through a
# relay (tests/support/cutting_relay.py) that resets the download's
# connection when half the file has passed. The requester must ask for the
# rest and finish with the whole file, its SHA-256 checked, having carried
# at most 1.25 times its size.
# usage: download_resume_test.sh BUILD_DIR [SIZE_MB]
set -euo pipefail
build=$(cd "$1" && pwd)
size_mb=${2:-1024}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/umf-resume-XXXXXX)
bin=$build/bin
source "$here/../support/provider_run.sh"
relay_pid=
cleanup() {
  stop_provider
  [ -n "$relay_pid" ] && kill "$relay_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

size=$((size_mb << 20))
mkdir -p "$work/board" "$work/out"
head -c "$size" /dev/urandom >"$work/board/big.bin"
printf '{"format": "umf-board/1", "title": "Resume", "columns": 1,\n "items": [{"title": "Big", "file": "big.bin"}]}\n' \
  >"$work/board/board.json"
"$bin/umf-provider" compose --board "$work/board/board.json" --screen 1920x1080 --preset kiosk --time 0.75 \
  --out "$work/screen.png" --map "$work/map.json" --config-dir "$work/cfg" >/dev/null
start_provider "$work/provider.log" --bind 127.0.0.1 --config-dir "$work/cfg" --board "$work/board/board.json"

python3 "$here/../support/cutting_relay.py" "$port" "$((size / 2))" "$work/counts" >"$work/relay.port" &
relay_pid=$!
for _ in $(seq 50); do [ -s "$work/relay.port" ] && break; sleep 0.1; done
relay_port=$(head -1 "$work/relay.port")
[ -n "$relay_port" ] || { echo "FAIL: the relay did not start"; exit 1; }
relay_url=${url/:$port\//:$relay_port/}

status=0
started=$(date +%s.%N)
XDG_CONFIG_HOME="$work/phone" "$bin/umf-requester" grab --url "$relay_url" --image "$work/screen.png" \
  --out "$work/out" >"$work/grab.json" 2>"$work/grab.log" || status=$?
echo "grab took $(echo "$(date +%s.%N) - $started" | bc) s"
cat "$work/grab.log" | tail -5
[ "$status" -eq 0 ] || { echo "FAIL: grab exit $status:"; cat "$work/grab.json"; tail -20 "$work/grab.log"; exit 1; }
grep -q 'the connection was lost at .*; resuming in' "$work/grab.log" ||
  { echo "FAIL: the download was not cut, or did not say it resumed:"; cat "$work/grab.log"; exit 1; }
cmp -s "$work/board/big.bin" "$work/out/big.bin" || { echo "FAIL: the file arrived changed"; exit 1; }
[ "$(ls -A "$work/out")" = "big.bin" ] || { echo "FAIL: more than the file was left:"; ls -A "$work/out"; exit 1; }
sleep 0.2  # the relay writes its counts as each connection ends
read -r down up <"$work/counts"
echo "carried $down bytes down and $up up for a file of $size bytes ($(( down * 100 / size )) %)"
[ "$down" -le $(( size * 5 / 4 )) ] || { echo "FAIL: more than 1.25 times the file was carried"; exit 1; }
echo "ok: a grab of $size_mb MiB cut at half resumed and arrived whole"
