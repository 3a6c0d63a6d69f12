// The flags and the run-folder handling that `imapsim sweep`, `table1` and
// `regress` share (docs/cluster.md): which executor runs the jobs (local
// process pool or a Slurm job array, with its options), the run folder, and
// --resume. The commands themselves are in the engine library.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "imap/engine/executor.hpp"
#include "imap/engine/run_dir.hpp"
#include "imap/engine/sweep.hpp"
#include "progress.hpp"

namespace imapsim {

struct ExecFlags {
    std::string executor;  // local (default) or slurm
    std::string jobs;      // -j: parallel children (local)
    std::string run_dir, resume;
    bool keep = false;
    // slurm
    std::string partition, time_limit, mem_per_task, cpus_per_task, max_concurrent, points_per_task,
        poll;
    std::vector<std::string> sbatch_args;
};

// Adds -j, --executor, --run-dir, --resume, --keep and the Slurm options.
void add_exec_flags(CLI::App* app, ExecFlags& f, const std::string& what);

// A run of one engine command: its folder, manifest, executor and context.
struct Session {
    std::string command;
    bool resume = false;
    std::unique_ptr<imap::engine::RunDir> dir;
    imap::engine::Manifest manifest;
    std::unique_ptr<imap::engine::Executor> executor;
    imap::engine::ExecContext ctx;
    bool exec_keep = false;  // --keep
};

// Checks the executor flags (before any work; UserError naming the flag).
void check_exec_flags(const ExecFlags& f);

// A new run: the run folder (--run-dir; default: a temporary folder for the
// local executor, ./imapsim-COMMAND-DATE-TIME for Slurm), its manifest and
// the executor. No job has run yet.
Session start_session(const ExecFlags& f, const std::string& command, nlohmann::json payload,
                      std::vector<imap::engine::Job> jobs, double timeout_s);

// --resume DIR: the run folder and its manifest (payload = the command's
// plan). Executor flags given now replace the stored ones.
Session resume_session(const ExecFlags& f, const std::string& command, double timeout_s);

// After the run: removes a temporary folder when nothing needs keeping, else
// prints where it is (and how to resume). Returns whether it was kept.
bool finish_session(Session& s, bool keep_needed, bool interrupted);

// Prints rows, notes and the executor's status through a progress bar.
struct Printer {
    explicit Printer(const std::string& unit, size_t total);
    Progress progress;
    void row(const std::string& line) { progress.step(line); }
    void note(const std::string& line) { progress.note(line); }
    void status(const std::string& s) { progress.set_status(s); }
};

// Runs a planned sweep (new or resumed) on the session: header, rows,
// summary, the run folder kept or removed (cmd_sweep.cpp; table1 uses it).
imap::engine::sweep::Result run_sweep_session(Session& s, const imap::engine::sweep::Plan& plan,
                                              size_t x_axis);

}  // namespace imapsim
