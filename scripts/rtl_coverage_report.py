#!/usr/bin/env python3
"""Per-file coverage figures of the RTL design from a merged Verilator
coverage file (scripts/rtl-coverage.sh; docs/rtl.md, "Code coverage").

usage: rtl_coverage_report.py MERGED.dat WAIVERS.txt SUMMARY.txt UNCOVERED.txt

A point is one of Verilator's coverage points of the design's sources
(rtl_model/hdl/*.sv): a line (block), a branch arm, a toggle of a signal bit.
Points of every instance of a module count once (covered when any instance
hit it), so a figure is the source's, not an instance's. Waivers
(WAIVERS.txt) take points out of the totals, each with its reason:
    FILE:LINE[-LINE] KIND REASON...         KIND: line, branch, toggle or *
    FILE signal=NAME toggle REASON...       every toggle point of a signal
    FILE signal=NAME[HI:LO] toggle REASON.. the toggle points of bits HI..LO
A waiver that matches no point, or that waives a point some run did hit
(its reason claims the point cannot be reached), is reported.
Targets (issue: line >= 95%, toggle >= 85%) are printed beside the totals.
"""
import collections
import os
import re
import sys

KINDS = ("line", "branch", "toggle")
TARGET = {"line": 95.0, "toggle": 85.0}


def parse(path):
    points = {}
    with open(path, "rb") as f:
        for raw in f:
            m = re.match(rb"^C '(.*)' (\d+)\s*$", raw)
            if not m:
                continue
            kv = {}
            for item in m.group(1).split(b"\x01"):
                if b"\x02" in item:
                    k, v = item.split(b"\x02", 1)
                    kv[k.decode()] = v.decode(errors="replace")
            page = kv.get("page", "")
            kind = page.split("/")[0].replace("v_", "")
            if kind not in KINDS:
                continue
            src = kv.get("f", "")
            if "/hdl/" not in src and not src.startswith("hdl/"):
                continue
            key = (os.path.basename(src), kind, int(kv.get("l", "0")), kv.get("n", ""),
                   kv.get("o", ""))
            points[key] = max(points.get(key, 0), int(m.group(2)))
    return points


# One waiver: a line range (lo..hi) of FILE, or a signal with an optional bit
# range bits = (LO, HI); n is its line in the waiver file.
Rule = collections.namedtuple("Rule", "file kind lo hi signal bits reason n")


def parse_waivers(path):
    rules = []
    if not os.path.exists(path):
        return rules
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = line.split(None, 2)
            if len(parts) < 3:
                sys.exit(f"{path}:{n}: expected 'FILE:LINE KIND REASON' or "
                         f"'FILE signal=NAME toggle REASON'")
            where, kind, reason = parts
            if kind.startswith("signal="):  # FILE signal=NAME toggle REASON
                sub = reason.split(None, 1)
                if len(sub) < 2 or sub[0] != "toggle":
                    sys.exit(f"{path}:{n}: a signal waiver is 'FILE signal=NAME toggle REASON'")
                m = re.match(r"^([A-Za-z_][\w.$]*)(?:\[(\d+):(\d+)\])?$", kind[7:])
                if not m or (m.group(2) and int(m.group(2)) < int(m.group(3))):
                    sys.exit(f"{path}:{n}: a signal is NAME or NAME[HI:LO] (HI >= LO)")
                bits = (int(m.group(3)), int(m.group(2))) if m.group(2) else None
                rules.append(Rule(where, "toggle", None, None, m.group(1), bits, sub[1], n))
                continue
            m = re.match(r"^(.+):(\d+)(?:-(\d+))?$", where)
            if not m or kind not in KINDS + ("*",):
                sys.exit(f"{path}:{n}: expected FILE:LINE[-LINE] line|branch|toggle|* REASON")
            lo = int(m.group(2))
            hi = int(m.group(3) or lo)
            rules.append(Rule(m.group(1), kind, lo, hi, None, None, reason, n))
    return rules


def waived(key, rules):
    file, kind, line, _, comment = key
    for r in rules:
        if r.file != file or (r.kind != "*" and r.kind != kind):
            continue
        if r.signal is not None:
            if comment.split("[")[0] != r.signal and comment.split(":")[0] != r.signal:
                continue
            if r.bits is None:  # the whole signal
                return r.n
            bit = re.search(r"\[(\d+)\]$", comment)  # the point's bit (the last index)
            if bit and r.bits[0] <= int(bit.group(1)) <= r.bits[1]:
                return r.n
        elif r.lo <= line <= r.hi:
            return r.n
    return 0


def main():
    merged, waivers, summary, uncovered = sys.argv[1:5]
    points = parse(merged)
    rules = parse_waivers(waivers)
    used = set()
    hit_waived = collections.Counter()  # waiver line -> points it waives that a run hit
    tot = collections.defaultdict(lambda: [0, 0, 0])  # (file, kind) -> covered, total, waived
    miss = []
    for key, count in sorted(points.items()):
        w = waived(key, rules)
        t = tot[(key[0], key[1])]
        if w:
            used.add(w)
            t[2] += 1
            if count > 0:
                hit_waived[w] += 1
            continue
        t[1] += 1
        if count > 0:
            t[0] += 1
        else:
            miss.append(key)
    files = sorted({f for f, _ in tot})
    lines = ["RTL code coverage of rtl_model/hdl (points of every instance counted once;"
             " waived points left out)",
             f"{'file':<18}" + "".join(f"{k:>30}" for k in KINDS)]

    def cell(c, t, w):
        if t == 0:
            return f"{'-':>30}"
        s = f"{c}/{t} {100.0 * c / t:5.1f}%" + (f" ({w} waived)" if w else "")
        return f"{s:>30}"

    grand = collections.defaultdict(lambda: [0, 0, 0])
    for f in files:
        row = f"{f:<18}"
        for k in KINDS:
            c, t, w = tot[(f, k)]
            row += cell(c, t, w)
            for i, v in enumerate((c, t, w)):
                grand[k][i] += v
        lines.append(row)
    row = f"{'total':<18}"
    for k in KINDS:
        row += cell(*grand[k])
    lines.append(row)
    for k, target in TARGET.items():
        c, t, _ = grand[k]
        pct = 100.0 * c / t if t else 0.0
        lines.append(f"{k}: {pct:.1f}% (target >= {target:.0f}%: "
                     f"{'met' if pct >= target else 'NOT met'})")
    unused = [r for r in rules if r.n not in used]
    for r in unused:
        lines.append(f"warning: waiver at line {r.n} matches no point ({r.file} {r.kind})")
    for n, k in sorted(hit_waived.items()):
        lines.append(f"warning: waiver at line {n} waives {k} point(s) that were hit "
                     f"(its reason does not hold)")
    with open(summary, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(uncovered, "w") as f:
        f.write("# points never hit (file:line kind [column] what), not waived\n")
        for file, kind, line, col, comment in miss:
            f.write(f"{file}:{line} {kind} {col} {comment}\n")


if __name__ == "__main__":
    main()
