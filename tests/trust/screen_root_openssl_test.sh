#!/bin/bash
# The screen's root as outside tools see it: `trust export` in its three
# forms, the fingerprint the pairing URL pins, `openssl s_client` and curl
# trusting only the exported root for every address and name the provider
# says it serves, and a certificate for a public name signed with the
# root's key refused by the root's name constraints.
# usage: screen_root_openssl_test.sh BUILD_DIR
set -euo pipefail
bin=$1/bin
work=$(mktemp -d /tmp/umf-root-XXXXXX)
source "$(dirname "$0")/../support/provider_run.sh"
trap 'rc=$?; stop_provider || rc=1; rm -rf "$work"; exit $rc' EXIT

start_provider "$work/provider.log" --config-dir "$work/cfg"
"$bin/umf-provider" trust export "$work/root.pem" --config-dir "$work/cfg" 2>/dev/null
"$bin/umf-provider" trust export "$work/root.crt" --der --config-dir "$work/cfg" 2>/dev/null
"$bin/umf-provider" trust export "$work/root.mobileconfig" --mobileconfig --config-dir "$work/cfg" 2>/dev/null
fp=$(der_sha256 "$work/root.pem")
[[ $url == *"&fp=$fp"* ]] || { echo "FAIL: the pairing URL does not pin the root $fp: $url"; exit 1; }
[ "$(sha256sum <"$work/root.crt" | cut -d' ' -f1)" = "$fp" ] || { echo "FAIL: --der is not the root's DER"; exit 1; }
grep -q '<string>com.apple.security.root</string>' "$work/root.mobileconfig" ||
  { echo "FAIL: --mobileconfig holds no root payload"; exit 1; }
# --port: other tests' providers may run beside this one.
"$bin/umf-provider" trust --config-dir "$work/cfg" --port "$port" | grep -q "^screen root (SHA-256): $fp$" ||
  { echo "FAIL: umf-provider trust does not print the root's fingerprint"; exit 1; }
if grep -q 'PRIVATE' "$work/root.pem" "$work/root.mobileconfig"; then echo "FAIL: a key was exported"; exit 1; fi
echo "ok: trust export writes the root $fp as PEM, DER and a profile; the pairing URL pins it"

# Every address and name the console lists, verified against the root alone.
serving=$(sed -n 's/^serving at: //p' "$work/provider.log")
[ -n "$serving" ] || { echo "FAIL: no 'serving at' line:"; cat "$work/provider.log"; exit 1; }
checked=0
for origin_served in $serving; do
  host=${origin_served#https://}
  host=${host%:*}
  host=${host#[}
  host=${host%]}
  if [[ $host =~ ^[0-9.]+$ || $host == *:* ]]; then
    servername= verified "$host" -verify_ip "$host" || { echo "FAIL: $host does not verify against the root"; exit 1; }
  else
    # A name: reached on loopback with the name in SNI, as mDNS would resolve it here.
    servername=$host verified 127.0.0.1 -verify_hostname "$host" ||
      { echo "FAIL: $host does not verify against the root"; exit 1; }
  fi
  checked=$((checked + 1))
done
[ "$checked" -ge 3 ] || { echo "FAIL: only $checked served origins listed: $serving"; exit 1; }
echo "ok: $checked served origins verify against the root: $serving"
openssl verify -CAfile "$work/root.pem" -untrusted "$work/root.pem" "$work/cfg/serving-cert.pem" >/dev/null ||
  { echo "FAIL: openssl verify refuses the serving certificate"; exit 1; }

# A browser-like client that trusts only the root: no -k.
[ "$(curl -s --cacert "$work/root.pem" -o /dev/null -w '%{http_code}' "https://127.0.0.1:$port/")" = 200 ] ||
  { echo "FAIL: curl --cacert root.pem refuses the page"; exit 1; }
[ "$(curl -s --cacert "$work/root.pem" "https://localhost:$port/trust/umf-root.crt" | sha256sum | cut -d' ' -f1)" = "$fp" ] ||
  { echo "FAIL: /trust/umf-root.crt is not the root"; exit 1; }
if curl -s -o /dev/null "https://127.0.0.1:$port/"; then echo "FAIL: curl without the root trusted the page"; exit 1; fi
echo "ok: curl trusting only the root gets the page and /trust/umf-root.crt; without it, refused"

# Whoever steals the root's key still cannot vouch for a public site.
for san in DNS:bank.example.com IP:8.8.8.8 "DNS:$(hostname -s).local,DNS:mail.example.org"; do
  openssl req -new -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -keyout "$work/forged.key" \
    -subj "/CN=forged" -addext "subjectAltName=$san" -out "$work/forged.csr" 2>/dev/null
  openssl x509 -req -in "$work/forged.csr" -CA "$work/root.pem" -CAkey "$work/cfg/root-key.pem" -days 30 \
    -copy_extensions copyall -out "$work/forged.pem" 2>/dev/null
  if out=$(openssl verify -CAfile "$work/root.pem" "$work/forged.pem" 2>&1); then
    echo "FAIL: a certificate for $san signed by the root verifies: $out"; exit 1
  fi
  grep -q 'permitted subtree violation' <<<"$out" || { echo "FAIL: $san refused for another reason: $out"; exit 1; }
done
echo "ok: certificates for public names and addresses signed with the root's key fail its name constraints"
