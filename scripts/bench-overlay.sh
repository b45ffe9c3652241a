#!/usr/bin/env bash
# CPU the desktop overlay costs while it pulses: umf-provider with an
# always-on preset over a 1920 x 1080 Xvfb screen with openbox and xcompmgr,
# measured from /proc over SECONDS seconds, for the provider and for the
# compositor (which does the blending). Usage: scripts/bench-overlay.sh [BUILD] [SECONDS]
set -euo pipefail
build=${1:-build/release}
seconds=${2:-10}
work=$(mktemp -d)
cleanup() { kill $(jobs -p) 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT

Xvfb :91 -screen 0 1920x1080x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
sleep 1
export DISPLAY=:91 QT_QPA_PLATFORM=xcb
openbox --sm-disable >/dev/null 2>&1 &
sleep 0.5
xcompmgr >/dev/null 2>&1 &
comp=$!
sleep 0.5
"$build/bin/umf-provider" --port 0 --no-qr --config-dir "$work/cfg" --preset visible >"$work/log" 2>&1 &
prov=$!
for _ in $(seq 50); do grep -q "overlay:" "$work/log" && break; sleep 0.2; done
grep "overlay:" "$work/log"
sleep 1  # settle

ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
hz=$(getconf CLK_TCK)
p0=$(ticks $prov); c0=$(ticks $comp); x0=$(ticks $xvfb)
sleep "$seconds"
p1=$(ticks $prov); c1=$(ticks $comp); x1=$(ticks $xvfb)
# The X server does the blending xcompmgr asks for (XRender, in software
# under Xvfb): its CPU is the overlay's real cost on this machine.
awk -v p=$((p1 - p0)) -v c=$((c1 - c0)) -v x=$((x1 - x0)) -v hz="$hz" -v s="$seconds" 'BEGIN {
  printf "provider: %.2f s CPU in %d s = %.1f %% of one core\n", p / hz, s, 100 * p / hz / s
  printf "xcompmgr: %.2f s CPU in %d s = %.1f %% of one core\n", c / hz, s, 100 * c / hz / s
  printf "Xvfb (the blending): %.2f s CPU in %d s = %.1f %% of one core\n", x / hz, s, 100 * x / hz / s }'
