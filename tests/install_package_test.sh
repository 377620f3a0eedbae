#!/usr/bin/env bash
# The Debian package, installed and run as a lab machine would (issue 24): builds the .deb from this
# (already built) tree with scripts/package.sh --no-build, which fails on any lintian error; unpacks
# it with dpkg -x into a scratch root; then, from another working directory and with no environment
# beyond PATH, runs the unpacked programs: --version of every program, pmsim-render on the default
# scene flat (small), pmsim --headless writing a screenshot, pmsim-exercise making and grading a class.
# Fails if a path of the source or build tree occurs in an installed program or data file.
# usage: install_package_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$(cd "$1" && pwd -P)"
build="$(cd "$2" && pwd -P)"
fail() { echo "install_package_test: $*" >&2; exit 1; }

bash "$src/scripts/package.sh" --no-build "$build"
deb="$(ls "$build"/package/pmsim_*_amd64.deb)"
version="$(dpkg-deb --field "$deb" Version)"
expected_version="$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")"
[ "$version" = "$expected_version" ] || fail "package version '$version' is not the project's '$expected_version'"

scratch="$(mktemp -d "${TMPDIR:-/tmp}/pmsim-install.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
dpkg -x "$deb" "$scratch/root"
bin="$scratch/root/usr/bin"
mkdir "$scratch/work"
cd "$scratch/work"
# Only PATH and HOME: no PMSIM_ASSETS, no DISPLAY; the programs must find everything themselves.
run() { env -i PATH=/usr/bin:/bin HOME="$scratch/work" "$@"; }

for p in "$bin"/*; do
  name="$(basename "$p")"
  out="$(run "$p" --version)" || fail "$name --version failed"
  [ "$out" = "$name $version" ] || fail "$name --version printed '$out', not '$name $version'"
  [ -f "$scratch/root/usr/share/man/man1/$name.1.gz" ] || fail "no man page for $name"
done
for p in pmsim pmsim-render; do [ -x "$bin/$p" ] || fail "the package has no $p"; done

run "$bin/pmsim-render" --set optics.relief=off --set render.width=96 --set render.height=96 \
    --out default.png --stats default.json || fail "pmsim-render of the default scene failed"
grep -q '"converged": *true' default.json || fail "the flat default render did not converge: $(cat default.json)"
# The image carries the version (PNG text chunk Software).
grep -aq "pmsim $version" default.png || fail "default.png does not name pmsim $version"

run "$bin/pmsim" --headless --size 480x320 --frames 2 --no-settle --set render.width=64 \
    --set render.height=64 --screenshot window.png || fail "pmsim --headless failed"
[ -s window.png ] || fail "pmsim --headless wrote no screenshot"
# The OpenImageIO module (another format than PNG) is found beside the programs too.
run "$bin/pmsim-render" "$scratch/root/usr/share/pmsim/scenes/quartz_plate_45.json" \
    --set render.width=32 --set render.height=32 --out plate.exr || fail "writing an EXR (OpenImageIO module) failed"
[ -s plate.exr ] || fail "no plate.exr"

# A class exercise from an installed template (assets found beside the program).
run "$bin/pmsim-exercise" make crystal-figures --students 2 --out class || fail "pmsim-exercise make failed"
[ -s class/key.json ] && [ -s class/student02.pmexercise.json ] || fail "pmsim-exercise wrote no class"
run "$bin/pmsim-exercise" grade class/key.json --out report.csv || fail "pmsim-exercise grade failed"
[ "$(wc -l < report.csv)" = 9 ] || fail "report.csv: expected a header and 8 rows"


desktop-file-validate "$scratch/root/usr/share/applications/pmsim.desktop" || fail "the desktop entry is invalid"
[ -f "$scratch/root/usr/share/icons/hicolor/256x256/apps/pmsim.png" ] || fail "no icon"

# The programs, the module, the assets, man pages and desktop entry. share/doc is left out: its
# docs/experiments files are records of runs on a developer's checkout and name the scene they read.
leaks="$(grep -rlaF -e "$src" -e "$build" --exclude-dir=doc "$scratch/root" || true)"
# Compressed files (man pages, changelog) are searched inside.
while IFS= read -r -d '' gz; do
  if zcat "$gz" | grep -qaF -e "$src" -e "$build"; then leaks+="$gz"$'\n'; fi
done < <(find "$scratch/root" -path "$scratch/root/usr/share/doc" -prune -o -name '*.gz' -print0)
[ -z "$leaks" ] || fail "installed files name the source or build tree ($src, $build):"$'\n'"$leaks"
echo "install_package_test: $deb installs and runs from $scratch/root; no tree path leaks"
