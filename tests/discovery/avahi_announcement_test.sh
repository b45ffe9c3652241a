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
if [ "${UMF_IN_NETNS:-}" != 1 ]; then
  for tool in avahi-daemon avahi-browse avahi-resolve dbus-daemon unshare; do
    command -v "$tool" >/dev/null || { echo "SKIP: $tool is not installed (scripts/install-deps.sh installs it)"; exit 77; }
  done
  if ! unshare --net --mount --uts true 2>/dev/null; then
    echo "SKIP: no network namespace can be made here (unshare --net needs CAP_SYS_ADMIN)"
    exit 77
  fi
  exec unshare --net --mount --uts env UMF_IN_NETNS=1 bash "$0" "$@"
fi
hostname umf-screen-test
ip link set lo up
ip link add umf0 type veth peer name umf1
ip link set umf1 up
ip link set umf0 multicast on up
ip addr add 10.78.0.1/24 dev umf0
work=$(mktemp -d /tmp/umf-avahi-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
daemons=()
cleanup() {
  stop_provider
  for pid in "${daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# No Avahi yet, and no system bus: the provider says so and serves.
export DBUS_SYSTEM_BUS_ADDRESS=unix:path=$work/bus
start_provider "$work/alone.log" --config-dir "$work/cfg"
for _ in $(seq 50); do grep -q '^announced: ' "$work/alone.log" && break; sleep 0.1; done
grep -q '^announced: nowhere (.*); phones find this screen by its address only$' "$work/alone.log" ||
  { echo "FAIL: a provider without Avahi did not say so:"; cat "$work/alone.log"; exit 1; }
curl -sk -o /dev/null "$origin/" || { echo "FAIL: the provider without Avahi does not serve"; exit 1; }
echo "ok: without Avahi: $(grep '^announced: ' "$work/alone.log")"
stop_provider

# A private system bus (avahi-daemon reads DBUS_SYSTEM_BUS_ADDRESS) and the daemon on umf0 only.
cat >"$work/bus.conf" <<XML
<!DOCTYPE busconfig PUBLIC "-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN"
 "http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd">
<busconfig>
  <type>system</type>
  <listen>unix:path=$work/bus</listen>
  <auth>EXTERNAL</auth>
  <policy context="default">
    <allow user="*"/> <allow own="*"/> <allow send_destination="*"/> <allow receive_sender="*"/>
  </policy>
</busconfig>
XML
cat >"$work/avahi.conf" <<CONF
[server]
use-ipv4=yes
use-ipv6=no
allow-interfaces=umf0
enable-dbus=yes
[wide-area]
enable-wide-area=no
[publish]
publish-hinfo=no
publish-workstation=no
CONF
dbus-daemon --config-file="$work/bus.conf" --nofork >"$work/bus.log" 2>&1 &
daemons+=($!)
for _ in $(seq 50); do [ -S "$work/bus" ] && break; sleep 0.1; done
# The daemon's pid file and runtime socket go to /run/avahi-daemon, private to this mount namespace.
mount -t tmpfs tmpfs /run
avahi-daemon --no-drop-root --no-chroot --no-rlimits -f "$work/avahi.conf" >"$work/avahi.log" 2>&1 &
daemons+=($!)
for _ in $(seq 100); do grep -q 'Server startup complete' "$work/avahi.log" && break; sleep 0.1; done
grep -q 'Server startup complete' "$work/avahi.log" || { echo "FAIL: avahi-daemon did not start:"; cat "$work/avahi.log"; exit 1; }

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
if [ -e /usr/lib/x86_64-linux-gnu/libnss_mdns4_minimal.so.2 ] || ls /lib/*/libnss_mdns4_minimal.so.2 >/dev/null 2>&1; then
  echo 'hosts: files mdns4_minimal [NOTFOUND=return] dns' >"$work/nsswitch.conf"
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

# Stopped, the provider withdraws its announcement.
stop_provider
sleep 1
if avahi-browse -rpt _umf._tcp | grep -q '^='; then echo "FAIL: the announcement outlived the provider"; exit 1; fi
echo "ok: the announcement is withdrawn when the provider stops"
