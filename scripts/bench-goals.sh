#!/usr/bin/env bash
# The budgets that instant regrowth is held to (docs/design/05-mesh.md "Budgets, not 9da944c"),
# measured with `sylva bench`; exits 1 when one is missed, so a change to a preset, the foliage or
# the mesher can be checked before it lands. A benchmark, not a test: run it on a machine with no
# other work, and read a miss under load as a reason to run it again.
#
#   scripts/bench-goals.sh [SYLVA_BINARY]        (default build/app/sylva)
#
# ROUNDS (default 3) processes per preset, each `sylva bench P --repeat ${REPEAT:-15} --json`; the
# median of their medians is judged, grow + mesh:
#   - each generator's default preset (the ones `sylva bench --render` and `--edit` take, and Honda f)
#     under 30 ms;
#   - every species preset under 40 ms a plant (a forest, a preset tagged "forest", is divided by
#     its tree_count; a shrub's stems are one plant);
#   - a mesh-only edit of species_oak re-meshes in under 15 ms (mesh_ms: a re-mesh runs the mesher
#     on the kept skeleton, nothing else);
#   - with a display (DISPLAY set), `sylva bench --edit` on species_oak: the render-only edit runs 0 ms
#     of grow and mesh, and the mesh-only edit 0 ms of grow.
set -euo pipefail
bin=${1:-build/app/sylva}
if [ ! -x "$bin" ]; then
  echo "bench-goals: no sylva binary at $bin (build it first: make test, or cmake --build build)" >&2
  exit 2
fi
cd "$(dirname "$0")/.."
defaults="lsystem_honda_a lsystem_honda_f self_organizing_default space_colonization_seed_cube guiding_vectors_default"
species=$(for f in presets/species_*.json; do basename "$f" .json; done)
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for r in $(seq "${ROUNDS:-3}"); do
  for name in $defaults $species; do
    "$bin" bench "presets/$name.json" --repeat "${REPEAT:-15}" --json 2>/dev/null >> "$out" ||
      { echo "bench-goals: sylva bench failed on presets/$name.json" >&2; exit 2; }
  done
done
edit=
if [ -n "${DISPLAY:-}" ]; then
  edit=$(mktemp)
  trap 'rm -f "$out" "$edit"' EXIT
  "$bin" bench --edit presets/species_oak.json --repeat "${REPEAT:-15}" --json 2>/dev/null > "$edit" ||
    { echo "bench-goals: sylva bench --edit failed" >&2; exit 2; }
fi
python3 - "$out" "${edit:-}" "$defaults" <<'PY'
import collections, json, statistics, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    j = json.loads(line)
    runs[j['preset']].append(j)
defaults = sys.argv[3].split()
def trees(name):   # a forest's trees; 1 for anything else (a shrub's stems are one plant)
    try:
        j = json.load(open('presets/%s.json' % name))
        return max(1, int(j['params'].get('tree_count', 1))) if 'forest' in j.get('tags', []) else 1
    except (OSError, ValueError, KeyError, TypeError):
        return 1
rows, missed = [], 0
def judge(goal, name, value, budget, unit='ms'):
    global missed
    ok = value < budget
    missed += not ok
    rows.append((goal, name, value, budget, unit, 'ok' if ok else 'MISSED'))
for name in sorted(runs):
    total = statistics.median(r['grow_ms'] + r['mesh_ms'] for r in runs[name])
    if name in defaults:
        judge('default: grow + mesh', name, total, 30.0)
    if name.startswith('species_'):
        n = trees(name)
        judge('species: grow + mesh' + (' / %d trees' % n if n > 1 else ''), name, total / n, 40.0)
    if name == 'species_oak':
        judge('mesh-only edit: re-mesh', name, statistics.median(r['mesh_ms'] for r in runs[name]), 15.0)
if sys.argv[2]:
    for line in open(sys.argv[2]):
        j = json.loads(line)
        if j['class'] == 'render':
            judge('render-only edit: grow + mesh', j['preset'], j['grow_ms'] + j['mesh_ms'], 1e-9)
        elif j['class'] == 're-mesh':
            judge('mesh-only edit: grow', j['preset'], j['grow_ms'], 1e-9)
            judge('mesh-only edit: worker', j['preset'], j['worker_ms'], 15.0)
else:
    print('(no DISPLAY: the render-only edit, 0 ms of grow and mesh, is not checked; run under xvfb-run -a)')
print('%-36s %-30s %9s %8s  %s' % ('goal', 'preset', 'measured', 'budget', ''))
for goal, name, value, budget, unit, verdict in rows:
    print('%-36s %-30s %9.2f %8s  %s' % (goal, name, value, ('%g %s' % (budget, unit)) if budget >= 1e-6 else '0 ms', verdict))
print('%d of %d goals met' % (len(rows) - missed, len(rows)))
sys.exit(1 if missed else 0)
PY
