#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang, -DPMSIM_FUZZ=ON: ASan + UBSan + coverage) and
# runs each for a bounded time, starting from a seed corpus made from assets/ plus every input
# already kept in tests/fuzz/regressions/<target>/. Every crash, oracle violation, leak or timeout
# found is copied into tests/fuzz/regressions/<target>/, which the ordinary build replays as ctest
# tests (reliability_fuzz_regressions_<target>).
# usage: scripts/fuzz.sh [seconds per target (default 20)] [target...]   (default: all targets)
# Build folder: build-fuzz (override PMSIM_FUZZ_BUILD). Exit 1 if anything was found.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-20}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scene_parser scene_setting lens_parser material_parser mineral_parser trace_lens plate_jones)
fi
build="${PMSIM_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${PMSIM_JOBS:-$(nproc)}"
CC="${CC:-clang}" CXX="${CXX:-clang++}" cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPMSIM_FUZZ=ON -DPMSIM_BUILD_UI=OFF -DPMSIM_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export TMPDIR="$build/tmp"
mkdir -p "$TMPDIR"
found=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  seeds="$build/seeds/$t"
  artifacts="$build/artifacts/$t"
  rm -rf "$seeds"
  mkdir -p "$corpus" "$seeds" "$artifacts"
  PMSIM_FUZZ_MAKE_SEEDS="$seeds" "$build/fuzz/fuzz_$t"
  regressions="$root/tests/fuzz/regressions/$t"
  mkdir -p "$regressions"
  # Past findings seed the run too, except open ones (DISABLED_*: they would stop the run at
  # once; the fuzzer is expected to rediscover them and keeps the new input as an artifact).
  for f in "$regressions"/*; do
    case "$(basename "$f")" in DISABLED_*|README.md|.gitkeep) continue ;; esac
    [ -f "$f" ] && cp "$f" "$seeds/regression_$(basename "$f")"
  done
  # The seeds go in by name order (-seed_inputs): libFuzzer orders a corpus directory as readdir
  # returns it, which differs from one file system to the next, and that order steers every
  # mutation after it. A CI run on another machine once explored differently from the same seed.
  (cd "$seeds" && ls | LC_ALL=C sort | sed "s|^|$seeds/|" | paste -sd, -) >"$build/seed_list_$t.txt"
  ls "$artifacts" >"$build/artifacts_before_$t.txt"
  started=$SECONDS
  set +e
  # PMSIM_FUZZ_SEED fixes libFuzzer's random seed (CI: the same run on the same code, so a
  # submission is judged by its code, not by luck): the corpus folder starts empty and is not
  # reloaded mid-run, and PMSIM_FUZZ_RUNS bounds the number of inputs, so the inputs tried depend
  # on the code alone (the time bound is only a backstop). Unset, every run explores anew and keeps
  # growing $corpus.
  # Address-space randomisation is off too, and so is libFuzzer's use of compared values in its
  # mutations (-use_cmp=0): pointers are among those values, and heap addresses differ from run to
  # run even without ASLR, so two runs of one seed diverged after a few hundred inputs.
  # Repeatable runs also use one scratch path on every machine: the parsers walk it, and libFuzzer
  # counts loop iterations as coverage, so a deeper checkout folder would steer the run.
  seed_opt=()
  launcher=()
  export PMSIM_FUZZ_SCRATCH="$TMPDIR/$t"
  if [ -n "${PMSIM_FUZZ_SEED:-}" ]; then
    rm -rf "$corpus"
    mkdir -p "$corpus"
    seed_opt=(-seed="$PMSIM_FUZZ_SEED" -reload=0 -use_cmp=0)
    if setarch "$(uname -m)" -R true 2>/dev/null; then
      launcher=(setarch "$(uname -m)" -R)
    else
      echo "fuzz: setarch -R is not permitted here; runs may differ between machines" >&2
    fi
    PMSIM_FUZZ_SCRATCH="/tmp/pmsim-fuzz-scratch/$t"
  fi
  [ -n "${PMSIM_FUZZ_RUNS:-}" ] && seed_opt+=(-runs="$PMSIM_FUZZ_RUNS")
  mkdir -p "$PMSIM_FUZZ_SCRATCH"
  "${launcher[@]}" "$build/fuzz/fuzz_$t" "$corpus" -seed_inputs=@"$build/seed_list_$t.txt" "${seed_opt[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -artifact_prefix="$artifacts/" -print_final_stats=1 -close_fd_mask=1 2>"$build/fuzz_$t.log"
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$build/fuzz_$t.log" | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]*' "$build/fuzz_$t.log" | tail -1 | grep -o '[0-9]*' || echo "?")
  ls "$artifacts" | grep -vxF -f "$build/artifacts_before_$t.txt" >"$build/artifacts_new_$t.txt" || true
  new=$(wc -l <"$build/artifacts_new_$t.txt")
  echo "fuzz: $t: $((SECONDS - started)) s (bound ${seconds} s), $execs inputs, coverage $cov edges, $new new finding(s), exit $rc"
  if [ "$rc" -ne 0 ] || [ "$new" -gt 0 ]; then
    found=1
    while read -r name; do
      cp -n "$artifacts/$name" "$regressions/" && echo "fuzz: kept $regressions/$name"
    done <"$build/artifacts_new_$t.txt"
    grep -m3 -E 'ERROR|oracle|runtime error' "$build/fuzz_$t.log" || true
  fi
done
exit $found
