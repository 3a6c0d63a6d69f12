// Running the DP firmware on a model of the machine (core, tlm, rtl,
// lockstep: whichever this build has) and the waves of a run. Library
// imap_engine_models: the instruction-set core always, the SystemC TLM
// model, the RTL co-simulation and the wave writer when they are built.
// Errors are engine::Error (exit 2; machine faults exit 3).
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "imap/engine/model_run.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"

namespace imap::engine {

// The models this build runs, as "tlm (...), rtl (...), ..., core (...)".
std::string model_names();
// Error (exit 2) naming model_names() when `m` is not one of them.
void check_model_name(const std::string& m);
// The RTL design's synthesized area (cells per PE and per CP), one line on
// stdout, and its Fmax from place and route against clock_mhz, another
// (docs/rtl.md, "Place and route (iCE40)"); nothing when the build has no
// RTL.
void print_rtl_area(double clock_mhz);
// Those lines (none without RTL).
std::vector<std::string> rtl_area_lines(double clock_mhz);
// The synthesized area of configuration `cfg` as the run report's "area"
// object; null without RTL or synthesis figures.
nlohmann::json area_json(const isa::MachineConfig& cfg);
// The design's Fmax against cfg.clock_mhz as the run report's
// "design_fmax" object {mhz, technology, configuration, clock_mhz,
// clock_above, text}; null without RTL or place-and-route figures.
nlohmann::json fmax_json(const isa::MachineConfig& cfg);

// --model rtl / lockstep options (docs/rtl.md).
struct RtlOptions {
    std::string inject_fault;  // INSTR:PE:REG:MASK
    std::string mutant;        // planted bug (mutation-check configuration)
    std::string lockstep_waves = "rtl_divergence.fst";  // waves before a divergence, "" none
    // the RTL cache's folder for a configuration not built in ("" = the
    // default, imap/rtl/cache.hpp; "off" = refuse it)
    std::string cache_dir;
};

// Waves (docs/waves.md): the file (off when empty), the PEs, the window,
// the signal groups and the size limit.
struct WaveOptions {
    std::string vcd, pes, window, signals;
    double limit_mb = 200;
};
// Checks, before the run, that the VCD and its .gtkw view can be written
// and that `model` writes the format the name asks for (an .fst name on a
// model that writes VCD is refused); Error naming the file otherwise;
// nothing when no file is asked for.
void check_wave_outputs(const WaveOptions& w, const std::string& model);

// The waves of one run on the instruction-set machine: builds the tracer
// (nothing without a file), and after the run finishes the files and
// prints where they went, with a warning when the trace holds nothing
// (window past the end) or the .gtkw could not be written (the VCD is
// kept). Error for bad options.
class WaveSession {
  public:
    WaveSession(const WaveOptions& w, const isa::MachineConfig& cfg, const isa::Program& prog);
    ~WaveSession();
    WaveSession(const WaveSession&) = delete;
    WaveSession& operator=(const WaveSession&) = delete;
    bool active() const;
    isa::Observer* observer();  // ISA-level tracer (core, tlm), or nullptr
    void finish(uint64_t end_cycle);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Plans, assembles and runs the firmware on `model`, and computes the run's
// energy. Plan errors (does not fit) are Error (exit 2); machine faults are
// Error with kExitFault. With `waves` naming a file, the run is traced
// (core, tlm per instruction; rtl the design's signals). The rtl and
// lockstep models print their own lines (configuration, agreement) on stdout.
ModelRun run_model(const std::string& model, const golden::Params& p, const golden::Roi& roi,
                   const golden::ImageView& left, const golden::ImageView& right,
                   const isa::MachineConfig& cfg, const WaveOptions* waves = nullptr,
                   const RtlOptions* rtl = nullptr);

}  // namespace imap::engine
