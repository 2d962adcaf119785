#!/usr/bin/env bash
# Runs `sylva export` against hostile outputs and inputs under /usr/bin/time -v and prints, per
# case, the exit code, the peak resident memory and the first line of the message, and whether the
# files already in the scratch folder are byte for byte as they were (tests/render/io/hostile_files_test.cpp
# checks the same cases; this prints the figures).
# Usage: scripts/hostile-files.sh [BUILD_DIR]
set -uo pipefail
build=${1:-build}
src=$(cd "$(dirname "$0")/.." && pwd)
sylva=${SYLVA:-$build/app/sylva}
preset="$src/presets/lsystem_honda_a.json"
dir=$(mktemp -d /tmp/sylva-hostile.XXXXXX)
chmod 755 "$dir"   # the read-only case runs as nobody, who must reach the folder
log=$(mktemp -d /tmp/sylva-hostile-log.XXXXXX)
chmod 777 "$log"
trap 'chmod -R u+w "$dir"; umount "$dir/tmpfs" 2>/dev/null; rm -rf "$dir" "$log"' EXIT

echo "user file" >"$dir/keep.glb"
mkfifo "$dir/pipe.glb" "$dir/pipe2.glb" "$dir/pipe.json" "$dir/multi.mtl"
ln -s pipe2.glb "$dir/to_pipe.glb"
mkdir "$dir/folder.glb" "$dir/folder.json" "$dir/ro" "$dir/tmpfs"
echo "old export" >"$dir/ro/tree.glb"
chmod 555 "$dir/ro"
echo "old export" >"$dir/full.glb"
mknod "$dir/device.glb" c 1 3 2>/dev/null && mknod "$dir/device2.glb" c 1 3 && ln -s device2.glb "$dir/to_device.glb"
long=$(printf 'n%.0s' $(seq 248))   # xxx + 248 + .glb: 255 bytes
python3 - "$dir/big.json" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    f.write('{"sylva_preset": 1, "generator": "lsystem", "name": "' + "x" * (60 << 20) + '"}')
PY
as_nobody=""
[ "$(id -u)" = 0 ] && as_nobody="setpriv --reuid=65534 --regid=65534 --clear-groups"
mounted=0
[ "$(id -u)" = 0 ] && mount -t tmpfs -o size=64k sylva_hostile "$dir/tmpfs" 2>/dev/null && mounted=1 &&
  echo "old export" >"$dir/tmpfs/tree.glb"

snapshot() { (cd "$dir" && find . -path ./tmpfs -prune -o -print0 | sort -z | xargs -0 stat -c '%n %F %a %s' &&
              find . -path ./tmpfs -prune -o -type f -print0 | sort -z | xargs -0 sha256sum 2>/dev/null) }

run() {  # NAME PRESET OUTPUT [PREFIX...]
  local name=$1 in=$2 out=$3
  shift 3
  local before after
  before=$(snapshot)
  "$@" /usr/bin/time -v -o "$log/time" "$sylva" export "$in" -o "$out" >/dev/null 2>"$log/err"
  local rc=$?
  after=$(snapshot)
  local rss msg same
  rss=$(grep -o 'Maximum resident set size (kbytes): [0-9]*' "$log/time" | grep -o '[0-9]*$')
  msg=$(grep -v '^warning' "$log/err" | head -1 | sed "s|$dir/||g; s|n\{20,\}|n...n|g" | cut -c1-120)
  same=$([ "$before" = "$after" ] && echo unchanged || echo CHANGED)
  [ "$rc" = 0 ] && same="(written)"   # a success changes the folder: it adds the export
  printf '%-22s exit %-3s %5s MB  files %-9s %s\n' "$name" "$rc" "$((rss / 1024))" "$same" "$msg"
  rm -f "$log/time" "$log/err"
}

# Each case has its own special file, so that a build that replaces one does not hide the next.
echo "output onto:"
run fifo "$preset" "$dir/pipe.glb"
run "symlink to fifo" "$preset" "$dir/to_pipe.glb"
[ -e "$dir/device.glb" ] && run device "$preset" "$dir/device.glb"
[ -e "$dir/device.glb" ] && run "symlink to device" "$preset" "$dir/to_device.glb"
run folder "$preset" "$dir/folder.glb"
run "obj, mtl is a fifo" "$preset" "$dir/multi.obj"
[ -n "$as_nobody" ] || chmod 555 "$dir/ro"
run "read-only folder" "$preset" "$dir/ro/tree.glb" $as_nobody
run "full disk (ulimit -f)" "$preset" "$dir/full.glb" bash -c 'trap "" XFSZ; ulimit -f 2; exec "$@"' full
[ $mounted = 1 ] && run "full disk (64k tmpfs)" "$preset" "$dir/tmpfs/tree.glb"
run "256-byte name" "$preset" "$dir/xxxx$long.glb"
run "255-byte name" "$preset" "$dir/xxx$long.glb"
rm -f "$dir/xxx$long.glb"
echo "input from:"
run folder "$dir/folder.json" "$dir/out.glb"
run /dev/zero /dev/zero "$dir/out.glb"
run fifo "$dir/pipe.json" "$dir/out.glb"
run "60 MB preset" "$dir/big.json" "$dir/out.glb"
