#!/usr/bin/env bash
# Large transfers against a peer, side by side in one run: a SIZE_MB file
# over loopback TLS 1.3, fetched from nginx by curl and grabbed from a
# headless umf-provider by umf-requester (the download, its SHA-256 checked
# on both ends, written to disk); then put: curl PUT to nginx (WebDAV)
# against umf-requester put to the provider (both ends hash it). For each,
# the wall time and MB/s of the transfer, and the server's CPU seconds per
# GB (its process's user + system time over the transfer). The umf figures
# are the requester's own ("saved ... in T s", "sent ... in T s"): the
# transfer, not the aiming before it; under each, the whole command's time
# (starting, aiming at the screen image, and for a put the SHA-256 of the
# file taken before it is offered). At the end, the median of the runs for
# each and umf's ratio against nginx (above 1: umf is faster).
# A file hashed under a read lease is sent without hashing it again
# (provider/content/read_lease.hpp); with HOLD_OPEN_FOR_WRITING=1 the file
# is kept open for writing throughout, so the kernel grants no lease and
# the provider hashes it as it sends it.
# usage: [HOLD_OPEN_FOR_WRITING=1] scripts/bench-transfer.sh [BUILD] [SIZE_MB] [RUNS]
set -euo pipefail
build=${1:-build/release}
size_mb=${2:-1024}
runs=${3:-3}
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$build" && pwd)/bin
work=$(mktemp -d /tmp/umf-bench-transfer-XXXXXX)
nginx_pid=
provider_pid=
cleanup() {
  [ -n "$nginx_pid" ] && kill "$nginx_pid" 2>/dev/null
  [ -n "$provider_pid" ] && kill "$provider_pid" 2>/dev/null
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
command -v nginx >/dev/null || { echo "nginx is not installed (apt-get install nginx)"; exit 1; }
size=$((size_mb << 20))
free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
# user + system CPU seconds of a process so far (/proc/PID/stat, clock ticks).
cpu_seconds() { awk -v hz="$(getconf CLK_TCK)" '{ printf "%.3f", ($14 + $15) / hz }' "/proc/$1/stat"; }
per_gb() { echo "scale=3; ($2 - $1) * 1073741824 / $size" | bc; }
rate() { echo "scale=1; $size / 1000000 / $1" | bc; }

mkdir -p "$work/www" "$work/board" "$work/got" "$work/received" "$work/nginx"
head -c "$size" /dev/urandom >"$work/board/big.bin"
ln "$work/board/big.bin" "$work/www/big.bin"
[ "${HOLD_OPEN_FOR_WRITING:-0}" = 1 ] && exec 9<>"$work/board/big.bin"
printf '{"format": "umf-board/1", "title": "Bench", "columns": 1,\n "items": [{"title": "Big", "file": "big.bin"}]}\n' \
  >"$work/board/board.json"

# nginx: one worker, TLS 1.3 only, the same kind of key as the provider's (P-256).
openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -days 1 -subj /CN=127.0.0.1 \
  -addext subjectAltName=IP:127.0.0.1 -keyout "$work/nginx/key.pem" -out "$work/nginx/cert.pem" 2>/dev/null
nginx_port=$(free_port)
# Started as root, nginx's worker would be another user, unable to read the
# private work folder: it stays root here.
user_line=
[ "$(id -u)" -eq 0 ] && user_line="user root;"
cat >"$work/nginx/nginx.conf" <<CONF
$user_line
worker_processes 1;
daemon off;
pid $work/nginx/nginx.pid;
error_log $work/nginx/error.log;
events { worker_connections 64; }
http {
  access_log off;
  client_body_temp_path $work/nginx/body;
  proxy_temp_path $work/nginx/proxy;
  fastcgi_temp_path $work/nginx/fastcgi;
  uwsgi_temp_path $work/nginx/uwsgi;
  scgi_temp_path $work/nginx/scgi;
  server {
    listen 127.0.0.1:$nginx_port ssl;
    ssl_certificate $work/nginx/cert.pem;
    ssl_certificate_key $work/nginx/key.pem;
    ssl_protocols TLSv1.3;
    root $work/www;
    client_max_body_size 0;
    location /up/ { dav_methods PUT; create_full_put_path on; }
  }
}
CONF
nginx -c "$work/nginx/nginx.conf" -p "$work/nginx" &
nginx_pid=$!
sleep 0.5
nginx_worker=$(pgrep -P "$nginx_pid" | head -1)
[ -n "$nginx_worker" ] || { echo "nginx did not start:"; cat "$work/nginx/error.log"; exit 1; }

"$bin/umf-provider" compose --board "$work/board/board.json" --screen 1920x1080 --preset kiosk --time 0.75 \
  --out "$work/screen.png" --map "$work/map.json" --config-dir "$work/cfg" >/dev/null 2>&1
: >"$work/provider.log"
"$bin/umf-provider" --headless --port 0 --bind 127.0.0.1 --no-qr --config-dir "$work/cfg" --board "$work/board/board.json" \
  --puts always --put-dir "$work/received" --put-max-mb $((size_mb * 2)) >>"$work/provider.log" 2>&1 &
provider_pid=$!
url=
for _ in $(seq 100); do url=$(sed -n 's/^pairing URL: //p' "$work/provider.log"); [ -n "$url" ] && break; sleep 0.1; done
[ -n "$url" ] || { echo "no provider"; cat "$work/provider.log"; exit 1; }
sleep 3  # the board's file hashed in the background

now() { date +%s.%N; }
echo "transfer of $size_mb MiB over loopback TLS 1.3 on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
[ "${HOLD_OPEN_FOR_WRITING:-0}" = 1 ] && echo "the file is held open for writing: no lease, the provider hashes as it sends"
printf '%-34s %8s %9s %12s\n' "what" "seconds" "MB/s" "server CPU s/GB"
# The seconds of each run, by what was measured: "nginx-download" etc.
declare -A times
median() { tr ' ' '\n' <<<"$1" | grep . | sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# One curl transfer with nginx: WHAT, the file that must arrive equal to the
# original, then curl's own arguments. Prints its line of the table.
with_nginx() {
  local what=$1 arrived=$2 c0 c1 t0 t1 secs
  shift 2
  c0=$(cpu_seconds "$nginx_worker"); t0=$(now)
  curl -sSfk --tlsv1.3 "$@"
  t1=$(now); c1=$(cpu_seconds "$nginx_worker")
  secs=$(echo "$t1 - $t0" | bc)
  printf '%-34s %8.2f %9.1f %12.3f\n' "$what" "$secs" "$(rate "$secs")" "$(per_gb "$c0" "$c1")"
  times[nginx-${what%%:*}]+=" $secs"
  cmp -s "$work/board/big.bin" "$arrived" || { echo "$what: the file arrived changed"; exit 1; }
}
for run in $(seq "$runs"); do
  # Download: curl from nginx (no check) ...
  with_nginx "download: curl <- nginx (run $run)" "$work/got/nginx.bin" \
    -o "$work/got/nginx.bin" "https://127.0.0.1:$nginx_port/big.bin"
  rm -f "$work/got/nginx.bin"
  # ... and umf-requester grab from umf-provider (SHA-256 on both ends).
  c0=$(cpu_seconds "$provider_pid"); t0=$(now)
  XDG_CONFIG_HOME="$work/phone" "$bin/umf-requester" grab --url "$url" --image "$work/screen.png" --out "$work/got" \
    >"$work/grab.json" 2>"$work/grab.log" || { cat "$work/grab.json" "$work/grab.log"; exit 1; }
  t1=$(now); c1=$(cpu_seconds "$provider_pid")
  secs=$(sed -n 's/.*saved .* in \([0-9.]*\) s, .*/\1/p' "$work/grab.log")
  printf '%-34s %8.2f %9.1f %12.3f\n' "download: umf grab (run $run)" "$secs" "$(rate "$secs")" "$(per_gb "$c0" "$c1")"
  whole=$(echo "$t1 - $t0" | bc)
  printf '%-34s %8.2f %9.1f\n' "  the whole command" "$whole" "$(rate "$whole")"
  times[umf-download]+=" $secs"
  times[umf-download-whole]+=" $whole"
  cmp -s "$work/board/big.bin" "$work/got/big.bin" || { echo "the grab arrived changed"; exit 1; }
  rm -f "$work/got/"*
  # Put: curl PUT to nginx ...
  with_nginx "put: curl -> nginx (run $run)" "$work/www/up/big.bin" \
    -T "$work/board/big.bin" "https://127.0.0.1:$nginx_port/up/big.bin" -o /dev/null
  rm -f "$work/www/up/big.bin"
  # ... and umf-requester put to umf-provider.
  c0=$(cpu_seconds "$provider_pid"); t0=$(now)
  XDG_CONFIG_HOME="$work/phone" "$bin/umf-requester" put "$work/board/big.bin" --url "$url" --image "$work/screen.png" \
    >"$work/put.json" 2>"$work/put.log" || { cat "$work/put.json" "$work/put.log"; exit 1; }
  t1=$(now); c1=$(cpu_seconds "$provider_pid")
  secs=$(sed -n 's/.*sent [0-9.]* MB in \([0-9.]*\) s, .*/\1/p' "$work/put.log")
  printf '%-34s %8.2f %9.1f %12.3f\n' "put: umf put (run $run)" "$secs" "$(rate "$secs")" "$(per_gb "$c0" "$c1")"
  whole=$(echo "$t1 - $t0" | bc)
  printf '%-34s %8.2f %9.1f\n' "  the whole command" "$whole" "$(rate "$whole")"
  times[umf-put]+=" $secs"
  times[umf-put-whole]+=" $whole"
  cmp -s "$work/board/big.bin" "$work/received/big.bin" || { echo "the put arrived changed"; ls "$work/received"; exit 1; }
  rm -f "$work/received/"*
done
for what in download put; do
  n=$(median "${times[nginx-$what]}")
  u=$(median "${times[umf-$what]}")
  printf '%-8s median of %d runs: nginx %.1f MB/s, umf %.1f MB/s, ratio %.2f\n' "$what" "$runs" "$(rate "$n")" \
    "$(rate "$u")" "$(echo "scale=4; $n / $u" | bc)"
  w=$(median "${times[umf-$what-whole]}")
  printf '         the whole umf command: %.2f s (%.1f MB/s), ratio %.2f\n' "$w" "$(rate "$w")" \
    "$(echo "scale=4; $n / $w" | bc)"
done
