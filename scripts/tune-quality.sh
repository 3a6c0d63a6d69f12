#!/usr/bin/env bash
# Tuning sweep of the SPEC A.9 options around the quality preset on the shared
# Middlebury development scenes (docs/golden.md, "Tuning the quality preset").
# Every point is one `imapsim eval --all DATA --matcher golden --preset quality`
# with the swept flags; the occlusion cost follows the size of the match cost:
#   Wo = Wd = round(150 * terms / 9 * f * (0.5 + kc / 8)),  terms = (2rx+1)(2ry+1)
# so f = 1 is the preset's 150 for kc = 4 and a 3x3 window.
# Prints the best points, a leave-one-scene-out check (tune on three scenes,
# score the fourth) and the preset's neighbours (one swept value changed).
#   scripts/tune-quality.sh [BUILD_DIR] [DATA_DIR]     (QUICK=1: a 40-point grid)
set -euo pipefail
build="${1:-build}"
data="${2:-$(dirname "$0")/../../shared/data/middlebury}"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [[ "${QUICK:-0}" == 1 ]]; then
  kcs="4"; censuses="2"; admaxes="32"; windows="0:0 1:1"; factors="0.5 0.7 1.0 1.4 2.0"
else
  kcs="2 3 4 6 8"; censuses="1 2"; admaxes="16 32 64 255"
  windows="0:0 1:0 0:1 1:1 2:1 1:2 2:2"; factors="0.5 0.7 1.0 1.4 2.0"
fi

n=0
for kc in $kcs; do
  for census in $censuses; do
    for adm in $admaxes; do
      for win in $windows; do
        rx=${win%:*}; ry=${win#*:}
        for f in $factors; do
          W=$(python3 -c "print(round(150*(2*$rx+1)*(2*$ry+1)/9*$f*(0.5+$kc/8)))")
          n=$((n + 1))
          "$build/imapsim" eval --all "$data" --matcher golden --preset quality \
            --kc "$kc" --census "$census" --ad-max "$adm" --agg-rx "$rx" --agg-ry "$ry" \
            --Wo "$W" --Wd "$W" --json "$work/p$n.json" > /dev/null
          echo "kc=$kc census=$census ad-max=$adm agg=$rx,$ry f=$f Wo=Wd=$W" > "$work/p$n.txt"
        done
      done
    done
  done
done

python3 - "$work" "$n" <<'PY'
import json, sys
work, n = sys.argv[1], int(sys.argv[2])
pts = []
for k in range(1, n + 1):
    rows = json.load(open(f"{work}/p{k}.json"))
    label = open(f"{work}/p{k}.txt").read().strip()
    pts.append((label, {r["scene"]: r for r in rows}))
scenes = sorted(pts[0][1])
def mean(p, key="nonocc", only=None):
    ss = [s for s in scenes if only is None or s in only]
    return sum(p[1][s][key] for s in ss) / len(ss)
print(f"{n} points, {len(scenes)} scenes ({', '.join(scenes)}); mean bad-1 % (nonocc all disc)")
print("\nbest points:")
for p in sorted(pts, key=mean)[:12]:
    print(f"  {mean(p):5.2f} {mean(p,'all'):6.2f} {mean(p,'disc'):6.2f}  {p[0]}")
preset = [p for p in pts if p[0].startswith("kc=4 census=2 ad-max=32 agg=1,1 f=1.0 ")]
if preset:
    pr = preset[0]
    print(f"\nthe preset: {mean(pr):5.2f} {mean(pr,'all'):6.2f} {mean(pr,'disc'):6.2f}  {pr[0]}"
          f"  (rank {sorted(pts, key=mean).index(pr) + 1} of {n})")
print("\nleave one scene out (best on the other scenes -> its score on the held-out one):")
held = []
for s in scenes:
    rest = [t for t in scenes if t != s]
    best = min(pts, key=lambda p: mean(p, only=rest))
    held.append(best[1][s]["nonocc"])
    extra = f", preset {pr[1][s]['nonocc']:.2f}" if preset else ""
    print(f"  {s:8s} held out: {best[1][s]['nonocc']:5.2f} (others {mean(best, only=rest):.2f};"
          f" all four {mean(best):.2f}{extra})  {best[0]}")
print(f"  mean of the held-out scores: {sum(held) / len(held):.2f}"
      f" (best in-sample mean {mean(min(pts, key=mean)):.2f})")
if preset:
    print("\nthe preset's neighbours (one swept value changed):")
    keys = pr[0].split()[:5]
    for p in pts:
        ks = p[0].split()[:5]
        if sum(a != b for a, b in zip(ks, keys)) == 1:
            print(f"  {mean(p):5.2f} {mean(p,'all'):6.2f} {mean(p,'disc'):6.2f}  {p[0]}")
PY
