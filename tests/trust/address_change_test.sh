#!/bin/bash
# A new address while the provider runs, in a network namespace of the
# test's own (nothing leaves it): the serving certificate is issued again
# within seconds for the new address, the root (and so every pairing) stays,
# and the webcam requester, given the old pairing URL with the new address,
# connects and grabs without pairing again.
# usage: address_change_test.sh BUILD_DIR
set -euo pipefail
bin=$1/bin
if [ "${UMF_IN_NETNS:-}" != 1 ]; then
  if ! unshare --net true 2>/dev/null; then
    echo "SKIP: no network namespace can be made here (unshare --net needs CAP_SYS_ADMIN)"
    exit 77
  fi
  exec unshare --net env UMF_IN_NETNS=1 bash "$0" "$@"
fi
ip link set lo up
work=$(mktemp -d /tmp/umf-address-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
trap 'rc=$?; stop_provider || rc=1; rm -rf "$work"; exit $rc' EXIT

# One link over the whole screen, and the screen as shown, for a grab.
one_link_board "Address change" https://example.org/after-the-move
start_provider "$work/provider.log" --config-dir "$work/cfg" --board "$work/board.json" --screen 1920x1080
"$bin/umf-provider" trust export "$work/root.pem" --config-dir "$work/cfg" 2>/dev/null
before=$(der_sha256 "$work/cfg/serving-cert.pem")
servername= verified 127.0.0.1 -verify_ip 127.0.0.1 || { echo "FAIL: 127.0.0.1 does not verify"; exit 1; }

ip addr add 10.77.0.1/24 dev lo
started=$(date +%s%3N)
for _ in $(seq 100); do
  grep -q '^certificate: issued again' "$work/provider.log" && break
  sleep 0.1
done
grep -q '^certificate: issued again' "$work/provider.log" ||
  { echo "FAIL: no certificate issued for 10.77.0.1 within 10 s:"; cat "$work/provider.log"; exit 1; }
took=$(( $(date +%s%3N) - started ))
[ "$(der_sha256 "$work/cfg/serving-cert.pem")" != "$before" ] || { echo "FAIL: the serving certificate is the old one"; exit 1; }
servername= verified 10.77.0.1 -verify_ip 10.77.0.1 || { echo "FAIL: 10.77.0.1 does not verify against the root"; exit 1; }
echo "ok: the certificate was issued again for 10.77.0.1 in ${took} ms: $(grep '^certificate: issued again' "$work/provider.log")"

# The pairing URL made before the move, pointed at the new address.
moved="https://10.77.0.1:$port/#${url#*#}"
out=$("$bin/umf-requester" grab --url "$moved" --image "$work/screen.png" --no-window --out "$work/received" 2>"$work/requester.err") ||
  { echo "FAIL: the requester could not grab at the new address: $out"; cat "$work/requester.err"; exit 1; }
grep -q '"url":"https://example.org/after-the-move"' <<<"$out" || { echo "FAIL: the grab took something else: $out"; exit 1; }
echo "ok: umf-requester grabbed at 10.77.0.1 with the pairing URL made before the move: $out"
