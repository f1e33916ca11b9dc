#!/usr/bin/env bash
# Installs the Debian 12 packages sonarsim needs (only those missing), then builds Release into build/.
# Usage: .ci/setup.sh [TARGET...] (as root, or a user with sudo): every target (the tests, the benchmark, the
#        Python module), or only those named (`.ci/setup.sh sonarsim`: the viewer and the command line).
# Env:   SONARSIM_BUILD_DIR=build  SONARSIM_CMAKE_ARGS="..."
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config libglfw3-dev libimgui-dev libembree-dev libopenmesh-dev
          libglm-dev libtbb-dev catch2 libepoxy-dev libegl-dev libgl1-mesa-dev libosmesa6-dev libstb-dev
          zlib1g-dev nlohmann-json3-dev libcli11-dev xvfb xauth mesa-utils libegl-mesa0 clang libclang-rt-14-dev
          pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed python3-venv python3-setuptools
          python3-wheel ccache)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir="${SONARSIM_BUILD_DIR:-build}"
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release ${SONARSIM_CMAKE_ARGS:-} >/dev/null
if [ $# -gt 0 ]; then
  cmake --build "$build_dir" -j "$(nproc)" --target "$@"
  echo "setup: built $* in $build_dir"
else
  cmake --build "$build_dir" -j "$(nproc)"
  echo "setup: built $build_dir/sonarsim, the tests, the benchmark and the Python module"
fi
