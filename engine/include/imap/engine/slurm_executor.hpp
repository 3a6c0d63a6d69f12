// The Slurm executor (docs/cluster.md): the jobs of a run go to one job array,
// `sbatch --array=0-N%M`, a task packing one or more points. Each task runs
// `imapsim run-task` on a node, which runs `imapsim run` for its points (up
// to --cpus-per-task at a time) and writes one result file; the driver polls
// the task files and `squeue` (a task's final state from squeue's finished
// records, sacct, or the cluster's jobcomp/filetxt log), shows progress,
// and hands every point's result back as it appears. A task that fails,
// times out or is cancelled turns its unfinished points into failed results
// with the reason; Ctrl-C cancels the array (scancel) and waits for it to
// leave the queue. The run folder must be on a file system that the submit
// host and the nodes see under the same path.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "imap/engine/executor.hpp"

namespace imap::engine {

struct SlurmOptions {
    std::string partition;         // sbatch --partition (empty: the cluster's default)
    std::string time_limit;        // sbatch --time per task, e.g. 10:00 (empty: default)
    unsigned cpus_per_task = 1;    // sbatch --cpus-per-task; points run in parallel in a task
    std::string mem_per_task;      // sbatch --mem, e.g. 2G (empty: default)
    unsigned max_concurrent = 0;   // the %M of --array (0: no limit)
    unsigned points_per_task = 1;  // packing: points per array task
    std::vector<std::string> sbatch_args;  // extra sbatch arguments, as given
    double poll_s = 2.0;                   // squeue / result-file polling period
    double cancel_wait_s = 120;            // how long Ctrl-C waits for the array to leave the queue
    double result_grace_s = 30;            // how long a finished task's result file may lag (NFS)

    // engine::Error naming the flag for a value sbatch would refuse.
    void validate() const;
};

nlohmann::json to_json(const SlurmOptions& o);
SlurmOptions slurm_options_from_json(const nlohmann::json& j);

class SlurmExecutor : public Executor {
  public:
    explicit SlurmExecutor(SlurmOptions o);
    std::string name() const override { return "slurm"; }
    std::string describe() const override;
    nlohmann::json options_json() const override;
    bool run(const std::vector<Job>& jobs, const std::vector<size_t>& todo, const ExecContext& ctx,
             ExecHooks& hooks) override;
    const SlurmOptions& options() const { return o_; }

    // Checks before any work that the Slurm commands are on PATH.
    static void check_available();

  private:
    SlurmOptions o_;
};

// The body of one array task (`imapsim run-task`): runs the points of task
// `task` of submission `sub` of the run folder, up to `parallel` at a time
// (0: $SLURM_CPUS_PER_TASK, else 1), writing slurm/sub-N/task-K.status and
// the result file task-K.json (rewritten after every point). Returns the
// exit code of the task: 0, or 130 when stopped (SIGTERM from Slurm).
int run_task(const std::filesystem::path& run_dir, int sub, int task, unsigned parallel,
             std::function<bool()> stop_requested);

// The Slurm folder of submission `sub` of a run folder, and its task files.
std::filesystem::path submission_dir(const std::filesystem::path& run_dir, int sub);
std::filesystem::path task_result_file(const std::filesystem::path& run_dir, int sub, int task);
std::filesystem::path task_status_file(const std::filesystem::path& run_dir, int sub, int task);
std::filesystem::path task_log_file(const std::filesystem::path& run_dir, int sub, int task);

}  // namespace imap::engine
