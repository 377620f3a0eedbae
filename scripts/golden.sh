#!/usr/bin/env bash
# Regenerates the golden images in tests/golden/ from tests/golden/manifest.txt with the built
# tools (default build/). Run it only on purpose, after a change that is meant to change pixels,
# and say why in the commit: tests/regression_golden_test.cpp compares every render against them.
#   bash scripts/golden.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
golden="$root/tests/golden"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
while read -r name tool file settings; do
  case "$name" in ''|'#'*) continue ;; esac
  args=()
  for s in $settings; do args+=(--set "$s"); done
  case "$tool" in
    render)
      "$build/app/pmsim-render" "$root/assets/$file" "${args[@]}" --out "$tmp/$name.exr" 2>/dev/null
      mv "$tmp/$name.exr" "$golden/$name.exr" ;;
    vignetting)
      "$build/app/pmsim-experiments" --quick --out-dir "$tmp/$name" vignetting >/dev/null
      mv "$tmp/$name/vignetting_zones.png" "$golden/$name.png" ;;
    *) echo "golden.sh: unknown tool '$tool' for $name" >&2; exit 2 ;;
  esac
  echo "golden.sh: $name"
done < "$golden/manifest.txt"
