#!/bin/bash
# Two screens in one room, each provider with a configuration of its own:
# their fields differ (each screen's own, the default), compose draws the
# field its provider shows, and umf-requester paired with one screen takes
# that screen's link from its picture and nothing from the other screen's,
# saying it is another screen, or switching to it when it keeps that
# screen's pairing too (umf-requester pair), where with the shipped field on
# both screens (--shipped-field) it took the wrong screen's.
# usage: two_screens_test.sh BUILD_DIR
set -euo pipefail
build=$1
bin=$build/bin
work=$(mktemp -d /tmp/umf-two-screens-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
pids=()
trap 'kill "${pids[@]}" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT

# Screen S: a board of one link over the whole screen, the screen as shown
# ($work/S/screen.png), and its provider (its pairing URL in ${urls[S]}).
declare -A urls
# The seeds of screens a and b, fixed so that their pictures are the same in every run.
declare -A seeds=([a]=7e1d5c0ffee0b0a7 [b]=3b9f02d6a4c8e571)
screen() {
  local s=$1 field=$2
  mkdir -p "$work/$s/cfg"
  [ -z "${seeds[$s]:-}" ] || echo "${seeds[$s]}" >"$work/$s/cfg/field-seed"
  printf '{"format": "umf-board/1", "title": "Screen %s", "columns": 1,\n "items": [{"title": "Link", "url": "%s"}]}\n' \
    "$s" "https://example.org/screen-$s" >"$work/$s/board.json"
  "$bin/umf-provider" compose --board "$work/$s/board.json" --screen 1920x1080 --preset kiosk --time 0.75 $field \
    --out "$work/$s/screen.png" --map "$work/$s/map.json" --config-dir "$work/$s/cfg" >/dev/null
  start_provider "$work/$s.log" --config-dir "$work/$s/cfg" --board "$work/$s/board.json" --screen 1920x1080 \
    --bind 127.0.0.1 $field
  pids+=("$provider_pid")
  provider_pid=
  urls[$s]=$url
}
field_id() { sed -n 's/.*"field_id": "\([^"]*\)".*/\1/p' "$work/$1/map.json"; }
# Grab with screen PAIRED's URL (- for none: the screen kept or used last)
# from screen SHOWN's picture, with more options: the JSON line, and the
# exit code in $status.
grab() {
  local paired=$1 shown=$2
  shift 2
  local url=()
  [ "$paired" = - ] || url=(--url "${urls[$paired]}")
  status=0
  out=$("$bin/umf-requester" grab "${url[@]}" --image "$work/$shown/screen.png" --no-window \
        --out "$work/received" "$@" 2>"$work/requester.err") || status=$?
}
# The requester's own configuration: the screens it keeps are this test's.
export XDG_CONFIG_HOME=$work/requester-config

screen a ""
screen b ""
[ "$(field_id a)" != "$(field_id b)" ] && [[ $(field_id a) == b4-64x36-* ]] ||
  { echo "FAIL: the two screens do not show fields of their own: $(field_id a), $(field_id b)"; exit 1; }
grep -q "field $(field_id a)" "$work/a.log" ||
  { echo "FAIL: provider a does not show the field compose drew ($(field_id a)):"; cat "$work/a.log"; exit 1; }
echo "ok: two fields of their own: a $(field_id a), b $(field_id b); the provider shows what compose drew"

for s in a b; do
  grab "$s" "$s"
  [ "$status" = 0 ] && grep -q "\"url\":\"https://example.org/screen-$s\"" <<<"$out" ||
    { echo "FAIL: paired with $s, the picture of $s gave ($status): $out"; cat "$work/requester.err"; exit 1; }
  echo "ok: paired with $s, the picture of $s: $out"
done
# A picture of the whole other screen holds all its 2,000 windows, where
# chance gives a few of them a common place in this field; with a's and b's
# seeds, b's picture seen by a says "another screen" and a's seen by b only
# "not found" (a camera's view holds far fewer: web.browser.another_screen).
said_another=()
for pair in "a b" "b a"; do
  set -- $pair
  grab "$1" "$2"
  [ "$status" = 5 ] && ! grep -q '"url"' <<<"$out" ||
    { echo "FAIL: paired with $1, the picture of $2 gave ($status): $out"; exit 1; }
  grep -q '"code":"another_screen"' <<<"$out" && said_another+=("$1")
  echo "ok: paired with $1, the picture of $2 takes nothing (exit 5): $out"
done

[[ " ${said_another[*]} " == *" a "* ]] ||
  { echo "FAIL: paired with a, the picture of b did not say it is another screen"; exit 1; }

# Screens kept with `umf-requester pair`: paired with a, b's picture
# switches to b, kept too, and takes b's link; without --url the screen used
# last answers, or the kept one in view; --no-switch stops as before.
for s in b a; do
  "$bin/umf-requester" pair "${urls[$s]}" >"$work/pair.out" 2>"$work/requester.err" ||
    { echo "FAIL: umf-requester pair ${urls[$s]} failed:"; cat "$work/requester.err"; exit 1; }
done
kept=$XDG_CONFIG_HOME/umf/requester-screens.json
[ "$(stat -c %a "$kept")" = 600 ] || { echo "FAIL: $kept is not 0600"; exit 1; }
[ "$("$bin/umf-requester" pair --list | wc -l)" = 2 ] || { echo "FAIL: pair --list does not list two screens"; exit 1; }
if "$bin/umf-requester" pair --list | grep -q "t="; then echo "FAIL: pair --list shows a token"; exit 1; fi
echo "ok: two screens kept (0600), listed without their tokens"
grab a b
[ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-b"' <<<"$out" &&
  grep -q "switching to it" "$work/requester.err" ||
  { echo "FAIL: paired with a and b, b's picture with a's URL gave ($status): $out"; cat "$work/requester.err"; exit 1; }
echo "ok: paired with a and b, a's URL and b's picture: switched to b and took b's link"
# A hand-held camera's video of b: a second of "another screen", then the switch.
camera=$build/tests/web/umf_fake_camera
if [ -x "$camera" ]; then
  "$camera" --provider "$bin/umf-provider" --board "$work/b/board.json" --field-seed "$work/b/cfg/field-seed" \
    --frames 60 --out "$work/b.y4m" --work "$work/camera" >/dev/null
  status=0
  out=$("$bin/umf-requester" grab --url "${urls[a]}" --video "$work/b.y4m" --auto --no-window \
        --out "$work/received" 2>"$work/requester.err") || status=$?
  [ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-b"' <<<"$out" &&
    grep -q "switching to it" "$work/requester.err" ||
    { echo "FAIL: a's URL, a video of b gave ($status): $out"; cat "$work/requester.err"; exit 1; }
  echo "ok: a's URL, a camera's video of b: switched to b once it said another screen, and took b's link"
else
  echo "skipped: the video of b ($camera is not built: the web tests need emscripten and node)"
fi
grab - b
[ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-b"' <<<"$out" &&
  ! grep -q "switching" "$work/requester.err" ||
  { echo "FAIL: without --url, b (used last) did not answer its picture ($status): $out"; exit 1; }
grab - a
[ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-a"' <<<"$out" ||
  { echo "FAIL: without --url, a's picture did not switch to a ($status): $out"; cat "$work/requester.err"; exit 1; }
echo "ok: without --url, the screen used last answers, and the kept screen in view when it is another"
grab a b --no-switch
[ "$status" = 5 ] && grep -q '"code":"another_screen"' <<<"$out" ||
  { echo "FAIL: --no-switch, a's URL and b's picture gave ($status): $out"; exit 1; }
"$bin/umf-requester" pair --forget "${urls[b]}" 2>/dev/null
grab a b
[ "$status" = 5 ] && ! grep -q '"url"' <<<"$out" ||
  { echo "FAIL: b forgotten, a's URL and b's picture gave ($status): $out"; exit 1; }
echo "ok: with --no-switch, or b forgotten, b's picture takes nothing: $out"

# A new pairing and field for a while it runs (pair --rotate --field): it
# takes both at once. The old URL is refused; with the new one, a picture
# composed anew takes a's link, and the picture of the old field nothing.
a_port=${urls[a]#https://127.0.0.1:}
a_port=${a_port%%/*}
old_id=$(field_id a)
mkdir -p "$work/old-a" && cp "$work/a/screen.png" "$work/old-a/screen.png"
urls[a-old]=${urls[a]}
urls[a]=$("$bin/umf-provider" pair --rotate --field --config-dir "$work/a/cfg" --port "$a_port" --host 127.0.0.1 \
          --no-qr 2>"$work/rotate.err")
grep -q "takes only the new pairing now" "$work/rotate.err" && grep -q "shows the new field now" "$work/rotate.err" ||
  { echo "FAIL: the running provider did not take the rotation:"; cat "$work/rotate.err"; exit 1; }
"$bin/umf-provider" compose --board "$work/a/board.json" --screen 1920x1080 --preset kiosk --time 0.75 \
  --out "$work/a/screen.png" --map "$work/a/map.json" --config-dir "$work/a/cfg" >/dev/null
[ "$(field_id a)" != "$old_id" ] && grep -q "^field: $(field_id a) " "$work/a.log" ||
  { echo "FAIL: a does not show the new field $(field_id a) compose drew (was $old_id):"; tail -3 "$work/a.log"; exit 1; }
grab a a --no-switch
[ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-a"' <<<"$out" ||
  { echo "FAIL: the new URL and a's new picture gave ($status): $out"; cat "$work/requester.err"; exit 1; }
grab a old-a --no-switch
[ "$status" = 5 ] && ! grep -q '"url"' <<<"$out" ||
  { echo "FAIL: the new URL and the picture of a's old field gave ($status): $out"; exit 1; }
grab a-old a --no-switch
[ "$status" != 0 ] && grep -q '"code":"unauthorized"' <<<"$out" ||
  { echo "FAIL: the old URL after the rotation gave ($status): $out"; exit 1; }
echo "ok: rotated while it runs, a shows $(field_id a) (was $old_id), takes the new URL only, and its new picture gives a's link"

# The same two screens with the shipped field: the wrong screen answers.
screen c --shipped-field
screen d --shipped-field
grab c d
[ "$status" = 0 ] && grep -q '"url":"https://example.org/screen-c"' <<<"$out" ||
  { echo "FAIL: with the shipped field on both, expected screen c's link from d's picture, got ($status): $out"; exit 1; }
echo "ok: with the shipped field on both screens, paired with c, the picture of d took c's link: $out"
