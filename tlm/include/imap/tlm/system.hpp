// The top level of the TLM model and the one-call runner.
//
//   top                TlmSystem
//   +- cp              Cp: the SC_THREAD, owns the isa::Machine
//   +- array           Array
//   |  +- pe_0..pe_<P-1>   Pe (target socket: PE-local memory, no DMI)
//   |  +- mem          ArrayMem (address-major memory block, grants DMI)
//   +- ring            Ring (isa::RingPort: rxl / rxr)
//   +- maskbus         MaskBus (isa::StatusPort: rany / rall)
//   +- video           VideoSource (host images; target of top.cp.video)
//
// SystemC elaborates once per process: build one TlmSystem (or call run_tlm
// once) per process.
#pragma once

#include <cstdint>
#include <memory>
#include <systemc>
#include <utility>
#include <vector>

#include "imap/isa/machine.hpp"
#include "imap/isa/model_run.hpp"
#include "imap/tlm/components.hpp"
#include "imap/tlm/config.hpp"
#include "imap/tlm/cp.hpp"

namespace imap::tlm {

using ImageInput = isa::ImageVideoPort::Image;
struct OutputImages {
    ImageInput image[2];  // output ports 0 and 1
};

// The common run result (isa/model_run.hpp; wall_s: of sc_start, run_tlm
// only) and the TLM model's own statistics.
struct TlmRunResult : isa::ModelRun {
    RingStats ring;
    MaskBusStats maskbus;
    VideoStats video;
    uint64_t syncs = 0;      // quantum keeper synchronisations (quantum ends + video lines)
    uint64_t chunks = 0;     // Machine::run calls made by the CP thread
    double quantum_ns = 0;   // the global quantum used
    bool video_dmi = false;  // the CP moved video rows through the array's DMI pointer
};

namespace detail {
// Refuses (std::logic_error) to build a model once SystemC's elaboration is
// over; a base of TlmSystem so that it runs before any sc_module is made.
struct ElaborationGuard {
    ElaborationGuard();
};
}  // namespace detail

class TlmSystem : private detail::ElaborationGuard, public sc_core::sc_module {
  public:
    // Builds the hierarchy for cfg.pes PEs and loads the program. Throws
    // isa::ConfigError / isa::LoadError, and std::logic_error when SystemC
    // is past elaboration in this process.
    TlmSystem(sc_core::sc_module_name name, const isa::MachineConfig& cfg, const isa::Program& prog,
              const TlmConfig& tcfg = {});
    const char* kind() const override { return "imap::tlm::TlmSystem"; }

    // Host inputs, before sc_start.
    void set_param(int i, uint32_t v) { cp.machine().set_param(i, v); }
    void set_input(int port, ImageInput img) {
        cp.set_input_width(port, img.width);
        video.set_input(port, std::move(img));
    }
    void make_output(int port, int width, int height) { video.make_output(port, width, height); }
    const ImageInput& input(int port) const { return video.input(port); }
    const ImageInput& output(int port) const { return video.output(port); }
    OutputImages outputs() const;

    isa::Machine& machine() { return cp.machine(); }
    const isa::Machine& machine() const { return cp.machine(); }

    // After sc_start: rethrows the exception that stopped the CP (the
    // isa::Fault with its message intact), if any.
    void rethrow_if_faulted() const;
    // After sc_start: the accounting (wall_s = 0).
    TlmRunResult result() const;

    Cp cp;
    Array array;
    Ring ring;
    MaskBus maskbus;
    VideoSource video;
};

// Elaborates a TlmSystem "top", sets the params and images (two output
// images of out_w x out_h), runs sc_start to completion and returns the
// result; `out` receives the output images. Faults of the machine come out
// as the original exception (isa::Fault). May be called once per process
// (SystemC cannot elaborate twice): a second call throws std::logic_error.
TlmRunResult run_tlm(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const TlmConfig& tcfg = {});

}  // namespace imap::tlm
