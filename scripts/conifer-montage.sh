#!/bin/bash
# Makes out/conifers.png (out/ is git-ignored): spruce, fir, cedar, cypress and pine side by side
# at 256 px, three.js iso view above, front view below (the comparison's viewer).
# Usage: bash scripts/conifer-montage.sh [build]
set -e
build=${1:-build}
tmp=$(mktemp -d)
for s in spruce fir cedar cypress pine; do
  "$build/app/sylva" export "presets/species_$s.json" -o "$tmp/$s.glb" >/dev/null
  node tools/viewer/render.mjs "$tmp/$s.glb" "$tmp/${s}_iso.png" >/dev/null 2>&1
  node tools/viewer/render.mjs "$tmp/$s.glb" "$tmp/${s}_front.png" --view front >/dev/null 2>&1
done
cd "$tmp"
montage spruce_iso.png fir_iso.png cedar_iso.png cypress_iso.png pine_iso.png -tile 5x1 -geometry 256x256+2+2 iso.png
montage spruce_front.png fir_front.png cedar_front.png cypress_front.png pine_front.png -tile 5x1 -geometry 256x256+2+2 front.png
cd - >/dev/null
mkdir -p out
montage "$tmp/iso.png" "$tmp/front.png" -tile 1x2 -geometry +0+0 out/conifers.png
rm -r "$tmp"
echo out/conifers.png
