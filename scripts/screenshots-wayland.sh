#!/bin/bash
# Makes the README's picture of the provider on a Wayland desktop,
# docs/images/sway-desktop.png: a headless Sway (run as an unprivileged user)
# with a native foot and an Xwayland xterm showing text files and a grey
# foot, the field over them on the overlay layer, as the desktop's own
# screencopy sees it. It is the end-to-end test SwayProvider run with
# UMF_SCREENSHOT_DIR set, so the picture is of what that test checks.
#
#   scripts/screenshots-wayland.sh                 # writes docs/images/sway-desktop.png
#   UMF_SCREENSHOTS_OUT=/tmp/shots scripts/screenshots-wayland.sh
#
# Needs: sway foot xterm xwayland (scripts/install-deps.sh), root (to make
# the test user). Builds nothing: run `make` first if the binaries are stale.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tests=${UMF_TESTS:-$root/build/release/tests/umf_tests}
out=${UMF_SCREENSHOTS_OUT:-$root/docs/images}
mkdir -p "$out"
UMF_SCREENSHOT_DIR="$out" "$tests" --gtest_filter='SwayProvider.*'
echo "wrote $out/sway-desktop.png"
