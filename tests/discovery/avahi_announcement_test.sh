#!/bin/bash
# The provider announced over DNS-SD through a real Avahi daemon, in network,
# mount and UTS namespaces of the test's own (a veth pair for multicast, a
# private system bus, the host name "umf-screen-test"): avahi-browse finds
# _umf._tcp with the port and the root's fingerprint (never the token), the
# name resolves, the serving certificate names it, umf-requester whose
# pairing URL names an address the screen left finds it by its name, and a
# provider with no Avahi to talk to says so and serves on.
# usage: avahi_announcement_test.sh BUILD_DIR
set -euo pipefail
bin=$1/bin
source "$(dirname "$0")/../support/avahi_namespace.sh"
[ "${UMF_IN_NETNS:-}" = 1 ] || own_namespaces "avahi-daemon avahi-browse avahi-resolve dbus-daemon" "$0" "$@"
hostname umf-screen-test
ip link set lo up
ip link add umf0 type veth peer name umf1
ip link set umf1 up
ip link set umf0 multicast on up
ip addr add 10.78.0.1/24 dev umf0
work=$(mktemp -d /tmp/umf-avahi-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
cleanup() {
  local rc=$?
  stop_provider || rc=1
  stop_avahi "$work"
  rm -rf "$work"
  exit $rc
}
trap cleanup EXIT
# The requester's own configuration: the screens it keeps are this test's.
export XDG_CONFIG_HOME=$work/requester-config

# No Avahi yet, and no system bus: the provider says so and serves.
export DBUS_SYSTEM_BUS_ADDRESS=unix:path=$work/bus
start_provider "$work/alone.log" --config-dir "$work/cfg"
for _ in $(seq 50); do grep -q '^announced: ' "$work/alone.log" && break; sleep 0.1; done
grep -q '^announced: nowhere (.*); phones find this screen by its address only$' "$work/alone.log" ||
  { echo "FAIL: a provider without Avahi did not say so:"; cat "$work/alone.log"; exit 1; }
curl -sk -o /dev/null "$origin/" || { echo "FAIL: the provider without Avahi does not serve"; exit 1; }
echo "ok: without Avahi: $(grep '^announced: ' "$work/alone.log")"
# umf-requester discover asks the same missing Avahi: it says so, and that the pairing URL still works.
rc=0
"$bin/umf-requester" discover >"$work/discover.out" 2>"$work/discover.err" || rc=$?
[ "$rc" = 4 ] && [ ! -s "$work/discover.out" ] &&
  grep -qx 'discover: cannot ask Avahi (.*); is avahi-daemon running? A screen can still be reached by its pairing URL\.' "$work/discover.err" ||
  { echo "FAIL: discover without Avahi exited $rc, not 4 with its message:"; cat "$work/discover.out" "$work/discover.err"; exit 1; }
echo "ok: discover without Avahi exits 4: $(cat "$work/discover.err")"
stop_provider

# A private system bus at $work/bus (avahi-daemon reads DBUS_SYSTEM_BUS_ADDRESS) and the
# daemon on umf0 only, its pid file and runtime socket in a /run private to this mount namespace.
mount -t tmpfs tmpfs /run
start_avahi "$work" umf0

# One link over the whole screen, and the screen as shown, for a grab.
one_link_board "Found by name" https://example.org/found-by-name
start_provider "$work/provider.log" --config-dir "$work/cfg" --board "$work/board.json" --screen 1920x1080
for _ in $(seq 100); do grep -q '^announced: ' "$work/provider.log" && break; sleep 0.1; done
line=$(grep '^announced: ' "$work/provider.log" || true)
[[ $line == "announced: \"umf on umf-screen-test\" (_umf._tcp) at https://umf-screen-test.local:$port through Avahi" ]] ||
  { echo "FAIL: the provider did not announce itself: ${line:-nothing}"; cat "$work/provider.log" "$work/avahi.log"; exit 1; }
fp=${url##*fp=}
fp=${fp%%&*}
token=${url#*#t=}
token=${token%%&*}
found=$(avahi-browse -rpt _umf._tcp)
grep -q "^=;umf0;IPv4;umf\\\\032on\\\\032umf-screen-test;_umf._tcp;local;umf-screen-test.local;10.78.0.1;$port;.*\"fp=$fp\"" <<<"$found" ||
  { echo "FAIL: avahi-browse does not find the screen with its port and fingerprint:"; echo "$found"; exit 1; }
if grep -q "$token" <<<"$found"; then echo "FAIL: the token is announced"; exit 1; fi
[ "$(avahi-resolve -4 -n umf-screen-test.local | cut -f2)" = 10.78.0.1 ] ||
  { echo "FAIL: umf-screen-test.local does not resolve to 10.78.0.1"; exit 1; }
echo "ok: $line; avahi-browse: $(grep '^=' <<<"$found")"

# The certificate names the announced name and the address: a browser that trusts the root opens either.
"$bin/umf-provider" trust export "$work/root.pem" --config-dir "$work/cfg" 2>/dev/null
servername=umf-screen-test.local verified 10.78.0.1 -verify_hostname umf-screen-test.local ||
  { echo "FAIL: the certificate does not verify for umf-screen-test.local"; exit 1; }
servername= verified 10.78.0.1 -verify_ip 10.78.0.1 || { echo "FAIL: the certificate does not verify for 10.78.0.1"; exit 1; }
echo "ok: the serving certificate verifies against the root for umf-screen-test.local and 10.78.0.1"

# A pairing URL whose address the screen no longer has: the requester finds
# it by the .local name the URL also carries (resolved through Avahi by
# nss-mdns, as a desktop's resolver is set up).
[[ $url == *"&n=umf-screen-test.local" ]] || { echo "FAIL: the pairing URL carries no .local name: $url"; exit 1; }
if mdns_nsswitch "$work/nsswitch.conf"; then
  mount --bind "$work/nsswitch.conf" /etc/nsswitch.conf
  moved="https://10.78.0.99:$port/#${url#*#}"
  out=$("$bin/umf-requester" grab --url "$moved" --image "$work/screen.png" --no-window --out "$work/received" \
        2>"$work/requester.err") || { echo "FAIL: the requester did not find the screen by name: $out"; cat "$work/requester.err"; exit 1; }
  grep -q '"url":"https://example.org/found-by-name"' <<<"$out" || { echo "FAIL: the grab took something else: $out"; exit 1; }
  echo "ok: umf-requester with the address 10.78.0.99 (gone) found the screen as umf-screen-test.local: $out"
else
  echo "FAIL: libnss-mdns is not installed (scripts/install-deps.sh installs it): nothing here resolves .local names"
  exit 1
fi

# umf-requester discover lists the screen through the same daemon: its name, the
# .local name and port, the address and the root's fingerprint; --url marks it paired.
listed=$("$bin/umf-requester" discover 2>"$work/discover.err") ||
  { echo "FAIL: discover did not find the screen:"; cat "$work/discover.err"; exit 1; }
[ "$listed" = "umf on umf-screen-test  https://umf-screen-test.local:$port  10.78.0.1  fp $fp" ] ||
  { echo "FAIL: discover lists something else: $listed"; exit 1; }
listed_json=$("$bin/umf-requester" discover --json 2>"$work/discover.err") ||
  { echo "FAIL: discover --json did not find the screen:"; cat "$work/discover.err"; exit 1; }
[ "$listed_json" = "{\"name\":\"umf on umf-screen-test\",\"host\":\"umf-screen-test.local\",\"port\":$port,\"addresses\":[\"10.78.0.1\"],\"fingerprint\":\"$fp\",\"version\":\"1\"}" ] ||
  { echo "FAIL: discover --json lists something else: $listed_json"; exit 1; }
paired=$("$bin/umf-requester" discover --url "$url" 2>"$work/discover.err") ||
  { echo "FAIL: discover --url did not find the screen:"; cat "$work/discover.err"; exit 1; }
[ "$paired" = "$listed  (paired)" ] || { echo "FAIL: discover --url does not mark the screen paired: $paired"; exit 1; }
paired_json=$("$bin/umf-requester" discover --json --url "$url" 2>"$work/discover.err") ||
  { echo "FAIL: discover --json --url did not find the screen:"; cat "$work/discover.err"; exit 1; }
[ "$paired_json" = "${listed_json%\}},\"paired\":true}" ] ||
  { echo "FAIL: discover --json --url does not say paired: $paired_json"; exit 1; }
if grep -q "$token" <<<"$listed $listed_json $paired $paired_json"; then echo "FAIL: discover shows the token"; exit 1; fi
echo "ok: discover: $paired; --json: $listed_json"
"$bin/umf-requester" pair "$url" >/dev/null 2>"$work/pair.err" ||
  { echo "FAIL: umf-requester pair did not keep the screen:"; cat "$work/pair.err"; exit 1; }
kept=$("$bin/umf-requester" discover 2>"$work/discover.err")
[ "$kept" = "$listed  (paired)" ] || { echo "FAIL: discover does not mark the kept screen paired: $kept"; exit 1; }
echo "ok: a screen kept with umf-requester pair is marked without --url: $kept"

# Stopped, the provider withdraws its announcement.
stop_provider
sleep 1
if avahi-browse -rpt _umf._tcp | grep -q '^='; then echo "FAIL: the announcement outlived the provider"; exit 1; fi
echo "ok: the announcement is withdrawn when the provider stops"
# Nothing announced any more: discover prints nothing and says so on stderr.
rc=0
"$bin/umf-requester" discover --timeout 1 >"$work/discover.out" 2>"$work/discover.err" || rc=$?
[ "$rc" = 5 ] && [ ! -s "$work/discover.out" ] && grep -qx 'discover: no screen answered within 1 s' "$work/discover.err" ||
  { echo "FAIL: discover with no screen exited $rc, not 5 with nothing listed:"; cat "$work/discover.out" "$work/discover.err"; exit 1; }
echo "ok: discover --timeout 1 with no screen exits 5, nothing on stdout: $(cat "$work/discover.err")"
