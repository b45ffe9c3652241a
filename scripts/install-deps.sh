#!/usr/bin/env bash
# Installs every Debian package umf builds, tests or runs with.
# Idempotent and non-interactive: packages already present are skipped, so a
# second run costs only a dpkg query.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ca-certificates
  # shared/ (the core library)
  libeigen3-dev nlohmann-json3-dev
  # tests and benchmarks; clang and its runtime for the fuzz targets (libFuzzer, sanitizers)
  libgtest-dev libgmock-dev libbenchmark-dev poppler-utils python3-websockets clang libclang-rt-dev
  # provider/: Qt 6, Beast server, TLS, pairing QR codes, X11 window lookup
  qt6-base-dev qt6-base-dev-tools libgl-dev libx11-dev libxres-dev libxcb1-dev curl
  libboost-dev libboost-system-dev libssl-dev openssl libqrencode-dev
  # requester/ and the camera simulator
  libopencv-dev libopencv-contrib-dev libapriltag-dev
  # web/: WebAssembly build and browser tests (certutil, in libnss3-tools, for a trusted root in Chromium)
  emscripten chromium firefox-esr libnss3-tools
  # headless desktop for overlay and window tests
  xvfb xauth x11-utils x11-xserver-utils xdotool openbox mupdf xterm xcompmgr picom libxext-dev
  # Wayland desktops: the client library and scanner for the layer-shell field,
  # and the compositors the desktop tests run headless (Sway with foot and
  # Xwayland, GNOME Shell with the umf extension, KWin, weston), grim, D-Bus;
  # Mesa's software OpenGL (llvmpipe) for KWin compositing with OpenGL
  libwayland-dev wayland-protocols sway grim foot xwayland weston dbus dbus-daemon gnome-shell kwin-wayland
  libgl1-mesa-dri libegl-mesa0
  # the provider announces itself over DNS-SD through Avahi, umf-requester discover browses
  # with libavahi-client, and requesters resolve .local names through nss-mdns; the tests run
  # a daemon and its tools in network namespaces of their own (iproute2)
  avahi-daemon libavahi-client-dev avahi-utils libnss-mdns iproute2
  # packaging/: the icon's PNG sizes, and what the package test checks the
  # packages with (lintian, the menu entry's and AppStream validators, man,
  # a user systemd for the user unit)
  librsvg2-bin lintian desktop-file-utils appstream man-db systemd
)

# node and npm may come from another repository whose nodejs bundles npm
# (and conflicts with Debian's npm): add Debian's only when there is no node.
if ! command -v node >/dev/null 2>&1; then packages+=(nodejs); fi
if ! command -v npm >/dev/null 2>&1; then packages+=(npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
