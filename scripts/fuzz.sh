#!/usr/bin/env bash
# Runs the fuzz harnesses of tests/fuzz for longer than the test suite does
# (docs/testing.md): the same seeded mutation loops, with a bigger wall-time
# budget per target and no input-count limit.
#   scripts/fuzz.sh [SECONDS] [BUILD_DIR] [TARGET...]
#     SECONDS    budget per target (default 600)
#     BUILD_DIR  a configured build folder (default build; created as Release)
#     TARGET     asm program image calib (default: every target that is built)
#   IMAP_FUZZ_SEED=N picks another input sequence (default 1, as in CI);
#   IMAP_FUZZ_CALL_LIMIT=S is the time one input may take before it counts
#   as a hang (default 120).
# A failing input is saved next to the test binaries (fuzz-<target>-*);
# copy a reduced version to tests/fuzz/regressions/<target>/ with the fix.
#
#   scripts/fuzz.sh --libfuzzer [SECONDS] [BUILD_DIR] [TARGET...]
# instead builds the libFuzzer entry points with clang (ASan + UBSan, default
# folder build-libfuzzer) and runs them coverage-guided from the same seeds;
# crashes are saved as <BUILD_DIR>/tests/fuzz/lf-<target>-crash-*.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
libfuzzer=0
if [ "${1:-}" = "--libfuzzer" ]; then libfuzzer=1; shift; fi
secs="${1:-600}"
dir="${2:-$([ $libfuzzer = 1 ] && echo build-libfuzzer || echo build)}"
shift $(($# > 2 ? 2 : $#)) || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(asm program image calib)

if [ $libfuzzer = 1 ]; then
  command -v clang++ >/dev/null || { echo "fuzz.sh: --libfuzzer needs clang++" >&2; exit 2; }
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    gen=()
    command -v ninja >/dev/null && gen=(-G Ninja)
    cmake -S . -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_COMPILER=clang++ -DIMAP_LIBFUZZER=ON \
      -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
  fi
  status=0
  for t in "${targets[@]}"; do
    cmake --build "$dir" --target "libfuzzer_$t" -j "${JOBS:-2}" >/dev/null 2>&1 ||
      { echo "fuzz.sh: libfuzzer_$t is not available in $dir (skipped)"; continue; }
    work="$dir/tests/fuzz/lf-corpus-$t"
    mkdir -p "$work"
    echo "== libFuzzer $t: ${secs} s"
    (cd "$dir/tests/fuzz" && ASAN_OPTIONS=detect_leaks=0 ./"libfuzzer_$t" \
        -max_total_time="$secs" -timeout=120 -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="lf-$t-" "lf-corpus-$t" "$root/tests/fuzz/corpus/$t") \
      >"$dir/tests/fuzz/lf-$t.log" 2>&1 || status=1
    grep -E "^stat::number_of_executed_units|^stat::new_units|^stat::peak_rss|==ERROR|ERROR: libFuzzer|crash-|timeout-|oracle violated" \
      "$dir/tests/fuzz/lf-$t.log" || tail -5 "$dir/tests/fuzz/lf-$t.log"
  done
  exit $status
fi

if [ ! -f "$dir/CMakeCache.txt" ]; then
  gen=()
  command -v ninja >/dev/null && gen=(-G Ninja)
  cmake -S . -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
built=()
for t in "${targets[@]}"; do
  if cmake --build "$dir" --target "test_fuzz_$t" -j "${JOBS:-2}" >/dev/null 2>&1; then
    built+=("$t")
  else
    echo "fuzz.sh: target $t is not available in $dir (skipped)"
  fi
done

status=0
summary=()
for t in "${built[@]}"; do
  echo "== fuzz $t: ${secs} s"
  log="$dir/tests/fuzz/fuzz-$t.log"
  if (cd "$dir/tests/fuzz" && ./"test_fuzz_$t" --run_test=fuzz -- --seconds "$secs" --iterations 0) \
      >"$log" 2>&1; then
    :
  else
    status=1
  fi
  grep -E "^fuzz summary|^  !!|^fuzz:" "$log" || tail -20 "$log"
  summary+=("$(grep -E '^fuzz summary' "$log" || echo "fuzz summary: target=$t FAILED (see $log)")")
done
echo "== summary"
printf '%s\n' "${summary[@]}"
exit $status
