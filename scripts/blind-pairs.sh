#!/usr/bin/env bash
# The blind-judging kit (issue 23; docs/JUDGING.md): exports every species preset (not the forest
# or the maple cluster cards), renders each next to the nearest ez-tree 1.1.0 preset in the
# three.js viewer (tools/viewer) and writes anonymised A/B pairs, unlabelled recognition images
# and the key.
#
#   bash scripts/blind-pairs.sh [SYLVA_BINARY] [PRESET_DIR] [OUT_DIR]
#
# SYLVA_BINARY defaults to ./build/app/sylva, PRESET_DIR to presets/, OUT_DIR to out/judging
# (out/ is git-ignored: no judging image is committed). Give a reader OUT_DIR/judge/ only;
# OUT_DIR/key.json is for tools/viewer/judge-score.mjs. With ImageMagick's montage it also writes
# two overview sheets for the lead: OUT_DIR/pairs.jpg (every pair's iso view, in the key's order)
# and OUT_DIR/closeups.jpg (the fifteen leaf close-ups). SEED (23) picks the left/right order and the image names, VIEWS
# (iso,front) the views, SIZE (768) the size of each tree's image. Installs what it needs on
# first use, as scripts/compare-trees.sh does.
set -euo pipefail

SYLVA=${1:-./build/app/sylva}
PRESETS=${2:-presets}
OUT=${3:-out/judging}
SEED=${SEED:-23}
VIEWS=${VIEWS:-iso,front}
CLOSE_UPS=${CLOSE_UPS-detail_leaves,detail_bark}  # recognition plates only; CLOSE_UPS= for none
SIZE=${SIZE:-768}
VIEWER="$(cd "$(dirname "$0")/../tools/viewer" && pwd)"
start=$(date +%s)

[ -x "$SYLVA" ] || { echo "blind-pairs: no sylva binary at $SYLVA (build it, or pass its path)" >&2; exit 1; }
[ -d "$PRESETS" ] || { echo "blind-pairs: no preset directory $PRESETS" >&2; exit 1; }

. "$(dirname "$0")/viewer-deps.sh"
viewer_deps blind-pairs "$VIEWER"

GLB_DIR=$(mktemp -d)
trap 'rm -rf "$GLB_DIR"' EXIT
for preset in "$PRESETS"/species_*.json; do
  [ -e "$preset" ] || continue
  name=$(basename "$preset" .json)
  case "$name" in species_forest|species_maple_cards) continue ;; esac
  if ! "$SYLVA" export "$preset" -o "$GLB_DIR/$name.glb" >"$GLB_DIR/$name.log" 2>&1; then
    echo "blind-pairs: export of $preset failed:" >&2
    sed 's/^/  /' "$GLB_DIR/$name.log" >&2
    rm -f "$GLB_DIR/$name.glb"
  fi
done
echo "blind-pairs: exported $(ls "$GLB_DIR"/*.glb 2>/dev/null | wc -l) species in $(($(date +%s) - start)) s" >&2

status=0
node "$VIEWER/blind-pairs.mjs" --glb-dir "$GLB_DIR" --preset-dir "$PRESETS" --out-dir "$OUT" \
  --seed "$SEED" --views "$VIEWS" --close-ups "$CLOSE_UPS" --size "$SIZE" --binary "$SYLVA" || status=$?
# The overview sheets once kept in docs/ as judging_pairs_roundN.jpg and
# judging_closeups_roundN.jpg (rounds 1-44).
if [ $status -eq 0 ] && command -v montage >/dev/null; then
  pairs=$(ls "$OUT"/judge/pairs/pair_??_*.png 2>/dev/null | grep -v _front || true)
  [ -z "$pairs" ] || montage $pairs -tile 3x -geometry 640x320+4+4 -quality 75 "$OUT/pairs.jpg"
  closeups=$(ls "$OUT"/judge/recognition/tree_??_detail_leaves.png 2>/dev/null || true)
  [ -z "$closeups" ] || montage $closeups -tile 5x -geometry 300x300+3+3 -quality 75 "$OUT/closeups.jpg"
fi
echo "blind-pairs: done in $(($(date +%s) - start)) s; give a reader $OUT/judge/, keep $OUT/key.json" >&2
exit $status
