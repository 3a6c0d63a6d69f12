#!/usr/bin/env bash
# valgrind memcheck of one short co-simulation: the DP firmware on the TLM
# model (synthetic 64x32 pair, D = 16), checked bit for bit against the
# golden (docs/testing.md, "Valgrind"). Any invalid read / write, use of an
# uninitialised value or "definitely lost" leak makes it fail.
#   scripts/valgrind.sh [--expect-errors] [PROGRAM]
#     PROGRAM   default: build/tests/valgrind/memcheck_tlm_run
#     --expect-errors   run the test case with planted memory errors instead:
#                       passes only if memcheck reports errors (exit 99)
# The program links no OpenCV: libraries that OpenCV pulls in run start-up
# code before main that valgrind cannot always decode (libhwy's
# TimerResolution uses RDTSCP: "Unrecognised instruction", SIGILL on some
# CPUs). This script refuses a program that links them (ldd).
# Exit codes: 0 clean (or, with --expect-errors, errors found as planted),
# 99 memcheck found errors, 77 valgrind is not installed (CTest reports the
# test as skipped), 3 the program links a library that must not be there,
# 1 --expect-errors and memcheck found nothing, any other: the program's own
# exit code (e.g. 201 when a Boost test fails).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
expect_errors=0
if [ "${1:-}" = "--expect-errors" ]; then
  expect_errors=1
  shift
fi
exe="${1:-$here/../build/tests/valgrind/memcheck_tlm_run}"

if ! command -v valgrind >/dev/null 2>&1; then
  echo "valgrind.sh: valgrind is not installed; skipped (scripts/install-deps.sh installs it)"
  exit 77
fi
[ -x "$exe" ] || { echo "valgrind.sh: no program at '$exe'" >&2; exit 2; }

# What the program loads: none of OpenCV, nor libhwy by any other way.
libs=$(ldd "$exe" 2>&1) || { echo "valgrind.sh: ldd '$exe' failed: $libs" >&2; exit 3; }
echo "valgrind.sh: $exe loads:"
echo "$libs" | sed 's/^/  /'
bad=$(echo "$libs" | grep -E 'libopencv_|libhwy' || true)
if [ -n "$bad" ]; then
  echo "valgrind.sh: '$exe' links libraries whose start-up code valgrind may not run on" \
       "this CPU (they must stay out of the memcheck program):" >&2
  echo "$bad" >&2
  exit 3
fi

export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
case_name=tlm_frame_is_bit_exact
[ "$expect_errors" = 1 ] && case_name=planted_memory_error

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
  "$exe" --run_test="$case_name" --log_level=message
rc=$?
ms=$(( ($(date +%s%N) - start) / 1000000 ))
printf 'valgrind.sh: %s: exit %d after %d.%03d s\n' "$case_name" "$rc" $((ms / 1000)) $((ms % 1000))
if [ "$expect_errors" = 1 ]; then
  if [ "$rc" = 99 ]; then
    echo "valgrind.sh: memcheck reported the planted errors, as it must"
    exit 0
  fi
  echo "valgrind.sh: memcheck did not report the planted errors (exit $rc, expected 99)" >&2
  exit 1
fi
exit $rc
