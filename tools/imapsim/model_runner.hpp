// The flags of the subcommands that run the machine (run, exec, stream,
// sweep, bench): machine, RTL / lockstep and waves, and the text summary of
// a model run. The runs are the engine's (imap/engine/models.hpp).
#pragma once

#include <string>

#include "cli_common.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/model_run.hpp"
#include "imap/engine/models.hpp"
#include "imap/isa/config.hpp"

namespace imapsim {

#ifdef IMAPSIM_HAVE_TLM
inline constexpr const char* kDefaultModel = "tlm";
#else
inline constexpr const char* kDefaultModel = "core";
#endif

// Machine flags: --pes --clock-mhz --mem-bytes --ext-bytes --camera and
// --set NAME=VALUE for any machine or cost parameter (docs/isa.md lists them).
using MachineFlags = imap::engine::MachineSettings;
void add_machine_flags(CLI::App* app, MachineFlags& f);
inline imap::isa::MachineConfig parse_machine_flags(const MachineFlags& f) {
    return imap::engine::machine_config(f);
}
using imap::engine::camera_pixel_mhz;

// --model rtl / lockstep options (docs/rtl.md), handed to run_model.
using RtlFlags = imap::engine::RtlOptions;
void add_rtl_flags(CLI::App* app, RtlFlags& f);
// --rtl-cache DIR (docs/rtl.md, "Any configuration on demand"); applied for
// this process and the ones it starts.
void add_rtl_cache_flag(CLI::App* app, std::string& dir);
void apply_rtl_cache_flag(const std::string& dir);

// Waves (docs/waves.md): --vcd FILE (off when empty), --trace-pes,
// --trace-window, --trace-signals, --trace-limit-mb.
using WaveFlags = imap::engine::WaveOptions;
void add_wave_flags(CLI::App* app, WaveFlags& f);

using imap::engine::area_json;
using imap::engine::check_model_name;
using imap::engine::check_wave_outputs;
using imap::engine::compare_maps;
using imap::engine::Comparison;
using imap::engine::divergence_report;
using imap::engine::fmax_json;
using imap::engine::model_names;
using imap::engine::ModelRun;
using imap::engine::print_rtl_area;
using imap::engine::run_model;
using imap::engine::run_report;
using imap::engine::WaveSession;

// The run's summary: firmware, bit-exactness, cycles and phases against the
// machine bound, re-layout, utilisation, energy, [A+] assumptions, wall time.
void print_run_summary(const ModelRun& run, const Comparison& cmp,
                       const imap::isa::MachineConfig& cfg, double golden_ms);

}  // namespace imapsim
