#!/bin/bash
# Makes the README's screenshots in docs/images/ on a throwaway X11 desktop:
# Xvfb (1920x1080x24) on a free display, openbox, xcompmgr, an xterm and
# mupdf showing a generated PDF, and build/release/bin/umf-provider over them.
#
#   scripts/screenshots.sh            # writes docs/images/*.png
#   UMF_SCREENSHOTS_OUT=/tmp/shots scripts/screenshots.sh
#   UMF_BIN=build/debug/bin scripts/screenshots.sh
#
# Writes overlay-desktop.png (the field over the desktop), overlay-focus.png
# (the field only around a requester's aim, with the pointer ring and title),
# put-prompt.png (the card asking whether to take a file a phone puts),
# tuning-window.png (umf-provider --tune) and, when trayer is installed,
# tray-menu.png (the tray icon's menu). The aim and the put come from small
# Python clients speaking docs/PROTOCOL.md to the provider on 127.0.0.1.
#
# Needs: xvfb openbox xcompmgr xterm mupdf xdotool imagemagick (import,
# convert) python3 with python3-websockets; trayer for the tray menu.
# Builds nothing: run `make` first if the binaries are stale.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
bin=${UMF_BIN:-$root/build/release/bin}
out=${UMF_SCREENSHOTS_OUT:-$root/docs/images}
python=${UMF_PYTHON:-/usr/bin/python3}
size=1920x1080x24
width=1280  # of the full-screen pictures in the README

die() { echo "$0: $*" >&2; exit 1; }

for program in Xvfb openbox xcompmgr xterm mupdf xdotool import convert; do
    command -v "$program" >/dev/null ||
        die "$program is not installed (apt-get install xvfb openbox xcompmgr xterm mupdf xdotool imagemagick)"
done
# A stand-in convert that only reads PNGs can sit before ImageMagick's in PATH.
convert -version 2>/dev/null | grep -q ImageMagick || die "convert is not ImageMagick's (apt-get install imagemagick)"
[[ -x $bin/umf-provider ]] || die "$bin/umf-provider is missing: build it first (make), or set UMF_BIN"
[[ -x $python ]] || die "$python is missing: set UMF_PYTHON to a python3 with the websockets module"
"$python" -c 'import websockets' 2>/dev/null ||
    die "$python has no websockets module (apt-get install python3-websockets)"
tray=1
command -v trayer >/dev/null || { tray=0; echo "$0: trayer is not installed: no tray-menu.png (apt-get install trayer)" >&2; }

started=$(date +%s)
source "$root/scripts/background.sh"  # work, pids, spawn, stop, wait_for; cleanup on exit

mkdir -p "$out"

# --- Content: a wallpaper, a PDF, some notes ---------------------------------

cat >"$work/notes.txt" <<'EOF'
$ cat ~/notes/standup.txt
Stand-up, Tuesday
  - release 0.4: the tuning window ships, presets are kept per user
  - docs: screenshots for the README (this desktop)
  - phone client: retry the WebSocket after a screen change (1012)
  - kiosk board: 40 px modules read well from 3 m

$ ls ~/reports
q3-report.pdf  roadmap.md  standup.txt

$ mupdf ~/reports/q3-report.pdf &
EOF

"$python" - "$work/q3-report.pdf" <<'EOF'
# A one-page PDF by hand: Helvetica text and a bar chart, no libraries.
import sys

W, H = 600, 780
ops = []
def text(x, y, size, s, font="F1"):
    s = s.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")
    ops.append(f"BT /{font} {size} Tf {x} {y} Td ({s}) Tj ET")
def rect(x, y, w, h, rgb):
    ops.append("{:.3f} {:.3f} {:.3f} rg {} {} {} {} re f".format(*rgb, x, y, w, h))

rect(0, H - 90, W, 90, (0.17, 0.31, 0.43))
ops.append("1 1 1 rg")
text(48, H - 52, 26, "Quarterly report, Q3", "F2")
text(48, H - 74, 12, "Operations and usage")
ops.append("0 0 0 rg")
y = H - 130
for line in [
    "Usage grew steadily through the quarter. Most new installations are",
    "desktops shared in meeting rooms, where people take a document from",
    "the shared screen with their phone instead of asking for it by mail.",
    "",
    "Kiosk boards were tried in two lobbies. Larger modules made them",
    "readable from across the room; the pulse was turned down after",
    "feedback that it drew the eye.",
]:
    text(48, y, 12, line)
    y -= 17
