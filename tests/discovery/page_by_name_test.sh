#!/bin/bash
# The phone page follows the screen's .local name to a new address, with a
# real Avahi daemon on each side of a veth pair: the screen (this script's
# network, mount and UTS namespaces, host name umf-screen-test) and the
# phone (namespaces of their own, host name umf-phone, where Chromium runs
# the scenario name_follows of tests/web/browser/run.mjs). The name crosses
# the link by multicast DNS as between two machines; nothing leaves the
# namespaces.
# usage: page_by_name_test.sh BUILD_DIR NODE CHROMIUM SITE BOARD FIXTURES MODULES
set -euo pipefail
build=$1 node=$2 chromium=$3 site=$4 board=$5 fixtures=$6 modules=$7
bin=$build/bin
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../support/avahi_namespace.sh"
[ "${UMF_IN_NETNS:-}" = 1 ] || own_namespaces "avahi-daemon dbus-daemon nsenter certutil getent" "$0" "$@"
source "$here/../support/provider_run.sh"
work=$(mktemp -d /tmp/umf-page-name-XXXXXX)
phone=
cleanup() {
  stop_provider
  stop_avahi "$work/screen"
  stop_avahi "$work/phone"
  [ -n "$phone" ] && kill "$phone" 2>/dev/null
  wait 2>/dev/null || true
  # Chromium's helpers may outlive it by a moment: a second try, never a failure.
  rm -rf "$work" 2>/dev/null || { sleep 1; rm -rf "$work"; } || true
}
trap cleanup EXIT
mdns_nsswitch "$work/nsswitch.conf" ||
  { echo "FAIL: libnss-mdns is not installed (scripts/install-deps.sh installs it): nothing here resolves .local names"; exit 1; }

# The phone: namespaces held by a sleeping process, entered with nsenter.
unshare --net --mount --uts sleep infinity &
phone=$!
for _ in $(seq 50); do
  [ "$(readlink /proc/$phone/ns/net)" != "$(readlink /proc/$$/ns/net)" ] && break
  sleep 0.1
done
in_phone() { nsenter -t "$phone" -n -m -u "$@"; }

hostname umf-screen-test
ip link set lo up
ip link add umf0 type veth peer name umf1
ip link set umf1 netns "$phone"
ip link set umf0 multicast on up
ip addr add 10.78.0.1/24 dev umf0
in_phone bash -c "hostname umf-phone && ip link set lo up && ip link set umf1 multicast on up &&
                  ip addr add 10.78.0.2/24 dev umf1 && mount -t tmpfs tmpfs /run &&
                  mount --bind '$work/nsswitch.conf' /etc/nsswitch.conf"
mount -t tmpfs tmpfs /run
start_avahi "$work/screen" umf0
in_phone bash -c "source '$here/../support/avahi_namespace.sh' && start_avahi '$work/phone' umf1"
export DBUS_SYSTEM_BUS_ADDRESS=unix:path=$work/screen/bus

mkdir -p "$work/cfg" && cp "$(dirname "$board")/field-seed" "$work/cfg/"  # the field the video shows
start_provider "$work/provider.log" --config-dir "$work/cfg" --board "$board" --screen 1920x1080 --web "$site"
for _ in $(seq 100); do grep -q '^announced: ' "$work/provider.log" && break; sleep 0.1; done
grep -q '^announced: .* at https://umf-screen-test.local:' "$work/provider.log" ||
  { echo "FAIL: the provider did not announce itself:"; cat "$work/provider.log"; exit 1; }
[[ $url == "https://10.78.0.1:$port/#"*"&n=umf-screen-test.local" ]] ||
  { echo "FAIL: the pairing URL is not the address with the name: $url"; exit 1; }
"$bin/umf-provider" trust export "$work/root.pem" --config-dir "$work/cfg" 2>/dev/null
echo "ok: $(grep '^announced: ' "$work/provider.log")"

# The move: the screen leaves 10.78.0.1 for 10.78.0.3 (a new lease).
move="nsenter -t $$ -n sh -c 'ip addr del 10.78.0.1/24 dev umf0 && ip addr add 10.78.0.3/24 dev umf0'"
status=0
in_phone env HOME="$work" "$node" "$here/../web/browser/run.mjs" --scenario name_follows \
  --provider "$bin/umf-provider" --site "$site" --board "$board" --fixtures "$fixtures" --modules "$modules" \
  --chromium "$chromium" --pairing "$url" --root "$work/root.pem" --move "$move" --new-address 10.78.0.3 || status=$?
if [ "$status" != 0 ]; then
  echo "--- provider:"; cat "$work/provider.log"
  [ "$status" = 77 ] || for side in screen phone; do echo "--- the $side's avahi-daemon:"; tail -20 "$work/$side/avahi.log"; done
fi
exit "$status"
