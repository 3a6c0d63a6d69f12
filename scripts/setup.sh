#!/usr/bin/env bash
# One-stop entry point used by the README and by CI.
#   scripts/setup.sh run    install deps, build Release, run the main job (synthetic scene)
#   scripts/setup.sh test   install deps, build Release + sanitizer (ASan+UBSan), run all tests
#   scripts/setup.sh build  install deps, build Release only
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-run}"
jobs="${JOBS:-$(nproc)}"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE

configure_build() {  # dir build-type extra-args...
  local dir="$1" type="$2"; shift 2
  local gen=()
  command -v ninja >/dev/null && gen=(-G Ninja)
  cmake -S . -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE="$type" "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
}

# The fuzz tests' one-line figures (inputs tried, time, violations), from
# the log of the ctest run that just passed.
fuzz_figures() {  # build-dir
  echo "-- fuzz figures ($1):"
  grep -h "^fuzz summary:" "$1/Testing/Temporary/LastTest.log" 2>/dev/null || echo "   (none logged)"
}

case "$mode" in
  run|build|test) ;;
  *) echo "usage: $0 run|build|test" >&2; exit 2 ;;
esac

bash scripts/install-deps.sh
configure_build build Release

case "$mode" in
  run)
    ./build/imapsim
    ;;
  build) ;;
  test)
    # engine.slurm starts (and stops) its own single-node Slurm cluster with
    # the packages above (scripts/slurm-test-cluster.sh); its daemons need root.
    [ "$(id -u)" -eq 0 ] || echo "warning: not root: the Slurm test (engine.slurm) will fail" >&2
    echo "== Release test suite"
    ctest --test-dir build --output-on-failure -j "$jobs"
    fuzz_figures build
    echo "== Sanitizer (ASan+UBSan) test suite (docs/testing.md)"
    # The sanitizer build links the Release build's verilated RTL models
    # (compiled without sanitizers in both) instead of verilating them again.
    configure_build build-asan Asan -DIMAP_RTL_PREBUILT="$PWD/build"
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --test-dir build-asan --output-on-failure -j "$jobs"
    fuzz_figures build-asan
    ;;
esac
