#!/usr/bin/env bash
# out/lod_sheet.jpg (out/ is git-ignored; docs/lod_sheet.jpg is a copy): LOD0-LOD3 of three species
# presets rendered alike (one row each), then their impostor colour atlases on grey. Needs an X
# display (run under xvfb-run -a) and ImageMagick.
# Usage: scripts/lod-sheet.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
names=(species_oak species_pine species_maple_cards)
paths=()
for n in "${names[@]}"; do paths+=("$root/presets/$n.json"); done
"$build/app/sylva" bench --lods --repeat 1 --sheet "$tmp" --width 320 --height 320 "${paths[@]}"
levels=() atlases=()
for n in "${names[@]}"; do
  for k in 0 1 2 3; do levels+=("$tmp/${n}_lod$k.png"); done
  convert "$tmp/${n}_impostor.png" -background '#808080' -flatten "$tmp/${n}_flat.png"
  atlases+=("$tmp/${n}_flat.png")
done
mkdir -p "$root/out"
montage "${levels[@]}" -tile 4x3 -geometry 256x256+2+2 "$tmp/levels.png"
montage "${atlases[@]}" -tile 3x1 -geometry 340x170+2+2 "$tmp/atlases.png"
convert "$tmp/levels.png" "$tmp/atlases.png" -gravity center -background white -append +repage -depth 8 -quality 85 \
  "$root/out/lod_sheet.jpg"
echo "wrote $root/out/lod_sheet.jpg"
