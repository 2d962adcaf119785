#!/usr/bin/env bash
# Runs the tests under a virtual X server so the GUI smoke tests have a display.
# Usage: run-tests.sh BUILD_DIR [extra ctest arguments]
set -euo pipefail
build=${1:-build}
shift || true
if [ -z "${DISPLAY:-}" ] || ! command -v xdpyinfo >/dev/null 2>&1 || ! xdpyinfo >/dev/null 2>&1; then
  exec xvfb-run -a -s "-screen 0 1600x1000x24" ctest --test-dir "$build" --output-on-failure "$@"
fi
exec ctest --test-dir "$build" --output-on-failure "$@"
