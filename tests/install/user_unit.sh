#!/bin/bash
# The installed systemd user unit (umf-provider.service) under a user systemd
# of its own: enable it, start it, and a headless provider serves; kill it
# and systemd starts it again; stop it and it stays stopped. A user manager
# runs only where the system was booted with systemd, which it tells by
# /run/systemd/system: a mount namespace of this script's own holds that
# folder (a tmpfs over /run/systemd), so the machine's /run is left as it is.
# usage: user_unit.sh WORK_DIR   (exit 77: cannot run here; needs root)
set -euo pipefail
work=$1
if [ "${2-}" != inside ]; then
  unshare -m --propagation private true 2>/dev/null || { echo "SKIP: no mount namespace here (unshare -m)"; exit 77; }
  [ -x /lib/systemd/systemd ] || { echo "SKIP: systemd is not installed"; exit 77; }
  exec unshare -m --propagation private bash "$0" "$work" inside
fi
fail() { echo "FAIL: $*"; systemctl --user status umf-provider --no-pager 2>&1 | tail -15 || true; exit 1; }

mkdir -p /run/systemd
mount -t tmpfs tmpfs /run/systemd
mkdir /run/systemd/system
export XDG_RUNTIME_DIR=$work/runtime XDG_CONFIG_HOME=$work/config HOME=$work/home
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
mkdir -p "$XDG_CONFIG_HOME/umf" "$HOME"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
# What a kiosk puts in ~/.config/umf/provider.env (the unit's comment).
echo "UMF_PROVIDER_ARGS=--headless --port $port --config-dir $work/cfg --puts never" >"$XDG_CONFIG_HOME/umf/provider.env"

/lib/systemd/systemd --user >"$work/systemd.log" 2>&1 &
manager=$!
trap 'systemctl --user exit 2>/dev/null || kill "$manager" 2>/dev/null; wait "$manager" 2>/dev/null || true' EXIT
for _ in $(seq 100); do
  systemctl --user is-system-running >/dev/null 2>&1 && break
  sleep 0.1
done
systemctl --user is-system-running >/dev/null 2>&1 || { cat "$work/systemd.log"; fail "the user manager did not start"; }

serving() {
  for _ in $(seq 150); do
    [ "$(curl -sk -o /dev/null -w '%{http_code}' "https://127.0.0.1:$port/")" = 200 ] && return 0
    sleep 0.1
  done
  return 1
}
main_pid() { systemctl --user show -p MainPID --value umf-provider; }

systemctl --user enable --now umf-provider >/dev/null 2>&1 || fail "systemctl --user enable --now umf-provider"
[ -L "$XDG_CONFIG_HOME/systemd/user/default.target.wants/umf-provider.service" ] ||
  fail "enable made no link in default.target.wants"
serving || fail "the unit's provider does not serve on port $port"
first=$(main_pid)
[ "$first" -gt 0 ] || fail "the unit has no main process"
kill -9 "$first"
second=0
for _ in $(seq 150); do
  second=$(main_pid)
  [ "$second" -gt 0 ] && [ "$second" != "$first" ] && break
  sleep 0.1
done
[ "$second" -gt 0 ] && [ "$second" != "$first" ] || fail "killed, the provider was not started again"
serving || fail "started again, the provider does not serve"
systemctl --user stop umf-provider
[ "$(systemctl --user is-active umf-provider || true)" = inactive ] || fail "stopped, the unit is not inactive"
echo "ok: the user unit served on $port (pid $first), was started again when killed (pid $second), and stopped"
