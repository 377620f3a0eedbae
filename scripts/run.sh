#!/usr/bin/env bash
# Installs, builds and runs the main job: renders the default scene to out/default.png; then
# starts the app when there is a display, or writes headless screenshots of it to out/screenshots/.
# The first image comes as soon as it can: only pmsim-render is built first (the tests are built by
# scripts/test.sh alone), a flat preview of the default scene (optics.relief=off: the same section
# and polars without the slab's refraction, under a second) goes to out/default.png, the full
# render (about 100 s on 2 cores) replaces it with a progress line, and only then is the app built
# (the UI library and the app: about 30 s more on 2 cores), which the first image need not wait for.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
t0=$(date +%s)
PMSIM_TARGETS=pmsim-render bash "$root/scripts/build.sh"
mkdir -p "$root/out/screenshots"
render="$root/build/app/pmsim-render"
"$render" --set optics.relief=off --out "$root/out/default.png"
echo "pmsim: first image (a flat preview) in $root/out/default.png after $(($(date +%s) - t0)) s;" \
     "now the full render, traced through the slab (about 100 s on 2 cores)"
"$render" --progress --out "$root/out/default.png" --stats "$root/out/default.json"
echo "pmsim: default scene rendered to $root/out/default.png (stats in out/default.json)" \
     "after $(($(date +%s) - t0)) s"
if grep -q '^PMSIM_BUILD_UI:BOOL=ON' "$root/build/CMakeCache.txt"; then
  echo "pmsim: building the app"
  PMSIM_TARGETS=pmsim bash "$root/scripts/build.sh"
fi
if [ -x "$root/build/app/pmsim" ]; then
  if [ -n "${DISPLAY:-}" ] && [ -z "${CI:-}" ]; then
    exec "$root/build/app/pmsim"
  fi
  cd "$root"  # the presets write relative paths (the tour's out/ui/): into the checkout's out/
  for preset in "$root"/assets/ui/*.pmscript; do
    [ -e "$preset" ] || continue
    name="$(basename "$preset" .pmscript)"
    "$root/build/app/pmsim" --headless --script "$preset" \
        --screenshot "$root/out/screenshots/$name.png"
  done
  "$root/build/app/pmsim" --headless --frames 30 --screenshot "$root/out/screenshots/app.png"
  echo "pmsim: no display; screenshots of the app are in $root/out/screenshots/"
fi
