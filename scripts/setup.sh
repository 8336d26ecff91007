#!/usr/bin/env bash
# Installs the Debian packages rtpbr builds and tests with, only those missing,
# so a second run costs one dpkg-query. Root (or sudo) is needed only when
# something is missing.
set -euo pipefail

packages=(
  meson ninja-build pkg-config gcc g++ cmake
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libembree-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenimageio-dev openimageio-tools
  libcmocka-dev libglm-dev
  python3 python3-numpy python3-matplotlib
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
