// The cycle-accurate RTL model: a clocked, signal-level SystemC model of the
// same machine as the TLM model (docs/rtl.md).
//
//   top                 RtlSystem
//   +- clk              sc_clock at the configured period (clock_mhz)
//   +- cp               CpBus: the CP's instruction broadcast bus (pc, instr,
//   |                   opcode, valid, bubble, halted, phase, creg_0..15)
//   +- array            Array: the one clocked SC_METHOD of the model
//   |  +- pe_<i>        PeSignals of a traced PE: r<k>, c, t, m, mem_we /
//   |                   mem_addr / mem_wdata, ext_we / ext_addr / ext_wdata
//   +- ring             Ring (isa::RingPort): link_<i> = the value PE i drives
//   |                   onto the ring in the current hop; busy, hop, up
//   +- maskbus          MaskBus (isa::StatusPort): any, all, reduce (strobe),
//                       active (PEs with M = 1), depth (mask stack)
//
// The instruction semantics are the ISA core's: top.array owns an
// isa::Machine and executes each instruction with Machine::step(), then
// spends exactly the instruction's cycle cost in clock cycles, driving the
// signals cycle by cycle (ring hops hop by hop, xld / xst one byte per
// xfer_per_byte cycles, a taken branch's bubble). Cycle counts are therefore
// those of the cost table, as in the TLM model.
//
// SystemC elaborates once per process: build one RtlSystem (or call run_rtl
// or run_lockstep once) per process.
#pragma once

#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <systemc>
#include <utility>
#include <vector>

#include "imap/isa/machine.hpp"
#include "imap/isa/model_run.hpp"
#include "imap/rtl/config.hpp"
#include "imap/tlm/system.hpp"

namespace imap::rtl {

using ImageInput = isa::ImageVideoPort::Image;
using OutputImages = tlm::OutputImages;

// The common run result (isa/model_run.hpp; wall_s: of sc_start, run_rtl
// only) and the RTL model's own statistics.
struct RtlRunResult : isa::ModelRun {
    uint64_t clock_edges = 0;    // rising edges processed by top.array
    uint64_t signal_writes = 0;  // sc_signal writes made (only on a change)
    int traced_pes = 0;          // PEs with per-PE signals
};

// Called by top.array after every retired instruction (after a fault
// injection, if one is due), in the clocked process.
class RetireHook {
  public:
    virtual ~RetireHook() = default;
    // `index` counts every executed instruction from 0.
    virtual void on_retire(const isa::Machine& m, const isa::TraceEvent& e, uint64_t index) = 0;
};

// The CP's instruction broadcast bus.
class CpBus : public sc_core::sc_module {
  public:
    explicit CpBus(sc_core::sc_module_name name);
    const char* kind() const override { return "imap::rtl::CpBus"; }
    sc_core::sc_signal<uint32_t> pc;                        // PC of the instruction issued
    sc_core::sc_signal<uint64_t> instr;                     // its instruction word
    sc_core::sc_signal<uint8_t> opcode;                     // its decoded opcode (isa::Op)
    sc_core::sc_signal<bool> valid;                         // 1 in the cycle an instruction issues
    sc_core::sc_signal<bool> bubble;                        // 1 in the taken-branch bubble cycles
    sc_core::sc_signal<bool> halted;                        // 1 once the program has halted
    sc_core::sc_signal<uint32_t> phase;                     // current phase id
    sc_core::sc_vector<sc_core::sc_signal<uint32_t>> creg;  // creg_0..creg_15
};

// Signals of one traced PE.
class PeSignals : public sc_core::sc_module {
  public:
    PeSignals(sc_core::sc_module_name name, int index, const std::vector<int>& regs);
    const char* kind() const override { return "imap::rtl::PeSignals"; }
    const int index;
    sc_core::sc_vector<sc_core::sc_signal<uint8_t>> r;  // r<k> for each traced register k
    sc_core::sc_signal<bool> c, t, m;                   // carry, test, mask bit
    sc_core::sc_signal<bool> mem_we;                    // local memory write strobe
    sc_core::sc_signal<uint32_t> mem_addr;
    sc_core::sc_signal<uint8_t> mem_wdata;
    sc_core::sc_signal<bool> ext_we;  // external memory write strobe (xst)
    sc_core::sc_signal<uint32_t> ext_addr;
    sc_core::sc_signal<uint8_t> ext_wdata;
};

// The shift ring: computes rxl / rxr with the ISA's ring_shift and shows the
// transfer hop by hop on link_<i>.
class Ring : public sc_core::sc_module, public isa::RingPort {
  public:
    Ring(sc_core::sc_module_name name, int pes, int first, int count);
    const char* kind() const override { return "imap::rtl::Ring"; }
    void shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, int P, int hops,
               bool towards_higher) override;
    sc_core::sc_vector<sc_core::sc_signal<uint8_t>> link;  // link_<i> for traced PEs
    sc_core::sc_signal<bool> busy;                         // a ring transfer is under way
    sc_core::sc_signal<uint32_t> hop;                      // 1..k during a transfer
    sc_core::sc_signal<bool> up;                           // direction: 1 = rxl (towards higher)

    // Drives hop h (1-based) of the last transfer onto the links.
    void show_hop(uint32_t h, uint64_t& writes);
    void idle(uint64_t& writes);
    uint64_t transfers() const { return transfers_; }
    // The transfer for the cycle tracer: source row, direction, state.
    const uint8_t* source() const { return src_.data(); }
    bool towards_higher() const { return towards_higher_; }
    bool in_transfer() const { return busy_; }
    uint32_t current_hop() const { return hop_; }

