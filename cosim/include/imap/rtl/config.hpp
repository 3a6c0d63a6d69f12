// Parameters of an RTL run that are not parameters of the machine (the
// machine is configured by isa::MachineConfig, as for the TLM model): the
// waves of the design's own signals, the fault-injection hook that checks
// the lockstep co-simulation, and the planted bug of the mutation check.
// The configurations of the design this build holds (PE count and memory
// sizes are HDL parameters) and how to get another.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"

namespace imap::rtl {

// XOR `mask` into one piece of PE state of the RTL model right after the
// instruction with index `instruction` (0-based, in execution order, counting
// every executed instruction including zero-cost `phase`) retires. Applied to
// the RTL model only (through the testbench's backdoor): the lockstep
// co-simulation must catch it.
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

// The planted bugs of the mutation check (docs/rtl.md, "Mutation check"),
// built into the mutation-check configuration only (IMAP_RTL_MUTANTS).
struct Mutant {
    uint32_t id;
    const char* name;
    const char* what;
};
const std::vector<Mutant>& mutants();
// Throws isa::ConfigError for an unknown name (listing the known ones).
uint32_t mutant_id(const std::string& name);

// The design's assertions (docs/rtl.md, "Assertions"; rtl_model/hdl,
// checked in every verilated configuration): name, where, what it checks.
struct Assertion {
    const char* name;
    const char* where;  // the design unit ("imap_pe", "imap_cp", ...)
    const char* what;
};
const std::vector<Assertion>& assertions();
// What assertion `name` checks ("" for an unknown name).
std::string assertion_what(const std::string& name);

// Waves of the design's own signals (Verilator tracing): needs a variant of
// the configuration traced in the format (FST: every configuration of an
// IMAP_RTL_FST_ALL build; VCD: IMAP_RTL_TRACE_CONFIGS).
struct RtlWaves {
    std::string path;  // .vcd or .fst (by the extension); empty = no waves
    // machine cycles [t0, t1] (inclusive); the whole run by default
    uint64_t t0 = 0, t1 = UINT64_MAX;
    // stop tracing beyond about this file size (checked every 256 clocks; 0: none)
    uint64_t limit_bytes = 0;
    // PEs with their datapath in the waves (empty = all); the CP, the array
    // level (ring links, mask bus) and the board are always in.
    std::vector<int> pes;
    // groups: "cp", "array", "board", "pe" (empty = all)
    std::vector<std::string> groups;
    // Verilator's dumpvars prefixes for this selection (under `top`, the
    // model's SystemC name); a prefix ending in '!' selects that scope's own
    // signals only, not the units below it.
    std::vector<std::string> scopes(const std::string& top, int pes_total) const;
    void validate(const isa::MachineConfig& cfg) const;
};

// The GTKWave view written next to a waves file (extension replaced by .gtkw).
std::string gtkw_path(const std::string& waves_path);

struct RtlConfig {
    FaultInjection inject;
    RtlWaves waves;
    std::string mutant;  // planted bug by name (mutation-check configuration), "" none
    void validate(const isa::MachineConfig& cfg) const;
};

// ---- configurations of this build ------------------------------------------
struct ConfigName {
    int pes = 0;
    uint32_t mem_bytes = 0, ext_bytes = 0;
};
// Every configuration verilated into this build ("p256_m1024_x65536" ...),
// with its variants (fast, vcd, fst, mut).
std::vector<std::string> built_configurations();
bool has_configuration(const isa::MachineConfig& cfg);
// Throws isa::ConfigError when cfg cannot run on the RTL of this build: an
// unbuilt configuration (the message gives the exact command that builds
// it), or a run-time parameter beyond what the HDL of every configuration
// holds (registers, mask and return stacks, the transfer path's rows per
// cycle, program size, phases). `waves`: the wave format the run writes
// (waves_format: 0 none, 1 VCD, 2 FST), which needs a variant traced in it.
void check_runnable(const isa::MachineConfig& cfg, int waves = 0, bool needs_mutants = false,
                    size_t program_words = 0, size_t phases = 0);
// The wave format of a waves path by its extension: 0 for "" (no waves), 2
// for .fst, 1 (VCD) otherwise.
int waves_format(const std::string& path);
// The command that adds the configuration of cfg (traced in `waves`) to a build.
std::string build_command(const isa::MachineConfig& cfg, int waves = 0);

}  // namespace imap::rtl
