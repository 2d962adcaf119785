#!/usr/bin/env bash
# Installs the Debian packages Sylva builds and tests with; installs nothing already present.
# --fuzz: only clang (with its libFuzzer and sanitizer runtimes), for `make fuzz`.
set -euo pipefail

if [ "${1:-}" = --fuzz ]; then
  if command -v clang++ >/dev/null 2>&1; then exit 0; fi
  if [ "$(id -u)" = 0 ]; then sudo=(); else sudo=(sudo); fi
  echo "install-deps: installing clang for the fuzz harnesses"
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends clang
  exit 0
fi

packages=(
  build-essential cmake pkg-config
  libimgui-dev libglfw3-dev libglm-dev nlohmann-json3-dev libtinygltf-dev libstb-dev
  libepoxy-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libmeshoptimizer-dev libassimp-dev
  fonts-dejavu-core xvfb xauth libgl1-mesa-dri imagemagick
)
# node + npm for the glTF validator; some node builds bundle npm and conflict with Debian's npm.
if ! command -v node >/dev/null 2>&1; then packages+=(nodejs); fi
if ! command -v npm >/dev/null 2>&1; then packages+=(npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then sudo=(); else sudo=(sudo); fi
  echo "install-deps: installing ${missing[*]}"
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The export tests run the Khronos glTF validator (npm gltf-validator, into tools/node_modules).
bash "$(dirname "$0")/install-gltf-validator.sh"
