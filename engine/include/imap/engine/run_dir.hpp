// The run folder of a sweep, table1 or regression: everything a run needs to
// be reported, resumed or run elsewhere.
//
//   RUN_DIR/run.json              the manifest: command, binary, the command's
//                                 plan (payload), the jobs, the executor's options
//   RUN_DIR/points/<id>.log       each child's output, <id>.report.json its report
//   RUN_DIR/results/<id>.json     each finished job's RunResult (written by the driver)
//   RUN_DIR/slurm/sub-N/          one Slurm submission: tasks.json (task -> jobs),
//                                 task.sh, task-K.out (Slurm's log), task-K.status,
//                                 task-K.json (the task's result file)
//
// With the Slurm executor the folder must be visible under the same path on
// the submit host and on every node (docs/cluster.md).
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "imap/engine/executor.hpp"
#include "imap/engine/result.hpp"

namespace imap::engine {

inline constexpr int kManifestFormat = 1;

struct Manifest {
    int format = kManifestFormat;
    std::string command;     // sweep, table1, regress
    std::string exe;         // the imapsim binary the jobs run
    std::string created;     // ISO 8601, UTC
    nlohmann::json payload;  // the command's own plan (rebuilds its report on resume)
    std::vector<Job> jobs;
    nlohmann::json executor = nlohmann::json::object();  // options of the last executor
};

class RunDir {
  public:
    // A new run folder at `dir` (created; if it exists it must be empty), or,
    // with `dir` empty, a temporary one under the temp folder (removed by
    // the command when nothing needs keeping). engine::Error (exit 2) if it
    // cannot be made.
    static RunDir create(const std::string& dir, const std::string& command);
    // An existing run folder (--resume): it must hold a run.json.
    static RunDir open(const std::string& dir);

    RunDir(RunDir&&) noexcept;
    RunDir& operator=(RunDir&&) noexcept;
    ~RunDir();

    const std::filesystem::path& path() const { return path_; }
    bool temporary() const { return temporary_; }

    void save(const Manifest& m) const;  // run.json, atomically
    Manifest load() const;               // engine::Error naming the file when unreadable

    // Stores one job's result (results/<id>.json, atomically).
    void store(const Job& j, const RunResult& r) const;
    // The stored results of `jobs` (also those only in a Slurm task's result
    // file, e.g. when the driver was stopped while tasks ran on).
    std::vector<std::optional<RunResult>> results(const std::vector<Job>& jobs) const;

    // Deletes the folder (a temporary run that needs no keeping).
    void remove();

  private:
    RunDir() = default;
    void lock();
    std::filesystem::path path_;
    bool temporary_ = false;
    int lock_fd_ = -1;
};

// Runs every job of `m` that has no definitive result yet (with `resume`;
// otherwise every job) on `ex`. Results already in the folder are handed to
// hooks.on_result first (in job order); every new result is stored in the
// folder, then handed on. The manifest (with the executor's options) is
// saved before anything runs.
struct DriveOutcome {
    std::vector<std::optional<RunResult>> results;  // per job; empty: not run
    size_t reused = 0;                              // results taken from the folder (resume)
    bool interrupted = false;                       // stopped by hooks.stop_requested
    double wall_s = 0;
};
DriveOutcome drive(const RunDir& dir, Manifest& m, Executor& ex, const ExecContext& ctx,
                   ExecHooks& hooks, bool resume);

// Reads RUN_DIR/run.json without taking the folder's lock (the Slurm tasks
// read the manifest of a run their driver holds).
Manifest read_manifest(const std::filesystem::path& run_dir);

// ISO 8601 UTC time of now ("2026-12-01T20:58:42").
std::string iso_now();

// Writes a text file through a temporary name in its folder (never half-written).
void write_file_atomic(const std::filesystem::path& p, const std::string& text);
// Reads a whole file; engine::Error naming it when it cannot be read.
std::string read_text_file(const std::filesystem::path& p);

}  // namespace imap::engine
