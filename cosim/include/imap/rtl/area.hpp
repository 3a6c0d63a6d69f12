// Silicon of the design (docs/rtl.md, "Synthesis"): the PE and the CP
// synthesized by yosys to generic gates at build time, and the array's
// figures for a machine configuration (for the what-if sweep's area
// column).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "imap/isa/config.hpp"

namespace imap::rtl {

struct UnitArea {
    uint64_t cells = 0;        // generic cells (gates and flip-flops), memories excluded
    uint64_t flops = 0;        // of which flip-flops
    uint64_t memory_bits = 0;  // inferred memories (register file, RAMs)
    std::map<std::string, uint64_t> by_type;
};

struct SynthFigures {
    bool available = false;  // false when the build had no yosys
    UnitArea pe, cp;
    std::string tool;      // "Yosys 0.23 ..."
    std::string params;    // the HDL parameters synthesized
    int pe_mem_bytes = 0;  // the PE's local memory in that synthesis
    int cp_pes = 0;        // the PE count of the CP's synthesis
};

// The figures of this build.
const SynthFigures& synthesis();

struct ArrayArea {
    uint64_t cells = 0;  // P x PE cells + CP cells
    uint64_t pe_cells = 0, cp_cells = 0;
    uint64_t memory_bits = 0;  // on chip: P x (registers + local memory) + CP memories
    uint64_t ext_bits = 0;     // the external memory (board level, off chip)
};

// The array of cfg.pes PEs with cfg.mem_bytes each. The PE's cells are
// those synthesized at pe_mem_bytes (the address path grows with
// log2(mem_bytes); docs/rtl.md). Throws std::runtime_error when the build
// has no synthesis figures.
ArrayArea array_area(const isa::MachineConfig& cfg);

}  // namespace imap::rtl
