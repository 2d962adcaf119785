#!/usr/bin/env bash
# Blender contact sheet (issue 23; docs/JUDGING.md): exports every species preset as GLB, imports
# each with Blender 3.4's glTF importer, renders it in Cycles (CPU, no denoising) under a sun and a
# sky-coloured world, measures the share of unlit ("black") leaf pixels, and montages a labelled
# sheet.
#
#   bash scripts/blender-sheet.sh [SYLVA_BINARY] [PRESET_DIR] [OUT_PNG]
#
# SYLVA_BINARY defaults to ./build/app/sylva, PRESET_DIR to presets/, OUT_PNG to
# out/blender_species.png (out/ is git-ignored). SIZE (320) is each tile's size, SAMPLES (16) the Cycles samples,
# EXCLUDE (species_forest: nine trees, four million triangles) the presets left out, WORK_DIR
# (a temporary directory) where the renders, leaf masks and leaves.json go, CONTROL=1 adds a
# render of the first tree with black leaves to prove the measure sees them (and its tile),
# MONTAGE_ONLY=1 with WORK_DIR redraws the sheet from an earlier run, TRANSPARENT_BOUNCES
# Cycles' transparent bounce limit (64, the foliage setting docs/DESIGN-NOTES.md asks for:
# Blender's default of 8 runs out inside a crown of cut-out cards; 8 shows what that looks like). Installs Debian's
# blender, python3-numpy and imagemagick when missing (apt-get as root, sudo otherwise).
set -euo pipefail

SYLVA=${1:-./build/app/sylva}
PRESETS=${2:-presets}
OUT_PNG=${3:-out/blender_species.png}
SIZE=${SIZE:-320}
SAMPLES=${SAMPLES:-16}
EXCLUDE=${EXCLUDE:-species_forest}
CONTROL=${CONTROL:-0}
HERE="$(cd "$(dirname "$0")/.." && pwd)"
start=$(date +%s)

[ -x "$SYLVA" ] || { echo "blender-sheet: no sylva binary at $SYLVA (build it, or pass its path)" >&2; exit 1; }
[ -d "$PRESETS" ] || { echo "blender-sheet: no preset directory $PRESETS" >&2; exit 1; }

need=()
command -v blender >/dev/null 2>&1 || need+=(blender)
dpkg-query -W -f='${Status}' python3-numpy 2>/dev/null | grep -q 'ok installed' || need+=(python3-numpy)  # Blender's Python reads Debian's numpy
command -v montage >/dev/null 2>&1 || need+=(imagemagick)
fc-list 2>/dev/null | grep -qi dejavu || need+=(fonts-dejavu-core)
. "$(dirname "$0")/viewer-deps.sh"
apt_install_missing blender-sheet "${need[@]}"

if [ -n "${WORK_DIR:-}" ]; then
  WORK=$WORK_DIR
  mkdir -p "$WORK"
else
  WORK=$(mktemp -d)
  trap 'rm -rf "$WORK"' EXIT
fi
if [ "${MONTAGE_ONLY:-0}" = 1 ]; then
  [ -f "$WORK/renders/leaves.json" ] || { echo "blender-sheet: MONTAGE_ONLY=1 needs WORK_DIR of an earlier run" >&2; exit 1; }
else
  mkdir -p "$WORK/glb"
  glbs=()
  for preset in "$PRESETS"/species_*.json; do
    [ -e "$preset" ] || continue
    name=$(basename "$preset" .json)
    case " $EXCLUDE " in *" $name "*) continue ;; esac
    if "$SYLVA" export "$preset" -o "$WORK/glb/$name.glb" >"$WORK/glb/$name.log" 2>&1; then
      glbs+=("$WORK/glb/$name.glb")
    else
      echo "blender-sheet: export of $preset failed:" >&2
      sed 's/^/  /' "$WORK/glb/$name.log" >&2
    fi
  done
  [ ${#glbs[@]} -gt 0 ] || { echo "blender-sheet: nothing exported" >&2; exit 1; }
  echo "blender-sheet: exported ${#glbs[@]} species in $(($(date +%s) - start)) s; rendering in Cycles" >&2

  extra=()
  [ "$CONTROL" = 1 ] && extra=(--control)
  extra+=(--transparent-bounces "${TRANSPARENT_BOUNCES:-64}")
  status=0
  blender -b --factory-startup --python "$HERE/tools/blender/render_sheet.py" -- "$WORK/renders" \
    --size "$SIZE" --samples "$SAMPLES" "${extra[@]}" "${glbs[@]}" >"$WORK/blender.log" 2>&1 || status=$?
  grep '^SHEET ' "$WORK/blender.log" | sed 's/^SHEET /blender-sheet: /' || true
  if [ $status -ne 0 ] || [ ! -f "$WORK/renders/leaves.json" ]; then
    echo "blender-sheet: blender failed ($status); last lines of $WORK/blender.log:" >&2
    tail -20 "$WORK/blender.log" >&2
    exit 1
  fi
fi

# The sheet: each render on the viewer's background, labelled with its name and unlit-leaf share.
mapfile -t tiles < <(CONTROL=$CONTROL python3 - "$WORK/renders" <<'EOF'
import json, os, sys
d = sys.argv[1]
run = json.load(open(os.path.join(d, "leaves.json")))
print(run["samples"]); print(run["transparent_max_bounces"])
for t in run["trees"]:
    if t.get("control") and os.environ.get("CONTROL") != "1":
        continue
    name = t["name"].removeprefix("species_")
    if "leaf_px" in t:
        label = f"{name}\nunlit leaves {100 * t['leaf_unlit']:.1f}%"
        print(label.replace("\n", "\\n")); print(os.path.join(d, t["name"] + ".png"))
    else:
        print(f"{name}\\nfailed"); print("xc:#c8ccd0")
EOF
)
samples=${tiles[0]}
bounces=${tiles[1]}
args=()
for ((i = 2; i < ${#tiles[@]}; i += 2)); do args+=(-label "${tiles[i]}" "${tiles[i+1]}"); done
mkdir -p "$(dirname "$OUT_PNG")"
version=$(blender --version 2>/dev/null | head -1)
montage "${args[@]}" -tile 6x -geometry "${SIZE}x${SIZE}+4+4" -background '#e8ecef' -font DejaVu-Sans -pointsize 14 "$OUT_PNG"
convert "$OUT_PNG" -background '#e8ecef' -gravity north -splice 0x56 -font DejaVu-Sans -pointsize 18 -fill black \
  -annotate +0+6 "Sylva species GLBs in $version Cycles (CPU, $samples samples, no denoising, $bounces transparent bounces), iso view\nunlit leaves: share of leaf pixels that receive diffuse light < 0.03" \
  -colors 255 "PNG8:$OUT_PNG"  # a palette PNG: a sixth of the size
echo "blender-sheet: wrote $OUT_PNG (renders and leaves.json in $WORK/renders) in $(($(date +%s) - start)) s" >&2
