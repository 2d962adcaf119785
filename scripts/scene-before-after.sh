#!/usr/bin/env bash
# Renders the same tree before and after the scene work of issue 13 (physical sky, volumetric
# shafts, fog, ground, framing) at noon and golden hour, front-lit and backlit, and puts the eight
# images side by side in out/scene_before_after.png (git-ignored) (top row: before; bottom row: after).
#
#   scripts/scene-before-after.sh OLD_SYLVA NEW_SYLVA [PRESET] [OUT]
#
# OLD_SYLVA is a build of commit a70b52a (the last one before issue 13), for instance:
#   git worktree add /tmp/sylva-old a70b52a && make -C /tmp/sylva-old build && OLD=/tmp/sylva-old/build/app/sylva
# Needs a display (xvfb-run -a) and ImageMagick's montage.
set -euo pipefail
OLD=${1:?old sylva binary}
NEW=${2:?new sylva binary}
PRESET=${3:-presets/self_organizing_default.json}
OUT=${4:-out/scene_before_after.png}
mkdir -p "$(dirname "$OUT")"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
run() { if [ -n "${DISPLAY:-}" ]; then "$@"; else xvfb-run -a "$@"; fi; }
# The camera looks from azimuth ~30-35°: front-lit puts the sun behind it, backlit in front.
views=("noon-front:60:30" "noon-back:60:-150" "golden-front:8:30" "golden-back:8:-150")
files=()
for who in before after; do
  bin=$OLD; [ "$who" = after ] && bin=$NEW
  for v in "${views[@]}"; do
    IFS=: read -r name elev az <<<"$v"
    f="$TMP/$who-$name.png"
    run "$bin" export "$PRESET" -o "$f" --width 480 --height 270 \
      --set render.sun_elevation="$elev" --set render.sun_azimuth="$az" >/dev/null
    files+=(-label "$who: $name" "$f")
  done
done
montage "${files[@]}" -tile 4x2 -geometry +3+3 -font DejaVu-Sans -pointsize 14 "$OUT"
echo "$OUT"
