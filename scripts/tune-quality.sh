#!/usr/bin/env bash
# Tuning sweep of the SPEC A.9 options around the quality preset on the shared
# Middlebury development scenes (docs/golden.md, "Tuning the quality preset").
# One `imapsim eval --all DATA --param-sets FILE` scores every point; a point
# is the quality preset with --kc, --census, --ad-max, --agg-rx, --agg-ry and
# an occlusion cost that follows the size of the match cost:
#   Wo = Wd = round(400 * terms / 25 * f * (0.5 + kc / 8)),  terms = (2rx+1)(2ry+1)
# (f = 1 with kc = 4 and the preset's 5x5 window is its 400).
# Prints the best points, the rank of the preset, a leave-one-scene-out check
# (tune on three scenes, score the fourth) and the preset's neighbours (one
# swept value changed).
#   scripts/tune-quality.sh [BUILD_DIR] [DATA_DIR]
#     QUICK=1           a 10-point grid
#     WINDOWS=horizontal  only horizontal windows (ry = 0: 1x1, 3x1, 5x1; 600
#                       points); "the preset" is then variant quality-5x1
#                       (f = 1: Wo = Wd = 80), otherwise --preset quality
#                       (its 5x5 window, f = 1: 400)
set -euo pipefail
build="${1:-build}"
data="${2:-$(dirname "$0")/../../shared/data/middlebury}"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

windows="${WINDOWS:-all}"
case "$windows" in
all | horizontal) ;;
*)
  echo "tune-quality.sh: WINDOWS=$windows: expected all or horizontal" >&2
  exit 2
  ;;
esac
python3 - "$work/sets.txt" "${QUICK:-0}" "$windows" <<'PY'
import sys
out, quick, windows = sys.argv[1], sys.argv[2] == "1", sys.argv[3]
if quick and windows == "horizontal":
    grid = dict(kc=[4], census=[2], adm=[16], win=[(1, 0), (2, 0)], f=[0.5, 0.7, 1.0, 1.4, 2.0])
elif windows == "horizontal":
    grid = dict(kc=[2, 3, 4, 6, 8], census=[1, 2], adm=[8, 16, 32, 255],
                win=[(0, 0), (1, 0), (2, 0)], f=[0.5, 0.7, 1.0, 1.4, 2.0])
elif quick:
    grid = dict(kc=[4], census=[2], adm=[16], win=[(1, 1), (2, 2)], f=[0.5, 0.7, 1.0, 1.4, 2.0])
else:
    grid = dict(kc=[2, 3, 4, 6, 8], census=[1, 2], adm=[8, 16, 32, 255],
                win=[(0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (2, 2)],
                f=[0.5, 0.7, 1.0, 1.4, 2.0])
with open(out, "w") as fh:
    for kc in grid["kc"]:
        for census in grid["census"]:
            for adm in grid["adm"]:
                for rx, ry in grid["win"]:
                    for f in grid["f"]:
                        W = round(400 * (2 * rx + 1) * (2 * ry + 1) / 25 * f * (0.5 + kc / 8))
                        fh.write(f"--preset quality --kc {kc} --census {census} --ad-max {adm} "
                                 f"--agg-rx {rx} --agg-ry {ry} --Wo {W} --Wd {W}  # f={f}\n")
PY
# The flags are the part of each line before "#" (a comment to imapsim would
# end the flags anyway: strip it for the file).
sed 's/  # f=.*//' "$work/sets.txt" > "$work/flags.txt"
"$build/imapsim" eval --all "$data" --param-sets "$work/flags.txt" --json "$work/out.json" \
  > /dev/null

python3 - "$work/out.json" "$work/sets.txt" "$windows" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
preset_window = "2,0" if sys.argv[3] == "horizontal" else "2,2"
fs = [l.split("# f=")[1].strip() for l in open(sys.argv[2])]
pts = []
for r, f in zip(rows, fs):
    p = r["params"]
    key = (p["kc"], p["census"], p["ad_max"], f"{p['agg_rx']},{p['agg_ry']}", f)
    pts.append((key, r["scenes"], r))
scenes = sorted(pts[0][1])
def mean(p, k="nonocc", only=None):
    ss = [s for s in scenes if only is None or s in only]
    return sum(p[1][s][k] for s in ss) / len(ss)
def label(p):
    kc, census, adm, win, f = p[0]
    return f"kc={kc} census={census} ad-max={adm} agg={win} f={f} Wo=Wd={p[2]['params']['Wo']}"
print(f"{len(pts)} points, {len(scenes)} scenes ({', '.join(scenes)}); "
      "mean bad-1 % nonocc, all, disc")
order = sorted(pts, key=mean)
print("\nbest points:")
for p in order[:12]:
    print(f"  {mean(p):5.2f} {mean(p,'all'):6.2f} {mean(p,'disc'):6.2f}  {label(p)}")
preset = [p for p in pts if p[0] == (4, 2, 16, preset_window, "1.0")]
if preset:
    pr = preset[0]
    print(f"\nthe preset: {mean(pr):5.2f} {mean(pr,'all'):6.2f} {mean(pr,'disc'):6.2f}  "
          f"{label(pr)}  (rank {order.index(pr) + 1} of {len(pts)})")
print("\nleave one scene out (the best point on the other scenes, scored on the held-out one):")
held = []
for s in scenes:
    rest = [t for t in scenes if t != s]
    best = min(pts, key=lambda p: mean(p, only=rest))
    held.append(best[1][s]["nonocc"])
    extra = f"; the preset {pr[1][s]['nonocc']:.2f}" if preset else ""
    print(f"  {s:8s} {best[1][s]['nonocc']:5.2f} (on the others {mean(best, only=rest):.2f}"
          f"{extra})  {label(best)}")
print(f"  mean of the held-out scores {sum(held) / len(held):.2f}; "
      f"best in-sample mean {mean(order[0]):.2f}")
if preset:
    print("\nthe preset's neighbours (one swept value changed):")
    for p in pts:
        if sum(a != b for a, b in zip(p[0], pr[0])) == 1:
            print(f"  {mean(p):5.2f} {mean(p,'all'):6.2f} {mean(p,'disc'):6.2f}  {label(p)}")
PY