  private:
    int P_, first_, count_;
    std::vector<uint8_t> src_, scratch_, shadow_;
    bool towards_higher_ = true;
    uint64_t transfers_ = 0;
    bool busy_ = false;
    uint32_t hop_ = 0;
};

// The mask bus: the status reduction with the ISA's status_reduce.
class MaskBus : public sc_core::sc_module, public isa::StatusPort {
  public:
    explicit MaskBus(sc_core::sc_module_name name);
    const char* kind() const override { return "imap::rtl::MaskBus"; }
    uint32_t reduce(const uint8_t* t, const uint8_t* mask, int P, bool any) override;
    sc_core::sc_signal<bool> any, all;   // OR / AND of T over active PEs (last reduction)
    sc_core::sc_signal<bool> reduce_on;  // 1 in the cycle of a rany / rall
    sc_core::sc_signal<int> active;      // PEs with M = 1
    sc_core::sc_signal<int> depth;       // mask stack depth

    bool pending = false;  // a reduction happened in this instruction
    bool any_v = false, all_v = true;
};

class Array : public sc_core::sc_module {
  public:
    sc_core::sc_in<bool> clk;
    sc_core::sc_vector<PeSignals> pe;  // pe_<i> for the traced PEs

    SC_HAS_PROCESS(Array);
    Array(sc_core::sc_module_name name, isa::Machine& m, const RtlConfig& rcfg, CpBus& cp,
          Ring& ring, MaskBus& maskbus);
    const char* kind() const override { return "imap::rtl::Array"; }

    void set_hook(RetireHook* h) { hook_ = h; }
    // When set, the model stops the simulation after the halt only once this
    // returns true (lockstep: the other model has finished too).
    void set_stop_condition(std::function<bool()> f) { may_stop_ = std::move(f); }

    std::exception_ptr fault() const { return fault_; }
    bool finished() const { return finished_; }
    uint64_t edges() const { return edges_; }
    uint64_t signal_writes() const { return writes_; }
    uint64_t instructions() const { return index_; }

  private:
    void tick();
    void cycle();
    void issue();
    void continue_instruction();
    void end_strobes();
    void apply_injection();
    void update_pe_state();
    void update_cp_regs();
    void strobe_row(bool ext, uint32_t addr);  // all traced PEs, data from memory
    void stop();
    void trace_cycle(uint64_t edge);

    isa::Machine& m_;
    RtlConfig rcfg_;
    CpBus& cp_;
    Ring& ring_;
    MaskBus& mb_;
    int first_ = 0, count_ = 0;
    std::vector<int> regs_;
    std::vector<uint8_t> shadow_;  // traced regs | C | T | M, count_ bytes each
    std::array<uint32_t, isa::kCpRegs> creg_shadow_{};
    RetireHook* hook_ = nullptr;
    std::function<bool()> may_stop_;

    // The instruction in flight.
    isa::Word w_{};
    isa::CostClass cls_ = isa::CostClass::Cp;
    uint64_t cost_ = 0, k_ = 0;  // its cycles, and the current one (0 = issue)
    int64_t xloc_ = 0, xext_ = 0, xlen_ = 0;
    bool valid_ = false, bubble_ = false, mem_strobe_ = false, ext_strobe_ = false, reduce_ = false;
    // For the cycle tracer (rcfg_.cycle_tracer): the instruction in flight and
    // this cycle's memory strobe.
    uint32_t pc_ = 0;
    uint64_t word_ = 0;
    bool traced_edge_ = false, pe_state_ = false;
    uint8_t tmem_ = 0;  // waves::CycleInfo::Mem
    uint32_t tmem_addr_ = 0;

    uint64_t edges_ = 0, index_ = 0, writes_ = 0;
    bool done_ = false, stopped_ = false, finished_ = false;
    std::exception_ptr fault_;
};

class RtlSystem : private tlm::detail::ElaborationGuard, public sc_core::sc_module {
  private:
    std::shared_ptr<isa::Machine> m_;
    isa::ImageVideoPort video_;

  public:
    // Builds the hierarchy and loads the program. Throws isa::ConfigError /
    // isa::LoadError, and std::logic_error when SystemC is past elaboration.
    RtlSystem(sc_core::sc_module_name name, const isa::MachineConfig& cfg, const isa::Program& prog,
              const RtlConfig& rcfg = {});
    const char* kind() const override { return "imap::rtl::RtlSystem"; }

    // Host inputs, before sc_start.
    void set_param(int i, uint32_t v) { m_->set_param(i, v); }
    void set_input(int port, ImageInput img) { video_.input[port] = std::move(img); }
    void make_output(int port, int width, int height) { video_.make_output(port, width, height); }
    const ImageInput& output(int port) const { return video_.output[port]; }
    OutputImages outputs() const;

    isa::Machine& machine() { return *m_; }
    const isa::Machine& machine() const { return *m_; }
    std::shared_ptr<const isa::Machine> machine_ptr() const { return m_; }

    // After sc_start: rethrows the exception that stopped the model.
    void rethrow_if_faulted() const;
    RtlRunResult result() const;

    sc_core::sc_clock clk;
    CpBus cp;
    Ring ring;
    MaskBus maskbus;
    Array array;
};

namespace detail {
// Marks the process as having run its one SystemC simulation (run_rtl,
// run_lockstep); throws std::logic_error naming `who` on a second call.
void claim_process(const char* who);
}  // namespace detail

// Elaborates an RtlSystem "top", sets the params and images (two output
// images of out_w x out_h), runs sc_start to completion and returns the
// result; `out` receives the output images. Faults of the machine come out
// as the original exception (isa::Fault). Once per process (std::logic_error
// on a second call, or after run_lockstep).
RtlRunResult run_rtl(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const RtlConfig& rcfg = {});

}  // namespace imap::rtl
