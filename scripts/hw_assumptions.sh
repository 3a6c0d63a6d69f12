#!/bin/bash
# How the headline case (imapsim run defaults: ROI 128x128, D = 64, bidir,
# vote on, 256 PEs at 40 MHz) moves with each hardware-assumption parameter
# of the cost table (docs/isa.md section 2.2), one parameter at a time, on
# the core model. Writes CSV (param,value,cycles,ms,bit_exact) and, with
# gnuplot, a tornado plot. Usage: scripts/hw_assumptions.sh IMAPSIM OUT.csv [OUT.png]
set -euo pipefail
sim=${1:?imapsim binary}
csv=${2:?output CSV}
png=${3:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # name value
    local rep="$tmp/r.json"
    "$sim" run --model core --set "$1=$2" --report "$rep" > /dev/null
    python3 -c "import json,sys; j=json.load(open('$rep')); print('$1,$2,%d,%.3f,%s' % (j['cycles'], j['modeled_ms'], 'yes' if j['bit_exact'] else 'no'))"
}
{
    echo "param,value,cycles,ms,bit_exact"
    run alu 1
    for spec in "shift_bits 1" "minmax_extra 1 2" "ext_bytes_per_cycle 1 2 4 16 64" \
                "status 2 4 8" "video_line 2 32 256" "indirect_extra 0 2 4" "ring_hop 2" \
                "xfer_setup 0 32" "mask 2" "branch_taken 0 2" "mem 2" "cp 2" "alu 2"; do
        set -- $spec
        name=$1
        shift
        for v in "$@"; do run "$name" "$v"; done
    done
} > "$csv"
[ -z "$png" ] && exit 0
# tornado: per parameter the lowest and highest modeled time of its values
python3 - "$csv" "$tmp/bars.dat" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
base = float(rows[0]['ms'])
by = {}
for r in rows[1:]:
    by.setdefault(r['param'], []).append((float(r['ms']), r['value']))
bars = []
for p, v in by.items():
    lo, hi = min(v), max(v)
    bars.append((max(abs(lo[0] - base), abs(hi[0] - base)), p, min(lo[0], base), max(hi[0], base),
                 ','.join(x[1] for x in sorted(v, key=lambda t: t[0]))))
bars.sort()
with open(sys.argv[2], 'w') as f:
    for i, (_, p, lo, hi, vals) in enumerate(bars):
        f.write(f'{i} {lo:.4f} {hi:.4f} "{p} ({vals})" {base:.4f}\n')
PY
gnuplot <<GP
set terminal pngcairo size 900,560 font ",10" noenhanced
set output "$png"
set title "Headline case (128x128, D=64, bidir, vote, 256 PEs, 40 MHz): modeled ms per cost parameter"
set xlabel "modeled frame time (ms), one parameter changed from its default"
set ytics nomirror
set grid xtics
set style fill solid 0.6 border -1
unset key
base = $(awk -F, 'NR==2{print $4}' "$csv")
set arrow from base, graph 0 to base, graph 1 nohead dt 2 lw 2 lc rgb "black"
set yrange [-0.7:*]
plot "$tmp/bars.dat" using ((\$2+\$3)/2):1:(\$2):(\$3):(\$1-0.35):(\$1+0.35):ytic(4) with boxxyerror lc rgb "#4477aa"
GP
