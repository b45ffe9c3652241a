#!/usr/bin/env bash
# The Debian packages on a Debian 12 that has nothing else: a throwaway root
# made with debootstrap (minbase) from the package mirror, where apt must
# pull every dependency the packages name, then the installed programs run
# there: --version, man, desktop-file-validate, appstreamcli validate, and a
# headless provider from /usr/bin serving its page. Needs root and the
# mirror; takes minutes and downloads some hundred megabytes, so CI runs the
# lighter tests/install/debian_packages_test.sh instead.
# usage: scripts/check-packages-fresh-debian.sh [BUILD_DIR [MIRROR]]
set -euo pipefail
build=${1:-build/release}
mirror=${2:-http://deb.debian.org/debian}
root=$(mktemp -d /tmp/umf-fresh-debian-XXXXXX)
cleanup() {
  for m in proc dev/pts dev; do umount "$root/$m" 2>/dev/null || true; done
  rm -rf "$root"
}
trap cleanup EXIT
start=$(date +%s)
took() { echo "check: $1 ($(( $(date +%s) - start )) s)"; }

cmake --build "$build" --target package >/dev/null
debs=("$build"/packages/umf-{provider,requester,field}_*.deb)
debootstrap --variant=minbase bookworm "$root" "$mirror" >"$root.debootstrap.log" 2>&1 ||
  { tail -20 "$root.debootstrap.log"; exit 1; }
took "debootstrap"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
mkdir -p "$root/tmp/debs"
cp "${debs[@]}" "$root/tmp/debs/"
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "$@"; }
in_root apt-get update -qq
# The tools the checks use come first, so what the packages pull is counted apart.
in_root bash -c 'DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  man-db desktop-file-utils appstream curl ca-certificates >/dev/null'
before=$(in_root dpkg-query -W -f='${Package}\n' | wc -l)
in_root bash -c 'DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends /tmp/debs/*.deb' \
  >"$root/tmp/apt.log" 2>&1 || { tail -30 "$root/tmp/apt.log"; exit 1; }
after=$(in_root dpkg-query -W -f='${Package}\n' | wc -l)
took "apt installed the three packages and $(( after - before - 3 )) dependencies"
for p in umf-provider umf-requester umf-field umf-browser-host; do
  in_root "$p" --version
done
in_root man -w umf-provider
in_root desktop-file-validate /usr/share/applications/umf-provider.desktop
in_root appstreamcli validate --no-net /usr/share/metainfo/org.umf.provider.metainfo.xml
in_root bash -c 'umf-provider --headless --port 47999 --no-qr --config-dir /tmp/cfg > /tmp/provider.log 2>&1 &
  for i in $(seq 100); do curl -sk https://127.0.0.1:47999/ | grep -q app.js && break; sleep 0.1; done
  curl -sk https://127.0.0.1:47999/ | grep -q app.js || { cat /tmp/provider.log; exit 1; }
  grep "^web client:" /tmp/provider.log; kill %1'
took "ok: installed on a fresh Debian 12, the programs run and the provider serves its page"
