#!/bin/bash
# The Debian packages as a user gets them: cpack makes them from the build,
# lintian finds no error in them, apt installs them on this machine (their
# dependencies are the build's, so they are here), and then the installed
# programs work from /usr: --version, the manual pages, the menu entry and
# AppStream data validate, bash completion reads the program's help, a
# headless provider from /usr/bin serves the installed phone page, and the
# systemd user unit starts a headless provider and starts it again when it
# is killed. Everything is purged at the end.
# usage: debian_packages_test.sh BUILD_DIR   (exit 77: cannot run here)
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d /tmp/umf-debs-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
packages=(umf-provider umf-requester umf-field)
installed=
cleanup() {
  local rc=$?
  stop_provider || rc=1
  if [ -n "$installed" ]; then apt-get purge -y -qq "${packages[@]}" >/dev/null 2>&1 || true; fi
  rm -rf "$work"
  exit $rc
}
trap cleanup EXIT
skip() { echo "SKIP: $*"; exit 77; }

[ "$(id -u)" -eq 0 ] || skip "installing packages needs root (CI runs as root)"
for p in "${packages[@]}"; do
  if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    skip "$p is installed on this machine; the test would replace and purge it"
  fi
done
for tool in cpack lintian desktop-file-validate appstreamcli man apt-get; do
  command -v "$tool" >/dev/null || skip "$tool is missing (scripts/install-deps.sh installs it)"
done

# 1. The packages, and what lintian says of them.
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/packages" >"$work/cpack.log" 2>&1 ||
  { echo "FAIL: cpack:"; cat "$work/cpack.log"; exit 1; }
debs=()
for p in "${packages[@]}"; do
  deb=$(ls "$work/packages/${p}_"*.deb 2>/dev/null || true)
  [ -f "$deb" ] || { echo "FAIL: no $p package:"; ls "$work/packages"; exit 1; }
  debs+=("$deb")
done
version=$(dpkg-deb -f "${debs[0]}" Version)
grep -q "^project(umf VERSION $version " "$(dirname "$0")/../../CMakeLists.txt" ||
  { echo "FAIL: umf-provider's version $version is not the project's"; exit 1; }
grep -q 'libqt6core6' <<<"$(dpkg-deb -f "${debs[0]}" Depends)" ||
  { echo "FAIL: umf-provider's dependencies were not worked out:"; dpkg-deb -f "${debs[0]}" Depends; exit 1; }
lintian --no-tag-display-limit "${debs[@]}" >"$work/lintian.log" 2>&1 || true
if grep -q '^E: ' "$work/lintian.log"; then
  echo "FAIL: lintian finds errors:"; grep '^E: ' "$work/lintian.log"; exit 1
fi
echo "lintian: $(grep -c '^W: ' "$work/lintian.log" || true) warnings, no errors"

# 2. Installed by apt, as a user would.
installed=yes
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${debs[@]}" >"$work/apt.log" 2>&1 ||
  { echo "FAIL: apt-get install:"; tail -30 "$work/apt.log"; exit 1; }
for p in umf-provider umf-requester umf-field umf-browser-host; do
  said=$("/usr/bin/$p" --version)
  [ "$said" = "$p $version" ] || { echo "FAIL: /usr/bin/$p --version said '$said'"; exit 1; }
  page=$(man -w "$p") || { echo "FAIL: man finds no page for $p"; exit 1; }
  [ "$page" = "/usr/share/man/man1/$p.1.gz" ] || { echo "FAIL: man $p is $page"; exit 1; }
done
# Read whole before grep: grep -q stops reading at its match, and man,
# killed by the broken pipe, would fail the line under pipefail.
manual=$(MANWIDTH=100 man umf-provider 2>/dev/null)
grep -q 'umf-provider pair \[--port P\]' <<<"$manual" ||
  { echo "FAIL: man umf-provider does not show the help's usage"; exit 1; }
desktop-file-validate /usr/share/applications/umf-provider.desktop ||
  { echo "FAIL: the menu entry does not validate"; exit 1; }
grep -qx 'Exec=/usr/bin/umf-provider' /usr/share/applications/umf-provider.desktop ||
  { echo "FAIL: the menu entry does not run /usr/bin/umf-provider"; exit 1; }
appstreamcli validate --no-net /usr/share/metainfo/org.umf.provider.metainfo.xml >"$work/appstream.log" 2>&1 ||
  { echo "FAIL: the AppStream data does not validate:"; cat "$work/appstream.log"; exit 1; }
for size in 16x16 48x48 256x256 scalable; do
  ls /usr/share/icons/hicolor/$size/apps/umf-provider.* >/dev/null ||
    { echo "FAIL: no $size icon"; exit 1; }
done
completion=$(bash -c 'source /usr/share/bash-completion/completions/umf-provider
  COMP_WORDS=(umf-provider pa); COMP_CWORD=1; _umf_complete umf-provider; echo "${COMPREPLY[*]}"
  COMP_WORDS=(umf-field render --module-p); COMP_CWORD=2; _umf_complete umf-field; echo "${COMPREPLY[*]}"')
[ "$completion" = $'pair\n--module-px' ] || { echo "FAIL: bash completion gave '$completion'"; exit 1; }

# 3. A headless provider from /usr/bin serves the installed page.
bin=/usr/bin
start_provider "$work/provider.log" --config-dir "$work/cfg"
grep -q "^web client: /usr/share/umf/web " "$work/provider.log" ||
  { echo "FAIL: the installed provider did not take /usr/share/umf/web:"; cat "$work/provider.log"; exit 1; }
page=$(curl -sk "$origin/")
grep -q 'app.js' <<<"$page" || { echo "FAIL: /usr/bin/umf-provider served another page"; exit 1; }
stop_provider

# 4. The user unit, under a user systemd of its own (tests/install/user_unit.sh).
mkdir -p "$work/unit"
rc=0
bash "$(dirname "$0")/user_unit.sh" "$work/unit" || rc=$?
if [ "$rc" -eq 77 ]; then echo "the user unit was not checked: see SKIP above"; elif [ "$rc" -ne 0 ]; then exit 1; fi
echo "ok: the packages install, work from /usr, and purge"