text(48, y - 14, 16, "Documents taken per week", "F2")
base, left = y - 300, 70
ops.append("0.6 0.6 0.6 RG 1 w {} {} m {} {} l S".format(left, base, W - 40, base))
for i, v in enumerate([38, 52, 47, 61, 70, 66, 84, 91, 88, 102, 117, 124]):
    x = left + 10 + i * 40
    rect(x, base, 26, v * 2, (0.18, 0.5, 0.93) if i < 11 else (0.93, 0.45, 0.18))
    text(x + 4, base - 14, 9, f"W{i + 1}")
text(48, base - 50, 12, "Week 12 is the first week with the tuning window.")
text(48, base - 67, 12, "Next: palettes taken from the screen, focus mode for quiet rooms.")
text(48, 40, 9, "Page 1 of 1")

content = "\n".join(ops).encode()
objects = [
    b"<< /Type /Catalog /Pages 2 0 R >>",
    b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
    f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {W} {H}] /Contents 4 0 R "
    "/Resources << /Font << /F1 5 0 R /F2 6 0 R >> >> >>".encode(),
    b"<< /Length %d >>\nstream\n" % len(content) + content + b"\nendstream",
    b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica >>",
    b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica-Bold >>",
]
pdf = bytearray(b"%PDF-1.4\n")
offsets = []
for n, body in enumerate(objects, 1):
    offsets.append(len(pdf))
    pdf += b"%d 0 obj\n" % n + body + b"\nendobj\n"
xref = len(pdf)
pdf += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
for o in offsets:
    pdf += b"%010d 00000 n \n" % o
pdf += b"trailer\n<< /Size %d /Root 1 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (len(objects) + 1, xref)
open(sys.argv[1], "wb").write(pdf)
EOF

cat >"$work/wallpaper.py" <<'EOF'
# A gradient as the root window's background pixmap, named in _XROOTPMAP_ID,
# where xcompmgr looks for the wallpaper. Xlib through ctypes: no modules needed.
import ctypes, ctypes.util, sys
x = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11") or "libX11.so.6")
x.XOpenDisplay.restype = ctypes.c_void_p
x.XOpenDisplay.argtypes = [ctypes.c_char_p]
d = ctypes.c_void_p(x.XOpenDisplay(None))
if not d:
    sys.exit("wallpaper: cannot open the display")
ul = ctypes.c_ulong
x.XDefaultRootWindow.restype = ul; x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
x.XDefaultScreen.argtypes = [ctypes.c_void_p]
x.XDefaultDepth.argtypes = [ctypes.c_void_p, ctypes.c_int]
x.XDisplayWidth.argtypes = x.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
x.XCreatePixmap.restype = ul; x.XCreatePixmap.argtypes = [ctypes.c_void_p, ul, ctypes.c_uint, ctypes.c_uint, ctypes.c_uint]
x.XCreateGC.restype = ctypes.c_void_p; x.XCreateGC.argtypes = [ctypes.c_void_p, ul, ul, ctypes.c_void_p]
x.XSetForeground.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ul]
x.XFillRectangle.argtypes = [ctypes.c_void_p, ul, ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_uint, ctypes.c_uint]
x.XInternAtom.restype = ul; x.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
x.XChangeProperty.argtypes = [ctypes.c_void_p, ul, ul, ul, ctypes.c_int, ctypes.c_int, ctypes.c_void_p, ctypes.c_int]
x.XSetWindowBackgroundPixmap.argtypes = [ctypes.c_void_p, ul, ul]
x.XClearWindow.argtypes = [ctypes.c_void_p, ul]
x.XSetCloseDownMode.argtypes = [ctypes.c_void_p, ctypes.c_int]
x.XCloseDisplay.argtypes = [ctypes.c_void_p]
s = x.XDefaultScreen(d); root = x.XDefaultRootWindow(d)
w, h = x.XDisplayWidth(d, s), x.XDisplayHeight(d, s)
pm = x.XCreatePixmap(d, root, w, h, x.XDefaultDepth(d, s))
gc = x.XCreateGC(d, pm, 0, None)
top, bottom = (0x2b, 0x4f, 0x6e), (0x6d, 0x8f, 0xa8)
for y in range(0, h, 4):
    t = y / (h - 1)
    r, g, b = (round(a + (c - a) * t) for a, c in zip(top, bottom))
    x.XSetForeground(d, gc, (r << 16) | (g << 8) | b)
    x.XFillRectangle(d, pm, gc, 0, y, w, 4)
