#!/usr/bin/env bash
# The species contact sheet (issue 12): every species preset at seeds 1 and 2, then seed 1 in autumn
# and in winter, rendered by `sylva export ... .png` and assembled with ImageMagick's montage.
#   bash scripts/species-sheet.sh [BUILD_DIR] [OUT_PNG]      (defaults: build, out/species.png; out/ is git-ignored)
# Needs a display (run under xvfb-run -a -s "-screen 0 1280x1024x24" when there is none).
# SPECIES="oak pine" limits the species; SIZE sets each tile's edge in pixels (default 256).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=${2:-out/species.png}
mkdir -p "$(dirname "$OUT")"
SIZE=${SIZE:-256}
SYLVA="$BUILD/app/sylva"
SPECIES=${SPECIES:-"oak maple beech birch ash poplar willow pine spruce fir cedar cypress palm sapling bush"}
# One light for every tile, so species are compared like for like: a clear afternoon sun from the
# camera's side, no light shafts (at tile size they only wash the crowns out).
LIGHT=(--set light_shafts=off --set sun_elevation=32 --set sun_azimuth=70 --set fog_density=0.004)
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24" "$0" "$@"
fi
command -v montage >/dev/null || { echo "species-sheet: ImageMagick's montage is missing (apt-get install imagemagick)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
tiles=()
for s in $SPECIES; do
  preset="presets/species_$s.json"
  [ -f "$preset" ] || { echo "species-sheet: no $preset" >&2; exit 1; }
  "$SYLVA" export "$preset" -o "$TMP/$s.png" --seeds 1-2 --width "$SIZE" --height "$SIZE" "${LIGHT[@]}" >/dev/null
  "$SYLVA" export "$preset" -o "$TMP/$s-autumn.png" --seed 1 --width "$SIZE" --height "$SIZE" "${LIGHT[@]}" --set season=autumn >/dev/null
  "$SYLVA" export "$preset" -o "$TMP/$s-winter.png" --seed 1 --width "$SIZE" --height "$SIZE" "${LIGHT[@]}" --set season=winter >/dev/null
  name=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['name'])" "$preset")
  tiles+=(-label "$name, seed 1" "$TMP/$s-1.png" -label "seed 2" "$TMP/$s-2.png"
          -label "autumn" "$TMP/$s-autumn.png" -label "winter" "$TMP/$s-winter.png")
  echo "species-sheet: $s"
done
montage "${tiles[@]}" -tile 8x -geometry "${SIZE}x${SIZE}+3+3" -font DejaVu-Sans -pointsize 14 -background white "$TMP/sheet.png"
# A 256-colour palette keeps the sheet near 1.5 MB instead of 6 MB, with no visible banding.
convert "$TMP/sheet.png" -colors 256 "PNG8:$OUT"
echo "species-sheet: wrote $OUT"
