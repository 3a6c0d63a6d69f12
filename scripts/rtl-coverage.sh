#!/usr/bin/env bash
# Code coverage of the RTL design (docs/rtl.md, "Code coverage"): a build
# whose verilated configurations count lines, branches and toggles
# (-DIMAP_RTL_COVERAGE=ON, the mutation-check model left out), the RTL
# tests (the random suite among them) and the quick regression on the rtl
# and lockstep models, every process writing its counts; then the counts
# merged (verilator_coverage), per-file figures of hdl/ by kind with the
# waivers applied (rtl_model/coverage-waivers.txt), the uncovered points,
# lcov info and an HTML report (genhtml).
#
#   scripts/rtl-coverage.sh [OUT_DIR]      default build-cov/coverage
# A nightly command, not CI: the coverage build and its runs take about
# half an hour on 2 cores. Needs lcov (scripts/install-deps.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out="${1:-build-cov/coverage}"
jobs="${JOBS:-$(nproc)}"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
for tool in verilator_coverage genhtml lcov python3 cmake; do
  command -v "$tool" >/dev/null || {
    echo "rtl-coverage: '$tool' not found (Debian packages: verilator, lcov, python3, cmake;" \
         "scripts/install-deps.sh installs them)" >&2
    exit 2
  }
done
t0=$(date +%s)
echo "== coverage build (build-cov: every RTL configuration with --coverage)"
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
cmake -S . -B build-cov "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DIMAP_RTL_COVERAGE=ON \
  -DIMAP_RTL_MUTANTS=OFF >/dev/null
cmake --build build-cov -j "$jobs"
mkdir -p "$out"
out=$(cd "$out" && pwd)
rm -rf "$out/dat" && mkdir -p "$out/dat"
export IMAP_RTL_COVERAGE_DIR="$out/dat"
echo "== RTL tests (ctest -R '^rtl\\.': equivalence, firmware, lockstep, faults, waves, random suite)"
ctest --test-dir build-cov -R '^rtl\.' -j "$jobs" --output-on-failure || echo "rtl-coverage: some RTL tests failed (counted anyway)" >&2
echo "== quick regression on the rtl and lockstep models"
./build-cov/imapsim regress --suite quick --models rtl,lockstep -j "$jobs" \
  --junit "$out/regress.xml" || echo "rtl-coverage: some regression cases failed (counted anyway)" >&2
echo "== merge"
shopt -s nullglob
dats=("$out"/dat/cov-*.dat)
[ ${#dats[@]} -gt 0 ] || { echo "rtl-coverage: no coverage written (is the build a coverage build?)" >&2; exit 1; }
verilator_coverage --write "$out/merged.dat" "${dats[@]}"
verilator_coverage --write-info "$out/all.info" "$out/merged.dat"
lcov --quiet --extract "$out/all.info" "*rtl_model/hdl/*" --output-file "$out/hdl.info" \
  --rc lcov_branch_coverage=1 >/dev/null
genhtml --quiet --branch-coverage --output-directory "$out/html" "$out/hdl.info" \
  --title "IMAP-VISION RTL (rtl_model/hdl)" >/dev/null
python3 scripts/rtl_coverage_report.py "$out/merged.dat" rtl_model/coverage-waivers.txt \
  "$out/summary.txt" "$out/uncovered.txt"
cat "$out/summary.txt"
echo "files: $out/html/index.html (HTML), $out/hdl.info (lcov), $out/uncovered.txt (points" \
     "never hit), $out/merged.dat; ${#dats[@]} processes counted, $(( $(date +%s) - t0 )) s"
