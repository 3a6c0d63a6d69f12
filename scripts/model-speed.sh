#!/usr/bin/env bash
# Simulation speed of the TLM and RTL models at several PE counts on the same
# case (synthetic scene, whole image as ROI), one `imapsim run` per model and
# PE count; prints cycles per wall second and the TLM/RTL ratio.
#   scripts/model-speed.sh [BUILD_DIR] [SIZE] [D] [PES...]
set -euo pipefail
build="${1:-build}"; size="${2:-96x64}"; D="${3:-16}"; shift $(( $# > 3 ? 3 : $# )) || true
pes=("$@"); [ ${#pes[@]} -gt 0 ] || pes=(8 64 256)
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
w=${size%x*}; h=${size#*x}
printf "case: synthetic %s, ROI 0,0,%s,%s, D=%s, bidir, vote on\n" "$size" "$w" "$h" "$D"
printf "%6s %12s %14s %14s %10s\n" PEs cycles "RTL cycles/s" "TLM cycles/s" "TLM/RTL"
for p in "${pes[@]}"; do
  for m in rtl tlm; do
    "$build/imapsim" run --model "$m" --pes "$p" --size "$size" --roi "0,0,$w,$h" --D "$D" \
      --report "$tmp/$m.json" > "$tmp/$m.log" || { cat "$tmp/$m.log"; exit 1; }
  done
  python3 - "$tmp" "$p" <<'PY'
import json, sys
d, p = sys.argv[1], sys.argv[2]
r = json.load(open(d + "/rtl.json")); t = json.load(open(d + "/tlm.json"))
assert r["bit_exact"] and t["bit_exact"] and r["cycles"] == t["cycles"]
rc = r["cycles"] / r["wall_s"]; tc = t["cycles"] / t["wall_s"]
print("%6s %12d %14.3g %14.3g %10.1f" % (p, r["cycles"], rc, tc, tc / rc))
PY
done
