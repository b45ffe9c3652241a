#!/bin/bash
# Makes the README's pictures of a phone pointed at a browser window,
# docs/images/phone-browser-link.jpg (locked on a link: "Link: ...") and
# phone-browser-result.jpg (the link taken), end to end:
#   - a throwaway X11 desktop (Xvfb at 96 dpi, openbox) with Debian's
#     Chromium showing a page served on 127.0.0.1, the browser companion
#     loaded (browser/extension) and its host set up by
#     `umf-provider browser install`;
#   - `umf-provider serve --desktop x11` on that desktop (default preset);
#   - the phone: a phone-sized headless Chromium with the phone page
#     (tests/web/browser/phone_on_browser.mjs), its fake camera a hand-held
#     video of that desktop made by umf_fake_camera from a screenshot with
#     the field mixed in as the provider's overlay mixes it (`compose
#     --content`), aimed at the link.
# What the phone shows comes from the real provider: the field point the
# page located, the X11 window under it, the extension's answer for it.
#
#   scripts/screenshots-browser.sh            # writes docs/images/phone-browser-*.jpg
#   UMF_SCREENSHOTS_OUT=/tmp/shots scripts/screenshots-browser.sh
#   UMF_BUILD=build/debug scripts/screenshots-browser.sh
#
# It is also the test web.browser.phone_on_browser_window (pictures into the
# build folder): the phone's title must be the link's and the grab its URL.
#
# Needs: xvfb openbox xdotool chromium python3 nodejs,
# and a build with the browser tests' fixtures (`ctest -R web.browser.npm`
# installs playwright-core). Builds nothing.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${UMF_BUILD:-$root/build/release}
out=${UMF_SCREENSHOTS_OUT:-$root/docs/images}
chromium=${UMF_CHROMIUM:-/usr/bin/chromium}
modules=$build/tests/web/browser/node_modules

die() { echo "$0: $*" >&2; exit 1; }
# Exit 77 (CTest's skip, as web.browser.phone_on_browser_window runs it):
# something this machine lacks, not something that failed.
lacks() { echo "$0: skipped: $*" >&2; exit 77; }

for program in Xvfb openbox xdotool python3 node; do
    command -v "$program" >/dev/null || lacks "$program is not installed (scripts/install-deps.sh installs it)"
done
[[ -x $chromium ]] || lacks "no Chromium at $chromium (set UMF_CHROMIUM)"
for f in bin/umf-provider bin/umf-browser-host tests/web/umf_fake_camera web/site/index.html; do
    [[ -e $build/$f ]] || lacks "$build/$f is missing: build first (make), or set UMF_BUILD"
done
[[ -d $modules/playwright-core ]] || lacks "no playwright-core in $modules: run ctest --preset release -R web.browser.npm first"

source "$root/scripts/background.sh"  # work, pids, spawn, stop, wait_for; cleanup on exit
# spawn with its output in $work/LOG.
spawn_logged() {
    local log=$1
    shift
    spawn "$@" >"$work/$log" 2>&1
}
mkdir -p "$out" "$work/run" "$work/www" "$work/config"
chmod 700 "$work/run"
export HOME=$work XDG_CONFIG_HOME=$work/config XDG_CACHE_HOME=$work/cache XDG_RUNTIME_DIR=$work/run

