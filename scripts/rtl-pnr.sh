#!/usr/bin/env bash
# Place and route of the design on an iCE40 (docs/rtl.md, "Place and route
# (iCE40)"). The chip does not fit the largest iCE40 nextpnr-ice40 supports
# (HX8K, 7,680 logic cells): its CP alone synthesizes to more LUTs than
# that, even with 2 PEs and a 256-word instruction memory. So:
#   - one imap_pe with its 1 KB local memory (the default), inside the
#     harness rtl_model/synth/pnr_pe.sv: yosys synth_ice40 (the memory's
#     eight banks become block RAMs), then nextpnr-ice40 on the HX8K
#     (package ct256) with a fixed seed and --freq 40: LUT4, flip-flops,
#     block RAMs, logic cells, the Fmax of clk;
#   - the CP (P 2, 256-word instruction memory): synth_ice40 only (LUT4,
#     flip-flops, block RAMs), with the HX8K's capacity beside it;
#   - the whole chip (imap_top: P 2, 256-byte local memories, 256-word
#     instruction memory) in the harness rtl_model/synth/pnr_chip.sv (straps
#     tied to the default cost table, the testbench's counters left out):
#     synth_ice40 only;
#   - one imap_pe with 1 KB without the harness: synth_ice40 only.
# Writes the figures, the configuration, the device, the tool versions and
# this command into rtl_model/synth/pnr_ice40.json (checked in; the build
# embeds it and imapsim prints the Fmax). Reads only the design files
# (rtl_model/hdl), never the testbench.
# Usage: scripts/rtl-pnr.sh [OUT_DIR]   (default build-pnr/)
# Needs yosys, nextpnr-ice40 and python3 (Debian packages yosys,
# nextpnr-ice40, fpga-icestorm; scripts/install-deps.sh). Not run in CI.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-build-pnr}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
HDL=$ROOT/rtl_model/hdl
JSON_OUT=$ROOT/rtl_model/synth/pnr_ice40.json

# The units' parameters (the others at their defaults, imap_params.svh and
# imap_pe.sv: NREGS 16, MASK_DEPTH 8, XROWS 8, CALL_DEPTH 16). The device:
# HX8K, 7,680 logic cells and 32 block RAMs of 4 Kbit (Lattice iCE40 LP/HX
# family data sheet), the largest iCE40 of nextpnr-ice40.
PE_MEM=1024
CP_P=2 CP_MEM=32 CP_EXT=256 CP_IMEM=256
CHIP_P=2 CHIP_MEM=256 CHIP_EXT=256 CHIP_IMEM=256
DEVICE=hx8k PACKAGE=ct256 SEED=1 FREQ=40

for t in yosys nextpnr-ice40 python3; do
  command -v $t >/dev/null || { echo "rtl-pnr: $t not found (scripts/install-deps.sh)" >&2; exit 2; }
done
rd="read_verilog -sv -DSYNTHESIS -I$HDL $HDL/imap_pkg.sv"

cat >"$OUT/pe.ys" <<YS
$rd $HDL/imap_pe.sv $ROOT/rtl_model/synth/pnr_pe.sv
hierarchy -top imap_pnr_pe -chparam MEM_BYTES $PE_MEM
synth_ice40 -top imap_pnr_pe -json $OUT/pe.json
tee -q -o $OUT/pe.stat.json stat -json
YS
cat >"$OUT/cp.ys" <<YS
$rd $HDL/imap_cp.sv
hierarchy -top imap_cp -chparam P $CP_P -chparam MEM_BYTES $CP_MEM -chparam EXT_BYTES $CP_EXT -chparam IMEM_WORDS $CP_IMEM
synth_ice40 -top imap_cp
tee -q -o $OUT/cp.stat.json stat -json
YS
cat >"$OUT/chip.ys" <<YS
read_verilog -sv -DSYNTHESIS -DIMAP_NO_PERF -I$HDL $HDL/imap_pkg.sv $HDL/imap_pe.sv $HDL/imap_array.sv $HDL/imap_cp.sv $HDL/imap_top.sv $ROOT/rtl_model/synth/pnr_chip.sv
hierarchy -top imap_pnr_chip -chparam P $CHIP_P -chparam MEM_BYTES $CHIP_MEM -chparam EXT_BYTES $CHIP_EXT -chparam IMEM_WORDS $CHIP_IMEM
synth_ice40 -top imap_pnr_chip
tee -q -o $OUT/chip.stat.json stat -json
YS
cat >"$OUT/pe1k.ys" <<YS
$rd $HDL/imap_pe.sv
hierarchy -top imap_pe -chparam MEM_BYTES 1024
synth_ice40 -top imap_pe
tee -q -o $OUT/pe1k.stat.json stat -json
YS

