// The RTL model: the register-transfer design of the array
// (rtl_model/hdl/*.sv, SystemVerilog) verilated into a SystemC module and
// run by the testbench (rtl_model/verif/): clock, reset, the cost table and
// run-time configuration as strap inputs, the program and param block
// through the host port, the images through the video line port
// (docs/rtl.md).
//
//   top              the testbench (imap::rtl::detail::Bench)
//   +- dut           the design, one verilated configuration
//      +- imap_tb          the testbench top (rtl_model/verif/imap_tb.sv)
//         +- u_chip        the chip, imap_top (rtl_model/hdl/)
//         |  +- u_cp       control processor: fetch, decode, execute sequencer
//         |  |  +- u_mon   retire monitor (verif, bound in): retire record, fault
//         |  +- u_array    P x u_pe, the ring links, the mask bus
//         |  +- u_perf     performance counters
//         +- u_board       board model: external memory and transfer data path, video port
//
// SystemC elaborates once per process: call run_rtl or run_lockstep once.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/machine.hpp"
#include "imap/isa/model_run.hpp"
#include "imap/rtl/config.hpp"
#include "imap/tlm/system.hpp"

namespace imap::rtl {

using ImageInput = isa::ImageVideoPort::Image;
using OutputImages = tlm::OutputImages;

// The architectural state at the end of a run, read from the design
// through the testbench's backdoor (the same layouts as isa::Machine).
struct RtlState {
    int pes = 0, pe_regs = 0;
    std::vector<uint8_t> lanes;  // register r of PE p at r * pes + p, then C, T, M
    std::vector<uint8_t> mem;    // address-major: (pe, a) at a * pes + pe
    std::vector<uint8_t> ext;
    std::array<uint32_t, 16> creg{};
    std::array<uint32_t, 256> param{};
    int mask_depth = 0, call_depth = 0;
    uint32_t phase = 0;
    uint8_t reg(int pe, int r) const {
        return lanes[static_cast<size_t>(r) * static_cast<size_t>(pes) + static_cast<size_t>(pe)];
    }
    uint8_t flag(int pe, int which) const {  // 0 C, 1 T, 2 M
        return reg(pe, pe_regs + which);
    }
};

// The common run result (isa/model_run.hpp: cycles = the design's machine
// cycle counter, wall_s = the run without the program load, stats = the
// design's performance counters; `machine` is not set: the design's final
// state is `state`) and the RTL's own figures.
struct RtlRunResult : isa::ModelRun {
    uint64_t clocks = 0;        // clock periods of the run (machine cycles + zero-cost slots)
    std::string configuration;  // "p256_m1024_x65536 (fast)"
    bool waves_written = false;
    bool waves_empty = false;    // the window started after the run's end: one sample
    bool waves_limited = false;  // the trace stopped at RtlWaves::limit_bytes
    std::shared_ptr<const RtlState> state;
};

namespace detail {
// Marks the process as having run its one SystemC simulation (run_rtl,
// run_lockstep, the random suite); throws std::logic_error naming `who` on
// a second call.
void claim_process(const char* who);
}  // namespace detail

// An assertion of the design failed (docs/rtl.md, "Assertions"): the run
// stopped at that edge. An isa::Fault (PC, PE, cycle of the failing edge;
// imapsim: "the modeled machine faulted", exit code 3) whose message is the
// lockstep's report of it ("RTL assertion a_... failed at instruction N
// (cycle C, pc P: ...) in PE p: what it checks").
class AssertionFailure : public isa::Fault {
  public:
    AssertionFailure(const std::string& what, std::string assertion, uint64_t instruction,
                     uint32_t pc, int64_t pe, uint64_t cycle)
        : isa::Fault(what, pc, pe, kNone, cycle),
          assertion_(std::move(assertion)),
          instruction_(instruction) {}
    const std::string& assertion() const { return assertion_; }
    uint64_t instruction() const { return instruction_; }

  private:
    std::string assertion_;
    uint64_t instruction_;
};

// Elaborates the testbench with the configuration of cfg (check_runnable:
// isa::ConfigError naming what to build when it is not in this build), sets
// the params and images (two output images of out_w x out_h), runs the
// program to its halt and returns the result; `out` receives the output
// images. A fault of the design comes out as an isa::Fault (PC, PE,
// address, cycle, message), a failing assertion of the design as an
// AssertionFailure (after the waves asked for, which end there, are
// written). Once per process.
RtlRunResult run_rtl(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const RtlConfig& rcfg = {});

}  // namespace imap::rtl
