#!/usr/bin/env bash
# The README's picture of a checked class exercise (docs/images/exercise_checked.png): a granite
# student file made by pmsim-exercise (base seed 1, student01), answered in the app's Exercise tab
# by a script (two answers wrong on purpose), checked, the reveal layer on, the stage turned 20° so
# the layer is seen to turn with it. Flat rendering (optics.relief=off) at 512²: seconds, not minutes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/docs/images/exercise_checked.png}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$root/build/app/pmsim-exercise" make granite-minerals --students 1 --seed 1 --out "$tmp/class" >/dev/null
cat > "$tmp/answer.pmscript" <<'SCRIPT'
set optics.relief=off
set render.width=512
set render.height=512
exercise answer A1 biotite
exercise answer A2 1.5
exercise answer A3 length-slow
exercise answer A4 pale yellow, dark brown, dark brown
exercise answer B1 quartz
exercise answer B2 uniaxial
exercise answer B3 2
exercise answer C1 plagioclase
exercise answer C2 carlsbad
exercise save
exercise check
set stage_deg=20
exercise reveal on
wait converged 300
exercise wait
SCRIPT
"$root/build/app/pmsim" --headless --size 1280x800 "$tmp/class/student01.pmexercise.json" \
  --script "$tmp/answer.pmscript" --screenshot "$out"
echo "wrote $out"