t0=$(date +%s)
echo "rtl-pnr: yosys synth_ice40 of imap_pe (MEM_BYTES=$PE_MEM) in its harness -> $OUT/pe.log"
yosys -q -l "$OUT/pe.log" "$OUT/pe.ys" >/dev/null
echo "rtl-pnr: nextpnr-ice40 --$DEVICE --package $PACKAGE --seed $SEED --freq $FREQ -> $OUT/pnr.log"
nextpnr-ice40 --$DEVICE --package $PACKAGE --seed $SEED --freq $FREQ --timing-allow-fail \
  --json "$OUT/pe.json" \
  --report "$OUT/pnr.report.json" --asc "$OUT/pe.asc" -q -l "$OUT/pnr.log" || {
  echo "rtl-pnr: nextpnr-ice40 failed (see $OUT/pnr.log)" >&2; exit 1; }
t1=$(date +%s)
echo "rtl-pnr: yosys synth_ice40 of imap_cp (P=$CP_P, IMEM_WORDS=$CP_IMEM) -> $OUT/cp.log"
yosys -q -l "$OUT/cp.log" "$OUT/cp.ys" >/dev/null
t2=$(date +%s)
echo "rtl-pnr: yosys synth_ice40 of imap_pe (MEM_BYTES=1024) -> $OUT/pe1k.log"
yosys -q -l "$OUT/pe1k.log" "$OUT/pe1k.ys" >/dev/null
t3=$(date +%s)
echo "rtl-pnr: yosys synth_ice40 of the chip (P=$CHIP_P, MEM_BYTES=$CHIP_MEM, IMEM_WORDS=$CHIP_IMEM) -> $OUT/chip.log"
yosys -q -l "$OUT/chip.log" "$OUT/chip.ys" >/dev/null
t4=$(date +%s)

YOSYS_V=$(yosys -V) NEXTPNR_V=$(nextpnr-ice40 --version 2>&1 | head -1) \
PE_MEM=$PE_MEM CP_P=$CP_P CP_MEM=$CP_MEM CP_EXT=$CP_EXT CP_IMEM=$CP_IMEM \
CHIP_P=$CHIP_P CHIP_MEM=$CHIP_MEM CHIP_EXT=$CHIP_EXT CHIP_IMEM=$CHIP_IMEM \
DEVICE=$DEVICE PACKAGE=$PACKAGE SEED=$SEED FREQ=$FREQ OUT=$OUT JSON_OUT=$JSON_OUT \
S_PE=$((t1 - t0)) S_CP=$((t2 - t1)) S_PE1K=$((t3 - t2)) S_CHIP=$((t4 - t3)) python3 - <<'PY'
import hashlib, json, os
e = os.environ
# the design the figures are of: rtl_model/hdl as the build embeds it
# (imap::rtl::design_sha256, checked by the test rtl.pnr)
hdl = os.path.join(os.path.dirname(e["JSON_OUT"]), "..", "hdl")
h = hashlib.sha256()
for name in sorted(os.listdir(hdl)):
    if name.endswith((".sv", ".svh")):
        text = open(os.path.join(hdl, name), "rb").read()
        h.update(b"file hdl/%s %d\n" % (name.encode(), len(text)))
        h.update(text)
def cells(name, top):
    mods = json.load(open(e["OUT"] + "/" + name))["modules"]
    m = (mods.get(top) or mods["\\" + top])["num_cells_by_type"]
    return {"lut4": m.get("SB_LUT4", 0),
            "ff": sum(n for t, n in m.items() if t.startswith("SB_DFF")),
            "bram": m.get("SB_RAM40_4K", 0),
            "carry": m.get("SB_CARRY", 0)}
