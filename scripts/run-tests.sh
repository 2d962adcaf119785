#!/usr/bin/env bash
# Runs the tests under a virtual X server so the GUI tests have a display.
# Usage: run-tests.sh BUILD_DIR [extra ctest arguments]
# With no extra arguments it runs in two passes: the CPU tests (label `cpu`, sylva_tests) side by
# side on every core, then the GL and editor tests (label `gl`) one at a time, because the scripted
# editor sessions time key presses against frames and a second session on the same cores makes
# them miss. With extra arguments it is one ctest call with them (-j, -R, -L as given).
set -euo pipefail
build=${1:-build}
shift || true
run_ctest() {
  if [ -z "${DISPLAY:-}" ] || ! command -v xdpyinfo >/dev/null 2>&1 || ! xdpyinfo >/dev/null 2>&1; then
    xvfb-run -a -s "-screen 0 1600x1000x24" ctest --test-dir "$build" --output-on-failure "$@"
  else
    ctest --test-dir "$build" --output-on-failure "$@"
  fi
}
if [ $# -gt 0 ]; then
  run_ctest "$@"
  exit
fi
status=0
run_ctest -L cpu -j "$(nproc)" || status=1
run_ctest -L gl || status=1
exit $status
