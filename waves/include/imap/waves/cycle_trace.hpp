// Per-cycle waves of the RTL model (docs/waves.md, "The RTL model"): the
// clocked process of imap::rtl calls a CycleObserver once per clock edge with
// the machine state and what it drove on the ring and the memory strobes in
// that cycle; CycleTracer writes them as a VCD (time = cycle x clock period)
// plus a .gtkw view with the same conventions as IsaTracer. Plain C++.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "imap/waves/gtkw.hpp"
#include "imap/waves/isa_trace.hpp"
#include "imap/waves/trace_common.hpp"
#include "imap/waves/vcd.hpp"

namespace imap::waves {

// What the RTL process drove in one clock cycle, beyond the machine state.
struct CycleInfo {
    uint64_t cycle = 0;  // the clock edge (= machine cycle)
    bool issue = false;  // an instruction issued on this edge (cp.valid)
    uint32_t pc = 0;     // the instruction in flight
    uint64_t word = 0;
    bool bubble = false;    // taken-branch bubble cycle
    bool pe_state = false;  // PE registers / flags may have changed on this edge
    // Ring transfer: hop (1..k) of the transfer from `ring_src` (P bytes).
    bool ring_busy = false;
    uint32_t ring_hop = 0;
    bool ring_up = false;  // towards higher PEs (rxl)
    const uint8_t* ring_src = nullptr;
    // Memory strobes of this cycle.
    enum class Mem : uint8_t { None, Row, RowMasked, Stx, Ext } mem = Mem::None;
    uint32_t mem_addr = 0;  // Row / RowMasked / Ext: the row written
    // Status reduction (rany / rall) on this edge.
    bool reduce = false;
    bool any = false, all = true;
};

class CycleObserver {
  public:
    virtual ~CycleObserver() = default;
    virtual void on_cycle(const isa::Machine& m, const CycleInfo& c) = 0;
};

// Writes the VCD; same selection (PEs, window in cycles, groups, size limit)
// and the same file handling as IsaTracer (atomic, WaveError when the file
// cannot be created, no files left when destroyed without finish()).
class CycleTracer : public CycleObserver {
  public:
    CycleTracer(const std::string& vcd_path, const isa::MachineConfig& cfg,
                const isa::Program& prog, const TraceSelection& sel);
    ~CycleTracer() override;

    void on_cycle(const isa::Machine& m, const CycleInfo& c) override;
    // `end_cycle`: the machine's cycle counter at the end of the run.
    void finish(uint64_t end_cycle);

    const std::string& vcd_path() const { return path_; }
    std::string gtkw_path() const;
    uint64_t bytes() const { return w_.bytes_written(); }
    bool limit_reached() const { return w_.limit_reached(); }
    uint64_t traced_cycles() const { return traced_; }

  private:
    void sample_state(const isa::Machine& m, bool pes);

    std::string path_;
    isa::MachineConfig cfg_;
    const isa::Program& prog_;
    TraceSelection sel_;
    ClockScale clk_;
    VcdWriter w_;
    GtkwSave g_;
    int nregs_ = 16;
    SignalId pc_ = 0, instr_ = 0, phase_ = 0, valid_ = 0, bubble_ = 0, msp_ = 0, active_ = 0,
             reduce_ = 0, any_ = 0, all_ = 0, busy_ = 0, hop_ = 0, up_ = 0;
    std::vector<SignalId> creg_;
    std::vector<detail::PeSignals> pes_;
    detail::DisasmCache disasm_;
    uint32_t last_phase_ = UINT32_MAX;
    uint64_t last_cycle_ = 0, traced_ = 0, first_time_ = 0;
    bool started_ = false, done_ = false;
};

}  // namespace imap::waves
