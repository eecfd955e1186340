#!/usr/bin/env bash
# Installs what the project needs on Debian 12 (only what is missing), then configures and
# builds it into build/. Safe to run again: a no-op when everything is in place.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  g++ cmake ninja-build pkg-config
  mesa-vulkan-drivers libvulkan-dev vulkan-validationlayers glslang-tools
  libglm-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev libopenimageio-dev
  libgtest-dev libembree-dev
  libimgui-dev xvfb xauth
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
  python3-venv python3-setuptools python3-wheel python3-mypy
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

build_type=${SSGI_BUILD_TYPE:-RelWithDebInfo}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
cmake --build build -j2
