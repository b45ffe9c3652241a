# Sourced by the shell tests that run a provider (tests/trust, discovery,
# install, transfers): start_provider LOG ARGS... starts $bin/umf-provider headless in
# the background (--puts never unless $puts says otherwise; stop_provider
# ends it) and waits for its pairing URL; sets
# $provider_pid, $url, $port and $origin.
provider_pid=
stop_provider() {
  if [ -n "$provider_pid" ]; then
    kill "$provider_pid" 2>/dev/null || true
    wait "$provider_pid" 2>/dev/null || true
    provider_pid=
  fi
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