# --- The page: a project's news, its release-notes link placed from the
# viewport's bottom-left corner so that its screen rectangle follows from
# the window's alone.
link_left=96 link_bottom=300 link_width=560 link_height=84
cat >"$work/www/index.html" <<EOF
<!doctype html><html lang=en><head><meta charset=utf-8><title>umf news: version 0.5</title>
<style>
body{margin:0;font:20px/1.55 "DejaVu Sans",sans-serif;color:#1f2328;background:#fff}
header{background:#24325f;color:#fff;padding:22px 96px;font-size:26px;font-weight:bold}
header span{font-weight:normal;opacity:.8;margin-left:28px;font-size:20px}
main{padding:24px 96px;max-width:1100px}
h1{font-size:40px;margin:10px 0 6px}
.date{color:#667085;margin-bottom:18px}
#notes{position:fixed;left:${link_left}px;bottom:${link_bottom}px;width:${link_width}px;height:${link_height}px;
  box-sizing:border-box;display:flex;align-items:center;justify-content:center;border-radius:12px;
  background:#1a66d2;color:#fff;font-size:32px;font-weight:bold;text-decoration:none}
footer{position:fixed;left:96px;bottom:40px;color:#667085;font-size:18px}
</style></head><body>
<header>umf<span>Docs</span><span>Downloads</span><span>News</span></header>
<main>
<h1>Version 0.5: take what the browser shows</h1>
<div class=date>27 November 2026</div>
<p>Point your phone at a browser window and take the link, the picture or the
passage under the point, not a picture of the window. Put a link on the
window and it opens as a new tab there.</p>
<p>The browser companion works with Chromium, Chrome, Edge and Firefox. Set it
up with one command: <code>umf-provider browser install</code>.</p>
</main>
<a id=notes href="https://umf.example.org/news/0.5/release-notes">Release notes for 0.5</a>
<footer>Private windows are never reported. Only http and https addresses leave the computer.</footer>
</body></html>
EOF
(cd "$work/www" && PYTHONUNBUFFERED=1 exec python3 -m http.server 0 --bind 127.0.0.1) >"$work/http.log" 2>&1 &
pids=("$!" "${pids[@]}")
wait_for "grep -q 'port [0-9]' '$work/http.log'" || die "the page's server did not start: $(cat "$work/http.log")"
page="http://127.0.0.1:$(grep -o 'port [0-9]*' "$work/http.log" | head -1 | cut -d' ' -f2)/"

# --- The desktop --------------------------------------------------------------
number=90
while [[ -e /tmp/.X11-unix/X$number || -e /tmp/.X$number-lock ]]; do number=$((number + 1)); done
spawn_logged xvfb.log Xvfb ":$number" -screen 0 1920x1080x24 -dpi 96 -nolisten tcp
wait_for "[[ -S /tmp/.X11-unix/X$number ]]" 10 || die "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=:$number
spawn_logged openbox.log openbox
wait_for "xdotool getactivewindow || xprop -root _NET_SUPPORTING_WM_CHECK | grep -q window" 10 || true
command -v xsetroot >/dev/null && xsetroot -solid '#4a5570'

"$build/bin/umf-provider" browser install --host "$build/bin/umf-browser-host" >"$work/install.log" ||
    die "browser install failed: $(cat "$work/install.log")"
window_x=120 window_y=70 window_w=1680 window_h=940
chromium_args=(--no-first-run --no-default-browser-check --password-store=basic --disable-gpu
               --force-device-scale-factor=1 --disable-features=DisableLoadExtensionCommandLineSwitch
               "--load-extension=$root/browser/extension" "--user-data-dir=$XDG_CONFIG_HOME/chromium"
               "--window-position=$window_x,$window_y" "--window-size=$window_w,$window_h")
# As root Chromium needs --no-sandbox; --test-type keeps its warning bar about it out of the picture.
[[ $(id -u) == 0 ]] && chromium_args=(--no-sandbox --test-type "${chromium_args[@]}")
spawn_logged chromium.log "$chromium" "${chromium_args[@]}" "$page"
wait_for "xdotool search --name '^umf news'" 60 || die "Chromium showed no page: $(tail -20 "$work/chromium.log")"
sleep 3  # the page drawn, the window settled
window=$(xdotool search --name '^umf news' | head -1)
eval "$(xdotool getwindowgeometry --shell "$window")"  # X Y WIDTH HEIGHT of Chromium's own window
link_x=$((X + link_left)) link_y=$((Y + HEIGHT - link_bottom - link_height))
python3 - "$work/desktop.png" <<'PY'
# The root window as a PNG: Xlib through ctypes, zlib by hand, no modules needed.
import ctypes, ctypes.util, struct, sys, zlib
class XImage(ctypes.Structure):
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int),
                ("format", ctypes.c_int), ("data", ctypes.POINTER(ctypes.c_ubyte)), ("byte_order", ctypes.c_int),
                ("bitmap_unit", ctypes.c_int), ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int),
                ("depth", ctypes.c_int), ("bytes_per_line", ctypes.c_int), ("bits_per_pixel", ctypes.c_int)]
x = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11"))
x.XOpenDisplay.restype = ctypes.c_void_p
x.XDefaultRootWindow.restype = ctypes.c_ulong
x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
x.XDisplayWidth.argtypes = x.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
x.XGetImage.restype = ctypes.POINTER(XImage)
x.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int, ctypes.c_uint, ctypes.c_uint,
                        ctypes.c_ulong, ctypes.c_int]
