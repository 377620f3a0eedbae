#!/usr/bin/env bash
# Installs, builds and runs every test: this is the README's test command and what .ci/run calls.
#  1. the Release build (gcc) and its whole ctest suite, under a virtual X server so that the
#     app's windowed path runs too;
#  2. the same suite (without the UI) built with clang under AddressSanitizer + UndefinedBehavior-
#     Sanitizer, in a tree that also holds the libFuzzer targets;
#  3. the progressive renderer's cancel/restart test under ThreadSanitizer;
#  4. every fuzz target for a short repeatable run (seed 1, 10 000 inputs each; 120 s backstop) from
#     the seed corpus and every input it ever failed on.
# PMSIM_QUICK=1 runs step 1 only (for a fast local loop).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
t0=$(date +%s)
bash "$root/scripts/setup.sh" test
bash "$root/scripts/build.sh"
(cd "$root/build" && xvfb-run -a -s "-screen 0 1600x1000x24" ctest --output-on-failure -j "$(nproc)")
t1=$(date +%s)
echo "test.sh: release build and suite $((t1 - t0)) s"
[ "${PMSIM_QUICK:-0}" = 1 ] && exit 0

PMSIM_ASAN_CMAKE_ARGS="-DPMSIM_FUZZ=ON" bash "$root/scripts/sanitize.sh" asan
bash "$root/scripts/sanitize.sh" tsan
t2=$(date +%s)
echo "test.sh: sanitizer builds and suites $((t2 - t1)) s"
# The fuzzers reuse the asan tree (same compiler and flags). CI's pass is repeatable (fixed seed,
# at most PMSIM_FUZZ_RUNS inputs a target), so it judges the code, not luck; longer exploratory
# runs: scripts/fuzz.sh 600. A finding fails the run: its input is in tests/fuzz/regressions/
# of this checkout, to be committed with its fix.
PMSIM_FUZZ_SEED="${PMSIM_FUZZ_SEED:-1}" PMSIM_FUZZ_RUNS="${PMSIM_FUZZ_RUNS:-10000}" \
  PMSIM_FUZZ_BUILD="$root/build-asan" bash "$root/scripts/fuzz.sh" "${PMSIM_FUZZ_SECONDS:-120}"
t3=$(date +%s)
echo "test.sh: fuzzing $((t3 - t2)) s; total $((t3 - t0)) s"
