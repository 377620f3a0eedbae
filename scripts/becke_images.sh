#!/usr/bin/env bash
# Renders the README's Becke-line sequence and grain mount: an isotropic fragment of n = 1.60
# (sample.crystal with no = ne = 1.60: the library has no isotropic mineral near 1.60) in liquids of
# n_D 1.54 and 1.66, each at focus_um −FOCUS, 0, +FOCUS, in plane light at 40x with the objective
# stopped to NA 0.25 (as the Becke-line tests: a wider cone collects the bent light too) and the
# aperture diaphragm stopped down; and almandine ("garnet") in a liquid of 1.54 at 10x. 240 x 240,
# into docs/images/. STAGE_X/STAGE_Y (mm) put a fragment at the centre (the defaults: a
# fragment about 110 µm long of the fixed mount, chosen by eye); FOCUS (µm) the defocus; last, the
# quartz mount between crossed polars at the same place. The Becke sequence is exposed one stop
# down (render.exposure_ev=-1: the empty field mid-grey) so that the Becke line's light above the
# empty field's does not clip to the same white.
# Usage: scripts/becke_images.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
render="${1:-$root/build}/app/pmsim-render"
out="$root/docs/images"
focus=${FOCUS:-20}
x=${STAGE_X:-0.087} y=${STAGE_Y:--0.052}
common=(--set sample.type=grains --set analyzer=out --set render.width=240 --set render.height=240
        --set objective.magnification=40 --set objective.na=0.25 --set stage.x_mm="$x" --set stage.y_mm="$y")
for nd in 1.54 1.66; do
  for f in "-$focus" 0 "+$focus"; do
    name=$( [ "$f" = 0 ] && echo 0 || { [ "${f:0:1}" = - ] && echo minus || echo plus; } )
    "$render" "${common[@]}" --set 'sample.crystal={"no":1.60,"ne":1.60}' \
      --set sample.medium_index="$nd" --set focus_um="${f#+}" --set render.exposure_ev=-1 \
      --out "$out/becke_n160_in_${nd/./}_focus_${name}.png"
  done
done
"$render" --set sample.type=grains --set analyzer=out --set sample.mineral=garnet --set sample.medium_index=1.54 \
  --set objective.magnification=10 --set objective.na=0.25 --set render.width=240 --set render.height=240 \
  --set stage.x_mm=0 --set stage.y_mm=0 --out "$out/grain_mount_garnet.png"
# Crossed polars on the same mount as the Becke sequence, quartz in 1.54 at 40x: first-order greys,
# white and yellow from each fragment's thickness (core/specimen/jones_path.h).
"$render" "${common[@]/analyzer=out/analyzer=in}" --set sample.mineral=quartz --set sample.medium_index=1.54 \
  --set render.spp=128 --out "$out/grain_mount_quartz_crossed.png"
