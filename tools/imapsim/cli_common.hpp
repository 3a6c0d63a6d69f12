// Shared pieces of the imapsim subcommands: algorithm flags (SPEC A.1),
// exit codes and error reporting.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>

#include "imap/engine/params_json.hpp"
#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"

namespace imapsim {

// Exit codes (docs/errors.md).
enum ExitCode : int {
    kExitOk = 0,
    kExitMismatch = 1,       // ran, but the model's output differs from the golden
    kExitInput = 2,          // bad flags or input files; nothing written
    kExitFault = 3,          // the modeled machine faulted (bad address, runaway, ...)
    kExitInternal = 4,       // unexpected internal error
    kExitItemErrors = 5,     // stream / sweep ran to the end, but some frames or points
                             // failed (bad frame, machine fault); each is in the log
    kExitInterrupted = 130,  // stopped by SIGINT / SIGTERM; partial results written
};

// A user-facing error: printed as "imapsim: error: <what>" and mapped to an exit code.
class UserError : public std::runtime_error {
  public:
    explicit UserError(const std::string& what, int code = kExitInput)
        : std::runtime_error(what), code_(code) {}
    int code() const { return code_; }

  private:
    int code_;
};

// Raw text of the algorithm flags, parsed after CLI11 so that errors name
// the flag, the value and the allowed range. `preset` (paper or quality,
// empty = paper) gives the starting values; every flag given overrides its
// preset value (an empty string = not given; mode, seed-col, seed-disp,
// vote and frame count as given when on the command line (`given`) or
// different from their paper default).
struct AlgoFlags {
    std::string preset;
    std::string D, km, kb, gb, Wo, Wd;
    std::string dissim, ad_max, kc, census, agg_rx, agg_ry;  // SPEC A.9 options
    std::string mode = "bidir";
    std::string seed_col = "balanced";
    std::string seed_disp = "free";
    std::string vote = "on";
    std::string roi;  // empty = whole image
    std::string frame = "cyc";
    bool fill = false;
    std::set<std::string> given;  // flags seen on the command line (filled by CLI11)
};

// Adds --preset --D --km --kb --gb --Wo --Wd --mode --seed-col --seed-disp
// --vote --roi --frame --fill and the SPEC A.9 options --dissim --ad-max --kc
// --census --agg-rx --agg-ry to a subcommand, with defaults shown in --help.
void add_algo_flags(CLI::App* app, AlgoFlags& f);

// Converts the flags to golden parameters (throws UserError naming the flag).
// The ROI is returned separately: `has_roi` false means "whole image".
imap::golden::Params parse_algo_flags(const AlgoFlags& f, imap::golden::Roi* roi, bool* has_roi);

// The algorithm parameters as a JSON object (reports).
nlohmann::json algo_params_json(const imap::golden::Params& p);

// The machine parameters' JSON (engine library, one form for every report).
using imap::engine::machine_param_info_json;
using imap::engine::machine_params_json;
using imap::engine::param_value_json;
// The [A+] parameters as "name value unit" items joined by ", ".
std::string faster_assumptions_text(const imap::isa::MachineConfig& cfg);

// Strict integer parse of a flag value; error names the flag and the range.
long long parse_int_flag(const std::string& flag, const std::string& text, long long lo,
                         long long hi);

// Strict WxH parse of a size flag (one 'x', both parts integers in lo..hi);
// the error names the flag and the range.
void parse_size_flag(const std::string& flag, const std::string& text, int lo, int hi, int* w,
                     int* h);

// Strict real-number parse of a flag value (finite, lo < v <= hi when
// lo_open, else lo <= v <= hi); the error names the flag and the range.
double parse_real_flag(const std::string& flag, const std::string& text, double lo, double hi,
                       bool lo_open);

// Checks, before the work, that `path` (given with `flag`) can be written
// later: its folder exists, files can be created in it (permissions,
// read-only file system), and it is not a folder; with `image`, OpenCV can
// write its extension. UserError (exit 2) otherwise; nothing when empty.
void check_output_file(const std::string& flag, const std::string& path, bool image);

// A stereo pair's two images must have one size: UserError naming both files
// and their sizes otherwise.
void check_same_size(const std::string& left, int lw, int lh, const std::string& right, int rw,
                     int rh);

// golden::validate with its ParamError as a UserError (exit 2).
void validate_frame(const imap::golden::Params& p, const imap::golden::Roi& roi, int w, int h);

// The same for an output folder (`--out-dir`): it is a folder or can be
// created in an existing folder (the rule of every output flag: it creates
// the one thing it names, a file or this folder, in a folder that exists),
// and files can be created in it.
void check_output_dir(const std::string& flag, const std::string& dir);
// Creates an output folder (and its missing parents); UserError naming
// `flag` if it is a file or cannot be created.
void create_output_dir(const std::string& flag, const std::string& dir);

// The extension of `path` in lower case, with its dot (".avi"); "" if none.
std::string lower_extension(const std::string& path);

// The folder a file named `path` goes to: its parent, or "." for a bare
// file name ("n1.avi"), so that it can be made absolute or compared.
std::string folder_of(const std::string& path);
// True when the file `path` lies directly in folder `dir` (both taken
// relative to the current folder; "n1.json" is in ".", "out/x" in "out/").
bool file_in_folder(const std::string& path, const std::string& dir);

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

}  // namespace imapsim