pixmap_id = ul(pm)
for name in (b"_XROOTPMAP_ID", b"ESETROOT_PMAP_ID"):
    x.XChangeProperty(d, root, x.XInternAtom(d, name, 0), x.XInternAtom(d, b"PIXMAP", 0), 32, 0, ctypes.byref(pixmap_id), 1)
x.XSetWindowBackgroundPixmap(d, root, pm)
x.XClearWindow(d, root)
x.XSetCloseDownMode(d, 1)  # RetainPermanent: the pixmap outlives this client
x.XCloseDisplay(d)
EOF

# The requester: hello, then an aim at the field point given every 0.3 s,
# until killed. Writes the first target's title to the file given, so the
# shell knows the provider has drawn the ring.
cat >"$work/aim.py" <<'EOF'
import asyncio, json, ssl, sys
import websockets

url, token, u, v, ready = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]

async def main():
    tls = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    tls.check_hostname = False
    tls.verify_mode = ssl.CERT_NONE  # a screenshot tool on 127.0.0.1: the provider's certificate is self-signed
    async with websockets.connect(url, ssl=tls, max_size=1 << 20) as ws:
        await ws.send(json.dumps({"type": "hello", "v": 1, "id": 1, "token": token, "client": "screenshots"}))
        welcome = json.loads(await ws.recv())
        if welcome.get("type") != "welcome":
            sys.exit(f"aim.py: no welcome: {welcome}")
        n, told = 1, False
        while True:
            n += 1
            await ws.send(json.dumps({"type": "aim", "v": 1, "id": n, "point": [u, v], "confidence": 0.9}))
            reply = json.loads(await ws.recv())
            if reply.get("type") == "target" and not told:
                with open(ready, "w") as f:
                    f.write(f'{reply.get("kind")}: {reply.get("title", "")}\n')
                told = True
            await asyncio.sleep(0.3)

asyncio.run(main())
EOF

# The put: hello with a device name (so the card offers "always"), an aim at
# the field point given, then a file put there; writes the put's first
# answer to the file given once the provider is asking the screen, and
# keeps aiming (so the ring stays) until killed. Nothing is uploaded.
cat >"$work/put.py" <<'EOF'
import asyncio, json, ssl, sys
import websockets

url, token, u, v, ready = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]

async def main():
    tls = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    tls.check_hostname = False
    tls.verify_mode = ssl.CERT_NONE  # a screenshot tool on 127.0.0.1: the provider's certificate is self-signed
    async with websockets.connect(url, ssl=tls, max_size=1 << 20) as ws:
        await ws.send(json.dumps({"type": "hello", "v": 1, "id": 1, "token": token, "client": "Pixel 7",
                                  "device": "screenshots-pixel-7"}))
        welcome = json.loads(await ws.recv())
        if welcome.get("type") != "welcome" or "put" not in welcome.get("features", []):
            sys.exit(f"put.py: no welcome with puts: {welcome}")
        await ws.send(json.dumps({"type": "aim", "v": 1, "id": 2, "point": [u, v], "confidence": 0.9}))
        await ws.recv()
        await ws.send(json.dumps({"type": "put", "v": 1, "id": "p1", "point": [u, v], "kind": "file",
                                  "name": "q3-report-final.pdf", "mime": "application/pdf", "size": 2411724,
                                  "sha256": "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08"}))
        reply = json.loads(await ws.recv())
        with open(ready, "w") as f:
            f.write(f'{reply.get("type")}: {reply.get("status", reply.get("message", ""))}\n')
        n = 2
        while True:
            await asyncio.sleep(0.3)
            n += 1
            await ws.send(json.dumps({"type": "aim", "v": 1, "id": n, "point": [u, v], "confidence": 0.9}))

asyncio.run(main())
EOF

# --- The desktop --------------------------------------------------------------
# Xvfb picks a free display and writes its number once it accepts clients.
mkfifo "$work/display"
# (Not through spawn: the fifo is opened by the child, not this shell.)
Xvfb -displayfd 3 -screen 0 "$size" -nolisten tcp -noreset 3>"$work/display" 2>"$work/xvfb.log" &
pids=("$!" "${pids[@]}")
read -r number <"$work/display" || { cat "$work/xvfb.log" >&2; die "Xvfb did not start"; }
export DISPLAY=":$number"
unset WAYLAND_DISPLAY
export XDG_RUNTIME_DIR="$work/runtime" QT_QPA_PLATFORM=xcb
mkdir -m 700 "$XDG_RUNTIME_DIR"
echo "screenshots on DISPLAY=$DISPLAY"

