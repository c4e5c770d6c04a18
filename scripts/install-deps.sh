#!/usr/bin/env bash
# Installs what relight needs from Debian 12's packages; does nothing when all is there.
set -euo pipefail
packages=(build-essential cmake pkg-config
  libembree-dev libeigen3-dev libopenimageio-dev openimageio-tools libglfw3-dev libglm-dev
  libimgui-dev nlohmann-json3-dev libcli11-dev libgtest-dev libtbb-dev libepoxy-dev
  libassimp-dev libopencv-dev xvfb xauth libgl1-mesa-dri mesa-utils libegl1-mesa-dev clang-format
  clang libclang-rt-14-dev)  # the fuzz targets: clang and its libFuzzer (only recommended)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "dependencies: all installed"
  exit 0
fi
echo "dependencies: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends "${missing[@]}"
