#!/usr/bin/env bash
# Installs the Debian packages rtpbr builds and tests with, only those missing,
# so a second run costs one dpkg-query. Root (or sudo) is needed only when
# something is missing.
#   setup.sh [main|test]   main: what the main job needs (the Debian packages); test (the
#                          default): also the test-only tools from npm and PyPI into .deps/
set -euo pipefail
what=${1:-test}

packages=(
  meson ninja-build pkg-config gcc g++ cmake
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libembree-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libimgui-dev
  libopenimageio-dev openimageio-tools
  libcmocka-dev libglm-dev zlib1g-dev valgrind
  clang-14 libfuzzer-14-dev libclang-rt-14-dev
  python3 python3-numpy python3-matplotlib python3-venv
  xvfb xauth
)
# node and npm only when the machine has no node of its own (the CI image brings one)
command -v node >/dev/null 2>&1 || packages+=(nodejs npm)

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

# The rest is for tests only (the bundled-scene check, the cluster suite, the Slang consumer).
[[ $what == main ]] && exit 0

# The Khronos glTF Validator (npm) for the bundled-scene test, into .deps/ (git-ignored).
repo=$(cd "$(dirname "$0")/.." && pwd)
if [[ ! -f "$repo/.deps/node_modules/gltf-validator/package.json" ]]; then
  echo "setup: installing gltf-validator (npm) into .deps/" >&2
  npm install --silent --no-audit --no-fund --prefix "$repo/.deps" gltf-validator@2.0.0-dev.3.10 >/dev/null
fi

# A second Vulkan driver for the ray-query shadow tests (suite engine-ray-query,
# tests/engine/meson.build): Mesa 25's lavapipe, which has VK_KHR_ray_query (the system's Mesa
# 22.3 does not), from bookworm-backports' mesa-vulkan-drivers, unpacked into .deps/mesa-25 with
# an ICD file that names it by its path. Not installed: every other test keeps the system's
# driver. apt's lists for that one suite go to a temporary directory, so the system's sources
# are untouched; no root is needed.
mesa_dir="$repo/.deps/mesa-25"
if [[ ! -f "$mesa_dir/lvp_icd.json" || ! -f "$mesa_dir/libvulkan_lvp.so" ]]; then
  echo "setup: unpacking Mesa 25's lavapipe (bookworm-backports) into .deps/mesa-25" >&2
  tmp=$(mktemp -d)
  mkdir -p "$tmp/lists/partial" "$tmp/cache/archives/partial"
  echo "deb http://deb.debian.org/debian bookworm-backports main" > "$tmp/sources.list"
  apt_opts=(-o "Dir::Etc::sourcelist=$tmp/sources.list" -o Dir::Etc::sourceparts=- -o "Dir::State::Lists=$tmp/lists"
            -o "Dir::Cache=$tmp/cache" -o Debug::NoLocking=1 -o APT::Sandbox::User=root)
  apt-get "${apt_opts[@]}" update -qq
  (cd "$tmp" && apt-get "${apt_opts[@]}" download -qq mesa-vulkan-drivers/bookworm-backports)
  dpkg-deb -x "$tmp"/mesa-vulkan-drivers_*.deb "$tmp/root"
  mkdir -p "$mesa_dir"
  cp "$tmp/root/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so" "$mesa_dir/"
  printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.4.305"}}\n' \
    "$mesa_dir/libvulkan_lvp.so" > "$mesa_dir/lvp_icd.json"
  rm -rf "$tmp"
fi

# Dask distributed (oracle references on a cluster: tools/validate/rtpbr_oracle_cluster.py, suite
# 'cluster') into a venv in .deps/venv, from the pinned tools/validate/requirements-cluster.txt;
# redone only when that file changes (a copy of it in the venv says what is installed).
venv="$repo/.deps/venv"
requirements="$repo/tools/validate/requirements-cluster.txt"
if [[ ! -x "$venv/bin/python3" ]] || ! cmp -s "$requirements" "$venv/rtpbr-requirements.txt"; then
  if [[ "$(dpkg-query -W -f='${Status}' python3-venv 2>/dev/null || true)" != "install ok installed" ]]; then
    sudo_cmd=()
    [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends python3-venv >/dev/null
  fi
  echo "setup: installing Dask (pip) into .deps/venv" >&2
  /usr/bin/python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check -r "$requirements"
  cp "$requirements" "$venv/rtpbr-requirements.txt"
fi

# Slang's compiler (slangc) for a second HLSL front end in tests/consumers: the slangtorch wheel
# on PyPI ships it (only the binary is used; --no-deps: no torch). Into .deps/slang-venv (git-ignored).
# Optional: without it the Slang test is skipped, with a message.
if [[ ! -x "$repo/.deps/slangc" ]]; then
  echo "setup: installing slangtorch 1.3.22 (for slangc) from PyPI into .deps/slang-venv" >&2
  if /usr/bin/python3 -m venv "$repo/.deps/slang-venv" && \
     "$repo/.deps/slang-venv/bin/pip" install --quiet --no-deps slangtorch==1.3.22; then
    slangc=$(find "$repo/.deps/slang-venv" -path '*slangtorch/bin/slangc' | head -n 1)
    chmod +x "$slangc" && ln -sfn "$slangc" "$repo/.deps/slangc"
  else
    echo "setup: slangtorch could not be installed; the Slang compile check will be skipped" >&2
  fi
fi
