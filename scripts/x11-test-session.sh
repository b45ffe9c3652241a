#!/bin/bash
# A throwaway X11 desktop to try the provider's window resolvers by hand:
# Xvfb on a free display, openbox, and the programs given (default: an
# xterm). Prints the display, runs until interrupted (or --seconds N), then
# stops what it started.
#
#   scripts/x11-test-session.sh mupdf ~/report.pdf -- xterm -T notes
#   DISPLAY=:N build/release/bin/umf-provider ...   # in another terminal
#
# Needs: xvfb openbox (and the programs named).
set -euo pipefail

seconds=0
if [[ ${1:-} == --seconds ]]; then seconds=$2; shift 2; fi
size=${UMF_X11_SIZE:-1280x800x24}

for program in Xvfb openbox; do
    command -v "$program" >/dev/null || { echo "$0: $program is not installed (apt-get install xvfb openbox)" >&2; exit 1; }
done

source "$(dirname "$0")/background.sh"  # work, pids, spawn; everything stopped on exit, the server last

# Xvfb picks a free display and writes its number once it accepts clients.
mkfifo "$work/display"
# (Started here, not by spawn: the FIFO is opened in the background child,
# since opening it for writing waits for its reader below.)
Xvfb -displayfd 3 -screen 0 "$size" -nolisten tcp -noreset 3>"$work/display" 2>"$work/xvfb.log" &
pids=("$!" "${pids[@]}")
read -r number <"$work/display" || { cat "$work/xvfb.log" >&2; exit 1; }
export DISPLAY=":$number"

spawn openbox --sm-disable >/dev/null 2>&1
sleep 0.5

# Programs separated by "--".
(($# == 0)) && set -- xterm -T "umf test xterm"
while (($# > 0)); do
    command=()
    while (($# > 0)) && [[ $1 != -- ]]; do command+=("$1"); shift; done
    (($# > 0)) && shift
    spawn "${command[@]}" >/dev/null 2>&1
done

echo "DISPLAY=$DISPLAY"
# In the background, so a signal's trap runs at once rather than after it.
if ((seconds > 0)); then spawn sleep "$seconds"; else spawn sleep infinity; fi
wait "${pids[0]}"
