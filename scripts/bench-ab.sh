#!/usr/bin/env bash
# Grow + mesh of two builds, interleaved, for the "against 9da944c" figures of docs/design/05-mesh.md.
#
#   scripts/bench-ab.sh BASE_BINARY BASE_PRESET_DIR NEW_BINARY ROUNDS [PRESET_NAME...]
#
# Without preset names, every preset that both BASE_PRESET_DIR and presets/ hold (by file name).
# Each round runs every preset once per build, `sylva bench P --repeat ${REPEAT:-15} --json`, in
# ABBA order (odd rounds base first, even rounds new first) so that a drift of the machine's speed
# falls on both; each build reads its own copy of the preset (BASE_PRESET_DIR/NAME.json for the
# base, presets/NAME.json here for the new build). Prints per preset the medians of the runs'
# medians, grow and mesh, and new / base of their sums. --repeat 15 makes each median a warm
# process's, as the editor's is; a machine busy with other work makes every figure larger.
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n 4,4p "$0" | sed 's/^#   /usage: /' >&2
  exit 2
fi
base=$1 base_dir=$2 new=$3 rounds=$4
shift 4
if [ $# = 0 ]; then
  set -- $(for f in "$base_dir"/*.json; do n=$(basename "$f" .json); [ -f "presets/$n.json" ] && echo "$n"; done)
fi
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for r in $(seq "$rounds"); do
  for name in "$@"; do
    if [ $((r % 2)) = 1 ]; then order="base new"; else order="new base"; fi
    for side in $order; do
      if [ "$side" = base ]; then bin=$base preset=$base_dir/$name.json; else bin=$new preset=presets/$name.json; fi
      "$bin" bench "$preset" --repeat "${REPEAT:-15}" --json 2>/dev/null | sed "s/^{/{\"side\":\"$side\",/" >> "$out"
    done
  done
done
python3 - "$out" <<'PY'
import collections, json, statistics, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    try:
        j = json.loads(line)
    except ValueError:
        continue
    if 'preset' in j:
        runs[(j['preset'], j['side'])].append((j['grow_ms'], j['mesh_ms'], j['leaves'], j['triangles']))
# leaves and tris: new / base of the trees' leaf and triangle counts (a tree that carries more is
# not the same work).
print("%-34s %9s %9s %9s %9s %9s %7s %7s" % ("preset", "grow base", "mesh base", "grow new", "mesh new", "new/base",
                                            "leaves", "tris"))
for name in sorted({k[0] for k in runs}):
    b, n = runs[(name, 'base')], runs[(name, 'new')]
    if not b or not n:
        continue
    gb, mb = statistics.median(x[0] for x in b), statistics.median(x[1] for x in b)
    gn, mn = statistics.median(x[0] for x in n), statistics.median(x[1] for x in n)
    ratio = lambda k: n[0][k] / b[0][k] if b[0][k] else float('inf') if n[0][k] else 1.0
    print("%-34s %9.2f %9.2f %9.2f %9.2f %9.3f %7.2f %7.2f" % (name, gb, mb, gn, mn, (gn + mn) / (gb + mb), ratio(2), ratio(3)))
PY
