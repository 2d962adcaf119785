#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang + ASan + UBSan and runs each for SECONDS.
# Usage: run-fuzz.sh BUILD_DIR SECONDS [--if-clang]
#   --if-clang: skip with a message when clang is missing (make test); otherwise it is an error.
# Seeds: presets/ (preset, set), tests/fuzz/seeds/<harness>/, and every crash kept in
# tests/fuzz/regressions/<harness>/, which is also replayed first as a regression test.
# FUZZ_ONLY="texture keys" runs only those harnesses.
set -euo pipefail
build=${1:-build-fuzz}
seconds=${2:-60}
if ! command -v clang++ >/dev/null 2>&1; then
  if [ "${3:-}" = --if-clang ]; then
    echo "fuzz: clang++ not found, fuzzing skipped (bash scripts/install-deps.sh --fuzz installs it)"
    exit 0
  fi
  echo "fuzz: clang++ not found; run bash scripts/install-deps.sh --fuzz" >&2
  exit 1
fi
src=$(cd "$(dirname "$0")/../.." && pwd)
harnesses=${FUZZ_ONLY:-lsystem preset set obj texture keys export settings recovery edits}
cmake -S "$src" -B "$build" -DSYLVA_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' $harnesses) >/dev/null

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# One harness: its regressions, then SECONDS of fuzzing. Prints its line; non-zero when it fails.
run_one() {
  local h=$1
  local bin="$build/tests/fuzz/fuzz_$h"
  local corpus="$build/fuzz-corpus/$h"
  local crashes="$build/fuzz-crashes/$h"
  mkdir -p "$corpus" "$crashes"
  local seeds=()
  [ -d "$src/tests/fuzz/seeds/$h" ] && seeds+=("$src/tests/fuzz/seeds/$h")
  case $h in preset|set|recovery) seeds+=("$src/presets") ;; esac
  if [ $h = lsystem ] && command -v python3 >/dev/null 2>&1; then
    # The L-system texts of presets/, one file each.
    mkdir -p "$build/fuzz-seeds/lsystem"
    python3 - "$src/presets" "$build/fuzz-seeds/lsystem" <<'PY'
import json, pathlib, sys
for f in pathlib.Path(sys.argv[1]).glob("*.json"):
    src = json.loads(f.read_text()).get("params", {}).get("source")
    if isinstance(src, str):
        (pathlib.Path(sys.argv[2]) / (f.stem + ".txt")).write_text(src)
PY
    seeds+=("$build/fuzz-seeds/lsystem")
  fi
  local reg="$src/tests/fuzz/regressions/$h"
  if [ -d "$reg" ] && [ -n "$(ls -A "$reg")" ]; then   # every kept crash must now pass
    if ! "$bin" -runs=0 "$reg"/* >/dev/null 2>"$crashes/regressions.log"; then
      echo "fuzz_$h: a kept crash input fails again (see $crashes/regressions.log)" >&2
      return 1
    fi
  fi
  local log="$crashes/run.log"
  if "$bin" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 -max_len=8192 -print_final_stats=1 \
      -artifact_prefix="$crashes/" "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    local runs secs
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    secs=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    echo "fuzz_$h: ${seconds}s, $runs runs, $secs runs/s, 0 crashes"
  else
    echo "fuzz_$h: FAILED; input kept in $crashes/ (copy it to tests/fuzz/regressions/$h/); log $log" >&2
    tail -30 "$log" >&2
    return 1
  fi
}

# The harnesses run one per core (each is one process on one thread); FUZZ_JOBS overrides that.
# Each prints its own line when it ends.
jobs_max=${FUZZ_JOBS:-$(nproc)}
status=0
pids=()
for h in $harnesses; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do sleep 1; done
  run_one "$h" &
  pids+=($!)
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
exit $status
