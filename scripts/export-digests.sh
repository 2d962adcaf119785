#!/bin/bash
# SHA-256 of every file `sylva export` writes for each preset (GLB and OBJ with their MTL and PNGs,
# default options), one line per file, sorted: run it before and after a refactor that should change
# no output and diff the two lists. A preset the mesh budget refuses is listed as FAIL (both times).
#   scripts/export-digests.sh build/app/sylva before.sha
set -u
bin=$(realpath "$1"); out=$(realpath -m "$2"); tmp=$(mktemp -d)
cd "$(dirname "$0")/.."
for p in presets/*.json; do
  b=$(basename "$p" .json)
  for ext in glb obj; do "$bin" export "$p" -o "$tmp/$b.$ext" >/dev/null 2>&1 || echo "FAIL $b.$ext"; done
done
(cd "$tmp" && sha256sum -- * | sort -k2) > "$out"
rm -rf "$tmp"
