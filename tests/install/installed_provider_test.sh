#!/bin/bash
# An installed umf-provider serves the installed phone page: `cmake --install`
# into a fresh prefix, the build tree out of reach (the program is run from
# the prefix), and GET / must be the web client, not the built-in page; it
# takes its fields, page and browser extension from the prefix and says so.
# usage: installed_provider_test.sh BUILD_DIR
set -euo pipefail
build=$1
prefix=$(mktemp -d /tmp/umf-install-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
trap 'rc=$?; stop_provider || rc=1; rm -rf "$prefix"; exit $rc' EXIT

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in bin/umf-provider bin/umf-requester bin/umf-browser-host share/umf/web/index.html share/umf/web/app.js \
         share/umf/web/umf-detector.wasm share/umf/web/sw.js share/umf/browser-extension/manifest.json \
         share/umf/browser-extension/background.js share/umf/fields/b4-64x36.json share/umf/fields/b4-120x68.json; do
  [ -f "$prefix/$f" ] || { echo "FAIL: $f was not installed"; exit 1; }
done

version=$("$prefix/bin/umf-provider" --version --verbose)
grep -q '^umf-provider [0-9]' <<<"$version" || { echo "FAIL: --version said:"; echo "$version"; exit 1; }
for line in "fields: $prefix/share/umf/fields" "phone page: $prefix/share/umf/web" \
            "browser extension: $prefix/share/umf/browser-extension"; do
  grep -qx "$line" <<<"$version" ||
    { echo "FAIL: --version --verbose does not say '$line':"; echo "$version"; exit 1; }
done

# The browser companion's set-up names the installed host and extension.
setup=$(HOME="$prefix/home" XDG_CONFIG_HOME= "$prefix/bin/umf-provider" browser install)
manifest="$prefix/home/.config/chromium/NativeMessagingHosts/org.umf.browser.json"
grep -q "\"path\": \"$prefix/bin/umf-browser-host\"" "$manifest" ||
  { echo "FAIL: the host manifest does not name the installed host:"; cat "$manifest"; exit 1; }
grep -q "$prefix/share/umf/browser-extension" <<<"$setup" ||
  { echo "FAIL: browser install does not point at the installed extension:"; echo "$setup"; exit 1; }
HOME="$prefix/home" "$prefix/bin/umf-provider" browser install --system --prefix "$prefix/root" >/dev/null
[ -f "$prefix/root/usr/lib/mozilla/native-messaging-hosts/org.umf.browser.json" ] ||
  { echo "FAIL: browser install --system --prefix wrote no Firefox manifest"; exit 1; }

# Run from the prefix: the installed program, not the build tree's.
bin=$prefix/bin
start_provider "$prefix/provider.log" --config-dir "$prefix/cfg"
# The build tree has a web client too: the installed one must win.
if ! grep -q "^web client: $prefix/share/umf/web " "$prefix/provider.log"; then
  echo "FAIL: the installed provider did not take the installed web client:"; cat "$prefix/provider.log"; exit 1
fi
page=$(curl -sk "$origin/")
if ! grep -q 'app.js' <<<"$page"; then
  echo "FAIL: the installed provider served another page at /:"; head -c 600 <<<"$page"; exit 1
fi
wasm_type=$(curl -sk -o /dev/null -w '%{content_type}' "$origin/umf-detector.wasm")
[ "$wasm_type" = "application/wasm" ] || { echo "FAIL: umf-detector.wasm came as '$wasm_type'"; exit 1; }
echo "ok: $prefix/bin/umf-provider served the installed web client at $origin"
