#!/usr/bin/env bash
# Issue 17's goal "wind costs the lit and shadow passes < 15 % more": `sylva bench --render
# --preset-light` with and without `--set render.wind=true`, in alternated pairs (calm first in odd
# pairs, wind first in even ones, so that a drifting machine load cancels), per preset; prints each
# pass's median over the pairs and the median of the pairs' wind/calm ratios.
#   bash scripts/wind-cost.sh [PAIRS] [FRAMES] [PRESET...]   (needs DISPLAY, e.g. under xvfb-run)
# Environment: SYLVA (binary), WIDTH, HEIGHT (default 1280x720).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sylva=${SYLVA:-$root/build/app/sylva}
pairs=${1:-8}
frames=${2:-3}
shift $(($# < 2 ? $# : 2))
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=("$root/presets/species_oak.json" "$root/presets/species_pine.json")
width=${WIDTH:-1280}
height=${HEIGHT:-720}
run() {   # preset, extra args -> "shadow lit"
  "$sylva" bench --render --preset-light --json --repeat "$frames" --width "$width" --height "$height" "${@:2}" "$1" 2>/dev/null |
    jq -r '"\(.shadow_ms) \(.lit_ms)"'
}
for p in "${presets[@]}"; do
  rows=""
  for ((i = 1; i <= pairs; ++i)); do
    if ((i % 2)); then calm=$(run "$p"); wind=$(run "$p" --set render.wind=true)
    else wind=$(run "$p" --set render.wind=true); calm=$(run "$p"); fi
    rows+="$calm $wind"$'\n'
  done
  printf '%s' "$rows" | awk -v name="$(basename "$p" .json)" -v n="$pairs" -v w="$width" -v h="$height" '
    function median(a, k,   i, j, t) {   # sorts a[1..k] in place
      for (i = 2; i <= k; ++i) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; --j) a[j + 1] = a[j]; a[j + 1] = t }
      return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
    }
    { ++k; cs[k] = $1; cl[k] = $2; ws[k] = $3; wl[k] = $4; rs[k] = $1 > 0 ? $3 / $1 : 0; rl[k] = $2 > 0 ? $4 / $2 : 0 }
    END {
      printf "%s %dx%d, %d pairs: shadow %.1f -> %.1f ms (median ratio %.3f), lit %.1f -> %.1f ms (median ratio %.3f)\n",
             name, w, h, n, median(cs, k), median(ws, k), median(rs, k), median(cl, k), median(wl, k), median(rl, k)
    }'
done
