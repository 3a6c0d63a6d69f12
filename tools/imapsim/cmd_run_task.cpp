// imapsim run-task: one array task of a Slurm run (docs/cluster.md). Not for
// users: the job array's task.sh calls it on a node with the run folder, the
// submission and the task index; it runs `imapsim run` for the task's points
// and writes the task's status and result file into the run folder.
#include <memory>

#include "cli_common.hpp"
#include "imap/engine/slurm_executor.hpp"
#include "interrupt.hpp"

namespace imapsim {

namespace {
struct RunTaskOptions {
    std::string run_dir;
    int submission = 0, task = -1;
    unsigned jobs = 0;
};
}  // namespace

Subcommand register_run_task(CLI::App& app) {
    auto o = std::make_shared<RunTaskOptions>();
    CLI::App* sub = app.add_subcommand(
        "run-task", "one task of a Slurm job array (called by the array's task.sh)");
    sub->group("");  // hidden from --help
    sub->add_option("--run-dir", o->run_dir, "the run folder")->required();
    sub->add_option("--submission", o->submission, "submission number (slurm/sub-N)")->required();
    sub->add_option("--task", o->task, "array task index ($SLURM_ARRAY_TASK_ID)")->required();
    sub->add_option("-j,--jobs", o->jobs, "points at a time [default: $SLURM_CPUS_PER_TASK or 1]");
    return {sub, [o]() {
                ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "DISABLE", 0);
                interrupt::install();
                return imap::engine::run_task(o->run_dir, o->submission, o->task, o->jobs,
                                              [] { return interrupt::requested(); });
            }};
}

}  // namespace imapsim
