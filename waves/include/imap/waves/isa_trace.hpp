// Instruction-granularity waves of the ISA machine (the `core` and `tlm`
// models): an isa::Observer that writes a VCD plus a .gtkw view of the CP and
// of selected PEs inside a cycle window (docs/waves.md).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "imap/waves/gtkw.hpp"
#include "imap/waves/trace_common.hpp"
#include "imap/waves/vcd.hpp"

namespace imap::waves {

// Measured on the headline forward pass (docs/waves.md): VCD bytes per traced
// PE and machine cycle with all groups on, and the CP part per cycle. Used for
// the size estimate that warns before a large trace.
inline constexpr double kBytesPerPeCycle = 7.6;
inline constexpr double kCpBytesPerCycle = 245.0;

// Registers that hold one multi-byte value (low byte first), shown in the
// .gtkw view of each PE as one combined decimal vector `name` (the VCD keeps
// the byte registers). The firmware declares its groups
// (imap::firmware::wave_groups()); the tracer knows nothing of their meaning.
struct RegisterGroup {
    std::string name;
    std::vector<int> regs;  // PE registers, low byte first
};

// What to trace. Groups: cp (cycle, PC, instruction text, phase, c0..c15),
// ring (per PE: ring strobe and received byte), mask (per PE: M; CP: mask
// stack depth and active PEs), mem (per PE: write strobe, address, data),
// regs (per PE: r0..r15, C, T).
struct TraceSelection {
    std::vector<int> pes;  // sorted, unique
    uint64_t t0 = 0;       // window [t0, t1) in cycles
    uint64_t t1 = UINT64_MAX;
    bool cp = true, ring = true, mask = true, mem = true, regs = true;
    uint64_t limit_bytes = 200ull << 20;  // hard stop; 0 = none
    std::string limit_name = "--trace-limit-mb 200";
    std::vector<RegisterGroup> groups;  // combined vectors in the view (regs group)
};

// Parses the imapsim options (empty string = default) into a selection.
// Throws WaveError with "invalid value 'X' for --option: expected ...".
//   pes:     "a:b" (inclusive) or "1,5,9" or a mix "0:3,10"; default 0:3
//   window:  "t0:t1" in cycles, or with a unit on each bound ("2.5us:3us",
//            "100000ns:...": ns/us/ms, converted with the clock); either
//            bound may be empty ("100000:" = to the end); default: all
//   signals: comma list of cp,ring,mask,mem,regs or "all"; default all
//   limit_mb: > 0 megabytes (1 MB = 2^20 bytes); default 200
TraceSelection parse_trace_selection(const std::string& pes, const std::string& window,
                                     const std::string& signals, double limit_mb,
                                     const isa::MachineConfig& cfg);

// The observer. Declares the signals and opens the VCD on construction
// (WaveError when the file cannot be created); finish() writes the last
// values, renames the VCD into place and writes the .gtkw next to it (same
// name with the extension replaced by .gtkw). A finished VCD is kept when
// the .gtkw cannot be written: finish() then returns normally and
// gtkw_error() says why (the caller warns). Destroyed without finish(): no
// files are left.
class IsaTracer : public isa::Observer {
  public:
    IsaTracer(const std::string& vcd_path, const isa::MachineConfig& cfg, const isa::Program& prog,
              const TraceSelection& sel);
    ~IsaTracer() override;

    void on_instruction(const isa::Machine& m, const isa::TraceEvent& e) override;
    // `end_cycle`: the machine's cycle counter at the end of the run.
    void finish(uint64_t end_cycle);

    const std::string& vcd_path() const { return path_; }
    std::string gtkw_path() const;
    uint64_t bytes() const { return w_.bytes_written(); }
    bool limit_reached() const { return w_.limit_reached(); }
    uint64_t traced_instructions() const { return traced_; }
    // After finish(): why the .gtkw view could not be written ("" = it was).
    const std::string& gtkw_error() const { return gtkw_error_; }
    // Estimated VCD size for the selection over `cycles` machine cycles.
    static double estimate_bytes(const TraceSelection& sel, uint64_t cycles);

  private:
    void sample_state(const isa::Machine& m);

    std::string path_;
    isa::MachineConfig cfg_;
    const isa::Program& prog_;
    TraceSelection sel_;
    ClockScale clk_;
    VcdWriter w_;
    GtkwSave g_;
    int nregs_ = 16;
    SignalId pc_ = 0, instr_ = 0, op_ = 0, args_ = 0, phase_ = 0, cycle_ = 0, msp_ = 0, active_ = 0;
    std::string gtkw_error_;
    std::vector<SignalId> creg_;
    std::vector<detail::PeSignals> pes_;
    detail::DisasmCache disasm_;
    uint32_t last_phase_ = UINT32_MAX;
    uint64_t last_cycle_ = 0, traced_ = 0;
    bool started_ = false, done_ = false;
    uint64_t first_time_ = 0;
};

}  // namespace imap::waves
