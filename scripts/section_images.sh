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
declare -A at40=([granite_hand_placed]="-1.5 -0.7")
for section in granite_hand_placed; do
  for mag in 4 40; do
    na=0.10 x=0 y=0
    [ "$mag" = 40 ] && na=0.65 && read -r x y <<<"${at40[$section]}"
    "$render" "$scene" --set sample.section="$section" --set objective.magnification="$mag" \
      --set objective.na="$na" --set stage.x_mm="$x" --set stage.y_mm="$y" \
      --set render.width=480 --set render.height=360 --scale-bar \
      --out "$root/docs/images/section_${section}_${mag}x.png"
  done
done
# Rocks grown from a recipe (assets/rocks): 4x and 40x, between crossed polars and in plane light;
# the 40x view at a point of each rock chosen by eye (where several grains meet).
declare -A rock40=([granite]="2.3 -0.55" [andesite]="0.8 0.3" [amphibolite]="0.5 0.2" [quartzite]="0.2 0.1" [marble]="0.4 -0.3" [sandstone]="-0.1 -0.1" [peridotite]="0.3 0.2" [gabbro]="-1.6 0.3" [basalt]="1.0 0.6" [schist]="-2.95 -2.3" [pegmatite]="2.75 -0.35" [granodiorite]="-4.0 4.78")
for rock in granite andesite amphibolite quartzite marble sandstone peridotite gabbro basalt schist pegmatite granodiorite; do
  common=(--set sample.section="$rock" --set render.width=480 --set render.height=360 --scale-bar)
  read -r x y <<<"${rock40[$rock]}"
  for light in crossed plane; do
    suffix="" polars=()
    [ "$light" = plane ] && suffix=_plane && polars=(--set analyzer=out)
    "$render" "$scene" "${common[@]}" "${polars[@]}" --set objective.magnification=4 --set objective.na=0.10 \
      --out "$root/docs/images/rock_${rock}_4x${suffix}.png"
    "$render" "$scene" "${common[@]}" "${polars[@]}" --set objective.magnification=40 --set objective.na=0.65 \
      --set stage.x_mm="$x" --set stage.y_mm="$y" --out "$root/docs/images/rock_${rock}_40x${suffix}.png"
  done
done
# A pleochroic halo in the grown granite's biotite: a zircon at -1.448, -0.854 mm in plane light at
# 40x, the stage at 0 and 90 degrees (the halo darkest with the biotite's cleavage along the polarizer).
for stage in 0 90; do
  "$render" "$scene" --set sample.section=granite --set render.width=320 --set render.height=240 --scale-bar \
    --set objective.magnification=40 --set objective.na=0.65 --set stage.x_mm=-1.448 --set stage.y_mm=-0.854 \
    --set analyzer=out --set stage_deg="$stage" --out "$root/docs/images/granite_halo_40x_plane_stage${stage}.png"
done
# An apatite needle in the grown granite's quartz at 2.21, 2.12 mm, between crossed polars at 40x:
# its c axis lies at 68.8 degrees in the section, so at stage 111.2 its length is along the polarizer
# (extinct: parallel extinction) and at 156.2 at 45 degrees to it (its first-order grey).
for stage in 111.2 156.2; do
  "$render" "$scene" --set sample.section=granite --set render.width=320 --set render.height=240 --scale-bar \
    --set objective.magnification=40 --set objective.na=0.65 --set stage.x_mm=2.21 --set stage.y_mm=2.12 \
    --set stage_deg="$stage" --out "$root/docs/images/granite_apatite_40x_stage${stage%.*}.png"
done
