#!/usr/bin/env bash
# Builds the Debian package build/package/pmsim_<version>_amd64.deb (CPack; dependencies from the
# shared libraries the programs link, by dpkg-shlibdeps) and checks it with lintian, which must
# report no error. Builds only what is installed (the programs, the OpenImageIO module, the icon
# and man pages), not the tests.
# usage: scripts/package.sh [--no-build] [build folder (default build/)]
#   --no-build: package the build folder as it is (the test suite's package test, which runs inside
#   a built tree while other tests run, and must not reconfigure it).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_it=1
[ "${1:-}" = --no-build ] && { build_it=0; shift; }
build="${1:-$root/build}"
if [ "$build_it" = 1 ]; then
  bash "$root/scripts/setup.sh" package
  generator=()
  [ -f "$build/CMakeCache.txt" ] || { command -v ninja >/dev/null 2>&1 && generator=(-G Ninja); }
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j "$(nproc)" --target pmsim pmsim-render pmsim-trace pmsim-bench \
        pmsim-experiments pmsim-ebsd-example pmsim-exercise pmsim_oiio pmsim_install_files
fi
# umask 022: the package's files get the modes Debian expects (0755 folders and programs, 0644 data)
# whatever the checkout's umask.
rm -rf "$build/package" "$build/_CPack_Packages"
(umask 022 && cd "$build" && cpack -G DEB >"$build/cpack.log" 2>&1) || { cat "$build/cpack.log"; exit 1; }
deb="$(ls "$build"/package/pmsim_*_amd64.deb)"
echo "package.sh: $deb ($(du -h "$deb" | cut -f1))"
dpkg-deb --field "$deb" Depends | tr ',' '\n' | sed 's/^ */  depends: /'
# lintian: errors fail the package (exit 1); warnings are printed for the record. Exit 2 and up:
# lintian itself failed, which must not pass for a clean package either.
rc=0
lintian --fail-on error --tag-display-limit 0 "$deb" >"$build/lintian.log" 2>&1 || rc=$?
grep -v "running with root privileges" "$build/lintian.log" || true
if [ "$rc" -ne 0 ]; then
  echo "package.sh: lintian exit $rc (1: errors in the package; 2: lintian failed)" >&2
  exit 1
fi
echo "package.sh: lintian: no errors ($(grep -c '^W:' "$build/lintian.log" || true) warnings)"
