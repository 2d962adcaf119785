#!/usr/bin/env bash
# Issue 17's wind export, checked outside Sylva: `sylva export PRESET --wind SECONDS` ->
#   1. the Khronos validator (0 errors, 0 warnings),
#   2. three.js (tools/viewer, headless Chromium): the "wind" clip posed at two moments gives two
#      different images, and at 0 s and SECONDS the same image (a seamless loop),
#   3. Blender 3.4 (tools/blender/check_wind.py): armature, action, motion, seamless loop,
#   4. the file-size cost per second of animation (two loop lengths).
#   bash scripts/wind-check.sh [SYLVA_BINARY] [PRESET] [SECONDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sylva=${1:-$root/build/app/sylva}
preset=${2:-$root/presets/species_oak.json}
seconds=${3:-4}
out=${WIND_CHECK_OUT:-$(mktemp -d)}
mkdir -p "$out"
glb=$out/wind.glb
"$sylva" export "$preset" -o "$glb" --wind "$seconds"
"$sylva" export "$preset" -o "$out/still.glb" >/dev/null
"$sylva" export "$preset" -o "$out/wind2x.glb" --wind "$((seconds * 2))" >/dev/null 2>&1
still=$(stat -c %s "$out/still.glb"); one=$(stat -c %s "$glb"); two=$(stat -c %s "$out/wind2x.glb")
echo "size: still $still B, --wind $seconds $one B, --wind $((seconds * 2)) $two B;" \
     "skin (fixed) $((one - still - (two - one))) B, animation $(((two - one) / seconds)) B per second"

node "$root/scripts/validate-gltf.js" "$glb"

if [ -d "$root/tools/viewer/node_modules/three" ] && [ -x "${SYLVA_CHROMIUM:-/usr/bin/chromium}" ]; then
  half=$(awk "BEGIN { print $seconds / 4 }")
  for t in 0 "$half" "$seconds"; do
    node "$root/tools/viewer/render.mjs" "$glb" "$out/three_$t.png" --size 384 --view front --animation wind --time "$t"
  done
  moved=$(compare -metric AE -fuzz 8% "$out/three_0.png" "$out/three_$half.png" /dev/null 2>&1 || true)
  gap=$(compare -metric AE -fuzz 8% "$out/three_0.png" "$out/three_$seconds.png" /dev/null 2>&1 || true)
  echo "three.js: $moved pixels differ between 0 s and $half s; $gap between 0 s and $seconds s"
  [ "${moved%% *}" -gt 50 ] || { echo "three.js: the wind does not move the tree"; exit 1; }
  [ "${gap%% *}" -lt 20 ] || { echo "three.js: the loop is not seamless"; exit 1; }
else
  echo "three.js: skipped (npm ci in tools/viewer; apt-get install chromium)"
fi

if command -v blender >/dev/null; then
  blender -b --factory-startup --python "$root/tools/blender/check_wind.py" -- "$glb" 2>&1 | grep -E "^check_wind" 
  [ "${PIPESTATUS[0]}" -eq 0 ] || exit 1
else
  echo "blender: skipped (apt-get install blender)"
fi
echo "wind-check: ok ($out)"
