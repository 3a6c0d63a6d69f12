// Lockstep co-simulation (docs/rtl.md, "Lockstep"): the TLM model
// (instruction-set model in SystemC TLM-2.0) and the RTL design run the same
// program on the same inputs in one elaboration. The design's trace port
// exports a retire record for every instruction and the taps of every state
// write; the checker keeps a shadow of the RTL's architectural state from
// them and, at every retired instruction, compares it with the TLM model's
// state after the same instruction (the two meet at each instruction: the
// TLM model waits in an observer, the testbench holds the RTL's clock). The
// first divergence stops both and is reported with the instruction index,
// cycle, PC, disassembly, PE, field and the two values; the RTL is then
// re-run from reset by a traced instance of the design to write the waves
// of the cycles before the divergence.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "imap/rtl/system.hpp"
#include "imap/tlm/system.hpp"

namespace imap::rtl {

struct LockstepConfig {
    RtlConfig rtl;  // fault injection, planted bug (waves are not traced here)
    // Waves of the last `waves_cycles` machine cycles before a divergence
    // (.vcd or .fst; "" = none). Written when the configuration has a traced
    // variant; otherwise the report says which option builds one.
    std::string divergence_waves = "rtl_divergence.fst";
    uint64_t waves_cycles = 200;
    // The checker's full compares of all PE registers and flags / the whole
    // local memory every this many instructions (0: automatic, about 256
    // bytes of comparison per instruction; docs/rtl.md, "Lockstep").
    uint64_t full_compare_every = 0;
    void validate(const isa::MachineConfig& cfg) const;
};

struct Divergence {
    uint64_t instruction = 0;  // index of the retired instruction compared
    uint64_t cycle = 0;        // its issue cycle (reference)
    uint32_t pc = 0;           // its PC (reference)
    uint64_t word = 0;
    std::string disassembly;
    std::string what;      // "r5", "C", "T", "M", "pc", "cycle", "c3", "local memory", "fault", ...
    int64_t pe = -1;       // PE index when the state is per PE
    int64_t address = -1;  // memory address when known
    uint64_t tlm_value = 0, rtl_value = 0;
    std::string detail;             // free text (faults, ...)
    std::string reference = "TLM";  // the other side's name in the message
    std::string waves;              // waves file written, or why not
    // an assertion of the design failed (docs/rtl.md, "Assertions"): its
    // name; instruction / cycle / pc / pe are the RTL's at the failing edge
    // and `what` says what the assertion checks
    std::string assertion;
    std::string message() const;  // one line naming all of the above
};

struct LockstepResult {
    bool diverged = false;
    Divergence divergence;  // when diverged
    uint64_t compared = 0;  // retired instructions compared
    uint64_t instructions = 0;
    tlm::TlmRunResult tlm;  // wall_s = 0 (one sc_start for both)
    RtlRunResult rtl;       // wall_s = wall time of the co-simulation
    double wall_s = 0;
};

// Elaborates both models, runs to the halt of both (or to the first
// divergence), compares the final state (memories, registers, outputs,
// cycle count) and returns. `out` receives the TLM model's output images.
// A machine fault on both sides at the same instruction comes out as the
// TLM model's isa::Fault. Once per process.
LockstepResult run_lockstep(const isa::MachineConfig& cfg, const isa::Program& prog,
                            const std::vector<std::pair<int, uint32_t>>& params,
                            const ImageInput& left, const ImageInput& right, int out_w, int out_h,
                            OutputImages* out, const LockstepConfig& lcfg = {});

}  // namespace imap::rtl
