// Timing of the design (docs/rtl.md, "Place and route (iCE40)"): the figures
// of scripts/rtl-pnr.sh (yosys synth_ice40 + nextpnr-ice40 of a small
// configuration of the chip), checked in as rtl_model/synth/pnr_ice40.json
// and embedded at build time; the design's Fmax against a clock.
#pragma once

#include <cstdint>
#include <string>

namespace imap::rtl {

struct PnrUnit {
    uint64_t lut4 = 0, ff = 0, bram = 0;  // SB_LUT4, SB_DFF*, SB_RAM40_4K (synth_ice40)
};

struct PnrFigures {
    bool available = false;     // false when the build embedded no figures
    std::string technology;     // "iCE40 HX8K"
    std::string package;        // "ct256"
    std::string tool;           // the nextpnr version line
    std::string configuration;  // what was placed: "one PE of 1024 bytes, ..."
    PnrUnit pe;                 // the placed PE (with its harness)
    uint64_t logic_cells = 0, logic_cells_available = 0;
    double fmax_mhz = 0;   // the clock's achieved Fmax (nextpnr, fixed seed)
    PnrUnit cp;            // the CP, synthesized only
    bool cp_fits = false;  // whether the CP's LUT4 fit the device's logic cells
    PnrUnit pe1k;          // one imap_pe with 1 KB, synthesized only
    PnrUnit chip;          // the whole chip of a few PEs, synthesized only (if recorded)
    bool chip_fits = false;
    std::string hdl_sha256;  // the design the figures are of (design_sha256() then)
};

// Parses the JSON written by scripts/rtl-pnr.sh. Throws std::runtime_error
// naming the missing or invalid field.
PnrFigures parse_pnr(const std::string& json);

// The hash of this build's design files (rtl_model/hdl, as embedded): for
// each file in name order, "file hdl/NAME SIZE\n" and its text, SHA-256.
// scripts/rtl-pnr.sh records the same hash of the files it placed.
std::string design_sha256();

// The figures of this build (parsed once).
const PnrFigures& place_and_route();

// Whether a clock of clock_mhz is above the design's Fmax (false without
// figures).
bool above_fmax(const PnrFigures& f, double clock_mhz);

// One line: "design Fmax: at most 23.40 MHz on iCE40 HX8K (nextpnr-ice40,
// one PE of 32 bytes; the CP does not fit, docs/rtl.md); the 40 MHz clock is
// above it" ("" without figures). "at most": what was placed is a part of
// the design, whose Fmax bounds the whole's.
std::string fmax_text(const PnrFigures& f, double clock_mhz);

}  // namespace imap::rtl
