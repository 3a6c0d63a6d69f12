// The lockstep checker: compares the RTL's architectural state with a
// reference instruction-set model at every retired instruction. The CP state
// comes from the design's retire record; the PE state is read from the
// design's own state elements (Backdoor) right after the retire edge. Per
// instruction it compares what the instruction can have written (the
// register its rd field names in the design's register file, the C, T and M
// flags, the memory rows of st / stx / vin / xld / xst); every
// `reg_every` instructions all registers and flags, every `mem_every` the
// whole local memory (a write to a place the instruction does not name),
// and at the end the complete state (docs/rtl.md, "Lockstep").
//
// References: the TLM model (TlmReference: its CP thread waits in an
// observer after each instruction until the RTL has retired the same one)
// or the instruction-set model stepped directly (StepReference: the random
// suite, many programs in one process).
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <systemc>
#include <vector>

#include "bench.hpp"
#include "imap/isa/machine.hpp"
#include "imap/rtl/lockstep.hpp"
#include "imap/tlm/system.hpp"

namespace imap::rtl::detail {

class Reference {
  public:
    virtual ~Reference() = default;
    // True once the reference has executed instruction `index` (its state
    // is the one after it) or has stopped before it (fault, halt).
    virtual bool ready(uint64_t index) = 0;
    // It executed `index` (ready and not stopped before it).
    virtual bool executed(uint64_t index) const = 0;
    virtual const isa::Machine& machine() const = 0;
    virtual const isa::TraceEvent& event() const = 0;  // of the last executed instruction
    virtual const isa::Fault* fault() const = 0;       // when it faulted
    virtual std::string error() const { return ""; }   // another exception
    // Let the reference go on past `index`.
    virtual void release(uint64_t index) = 0;
    virtual const sc_core::sc_event* wake() { return nullptr; }
    virtual const char* name() const = 0;
};

// The instruction-set model, stepped on demand.
class StepReference final : public Reference {
  public:
    StepReference(const isa::MachineConfig& cfg, const isa::Program& prog,
                  const std::vector<std::pair<int, uint32_t>>& params, const Image& left,
                  const Image& right, int out_w, int out_h);
    bool ready(uint64_t index) override;
    bool executed(uint64_t index) const override { return count_ > index; }
    const isa::Machine& machine() const override { return m_; }
    const isa::TraceEvent& event() const override { return ev_; }
    const isa::Fault* fault() const override { return fault_ ? &*fault_ : nullptr; }
    std::string error() const override { return error_; }
    void release(uint64_t) override {}
    const char* name() const override { return "ISA"; }
    isa::ImageVideoPort& video() { return video_; }

  private:
    isa::Machine m_;
    isa::ImageVideoPort video_;
    isa::TraceEvent ev_{};
    uint64_t count_ = 0;
    std::optional<isa::Fault> fault_;
    std::string error_;
};

// The TLM model (hosted CP), met at every instruction.
class TlmReference final : public sc_core::sc_module, public Reference, private isa::Observer {
  public:
    SC_HAS_PROCESS(TlmReference);
    TlmReference(sc_core::sc_module_name n, tlm::TlmSystem& sys);
    bool ready(uint64_t index) override;
    bool executed(uint64_t index) const override { return count_ > index; }
    const isa::Machine& machine() const override { return sys_.machine(); }
    const isa::TraceEvent& event() const override { return ev_; }
    const isa::Fault* fault() const override { return fault_ ? &*fault_ : nullptr; }
    std::string error() const override { return error_; }
    void release(uint64_t index) override;
    const sc_core::sc_event* wake() override { return &reached_; }
    const char* name() const override { return "TLM"; }
    bool finished() const { return finished_; }

  private:
    void on_instruction(const isa::Machine& m, const isa::TraceEvent& e) override;
    void starter();
    void on_done();
    tlm::TlmSystem& sys_;
    isa::TraceEvent ev_{};
    uint64_t count_ = 0, released_ = 0;
    bool finished_ = false;
    std::optional<isa::Fault> fault_;
    std::string error_;
    sc_core::sc_event reached_, release_ev_;
};

class Checker final : public Listener {
  public:
    Checker(Reference& ref, const isa::Program& prog, int pes);
    Verdict on_retire(const RetireRecord& r, const Shadow& s, const Backdoor& bd,
                      const Touched& t) override;
    Verdict on_fault(const FaultRecord& f, const Shadow& s) override;
    const sc_core::sc_event* wake_event() override { return ref_.wake(); }

    // After the run: the cycle count, the complete final state (the shadow,
    // and the design's true state through the backdoor) and the faults.
    void final_check(const Job& job, const Shadow& s, const Backdoor& bd);

    // Full compares of all registers and flags / the whole local memory every
    // this many instructions (0: automatic, auto_intervals(); 1: every
    // instruction). Set before the run.
    uint64_t reg_every = 0, mem_every = 0;
    // About 256 bytes of extra comparison per instruction on average: all
    // (pe_regs + 3) lanes of P PEs every ceil(P * (pe_regs + 3) / 256)
    // instructions, the P * mem_bytes local memory every
    // ceil(P * mem_bytes / 256).
    static uint64_t auto_reg_every(int pes, int pe_regs);
    static uint64_t auto_mem_every(int pes, uint32_t mem_bytes);
    uint64_t full_reg_compares = 0, full_mem_compares = 0;

    bool diverged = false;
    Divergence div;
    uint64_t compared = 0;
    uint64_t fault_index = UINT64_MAX;  // instruction index of the RTL's fault
    // Called after each successfully compared instruction (coverage).
    std::function<void(const RetireRecord&, const isa::Machine&)> on_compared;
    // Called after each compared instruction, before the RTL goes on
    // (fault injection through the backdoor).
    std::function<void(const RetireRecord&)> after_compare;

  private:
    Verdict diverge(const RetireRecord* r, std::string what, int64_t pe, int64_t addr,
                    uint64_t refv, uint64_t rtlv, std::string detail = "");
    bool compare_state(const RetireRecord& r, const Shadow& s, const Backdoor& bd,
                       const Touched& t);
    // lane row `reg` of the design (0..NR-1 a register, NR C, NR+1 T, NR+2 M)
    // against the reference; false after a divergence
    bool compare_row(const RetireRecord& r, const Backdoor& bd, int NR, int reg,
                     const std::string& detail);
    std::vector<uint8_t> row_, flags_;
    Reference& ref_;
    const isa::Program& prog_;
    int prev_active_ = -1;
};

// Builds the fault the RTL reported as an isa::Fault (message in the
// instruction-set model's style).
isa::Fault to_fault(const FaultRecord& f, const isa::Program& prog, const isa::MachineConfig& cfg);

}  // namespace imap::rtl::detail
