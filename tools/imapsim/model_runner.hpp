// Running the firmware on a chosen model and reporting it; shared by the
// subcommands that run the machine (run, and later stream, sweep, bench).
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "imap/firmware/bounds.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/isa/config.hpp"

namespace imapsim {

#ifdef IMAPSIM_HAVE_TLM
inline constexpr const char* kDefaultModel = "tlm";
#else
inline constexpr const char* kDefaultModel = "core";
#endif

// Machine flags: --pes --clock-mhz --mem-bytes --ext-bytes and --set NAME=VALUE
// for any machine or cost parameter (docs/isa.md lists them).
struct MachineFlags {
    std::string pes, clock_mhz, mem_bytes, ext_bytes;
    std::string camera;  // ideal | ntsc | pixel-clock:MHZ (camera_pixel_mhz)
    std::vector<std::string> sets;
};
void add_machine_flags(CLI::App* app, MachineFlags& f);
imap::isa::MachineConfig parse_machine_flags(const MachineFlags& f);
// --camera's value (ideal | ntsc | pixel-clock:MHZ) as camera_pixel_mhz;
// UserError naming the allowed values.
std::string camera_pixel_mhz(const std::string& v);

// --model rtl / lockstep options (docs/rtl.md). set_rtl_flags() hands them
// to run_model (kept out of its signature).
struct RtlFlags {
    std::string inject_fault;  // INSTR:PE:REG:MASK
    std::string mutant;        // planted bug (mutation-check configuration)
    std::string lockstep_waves = "rtl_divergence.fst";  // waves before a divergence, "" none
};
void add_rtl_flags(CLI::App* app, RtlFlags& f);
void set_rtl_flags(const RtlFlags& f);

std::string model_names();  // "tlm, core" ...
// The RTL design's synthesized area (cells per PE and per CP), one line;
// nothing when the binary has no RTL.
void print_rtl_area();
void check_model_name(const std::string&);  // UserError if unknown

struct ModelRun {
    std::string model;
    imap::firmware::FramePlan plan;
    size_t program_words = 0;
    imap::isa::Program program;  // the program that ran
    std::string source;          // its generated source (constants, plan macros, .include of dp.s)
    imap::firmware::FrameResult result;
    // The machine's bound of each phase (docs/firmware.md, section 11).
    imap::firmware::FrameBounds bounds;
    // What the model itself reports, merged into the run report: "rtl"
    // (configuration, clocks), "lockstep" (instructions retired and
    // compared, both models' cycles, the first divergence).
    nlohmann::json model_info = nlohmann::json::object();
    // Where the energy model's event counts come from: "isa" (the
    // instruction-set executor that ran: core, tlm), or for rtl / lockstep
    // the instruction-set model's counts of the same program (docs/energy.md 5).
    std::string energy_source = "isa";
    // A lockstep divergence: its one-line message (empty when none). The
    // run stopped there, so `result` holds no map.
    std::string divergence;
};

// Waves (docs/waves.md): --vcd FILE (off when empty), --trace-pes,
// --trace-window, --trace-signals, --trace-limit-mb.
struct WaveFlags {
    std::string vcd, pes, window, signals;
    double limit_mb = 200;
};
void add_wave_flags(CLI::App* app, WaveFlags& f);
// Checks, before the run, that the VCD and its .gtkw view can be written
// and that `model` writes the format the name asks for (an .fst name on a
// model that writes VCD is refused); UserError naming the file otherwise;
// nothing when --vcd is not given.
void check_wave_outputs(const WaveFlags& f, const std::string& model);

// The waves of one run: builds the tracer for `f` (nothing without --vcd),
// and after the run finishes the files and prints where they went, with a
// warning when the trace holds nothing (window past the end) or the .gtkw
// could not be written (the VCD is kept). UserError for bad options.
class WaveSession {
  public:
    WaveSession(const WaveFlags& f, const imap::isa::MachineConfig& cfg,
                const imap::isa::Program& prog);
    ~WaveSession();
    WaveSession(const WaveSession&) = delete;
    WaveSession& operator=(const WaveSession&) = delete;
    bool active() const;
    imap::isa::Observer* observer();  // ISA-level tracer (core, tlm), or nullptr
    void finish(uint64_t end_cycle);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Plans, assembles and runs the firmware on `model`. Plan errors (does not
// fit) are UserError (exit 2); machine faults are UserError with kExitFault.
// With `waves` and a non-empty waves->vcd, the run is traced (core, tlm).
ModelRun run_model(const std::string& model, const imap::golden::Params& p,
                   const imap::golden::Roi& roi, const imap::golden::ImageView& left,
                   const imap::golden::ImageView& right, const imap::isa::MachineConfig& cfg,
                   const WaveFlags* waves = nullptr);

struct Comparison {
    bool equal = true;
    size_t differing = 0;
    int first_x = -1, first_y = -1;
    int model_value = 0, golden_value = 0;
};
Comparison compare_maps(const imap::golden::DisparityMap& got,
                        const imap::golden::DisparityMap& want);

void print_run_summary(const ModelRun& run, const Comparison& cmp,
                       const imap::isa::MachineConfig& cfg, double golden_ms);

// The report of a lockstep run that diverged: the model's fields (the
// lockstep's, with the divergence) and the parameters; no map, no cycles.
nlohmann::json divergence_report(const ModelRun& run, const imap::golden::Params& p,
                                 const imap::golden::Roi& roi, const imap::isa::MachineConfig& cfg);

nlohmann::json run_report(const ModelRun& run, const Comparison& cmp, const imap::golden::Params& p,
                          const imap::golden::Roi& roi, const imap::isa::MachineConfig& cfg,
                          double golden_ms);

}  // namespace imapsim
