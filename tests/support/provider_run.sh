# Sourced by the shell tests that run a provider (tests/trust, discovery,
# install, transfers): start_provider LOG ARGS... starts $bin/umf-provider headless in
# the background (--puts never unless $puts says otherwise; stop_provider
# ends it, end_process PID NAME any other) and waits for its pairing URL; sets
# $provider_pid, $url, $port and $origin.
provider_pid=
# end_process PID NAME: SIGTERM, and the process gone within 15 s; where it
# is not, its threads' stacks (gdb) and SIGKILL, and status 1: a program that
# does not end on SIGTERM is a fault of its own, not something to wait out.
end_process() {
  local pid=$1 name=$2
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 150); do
    kill -0 "$pid" 2>/dev/null || { wait "$pid" 2>/dev/null; return 0; }
    sleep 0.1
  done
  echo "FAIL: $name (pid $pid) did not exit within 15 s of SIGTERM; its threads:"
  command -v gdb >/dev/null &&
    timeout 60 gdb -p "$pid" -batch -ex 'thread apply all bt' 2>/dev/null | grep -E '^(Thread|#)' | head -120
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  return 1
}
# Fails (status 1) where the provider did not end on SIGTERM.
stop_provider() {
  local pid=$provider_pid
  provider_pid=
  [ -z "$pid" ] || end_process "$pid" umf-provider
}
start_provider() {
  local log=$1
  shift
  # The log exists before the provider starts, so a first read finds it.
  : >"$log"
  "$bin/umf-provider" --headless --port 0 --no-qr --puts "${puts:-never}" "$@" >>"$log" 2>&1 &
  provider_pid=$!
  url=
  for _ in $(seq 200); do
    url=$(sed -n 's/^pairing URL: //p' "$log")
    [ -n "$url" ] && break
    sleep 0.1
  done
  [ -n "$url" ] || { echo "FAIL: the provider printed no pairing URL:"; cat "$log"; exit 1; }
  port=$(sed -n 's/^umf-provider: listening on https:\/\/[^ ]*:\([0-9]*\) .*/\1/p' "$log")
  origin=${url%%/#*}
}
# The SHA-256 of a PEM certificate's DER, as pairing URLs carry it.
der_sha256() { openssl x509 -in "$1" -outform DER | sha256sum | cut -d' ' -f1; }
# s_client's verdict for the provider at ADDRESS, verifying NAME (-verify_hostname or -verify_ip).
verified() {
  local address=$1 how=$2 name=$3 connect
  connect=$address
  [[ $address == *:* ]] && connect="[$address]"
  openssl s_client -connect "$connect:$port" -CAfile "$work/root.pem" -verify_return_error "$how" "$name" \
    ${servername:+-servername "$servername"} </dev/null 2>&1 | grep -q 'Verify return code: 0 (ok)'
}
# A board of one URL over the whole screen ($work/board.json) and that screen
# as shown ($work/screen.png), so a grab from the screen's picture takes URL.
one_link_board() {
  local title=$1 link=$2
  printf '{"format": "umf-board/1", "title": "%s", "columns": 1,\n "items": [{"title": "Project site", "url": "%s"}]}\n' \
    "$title" "$link" >"$work/board.json"
  "$bin/umf-provider" compose --board "$work/board.json" --screen 1920x1080 --preset kiosk --time 0.75 \
    --out "$work/screen.png" --map "$work/map.json" --config-dir "$work/cfg" >/dev/null
}