# The wallpaper before the compositor, which paints the root's background.
"$python" "$work/wallpaper.py"
spawn openbox --sm-disable >"$work/openbox.log" 2>&1
wait_for 'xprop -root _NET_SUPPORTING_WM_CHECK | grep -q "window id"' || die "openbox did not start"
spawn xcompmgr >"$work/xcompmgr.log" 2>&1

spawn mupdf -r 96 "$work/q3-report.pdf" >"$work/mupdf.log" 2>&1
wait_for 'xdotool search --onlyvisible --name "q3-report.pdf"' || die "mupdf did not show its window"
mupdf_window=$(xdotool search --onlyvisible --name "q3-report.pdf" | head -1)
xdotool windowmove "$mupdf_window" 90 30

# The cursor hidden (DECTCEM): whether and how it shows depends on timing
# and focus, and the pictures should be the same on every run.
printf '\033[?25l' >>"$work/notes.txt"
spawn xterm -geometry 76x20+1000+140 -fa 'DejaVu Sans Mono' -fs 11 -bg '#fdf6e3' -fg '#073642' \
    -T "notes" -hold -e cat "$work/notes.txt" >/dev/null 2>&1
wait_for 'xdotool search --onlyvisible --name "^notes$"' || die "xterm did not show its window"
xdotool windowactivate --sync "$(xdotool search --onlyvisible --name "^notes$" | head -1)"
sleep 0.5

# --- The provider ---------------------------------------------------------------
provider_pid=
# Starts umf-provider with the arguments given and waits for its overlay.
start_provider() {
    local log=$work/provider.log
    : >"$log"
    spawn "$bin/umf-provider" --config-dir "$work/config" --bind 127.0.0.1 --port 0 --no-qr "$@" >"$log" 2>&1
    provider_pid=${pids[0]}
    wait_for "grep -q '^overlay: ' '$log'" 15 || { cat "$log" >&2; die "umf-provider did not start its overlay"; }
    port=$(sed -n 's|^umf-provider: listening on https://127.0.0.1:\([0-9]*\).*|\1|p' "$log")
    token=$(sed -n 's|^pairing URL: .*#t=\([A-Za-z0-9_-]*\)&.*|\1|p' "$log")
    [[ -n $port && -n $token ]] || { cat "$log" >&2; die "no port or token in umf-provider's output"; }
}
stop_provider() { stop "$provider_pid"; }
written=()
# The root window, scaled for the README.
shoot_root() {
    import -window root "$work/root.png"
    convert "$work/root.png" -resize "${width}x" -strip -colors 256 "PNG8:$1"
    written+=("$(basename "$1")")
}

# 1. The field over the desktop, static at a visible opacity.
start_provider --preset visible --period 0 --opacity-min 0.35 --opacity-max 0.35
wait_for 'xdotool search --onlyvisible --name "^umf overlay$"' || die "the overlay did not show"
sleep 0.7
shoot_root "$out/overlay-desktop.png"
stop_provider

# 2. The focus region: the field only around where a phone aims. Minimum and
# maximum alike: confident aims lower the opacity towards the minimum, and
# the picture should not depend on how long that ran.
start_provider --preset visible --period 0 --opacity-min 0.5 --opacity-max 0.5 --region focus --focus-radius 7
# A field point over the PDF's chart, at pixel (480, 660): the field is
# 64 x 36 modules of 30 px on 1920 x 1080.
spawn "$python" "$work/aim.py" "wss://127.0.0.1:$port/ws" "$token" 16 22 "$work/aimed" 2>"$work/aim.log"
aim_pid=${pids[0]}
wait_for "test -s '$work/aimed'" 10 || { cat "$work/aim.log" >&2; die "the aim got no target"; }
sleep 1
# At full size, cropped around the aim, so the ring's title can be read.
import -window root "$work/root.png"
convert "$work/root.png" -crop 1280x720+0+200 +repage -strip -colors 256 "PNG8:$out/overlay-focus.png"
written+=(overlay-focus.png)
echo "aimed at: $(cat "$work/aimed")"
stop "$aim_pid"
stop_provider

