#!/bin/bash
# Makes docs/images/invisible-preset.png: a part of a board as the provider
# shows it at the invisible preset's strongest (opacity 0.04, half a pulse
# period in), beside the same part without the field, and the difference
# between the two with its contrast stretched ten times, so that the field
# the first picture hides can be seen at all. Both screens come from
# `umf-provider compose` (the provider's own composition).
#
#   scripts/picture-invisible.sh            # writes docs/images/invisible-preset.png
#   UMF_BIN=build/debug/bin scripts/picture-invisible.sh
#
# Needs imagemagick (convert). Builds nothing: run `make` first if stale.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
bin=${UMF_BIN:-$root/build/release/bin}
out=${UMF_PICTURE_OUT:-$root/docs/images/invisible-preset.png}
board=$root/tests/web/browser/board/board.json
crop=640x360+40+120  # the board's first tiles, at the screen's own pixels

die() { echo "$0: $*" >&2; exit 1; }
[[ -x $bin/umf-provider ]] || die "$bin/umf-provider is missing: build it first (make), or set UMF_BIN"
convert -version 2>/dev/null | grep -q ImageMagick || die "convert is not ImageMagick's (apt-get install imagemagick)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
compose() {  # NAME, then compose's options
    local name=$1
    shift
    "$bin/umf-provider" compose --board "$board" --config-dir "$work/config" --out "$work/$name.png" \
        --map "$work/$name.json" "$@" > /dev/null
}
compose shown --preset invisible --time 0.75
compose content --preset invisible --opacity-min 0 --opacity-max 0 --time 0
convert "$work/shown.png" -crop "$crop" +repage "$work/a.png"
convert "$work/content.png" -crop "$crop" +repage "$work/b.png"
# The difference around mid grey, ten times: 0.04 of the range is about
# ten levels, shown as a hundred.
convert "$work/a.png" "$work/b.png" -fx '0.5 + 10 * (u - v)' "$work/d.png"
convert "$work/a.png" "$work/b.png" "$work/d.png" -bordercolor white -border 8 +append -resize 1280x "$out"
echo "wrote $out"
