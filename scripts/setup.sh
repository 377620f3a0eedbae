#!/usr/bin/env bash
# Installs pmsim's build and test dependencies from Debian's packages (Debian 12, as root).
set -euo pipefail
PKGS=(cmake g++ pkg-config ninja-build
      libglfw3-dev libimgui-dev libosmesa6-dev libegl-dev libegl1-mesa-dev libgl1-mesa-dri
      libglm-dev libembree-dev libopenimageio-dev openimageio-tools libtbb-dev
      nlohmann-json3-dev libcli11-dev libpng-dev libgtest-dev libbenchmark-dev colord-data xvfb xauth
      clang libclang-rt-14-dev)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
