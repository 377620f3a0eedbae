#!/usr/bin/env bash
# Installs, builds and runs the main job: renders the default scene to out/default.png; then
# starts the app when there is a display, or writes headless screenshots of it to out/screenshots/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
mkdir -p "$root/out/screenshots"
"$root/build/app/pmsim-render" --out "$root/out/default.png" --stats "$root/out/default.json"
echo "pmsim: default scene rendered to $root/out/default.png (stats in out/default.json)"
if [ -x "$root/build/app/pmsim" ]; then
  if [ -n "${DISPLAY:-}" ] && [ -z "${CI:-}" ]; then
    exec "$root/build/app/pmsim"
  fi
  for preset in "$root"/assets/ui/*.pmscript; do
    [ -e "$preset" ] || continue
    name="$(basename "$preset" .pmscript)"
    "$root/build/app/pmsim" --headless --script "$preset" \
        --screenshot "$root/out/screenshots/$name.png"
  done
  "$root/build/app/pmsim" --headless --frames 30 --screenshot "$root/out/screenshots/app.png"
  echo "pmsim: no display; screenshots of the app are in $root/out/screenshots/"
fi
