// Lockstep co-simulation of the TLM model and the RTL model in one SystemC
// elaboration (docs/rtl.md): a TlmSystem "tlm" and an RtlSystem "rtl" run
// the same program on the same inputs; after every `interval`-th retired
// instruction each side records its architectural state (PC, cycle counter,
// CP registers and stacks depth, PE register / C / T / M lanes, a hash of
// the local and external memories and of the param block) and the two
// records are compared. The first divergence is reported with the
// instruction index, cycle, PC, disassembly, PE and the two values.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "imap/rtl/system.hpp"
#include "imap/tlm/system.hpp"

namespace imap::rtl {

struct LockstepConfig {
    uint64_t interval = 1;  // compare every N-th retired instruction (>= 1); halt always
    RtlConfig rtl;          // RTL model parameters, including the fault injection
    void validate(const isa::MachineConfig& cfg) const;
};

struct Divergence {
    uint64_t instruction = 0;  // index of the retired instruction compared
    uint64_t cycle = 0;        // cycle counter (TLM) before it
    uint32_t pc = 0;           // its PC (TLM)
    uint64_t word = 0;
    std::string disassembly;
    std::string what;      // "r5", "C", "T", "M", "pc", "cycles", "c3", "local memory", ...
    int64_t pe = -1;       // PE index when the state is per PE
    int64_t address = -1;  // memory address when known
    uint64_t tlm_value = 0, rtl_value = 0;
    std::string message() const;  // one line naming all of the above
};

struct LockstepResult {
    bool diverged = false;
    Divergence divergence;  // when diverged
    uint64_t compared = 0;  // state records compared
    uint64_t instructions = 0;
    tlm::TlmRunResult tlm;  // wall_s = 0 (one sc_start for both)
    RtlRunResult rtl;       // wall_s = wall time of the co-simulation
    double wall_s = 0;
};

// Elaborates both models, runs to the halt of both (or to the first
// divergence), compares the final state, and returns. `out` receives the
// TLM model's output images. A machine fault (on both sides) comes out as
// the original isa::Fault. Once per process (std::logic_error otherwise,
// also after run_rtl; run_tlm has its own guard and must not be mixed).
LockstepResult run_lockstep(const isa::MachineConfig& cfg, const isa::Program& prog,
                            const std::vector<std::pair<int, uint32_t>>& params,
                            const ImageInput& left, const ImageInput& right, int out_w, int out_h,
                            OutputImages* out, const LockstepConfig& lcfg = {});

}  // namespace imap::rtl
