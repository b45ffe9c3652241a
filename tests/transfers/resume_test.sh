#!/bin/bash
# A large transfer through a connection that is cut once in the middle: a
# real provider on loopback TLS, umf-requester aiming at a picture of its
# screen, and between them a relay (tests/support/cutting_relay.py) that
# resets the transfer's connection when half the file has passed.
#   grab: the board's one tile is SIZE_MB random megabytes; the requester
#         asks for the rest (Range) and must end with the whole file.
#   put:  the requester puts SIZE_MB random megabytes (--puts always); it
#         asks how much arrived (HEAD) and sends the rest (Upload-Offset),
#         and the screen must end with the whole file.
# Either way the SHA-256 is checked, the requester says it resumed, and at
# most 1.25 times the file crossed the relay.
#   put_changed: a put whose file changes (a byte before the cut) at the
#         moment of the cut: the resumed request says the SHA-256 of the
#         bytes the screen should hold, the screen refuses it (412), and the
#         put ends there with the reason (exit 3): nothing kept, the rest
#         never sent.
#   put_changed_uncut: the same change half way, the connection left be:
#         the requester names the hash of the file as it is at the end, the
#         screen finds its bytes are not that file, and the put ends with
#         the reason (exit 3), nothing kept.
# usage: resume_test.sh BUILD_DIR grab|put|put_changed|put_changed_uncut [SIZE_MB]
set -euo pipefail
build=$(cd "$1" && pwd)
mode=$2
size_mb=${3:-1024}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/umf-resume-XXXXXX)
bin=$build/bin
source "$here/../support/provider_run.sh"
relay_pid=
cleanup() {
  local rc=$?
  stop_provider || rc=1
  [ -n "$relay_pid" ] && kill "$relay_pid" 2>/dev/null
  [ -n "${KEEP_WORK:-}" ] || rm -rf "$work"
  exit $rc
}
trap cleanup EXIT
case $mode in grab | put | put_changed | put_changed_uncut) ;;
*) echo "usage: resume_test.sh BUILD_DIR grab|put|put_changed|put_changed_uncut [SIZE_MB]"; exit 2 ;; esac

size=$((size_mb << 20))
mkdir -p "$work/board" "$work/out" "$work/received"
head -c "$size" /dev/urandom >"$work/board/big.bin"
printf '{"format": "umf-board/1", "title": "Resume", "columns": 1,\n "items": [{"title": "Big", "file": "big.bin"}]}\n' \
  >"$work/board/board.json"
"$bin/umf-provider" compose --board "$work/board/board.json" --screen 1920x1080 --preset kiosk --time 0.75 \
  --out "$work/screen.png" --map "$work/map.json" --config-dir "$work/cfg" >/dev/null
puts=always
start_provider "$work/provider.log" --bind 127.0.0.1 --config-dir "$work/cfg" --board "$work/board/board.json" \
  --put-dir "$work/received" --put-max-mb $((size_mb * 2))

direction=down
change=()
[ "$mode" != grab ] && direction=up
[ "$mode" = put_changed ] && change=("$work/board/big.bin" 1000)
[ "$mode" = put_changed_uncut ] && change=("$work/board/big.bin" 1000 keep)
python3 "$here/../support/cutting_relay.py" "$port" "$((size / 2))" "$work/counts" "$direction" "${change[@]}" \
  >"$work/relay.port" &
relay_pid=$!
for _ in $(seq 50); do [ -s "$work/relay.port" ] && break; sleep 0.1; done
relay_port=$(head -1 "$work/relay.port")
[ -n "$relay_port" ] || { echo "FAIL: the relay did not start"; exit 1; }
relay_url=${url/:$port\//:$relay_port/}

status=0
if [ "$mode" = grab ]; then
  XDG_CONFIG_HOME="$work/phone" "$bin/umf-requester" grab --url "$relay_url" --image "$work/screen.png" \
    --out "$work/out" >"$work/requester.json" 2>"$work/requester.log" || status=$?
else
  XDG_CONFIG_HOME="$work/phone" "$bin/umf-requester" put "$work/board/big.bin" --url "$relay_url" \
    --image "$work/screen.png" >"$work/requester.json" 2>"$work/requester.log" || status=$?
fi
grep -E 'saved .* in |sent [0-9.]+ MB in ' "$work/requester.log" || true
if [ "$mode" = put_changed ]; then
  [ "$status" -eq 3 ] || { echo "FAIL: exit $status, not 3:"; cat "$work/requester.json"; tail -20 "$work/requester.log"; exit 1; }
  grep -q 'not the start of this file' "$work/requester.json" ||
    { echo "FAIL: the reason is not given:"; cat "$work/requester.json"; exit 1; }
  [ -z "$(ls -A "$work/received")" ] || { echo "FAIL: something was kept:"; ls -A "$work/received"; exit 1; }
  read -r down up <"$work/counts"
  [ "$up" -lt $(( size * 3 / 4 )) ] || { echo "FAIL: $up bytes went up after the file changed"; exit 1; }
  echo "ok: the changed file was refused at the resume, after $up of $size bytes: $(grep -o '"message":"[^"]*"' "$work/requester.json")"
  exit 0
fi
if [ "$mode" = put_changed_uncut ]; then
  [ "$status" -eq 3 ] || { echo "FAIL: exit $status, not 3:"; cat "$work/requester.json"; tail -20 "$work/requester.log"; exit 1; }
  grep -q 'changed while it was being sent' "$work/requester.json" ||
    { echo "FAIL: the reason is not given:"; cat "$work/requester.json"; exit 1; }
  [ -z "$(ls -A "$work/received")" ] || { echo "FAIL: something was kept:"; ls -A "$work/received"; exit 1; }
  echo "ok: the file changed while it was sent was not kept: $(grep -o '"message":"[^"]*"' "$work/requester.json")"
  exit 0
fi
[ "$status" -eq 0 ] ||
  { echo "FAIL: $mode exit $status:"; cat "$work/requester.json"; tail -20 "$work/requester.log"; exit 1; }
grep -q 'the connection was lost at ' "$work/requester.log" ||
  { echo "FAIL: the transfer was not cut, or the requester did not say it resumed:"; cat "$work/requester.log"; exit 1; }
arrived=$work/out
[ "$mode" = put ] && arrived=$work/received
cmp -s "$work/board/big.bin" "$arrived/big.bin" || { echo "FAIL: the file arrived changed"; ls -la "$arrived"; exit 1; }
[ "$(ls -A "$arrived")" = "big.bin" ] || { echo "FAIL: more than the file was left:"; ls -A "$arrived"; exit 1; }
read -r down up <"$work/counts"
carried=$down
[ "$mode" = put ] && carried=$up
echo "carried $down bytes down and $up up for a file of $size bytes ($(( carried * 100 / size )) %)"
[ "$carried" -le $(( size * 5 / 4 )) ] || { echo "FAIL: more than 1.25 times the file was carried"; exit 1; }
echo "ok: a $mode of $size_mb MiB cut at half resumed and arrived whole"
