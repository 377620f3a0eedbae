#!/usr/bin/env bash
# Configures and builds pmsim (Release) into build/ after installing the dependencies.
# Arguments go to the configure step (e.g. -DPMSIM_BUILD_UI=OFF). PMSIM_TARGETS="pmsim-render
# pmsim" builds only those targets: scripts/run.sh needs two programs, not the ~100 test
# executables that make up most of a full build; unset, everything is built (scripts/test.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
cmake -S "$root" -B "$root/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
targets=()
if [ -n "${PMSIM_TARGETS:-}" ]; then
  # shellcheck disable=SC2206  # a space-separated list of target names
  targets=(--target ${PMSIM_TARGETS})
fi
cmake --build "$root/build" -j "$(nproc)" "${targets[@]}"
