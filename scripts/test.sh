#!/usr/bin/env bash
# Installs, builds and runs every test (ctest) under a virtual X server, so that the windowed
# path of the app is exercised too. This is the README's test command and what .ci/run calls.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
cd "$root/build"
xvfb-run -a -s "-screen 0 1600x1000x24" ctest --output-on-failure -j "$(nproc)"
