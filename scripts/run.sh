#!/usr/bin/env bash
# The main job until the provider exists: make the default field for a
# 1920 x 1080 screen, prove it 4-orientable, and draw it for screen and print.
set -euo pipefail
build=${1:-build/release}
tool="$build/bin/umf-field"
out=out
mkdir -p "$out"

echo "== generate a binary 64 x 36 field (30 px modules fill a 1920 x 1080 screen)"
"$tool" generate --width 64 --height 36 --window 4 --colors 2 --seed 1 --out "$out/b4-64x36.json"
echo "== verify"
"$tool" verify "$out/b4-64x36.json"
echo "== render"
"$tool" render "$out/b4-64x36.json" --out "$out/b4-64x36.png" --module-px 30
"$tool" render "$out/b4-64x36.json" --out "$out/b4-64x36.svg" --module-px 30
"$tool" render "$out/b4-64x36.json" --out "$out/b4-64x36.pdf" --module-mm 4 --quiet-zone 2 \
  --caption "umf b4-64x36-s1, 4 mm modules"
echo "== info"
"$tool" info "$out/b4-64x36.json"
echo
echo "Done: $out/b4-64x36.png (screen, 1920 x 1080) and $out/b4-64x36.pdf (print, 4 mm modules)."
