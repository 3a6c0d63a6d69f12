#!/usr/bin/env bash
# One short co-simulation (the DP firmware on the TLM model, synthetic 64x32
# scene, D = 16) under valgrind memcheck: any invalid read / write, use of an
# uninitialised value or "definitely lost" leak makes it fail (docs/testing.md).
#   scripts/valgrind.sh [IMAPSIM]        (default: build/imapsim)
# Exit codes: 0 clean, 99 memcheck found errors, 77 valgrind is not
# installed (the CTest test valgrind.tlm_run reports it as skipped), any
# other: imapsim itself failed (its own exit code).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
exe="${1:-$here/../build/imapsim}"

if ! command -v valgrind >/dev/null 2>&1; then
  echo "valgrind.sh: valgrind is not installed; skipped (scripts/install-deps.sh installs it)"
  exit 77
fi
[ -x "$exe" ] || { echo "valgrind.sh: no imapsim at '$exe'" >&2; exit 2; }

export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# SystemC runs each SC_THREAD on its own heap-allocated stack (QuickThreads):
# memcheck prints "Warning: client switching stacks?" for the first switches
# and handles them as stack switches, which they are. Raising
# --max-stackframe to silence it would be wrong: memcheck would then take a
# switch for a huge stack frame and mark the heap between the stacks as
# stack memory. No suppressions are needed (scripts/valgrind.supp is empty).
start=$(date +%s%N)
valgrind --tool=memcheck --error-exitcode=99 \
  --leak-check=full --show-leak-kinds=definite --errors-for-leak-kinds=definite \
  --suppressions="$here/valgrind.supp" --num-callers=30 \
  "$exe" run --model tlm --size 64x32 --D 16 --report "$tmp/report.json"
rc=$?
ms=$(( ($(date +%s%N) - start) / 1000000 ))
printf 'valgrind.sh: exit %d after %d.%03d s\n' "$rc" $((ms / 1000)) $((ms % 1000))
exit $rc
