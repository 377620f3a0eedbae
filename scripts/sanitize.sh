#!/usr/bin/env bash
# Sanitizer runs (docs/robustness.md):
#   asan  — a separate build with -DPMSIM_SANITIZE=ON (AddressSanitizer + UndefinedBehaviorSanitizer,
#           any UB report is fatal) and -DPMSIM_BUILD_UI=OFF, running the whole non-UI ctest suite;
#   tsan  — a ThreadSanitizer build (-DPMSIM_TSAN=ON) running the progressive renderer's
#           cancel/restart test (tests/reliability_renderer_restart_test.cpp) while a second thread
#           takes snapshots.
# usage: scripts/sanitize.sh [asan|tsan|all]   (default all)
# Build folders: build-asan and build-tsan (override: PMSIM_ASAN_BUILD, PMSIM_TSAN_BUILD).
# PMSIM_ASAN_CMAKE_ARGS adds configure options to the asan build (CI: -DPMSIM_FUZZ=ON, so that
# scripts/fuzz.sh can reuse the same objects instead of a third build).
# Compiler: clang (CC/CXX override). Prints the time each step took.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
what="${1:-all}"
jobs="${PMSIM_JOBS:-$(nproc)}"
export CC="${CC:-clang}" CXX="${CXX:-clang++}"
asan_dir="${PMSIM_ASAN_BUILD:-$root/build-asan}"
tsan_dir="${PMSIM_TSAN_BUILD:-$root/build-tsan}"
status=0
now() { date +%s; }

if [[ "$what" == asan || "$what" == all ]]; then
  t0=$(now)
  cmake -S "$root" -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${PMSIM_SAN_OPT:--O1 -gline-tables-only}" \
        -DPMSIM_SANITIZE=ON -DPMSIM_BUILD_UI=OFF ${PMSIM_ASAN_CMAKE_ARGS:-} >/dev/null
  # -k 0: a target that fails to build does not stop the others; its tests then fail as missing.
  cmake --build "$asan_dir" -j "$jobs" -- -k 0 || { echo "sanitize: some targets failed to build"; status=1; }
  t1=$(now)
  # halt_on_error: a UBSan report fails the test instead of scrolling by. Leak checking stays on.
  # intercept_tls_get_addr=0: with glibc 2.36, LeakSanitizer (clang 14) reads a bogus dynamic-TLS
  # range of a dlopen()ed library (the OpenImageIO module, core/io/image_codec.h) and its tracer
  # crashes at exit ("DTLS 14 at 0x4771-0x800005873", signal 11); without the interception LSan
  # skips dynamic TLS blocks, which hold no heap pointers of ours.
  export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  # Tests that size their work for a release build check the same code on less of it here
  # (tests/bench_json_test.cpp: the bench at 32² instead of 96²).
  export PMSIM_SANITIZED=1
  # Four statistical comparisons of traced images run in the release suite only: their noise
  # bounds need their path counts, and each took 85-110 s of the ASan suite's 2-core CPU (a fifth
  # of it). Their code runs here all the same, in the lighter tests beside them: the crossed slab
  # in SpecimenSectionCrossed.GrainAtExtinctionStaysDark and CompensatorIsAppliedToTheTraced-
  # Response, the relief slab in SpecimenSectionRelief.GarnetHasADarkOutlineQuartzNearlyNone, the
  # backward and forward plane-light renderers in SpecimenForwardPlaneLight.MatchedIndices... and
  # SpecimenRelief.*.
  release_only='SpecimenSectionCrossed\.(HighReliefAddsADarkOutline|MatchedMediumGivesTheFlatColours)|SpecimenForwardPlaneLight\.MatchesTheBackwardRenderer|SpecimenSectionRelief\.MediumIndexSetsTheOutlineContrast'
  ctest --test-dir "$asan_dir" -j "$jobs" --output-on-failure --timeout 1800 -E "$release_only" || status=1
  t2=$(now)
  echo "sanitize: asan+ubsan build $((t1 - t0)) s, ctest $((t2 - t1)) s"
fi

if [[ "$what" == tsan || "$what" == all ]]; then
  t0=$(now)
  cmake -S "$root" -B "$tsan_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${PMSIM_SAN_OPT:--O1 -gline-tables-only}" \
        -DPMSIM_TSAN=ON -DPMSIM_BUILD_UI=OFF >/dev/null
  cmake --build "$tsan_dir" -j "$jobs" --target reliability_renderer_restart_test
  t1=$(now)
  # libtbb itself is not instrumented: its scheduler's synchronisation is invisible to TSan. Two
  # consequences are suppressed, nothing else: calls made from inside libtbb, and the "race on
  # vptr"/field races of TBB's own task objects (tbb::detail::, e.g. start_for, blocked_range),
  # whose memory libtbb's small-object pool recycles between tasks
  # after synchronising in code TSan cannot see. A race in pmsim code has a pmsim frame on top.
  supp="$tsan_dir/tsan.supp"
  printf 'called_from_lib:libtbb.so.12\nrace_top:tbb::detail::\n' >"$supp"
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp"
  # One TBB worker per renderer: see render_threads() in the test (the UI, render and display
  # threads still race as in the app).
  PMSIM_RENDER_THREADS=1 "$tsan_dir/tests/reliability_renderer_restart_test" || status=1
  t2=$(now)
  echo "sanitize: tsan build $((t1 - t0)) s, restart test $((t2 - t1)) s"
fi
exit $status
