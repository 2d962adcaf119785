#!/usr/bin/env bash
# Runs every test under a virtual X server so the GUI smoke tests have a display.
set -euo pipefail
build=${1:-build}
if [ -z "${DISPLAY:-}" ] || ! command -v xdpyinfo >/dev/null 2>&1 || ! xdpyinfo >/dev/null 2>&1; then
  exec xvfb-run -a -s "-screen 0 1600x1000x24" ctest --test-dir "$build" --output-on-failure
fi
exec ctest --test-dir "$build" --output-on-failure