d = x.XOpenDisplay(None) or sys.exit("screenshot: cannot open the display")
w, h = x.XDisplayWidth(d, 0), x.XDisplayHeight(d, 0)
img = x.XGetImage(d, x.XDefaultRootWindow(d), 0, 0, w, h, 0xFFFFFFFF, 2).contents  # ZPixmap
if img.bits_per_pixel != 32: sys.exit("screenshot: %d bits per pixel" % img.bits_per_pixel)
raw = ctypes.string_at(img.data, img.bytes_per_line * h)
rows = bytearray()
for y in range(h):
    line = raw[y * img.bytes_per_line:y * img.bytes_per_line + 4 * w]
    rgb = bytearray(3 * w)
    rgb[0::3], rgb[1::3], rgb[2::3] = line[2::4], line[1::4], line[0::4]  # BGRX in memory
    rows += b"\0" + rgb
chunk = lambda t, b: struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b))
with open(sys.argv[1], "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(bytes(rows), 6)) + chunk(b"IEND", b""))
PY

# --- The provider, and the camera's video of its screen ------------------------
spawn_logged provider.log "$build/bin/umf-provider" serve --desktop x11 --port 0 --bind 127.0.0.1 --no-qr \
    --config-dir "$work/provider" --web "$build/web/site"
wait_for "grep -q '^pairing URL: ' '$work/provider.log'" 20 || die "the provider did not start: $(cat "$work/provider.log")"
pairing=$(grep -m1 '^pairing URL: ' "$work/provider.log" | cut -d' ' -f3)
port=$(sed -E 's|https://[^:]+:([0-9]+)/.*|\1|' <<<"$pairing")
wait_for "'$build/bin/umf-provider' browser status --port $port | grep -q 'umf news'" 60 ||
    die "the browser never told the provider its page: $("$build/bin/umf-provider" browser status --port "$port" 2>&1)"

"$build/tests/web/umf_fake_camera" --provider "$build/bin/umf-provider" --content "$work/desktop.png" \
    --aim "$link_x,$link_y,$link_width,$link_height" --preset balanced --distance 330 --frames 45 \
    --field-seed "$work/provider/field-seed" --out "$work/camera.y4m" --work "$work/screens" >"$work/camera.json" ||
    die "the camera's video does not lock on the link: $(cat "$work/camera.json")"

# --- The phone ------------------------------------------------------------------
node "$root/tests/web/browser/phone_on_browser.mjs" --pairing "$pairing" --video "$work/camera.y4m" \
    --modules "$modules" --chromium "$chromium" --out "$out" \
    --expect-url https://umf.example.org/news/0.5/release-notes --expect-title "Link: Release notes for 0.5" ||
    die "the phone did not take the link; the provider said: $(tail -30 "$work/provider.log")"
echo "wrote $out/phone-browser-link.jpg and $out/phone-browser-result.jpg"
