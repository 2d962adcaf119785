#!/usr/bin/env bash
# Renders Sylva's species presets and ez-tree's presets in the same three.js viewer (headless
# Chromium) and measures leaf coverage of the crown hull (issue 11; docs/COMPARE.md).
#
#   bash scripts/compare-trees.sh [SYLVA_BINARY] [PRESET_DIR]
#
# SYLVA_BINARY defaults to ./build/app/sylva, PRESET_DIR to presets/ (both relative to where it
# is run, normally the repository root). Writes out/compare/*.png, out/compare/coverage.json
# and out/side_by_side.png (out/ is git-ignored), and prints the coverage table. Installs what it needs on first use:
# Debian chromium and imagemagick (apt, only when missing) and tools/viewer's npm packages
# (only when missing). SYLVA_CHROMIUM overrides the browser path; SIZE the image size (768).
set -euo pipefail

SYLVA=${1:-./build/app/sylva}
PRESETS=${2:-presets}
OUT_DIR=${OUT_DIR:-out/compare}
GRID=${GRID:-out/side_by_side.png}
SIZE=${SIZE:-768}
VIEWER="$(cd "$(dirname "$0")/../tools/viewer" && pwd)"
start=$(date +%s)

if [ ! -x "$SYLVA" ]; then
  echo "compare-trees: no sylva binary at $SYLVA (build it, or pass its path)" >&2
  exit 1
fi
if [ ! -d "$PRESETS" ]; then
  echo "compare-trees: no preset directory $PRESETS" >&2
  exit 1
fi

# Debian packages and the viewer's npm packages, only when missing.
. "$(dirname "$0")/viewer-deps.sh"
viewer_deps compare-trees "$VIEWER"

# Export every species preset.
GLB_DIR=$(mktemp -d)
trap 'rm -rf "$GLB_DIR"' EXIT
export_start=$(date +%s)
for preset in "$PRESETS"/species_*.json; do
  [ -e "$preset" ] || continue
  name=$(basename "$preset" .json)
  if ! "$SYLVA" export "$preset" -o "$GLB_DIR/$name.glb" >"$GLB_DIR/$name.log" 2>&1; then
    echo "compare-trees: export of $preset failed:" >&2
    sed 's/^/  /' "$GLB_DIR/$name.log" >&2
    rm -f "$GLB_DIR/$name.glb"
  fi
done
export_end=$(date +%s)
echo "compare-trees: exported $(ls "$GLB_DIR"/*.glb 2>/dev/null | wc -l) species presets in $((export_end - export_start)) s" >&2

status=0
node "$VIEWER/compare.mjs" --glb-dir "$GLB_DIR" --preset-dir "$PRESETS" --out-dir "$OUT_DIR" \
  --grid "$GRID" --size "$SIZE" --binary "$SYLVA" || status=$?
echo "compare-trees: done in $(($(date +%s) - start)) s" >&2
exit $status
