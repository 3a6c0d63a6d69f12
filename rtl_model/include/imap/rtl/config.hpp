// Parameters of the RTL model that are not parameters of the machine (the
// machine itself is configured by isa::MachineConfig, as for the TLM model):
// which PEs and registers get per-PE signals, and the fault-injection hook
// used to check the lockstep co-simulation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"

namespace imap::waves {
class CycleObserver;  // imap/waves/cycle_trace.hpp
}

namespace imap::rtl {

// XOR `mask` into one piece of PE state of the RTL model right after the
// instruction with index `instruction` (0-based, in execution order, counting
// every executed instruction including zero-cost `phase`) retires. Applied to
// the RTL model only: the lockstep co-simulation must catch it.
struct FaultInjection {
    static constexpr int kRegC = -1;  // carry flag
    static constexpr int kRegT = -2;  // test flag
    static constexpr int kRegM = -3;  // mask bit
    bool enabled = false;
    uint64_t instruction = 0;
    int pe = 0;
    int reg = 0;  // 0..pe_regs-1, or kRegC / kRegT / kRegM
    uint8_t mask = 1;
};

// "INSTR:PE:REG:MASK", e.g. "120:3:r5:0x10" or "40:0:c:1". REG is rN, N, c,
// t or m; MASK is decimal or 0x-hex, 1..255. Throws isa::ConfigError.
FaultInjection parse_fault_injection(const std::string& spec);
// Name of a register of FaultInjection::reg ("r5", "C", "T", "M").
std::string reg_name(int reg);

struct RtlConfig {
    // PEs that get per-PE signals (top.array.pe_<i>, top.ring.link_<i>):
    // trace_pe_first .. trace_pe_first + trace_pe_count - 1; a count of -1
    // means "up to the last PE", 0 means none.
    int trace_pe_first = 0;
    int trace_pe_count = -1;
    // PE registers that get a signal in each traced PE; empty = all.
    std::vector<int> trace_regs;
    FaultInjection inject;
    // Per-cycle waves: when set, the clocked process calls it once per clock
    // edge of the run (not owned; nullptr = no tracing, no cost).
    waves::CycleObserver* cycle_tracer = nullptr;

    // Throws isa::ConfigError naming the parameter, the value and the range.
    void validate(const isa::MachineConfig& cfg) const;
    // Resolved range (after validate): [first, first + count).
    int traced_first(const isa::MachineConfig& cfg) const;
    int traced_count(const isa::MachineConfig& cfg) const;
    std::vector<int> traced_regs(const isa::MachineConfig& cfg) const;
};

}  // namespace imap::rtl
