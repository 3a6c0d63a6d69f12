#!/usr/bin/env bash
# Sweep of the golden's match/occlusion weights on the shared Middlebury
# scenes; prints one line per point sorted by the mean bad-1 (nonocc).
# The defaults in golden/include/imap/golden/params.hpp come from this sweep
# (docs/golden.md, "Tuning").
#   scripts/tune-defaults.sh [BUILD_DIR] [DATA_DIR]
set -euo pipefail
build="${1:-build}"
data="${2:-$(dirname "$0")/../../shared/data/middlebury}"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for km in 1 2 4 8; do
  for kbgb in 0:0 1:32 1:64 1:128 2:64; do
    kb=${kbgb%:*}; gb=${kbgb#*:}
    for Wo in 10 20 40 60 100 160; do
      for frac in 25 50 100; do
        Wd=$(( Wo * frac / 100 ))
        mean=$("$build/imapsim" eval --all "$data" --matcher golden \
                 --km "$km" --kb "$kb" --gb "$gb" --Wo "$Wo" --Wd "$Wd" |
               awk '$1 == "mean" { print $3, $4, $5 }')
        echo "$mean km=$km kb=$kb gb=$gb Wo=$Wo Wd=$Wd" >> "$out"
      done
    done
  done
done
echo "nonocc all disc  parameters   (mean bad-1 % over the scenes, best first)"
sort -n "$out" | head -n 15
