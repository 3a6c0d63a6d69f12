// Shared pieces of the imapsim subcommands: algorithm flags (SPEC A.1),
// exit codes and error reporting.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "imap/engine/error.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"

namespace imapsim {

// Exit codes (docs/errors.md) and the user-facing error: the engine's.
using ExitCode = imap::engine::Exit;
using imap::engine::kExitFault;
using imap::engine::kExitInput;
using imap::engine::kExitInternal;
using imap::engine::kExitInterrupted;
using imap::engine::kExitItemErrors;
using imap::engine::kExitMismatch;
using imap::engine::kExitOk;
// Printed as "imapsim: error: <what>" and mapped to an exit code.
using UserError = imap::engine::Error;

// Raw text of the algorithm flags (the engine's AlgoSettings): parsed after
// CLI11 so that errors name the flag, the value and the allowed range.
using AlgoFlags = imap::engine::AlgoSettings;

// Adds --preset --D --km --kb --gb --Wo --Wd --mode --seed-col --seed-disp
// --vote --roi --frame --fill and the SPEC A.9 options --dissim --ad-max --kc
// --census --agg-rx --agg-ry to a subcommand, with defaults shown in --help.
void add_algo_flags(CLI::App* app, AlgoFlags& f);

// Converts the flags to golden parameters (Error naming the flag); the ROI
// separately: `has_roi` false means "whole image".
inline imap::golden::Params parse_algo_flags(const AlgoFlags& f, imap::golden::Roi* roi,
                                             bool* has_roi) {
    return imap::engine::algo_params(f, roi, has_roi);
}

// The algorithm and machine parameters' JSON, flag values and output
// checks: the engine library's (one form for every report and command).
using imap::engine::algo_params_json;
using imap::engine::check_output_dir;
using imap::engine::check_output_file;
using imap::engine::check_same_size;
using imap::engine::create_output_dir;
using imap::engine::faster_assumptions_text;
using imap::engine::file_in_folder;
using imap::engine::folder_of;
using imap::engine::lower_extension;
using imap::engine::machine_param_info_json;
using imap::engine::machine_params_json;
using imap::engine::param_value_json;
using imap::engine::parse_int_flag;
using imap::engine::parse_real_flag;
using imap::engine::parse_size_flag;
using imap::engine::validate_frame;

// After CLI11 refused arguments it did not expect: "unknown command 'swep'
// (did you mean sweep?)" or "unknown option --out-colour (did you mean
// --out-color?)", from the command line and the registered names; "" when
// no argument is unknown (the parse error says more).
std::string explain_unknown_arguments(CLI::App& app, int argc, char** argv);

// Each subcommand registers itself on the app and returns a runner that is
// called if the subcommand was selected. The runner returns the exit code.
using Runner = std::function<int()>;
struct Subcommand {
    CLI::App* app = nullptr;
    Runner run;
};

Subcommand register_golden(CLI::App& app);
Subcommand register_eval(CLI::App& app);
Subcommand register_synth(CLI::App& app);
Subcommand register_run(CLI::App& app);
Subcommand register_asm(CLI::App& app);
Subcommand register_disasm(CLI::App& app);
Subcommand register_exec(CLI::App& app);
Subcommand register_regress(CLI::App& app);
Subcommand register_bench(CLI::App& app);
Subcommand register_stream(CLI::App& app);
Subcommand register_sweep(CLI::App& app);
Subcommand register_table1(CLI::App& app);
Subcommand register_run_task(CLI::App& app);
Subcommand register_rtl_cache(CLI::App& app);

}  // namespace imapsim