pe = cells("pe.stat.json", "imap_pnr_pe")
cp = cells("cp.stat.json", "imap_cp")
pe1k = cells("pe1k.stat.json", "imap_pe")
chip = cells("chip.stat.json", "imap_pnr_chip")
rep = json.load(open(e["OUT"] + "/pnr.report.json"))
clk = [v for k, v in rep["fmax"].items() if "clk" in k]
if len(clk) != 1:
    raise SystemExit("rtl-pnr: no single clk domain in the nextpnr report: %s" % list(rep["fmax"]))
util = rep["utilization"]
lc_avail = util["ICESTORM_LC"]["available"]
out = {
    "technology": "iCE40 " + e["DEVICE"].upper(),
    "device": e["DEVICE"], "package": e["PACKAGE"],
    "tools": {"yosys": e["YOSYS_V"], "nextpnr": e["NEXTPNR_V"]},
    "command": "scripts/rtl-pnr.sh",
    "hdl_sha256": h.hexdigest(),
    "seed": int(e["SEED"]), "target_mhz": float(e["FREQ"]),
    "fits": "the PE with its local memory; not the CP, not the chip (more LUT4 than the "
            "device has logic cells)",
    "configuration": {"text": "one PE of %s bytes, its memory in block RAMs; the CP does not "
                              "fit" % e["PE_MEM"],
                      "placed": "imap_pe", "MEM_BYTES": int(e["PE_MEM"]),
                      "other": "NREGS 16, MASK_DEPTH 8, XROWS 8 (defaults)",
                      "harness": "rtl_model/synth/pnr_pe.sv (serial input shift register, "
                                 "XOR-folded output)"},
    "pe": dict(pe, logic_cells=util["ICESTORM_LC"]["used"], logic_cells_available=lc_avail,
               bram_available=util["ICESTORM_RAM"]["available"],
               fmax_mhz=round(clk[0]["achieved"], 2)),
    "cp": dict(cp, P=int(e["CP_P"]), MEM_BYTES=int(e["CP_MEM"]), EXT_BYTES=int(e["CP_EXT"]),
               IMEM_WORDS=int(e["CP_IMEM"]), fits=cp["lut4"] <= lc_avail),
    "pe_1k": dict(pe1k, MEM_BYTES=1024),
    "chip": dict(chip, P=int(e["CHIP_P"]), MEM_BYTES=int(e["CHIP_MEM"]),
                 EXT_BYTES=int(e["CHIP_EXT"]), IMEM_WORDS=int(e["CHIP_IMEM"]),
                 harness="rtl_model/synth/pnr_chip.sv (straps tied to the default cost "
                         "table, counters left out, serial inputs, XOR-folded outputs)",
                 fits=chip["lut4"] <= lc_avail),
    "run_seconds": {"pe_synth_pnr": int(e["S_PE"]), "cp_synth": int(e["S_CP"]),
                    "pe_1k_synth": int(e["S_PE1K"]), "chip_synth": int(e["S_CHIP"])},
}
open(e["JSON_OUT"], "w").write(json.dumps(out, indent=2) + "\n")
p = out["pe"]
print("rtl-pnr: imap_pe %s B on %s: %d LUT4, %d FF, %d BRAM, %d/%d logic cells, Fmax %.2f MHz" %
      (e["PE_MEM"], out["technology"], p["lut4"], p["ff"], p["bram"], p["logic_cells"], lc_avail,
       p["fmax_mhz"]))
print("rtl-pnr: imap_cp P=%s: %d LUT4, %d FF, %d BRAM (%s the %d logic cells)" %
      (e["CP_P"], cp["lut4"], cp["ff"], cp["bram"], "fits" if out["cp"]["fits"] else "exceeds",
       lc_avail))
print("rtl-pnr: imap_pe 1 KB: %d LUT4, %d FF, %d BRAM" % (pe1k["lut4"], pe1k["ff"], pe1k["bram"]))
print("rtl-pnr: chip P=%s, %s B: %d LUT4, %d FF, %d BRAM (%s the %d logic cells)" %
      (e["CHIP_P"], e["CHIP_MEM"], chip["lut4"], chip["ff"], chip["bram"],
       "fits" if out["chip"]["fits"] else "exceeds", lc_avail))
print("rtl-pnr: wrote " + e["JSON_OUT"])
PY
echo "rtl-pnr: $((t4 - t0)) s (PE synth + place and route $((t1 - t0)) s, CP synth $((t2 - t1)) s, PE 1 KB synth $((t3 - t2)) s, chip synth $((t4 - t3)) s)"
