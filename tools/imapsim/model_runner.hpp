// Running the firmware on a chosen model and reporting it; shared by the
// subcommands that run the machine (run, and later stream, sweep, bench).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_common.hpp"
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
    std::vector<std::string> sets;
};
void add_machine_flags(CLI::App* app, MachineFlags& f);
imap::isa::MachineConfig parse_machine_flags(const MachineFlags& f);

std::string model_names();                  // "tlm, core" ...
void check_model_name(const std::string&);  // UserError if unknown

struct ModelRun {
    std::string model;
    imap::firmware::FramePlan plan;
    size_t program_words = 0;
    imap::firmware::FrameResult result;
};

// Plans, assembles and runs the firmware on `model`. Plan errors (does not
// fit) are UserError (exit 2); machine faults are UserError with kExitFault.
ModelRun run_model(const std::string& model, const imap::golden::Params& p,
                   const imap::golden::Roi& roi, const imap::golden::ImageView& left,
                   const imap::golden::ImageView& right, const imap::isa::MachineConfig& cfg);

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

nlohmann::json run_report(const ModelRun& run, const Comparison& cmp, const imap::golden::Params& p,
                          const imap::golden::Roi& roi, const imap::isa::MachineConfig& cfg,
                          double golden_ms);

}  // namespace imapsim
