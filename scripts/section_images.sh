#!/usr/bin/env bash
# Renders the README's images of the shipped thin sections: each section between crossed polars
# at 4x (NA 0.10) and 40x (NA 0.65), 480 x 360, with the scale bar, into docs/images/. The 4x
# view is centred on the section; the 40x view on a point where several minerals meet (chosen by
# eye from --grains output; stage.x_mm, stage.y_mm below).
# Usage: scripts/section_images.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
render="${1:-$root/build}/app/pmsim-render"
scene="$root/assets/scenes/basalt_section_ortho.json"
declare -A at40=([granite]="-1.5 -0.7" [basalt]="1.5 -0.7" [gabbro]="-3 0.7" [schist]="3 -2")
for section in granite basalt gabbro schist; do
  for mag in 4 40; do
    na=0.10 x=0 y=0
    [ "$mag" = 40 ] && na=0.65 && read -r x y <<<"${at40[$section]}"
    "$render" "$scene" --set sample.section="$section" --set objective.magnification="$mag" \
      --set objective.na="$na" --set stage.x_mm="$x" --set stage.y_mm="$y" \
      --set render.width=480 --set render.height=360 --scale-bar \
      --out "$root/docs/images/section_${section}_${mag}x.png"
  done
done
# Rocks grown from a recipe (assets/rocks): 4x between crossed polars and in plane light, 40x.
for rock in andesite; do
  common=(--set sample.section="$rock" --set render.width=480 --set render.height=360 --scale-bar)
  "$render" "$scene" "${common[@]}" --set objective.magnification=4 --set objective.na=0.10 \
    --out "$root/docs/images/rock_${rock}_4x.png"
  "$render" "$scene" "${common[@]}" --set objective.magnification=4 --set objective.na=0.10 --set analyzer=out \
    --out "$root/docs/images/rock_${rock}_4x_plane.png"
  "$render" "$scene" "${common[@]}" --set objective.magnification=40 --set objective.na=0.65 \
    --set stage.x_mm=0.8 --set stage.y_mm=0.3 --out "$root/docs/images/rock_${rock}_40x.png"
done
