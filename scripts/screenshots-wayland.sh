#!/bin/bash
# Makes the README's pictures of the provider on Wayland desktops,
# docs/images/sway-desktop.png, gnome-desktop.png and kde-desktop.png: a
# headless Sway and a headless GNOME Shell (each run as an unprivileged
# user) with a native foot and an Xwayland xterm showing text files and a
# grey foot, and a virtual KWin compositing with OpenGL (llvmpipe) with a
# native weston-image showing a picture, an Xwayland xterm showing a text
# file and a grey xterm; the field over them (Sway and KWin: on the layer
# shell, as the compositor's own screenshot sees it; GNOME: the umf
# extension's actor, as Shell's screenshot sees it). They are the end-to-end
# tests SwayProvider, GnomeProvider and KdeProvider run with
# UMF_SCREENSHOT_DIR set, so the pictures are of what those tests check.
#
#   scripts/screenshots-wayland.sh                 # writes the three into docs/images/
#   UMF_SCREENSHOTS_OUT=/tmp/shots scripts/screenshots-wayland.sh
#
# Needs: sway gnome-shell kwin-wayland foot weston xterm xwayland
# (scripts/install-deps.sh), root
# (to make the test users). Builds nothing: run `make` first if the binaries are stale.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tests=${UMF_TESTS:-$root/build/release/tests/umf_tests}
out=${UMF_SCREENSHOTS_OUT:-$root/docs/images}
mkdir -p "$out"
UMF_SCREENSHOT_DIR="$out" "$tests" --gtest_filter='SwayProvider.*:GnomeProvider.*:KdeProvider.*'
echo "wrote $out/sway-desktop.png, $out/gnome-desktop.png and $out/kde-desktop.png"
