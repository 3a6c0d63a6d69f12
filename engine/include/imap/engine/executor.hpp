// Executors: where the child runs of a sweep, table1 or regression happen.
// A job is one `imapsim run` child (its arguments, without --report); an
// executor runs a set of jobs of a run folder and hands back one RunResult
// per finished job. `local` is a process pool on this machine (-j);
// `slurm` submits one job array (slurm_executor.hpp). Both write the child's
// log and report to RUN_DIR/points/<id>.log and <id>.report.json.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "imap/engine/result.hpp"

namespace imap::engine {

struct Job {
    std::string id;                 // stable, safe in a file name: names its log and report
    std::string model;              // the model it runs (--model)
    std::vector<std::string> args;  // imapsim arguments, "run", "--model", M, ... (no --report)
};

nlohmann::json to_json(const Job& j);
Job job_from_json(const nlohmann::json& j);

// The log and report of a job inside a run folder.
std::filesystem::path job_log(const std::filesystem::path& run_dir, const std::string& id);
std::filesystem::path job_report(const std::filesystem::path& run_dir, const std::string& id);
// The child's full command line (exe, args, --report REPORT).
std::vector<std::string> job_argv(const std::string& exe, const Job& j,
                                  const std::filesystem::path& run_dir);
// The command that reproduces the job by hand (exe and args, no --report).
std::string job_command(const std::string& exe, const Job& j);

// What an executor reports back while it runs (all calls come from the
// thread that called Executor::run).
struct ExecHooks {
    // Polled between actions: true stops the run (Ctrl-C); started jobs are
    // stopped, jobs not started get no result.
    std::function<bool()> stop_requested = [] { return false; };
    // A job finished (index into the job vector given to run()).
    std::function<void(size_t, RunResult)> on_result = [](size_t, RunResult) {};
    // A line worth printing ("submitted job array 123 ...").
    std::function<void(const std::string&)> on_note = [](const std::string&) {};
    // A short state for the progress line ("tasks: 2 pending, 1 running").
    std::function<void(const std::string&)> on_status = [](const std::string&) {};
};

struct ExecContext {
    std::string exe;                // the imapsim binary the children run
    std::filesystem::path run_dir;  // the run folder (points/ inside it exists)
    std::string command;            // "sweep", "regress", ... (names Slurm jobs)
    double timeout_s = 0;           // per job; 0: none
};

class Executor {
  public:
    virtual ~Executor() = default;
    virtual std::string name() const = 0;
    // One line for the header: "local, -j 2" / "slurm, partition debug, ...".
    virtual std::string describe() const = 0;
    // Its options, stored in the run folder (resume reuses them).
    virtual nlohmann::json options_json() const = 0;
    // Runs `todo` (indices into `jobs`); returns true if it was stopped
    // before every job of `todo` had a result.
    virtual bool run(const std::vector<Job>& jobs, const std::vector<size_t>& todo,
                     const ExecContext& ctx, ExecHooks& hooks) = 0;
};

// The process pool of this machine: up to `parallel` children at a time
// (0: one per core).
class LocalExecutor : public Executor {
  public:
    explicit LocalExecutor(unsigned parallel = 0);
    std::string name() const override { return "local"; }
    std::string describe() const override;
    nlohmann::json options_json() const override;
    bool run(const std::vector<Job>& jobs, const std::vector<size_t>& todo, const ExecContext& ctx,
             ExecHooks& hooks) override;
    unsigned parallel() const { return parallel_; }

  private:
    unsigned parallel_;
};

}  // namespace imap::engine
