# Sourced by the tests that run a real Avahi daemon in namespaces of their
# own (tests/discovery). start_avahi DIR IFACE starts a private system bus at
# DIR/bus and avahi-daemon on IFACE only (IPv4, no wide-area, publishing
# nothing of its own; no AAAA records over IPv4 either, so that a resolve
# gives the IPv4 address even once the kernel has given IFACE its IPv6
# link-local one), its pid file and socket in /run, which the caller
# mounted as a tmpfs private to its mount namespace; the pids go to
# DIR/pids, which stop_avahi DIR reads.

# own_namespaces "TOOL..." SCRIPT ARGS...: SCRIPT again, with ARGS, in
# network, mount and UTS namespaces of its own (UMF_IN_NETNS=1 there);
# exits 77 saying why where a tool is missing or no namespace can be made.
own_namespaces() {
  local tools=$1 tool
  shift
  for tool in $tools unshare; do
    command -v "$tool" >/dev/null || { echo "SKIP: $tool is not installed (scripts/install-deps.sh installs it)"; exit 77; }
  done
  if ! unshare --net --mount --uts true 2>/dev/null; then
    echo "SKIP: no network namespace can be made here (unshare --net needs CAP_SYS_ADMIN)"
    exit 77
  fi
  exec unshare --net --mount --uts env UMF_IN_NETNS=1 bash "$@"
}
start_avahi() {
  local dir=$1 iface=$2
  mkdir -p "$dir"
  cat >"$dir/bus.conf" <<XML
<!DOCTYPE busconfig PUBLIC "-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN"
 "http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd">
<busconfig>
  <type>system</type>
  <listen>unix:path=$dir/bus</listen>
  <auth>EXTERNAL</auth>
  <policy context="default">
    <allow user="*"/> <allow own="*"/> <allow send_destination="*"/> <allow receive_sender="*"/>
  </policy>
</busconfig>
XML
  cat >"$dir/avahi.conf" <<CONF
[server]
use-ipv4=yes
use-ipv6=no
allow-interfaces=$iface
enable-dbus=yes
[wide-area]
enable-wide-area=no
[publish]
publish-hinfo=no
publish-workstation=no
publish-aaaa-on-ipv4=no
CONF
  dbus-daemon --config-file="$dir/bus.conf" --nofork >"$dir/bus.log" 2>&1 &
  echo $! >>"$dir/pids"
  for _ in $(seq 50); do [ -S "$dir/bus" ] && break; sleep 0.1; done
  DBUS_SYSTEM_BUS_ADDRESS=unix:path=$dir/bus \
    avahi-daemon --no-drop-root --no-chroot --no-rlimits -f "$dir/avahi.conf" >"$dir/avahi.log" 2>&1 &
  echo $! >>"$dir/pids"
  for _ in $(seq 100); do grep -q 'Server startup complete' "$dir/avahi.log" && break; sleep 0.1; done
  grep -q 'Server startup complete' "$dir/avahi.log" || { echo "FAIL: avahi-daemon did not start:"; cat "$dir/avahi.log"; return 1; }
}
stop_avahi() {
  [ -f "$1/pids" ] || return 0
  kill $(cat "$1/pids") 2>/dev/null || true
  rm -f "$1/pids"
}
# Where libnss-mdns is installed, a nsswitch.conf at $1 that asks Avahi for .local names first.
mdns_nsswitch() {
  [ -e /usr/lib/x86_64-linux-gnu/libnss_mdns4_minimal.so.2 ] || ls /lib/*/libnss_mdns4_minimal.so.2 >/dev/null 2>&1 ||
    return 1
  echo 'hosts: files mdns4_minimal [NOTFOUND=return] dns' >"$1"
}
