#!/usr/bin/env bash
# Installs pmsim's dependencies from Debian's packages (Debian 12, as root).
# usage: scripts/setup.sh [test|package]
#   (none)   what building and running the programs needs (scripts/run.sh): the first run on a
#            fresh machine downloads only these;
#   package  adds what scripts/package.sh uses: help2man (man pages), dpkg-shlibdeps, lintian,
#            desktop-file-validate;
#   test     adds the test tools (clang and its sanitizer runtimes, Xvfb, colord-data for
#            scripts/gen_cie_tables.sh) and the package tools (the suite builds and installs the .deb).
set -euo pipefail
PKGS=(cmake g++ pkg-config ninja-build
      libglfw3-dev libimgui-dev libosmesa6-dev libegl-dev libegl1-mesa-dev libgl1-mesa-dri
      libglm-dev libembree-dev libopenimageio-dev libtbb-dev
      nlohmann-json3-dev libcli11-dev libpng-dev libgtest-dev)
PACKAGE_PKGS=(help2man dpkg-dev file lintian desktop-file-utils)
TEST_PKGS=(colord-data xvfb xauth clang libclang-rt-14-dev)
case "${1:-}" in
  "") ;;
  package) PKGS+=("${PACKAGE_PKGS[@]}") ;;
  test) PKGS+=("${PACKAGE_PKGS[@]}" "${TEST_PKGS[@]}") ;;
  *) echo "setup.sh: unknown set '$1' (expected: test or package)" >&2; exit 2 ;;
esac
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