# 3. A put: the card at the pointed place asks whether to take the file.
# Taken as soon as the card shows, while its countdown bar is still whole
# (it shrinks once a quarter second). The put folder is the script's own.
start_provider --preset visible --period 0 --opacity-min 0.35 --opacity-max 0.35 --put-dir "$work/put"
# A field point over the PDF's text, at pixel (420, 330).
: >"$work/put-ready"
spawn "$python" "$work/put.py" "wss://127.0.0.1:$port/ws" "$token" 14 11 "$work/put-ready" 2>"$work/put.log"
put_pid=${pids[0]}
wait_for "test -s '$work/put-ready'" 10 || { cat "$work/put.log" >&2; die "the put got no answer"; }
grep -q '^put_status: asking' "$work/put-ready" || die "the put was not asked about: $(cat "$work/put-ready")"
# The card: a window of umf-provider's the size of a card (the overlay
# covers the screen, the ring is smaller).
find_card() {
    local w
    for w in $(xdotool search --onlyvisible --class umf-provider); do
        eval "$(xdotool getwindowgeometry --shell "$w")"
        ((WIDTH >= 300 && WIDTH <= 460 && HEIGHT >= 80 && HEIGHT <= 300)) && { echo "$w"; return 0; }
    done
    return 1
}
wait_for find_card 5 || die "the put card did not show"
sleep 0.05  # a frame for the compositor
import -window root "$work/root.png"
convert "$work/root.png" -crop 960x540+60+120 +repage -strip -colors 256 "PNG8:$out/put-prompt.png"
written+=(put-prompt.png)
stop "$put_pid"
stop_provider

# 4. The tuning window. Without a tray: the screen it grabs for its preview
# would show the tray icon or not, as the race between the two went.
# A preset of the user's own, static so that the window's preview, which
# pulses with the preset, looks the same on every run; on demand, so the
# screen the window grabs for its preview has no field on it.
cat >"$work/config/presets.json" <<'EOF'
[
  {"name": "meeting room", "opacity_min": 0.3, "opacity_max": 0.3, "period_s": 0, "waveform": "sine",
   "module_px": 30, "palette": [], "blur": 0, "region": "focus", "focus_radius_modules": 8,
   "activation": "on_demand", "fade_s": 3}
]
EOF
start_provider --preset "meeting room" --tune
# The tuning window: a managed (framed) window of umf-provider's; the overlay
# is unmanaged and has no frame extents.
find_tuning() {
    local w
    for w in $(xdotool search --onlyvisible --class umf-provider); do
        xprop -id "$w" _NET_FRAME_EXTENTS | grep -q = &&
            xprop -id "$w" WM_NAME | grep -q -E '"umf: overlay tuning"|"umf overlay"' &&
            { echo "$w"; return 0; }
    done
    return 1
}
wait_for find_tuning || die "the tuning window did not show"
tune_window=$(find_tuning)
sleep 0.5
# "From screen": the palette taken from the desktop, so the swatches show.
# The button's place in the window (883 x 433 at Qt's default font).
xdotool mousemove --window "$tune_window" 721 350 click 1 mousemove 1000 1000
sleep 0.5
import -frame -window "$tune_window" "$work/tune.png"
convert "$work/tune.png" -strip -colors 256 "PNG8:$out/tuning-window.png"
written+=(tuning-window.png)

stop_provider

# 5. The tray menu.
if ((tray)); then
    spawn trayer --edge bottom --align right --widthtype request --height 28 --SetDockType true \
        --transparent false --tint 0x2b3a48 >"$work/trayer.log" 2>&1
    wait_for 'xdotool search --onlyvisible --class trayer' || die "trayer did not start"
    start_provider --preset "meeting room"
    wait_for 'xdotool search --onlyvisible --class umf-provider' || die "the tray icon did not show"
    sleep 0.5
    # Right-click the tray icon (the only one in trayer's panel), then point
    # at "Preset" so its submenu opens too.
    eval "$(xdotool getwindowgeometry --shell "$(xdotool search --onlyvisible --class trayer | head -1)")"
    xdotool mousemove $((X + WIDTH / 2)) $((Y + HEIGHT / 2)) click 3
    find_menu() {
        local w
        for w in $(xdotool search --onlyvisible --class umf-provider); do
            eval "$(xdotool getwindowgeometry --shell "$w")"
            ((HEIGHT > 60 && HEIGHT < 400)) && { echo "$w"; return 0; }
        done
        return 1
    }
    wait_for find_menu 5 || die "the tray menu did not open"
    eval "$(xdotool getwindowgeometry --shell "$(find_menu)")"
    # "Preset" is the second item: about 31 px below the menu's top.
    xdotool mousemove $((X + 50)) $((Y + 31))
    sleep 0.8
    import -window root "$work/root.png"
    top=$((Y - 60))
    convert "$work/root.png" -crop "720x$((1080 - top))+1200+$top" +repage -strip -colors 256 "PNG8:$out/tray-menu.png"
    written+=(tray-menu.png)
    xdotool key Escape key Escape
    stop_provider
fi

echo "wrote ${written[*]} to $out in $(($(date +%s) - started)) s"
