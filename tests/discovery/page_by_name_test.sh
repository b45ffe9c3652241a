#!/bin/bash
# The phone page and the screens' .local names, with a real Avahi daemon on
# each side of a veth pair: the screens (this script's network, mount and
# UTS namespaces, host name umf-screen-test) and the phone (namespaces of
# their own, host name umf-phone, where Chromium runs SCENARIO of
# tests/web/browser/run.mjs). Names cross the link by multicast DNS as
# between two machines; nothing leaves the namespaces.
#   name_follows   the page follows the screen's name to a new address
#   nearby_screen  a second screen (b, a field of its own) runs beside it;
#                  the page of the first, pointed at b, offers b's page
# usage: page_by_name_test.sh SCENARIO BUILD_DIR NODE CHROMIUM SITE BOARD FIXTURES MODULES
set -euo pipefail
scenario=$1 build=$2 node=$3 chromium=$4 site=$5 board=$6 fixtures=$7 modules=$8
bin=$build/bin
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../support/avahi_namespace.sh"
[ "${UMF_IN_NETNS:-}" = 1 ] || own_namespaces "avahi-daemon dbus-daemon nsenter certutil getent" "$0" "$@"
source "$here/../support/provider_run.sh"
work=$(mktemp -d /tmp/umf-page-name-XXXXXX)
phone= phone_net= b_pid=
cleanup() {
  local rc=$? pid
  stop_provider || rc=1
  [ -z "$b_pid" ] || end_process "$b_pid" "umf-provider b" || rc=1
  stop_avahi "$work/screen"
  stop_avahi "$work/phone"
  # Whatever still runs in the phone's namespaces (the sleeper, a Chromium
  # helper that outlived the runner) ends here, so nothing holds the test.
  if [ -n "$phone_net" ]; then
    for pid in $(ls /proc | grep -E '^[0-9]+$'); do
      [ "$(readlink "/proc/$pid/ns/net" 2>/dev/null)" = "$phone_net" ] && kill -9 "$pid" 2>/dev/null
    done
  fi
  rm -rf "$work" 2>/dev/null || { sleep 1; rm -rf "$work"; } || true
  exit $rc
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
phone_net=$(readlink /proc/$phone/ns/net)
[ "$phone_net" != "$(readlink /proc/$$/ns/net)" ] || { phone_net=; echo "FAIL: the phone's namespaces were not made"; exit 1; }
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

if [ "$scenario" = nearby_screen ]; then
  # Screen b first, so that the first screen's first browse finds it: the
  # field of the video other_screen_tile0.y4m, the same board.
  mkdir -p "$work/cfg-b" && cp "$(dirname "$board")/other-field-seed" "$work/cfg-b/field-seed"
  start_provider "$work/provider-b.log" --config-dir "$work/cfg-b" --board "$board" --screen 1920x1080 --web "$site"
  b_pid=$provider_pid b_url=$url b_port=$port provider_pid=
  for _ in $(seq 100); do grep -q '^announced: ' "$work/provider-b.log" && break; sleep 0.1; done
  "$bin/umf-provider" trust export "$work/root-b.pem" --config-dir "$work/cfg-b" 2>/dev/null
fi
mkdir -p "$work/cfg" && cp "$(dirname "$board")/field-seed" "$work/cfg/"  # the field the video shows
start_provider "$work/provider.log" --config-dir "$work/cfg" --board "$board" --screen 1920x1080 --web "$site"
for _ in $(seq 100); do grep -q '^announced: ' "$work/provider.log" && break; sleep 0.1; done
grep -q '^announced: .* at https://umf-screen-test.local:' "$work/provider.log" ||
  { echo "FAIL: the provider did not announce itself:"; cat "$work/provider.log"; exit 1; }
[[ $url == "https://10.78.0.1:$port/#"*"&n=umf-screen-test.local" ]] ||
  { echo "FAIL: the pairing URL is not the address with the name: $url"; exit 1; }
"$bin/umf-provider" trust export "$work/root.pem" --config-dir "$work/cfg" 2>/dev/null
echo "ok: $(grep '^announced: ' "$work/provider.log")"

if [ "$scenario" = nearby_screen ]; then
  for _ in $(seq 100); do grep -q '^nearby: ' "$work/provider.log" && break; sleep 0.1; done
  grep -q "^nearby: 1 other screen(s): \"umf on umf-screen-test\" at https://umf-screen-test.local:$b_port\$" "$work/provider.log" ||
    { echo "FAIL: the first screen does not list b nearby:"; cat "$work/provider.log"; exit 1; }
  echo "ok: $(grep '^nearby: ' "$work/provider.log")"
  extra=(--other-pairing "$b_url" --other-root "$work/root-b.pem")
else
  # The move: the screen leaves 10.78.0.1 for 10.78.0.3 (a new lease).
  move="nsenter -t $$ -n sh -c 'ip addr del 10.78.0.1/24 dev umf0 && ip addr add 10.78.0.3/24 dev umf0'"
  extra=(--move "$move" --new-address 10.78.0.3)
fi
status=0
in_phone env HOME="$work" "$node" "$here/../web/browser/run.mjs" --scenario "$scenario" \
  --provider "$bin/umf-provider" --site "$site" --board "$board" --fixtures "$fixtures" --modules "$modules" \
  --chromium "$chromium" --pairing "$url" --root "$work/root.pem" "${extra[@]}" || status=$?
if [ "$scenario" = nearby_screen ] && [ "$status" = 0 ]; then
  # What was taken came from b, and the first screen gave nothing away.
  grep -q ' took "' "$work/provider-b.log" || { echo "FAIL: b's log shows no grab"; status=1; }
  ! grep -q ' took "' "$work/provider.log" || { echo "FAIL: the first screen gave something away"; status=1; }
fi
if [ "$status" != 0 ]; then
  echo "--- provider:"; cat "$work/provider.log"
  [ -f "$work/provider-b.log" ] && { echo "--- provider b:"; cat "$work/provider-b.log"; }
  [ "$status" = 77 ] || for side in screen phone; do echo "--- the $side's avahi-daemon:"; tail -20 "$work/$side/avahi.log"; done
fi
exit "$status"
