#!/usr/bin/env bash
# Installs the Khronos glTF validator (npm gltf-validator) into tools/node_modules for the export tests.
set -euo pipefail
cd "$(dirname "$0")/../tools"
if [ -f node_modules/gltf-validator/package.json ]; then exit 0; fi
if ! command -v npm >/dev/null 2>&1; then
  echo "install-gltf-validator: npm is missing (scripts/install-deps.sh installs nodejs and npm)" >&2
  exit 1
fi
npm install --no-audit --no-fund --no-package-lock --loglevel=error >/dev/null
