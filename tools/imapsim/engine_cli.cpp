#include "engine_cli.hpp"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/slurm_executor.hpp"

namespace imapsim {

namespace fs = std::filesystem;
namespace eng = imap::engine;
using nlohmann::json;

void add_exec_flags(CLI::App* app, ExecFlags& f, const std::string& what) {
    const char* g = "Executor (docs/cluster.md)";
    app->add_option("-j,--jobs", f.jobs,
                    what + " run in parallel by the local executor [default: one per core]")
        ->group(g);
    app->add_option("--executor", f.executor,
                    "where the runs happen: local (this machine's cores) or slurm (one job "
                    "array) [default: local]")
        ->group(g);
    app->add_option("--run-dir", f.run_dir,
                    "run folder for the manifest, logs and results (must be shared with the "
                    "nodes for slurm) [default: a temporary folder, removed when everything "
                    "passed; slurm: ./imapsim-COMMAND-DATE-TIME]")
        ->group(g);
    app->add_option("--resume", f.resume,
                    "continue the run in this run folder: runs only the missing and failed "
                    "points, then reports all of them")
        ->group(g);
    app->add_flag("--keep", f.keep, "keep the run folder even when everything passed")->group(g);
    const char* s = "Slurm executor (docs/cluster.md)";
    app->add_option("--partition", f.partition, "sbatch --partition [default: the cluster's]")
        ->group(s);
    app->add_option("--time-limit", f.time_limit,
                    "time limit per array task (sbatch --time: MM, MM:SS, HH:MM:SS)")
        ->group(s);
    app->add_option("--cpus-per-task", f.cpus_per_task,
                    "CPUs per array task; a task runs that many of its points at a time "
                    "[default: 1]")
        ->group(s);
    app->add_option("--mem-per-task", f.mem_per_task,
                    "memory per array task (sbatch --mem, e.g. 2G)")
        ->group(s);
    app->add_option("--max-concurrent", f.max_concurrent,
                    "at most this many array tasks at a time (the %M of --array) [default: no "
                    "limit]")
        ->group(s);
    app->add_option("--points-per-task", f.points_per_task,
                    "runs packed into one array task [default: 1]")
        ->group(s);
    app->add_option("--sbatch-arg", f.sbatch_args,
                    "extra sbatch argument, e.g. --sbatch-arg=--account=hw; repeatable")
        ->group(s);
    app->add_option("--poll", f.poll, "seconds between squeue polls [default: 2]")->group(s);
}

namespace {

bool slurm_flags_given(const ExecFlags& f) {
    return !f.partition.empty() || !f.time_limit.empty() || !f.mem_per_task.empty() ||
           !f.cpus_per_task.empty() || !f.max_concurrent.empty() || !f.points_per_task.empty() ||
           !f.poll.empty() || !f.sbatch_args.empty();
}

std::unique_ptr<eng::Executor> make_executor(const ExecFlags& f, const json& stored) {
    std::string ex = f.executor;
    if (ex.empty()) ex = stored.value("executor", std::string("local"));
    if (ex == "local") {
        if (slurm_flags_given(f))
            throw UserError(
                "the Slurm options (--partition, --time-limit, ...) need --executor "
                "slurm (this run folder's executor is local)");
        unsigned j = stored.value("executor", std::string()) == "local" && f.jobs.empty()
                         ? stored.value("jobs", 0u)
                         : 0u;
        if (!f.jobs.empty()) j = static_cast<unsigned>(parse_int_flag("-j", f.jobs, 1, 1024));
        return std::make_unique<eng::LocalExecutor>(j);
    }
    eng::SlurmOptions o;
    if (stored.value("executor", std::string()) == "slurm")
        o = eng::slurm_options_from_json(stored);
    if (!f.partition.empty()) o.partition = f.partition;
    if (!f.time_limit.empty()) o.time_limit = f.time_limit;
    if (!f.mem_per_task.empty()) o.mem_per_task = f.mem_per_task;
    if (!f.cpus_per_task.empty())
        o.cpus_per_task =
            static_cast<unsigned>(parse_int_flag("--cpus-per-task", f.cpus_per_task, 1, 1024));
    if (!f.max_concurrent.empty())
        o.max_concurrent =
            static_cast<unsigned>(parse_int_flag("--max-concurrent", f.max_concurrent, 1, 100000));
    if (!f.points_per_task.empty())
        o.points_per_task = static_cast<unsigned>(
            parse_int_flag("--points-per-task", f.points_per_task, 1, 100000));
    if (!f.poll.empty()) o.poll_s = parse_real_flag("--poll", f.poll, 0, 3600, true);
    if (!f.sbatch_args.empty()) o.sbatch_args = f.sbatch_args;
    eng::SlurmExecutor::check_available();
    return std::make_unique<eng::SlurmExecutor>(o);
}

std::string stamp() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    ::localtime_r(&t, &tm);
    char b[32];
    std::strftime(b, sizeof b, "%Y%m%d-%H%M%S", &tm);
    return b;
}

}  // namespace

void check_exec_flags(const ExecFlags& f) {
    if (!f.executor.empty() && f.executor != "local" && f.executor != "slurm")
        throw UserError("invalid value '" + f.executor +
                        "' for --executor: expected local or slurm");
    if (f.executor == "local" && slurm_flags_given(f))
        throw UserError("the Slurm options (--partition, --time-limit, ...) need --executor slurm");
    if (!f.resume.empty() && !f.run_dir.empty())
        throw UserError("--resume DIR continues the run in DIR: give no --run-dir with it");
    if (!f.jobs.empty()) parse_int_flag("-j", f.jobs, 1, 1024);
    if (f.executor.empty() && f.resume.empty() && slurm_flags_given(f))
        throw UserError("the Slurm options (--partition, --time-limit, ...) need --executor slurm");
}

Session start_session(const ExecFlags& f, const std::string& command, json payload,
                      std::vector<eng::Job> jobs, double timeout_s) {
    check_exec_flags(f);
    Session s;
    s.command = command;
    s.executor = make_executor(f, json::object());
    std::string dir = f.run_dir;
    if (dir.empty() && s.executor->name() == "slurm") dir = "imapsim-" + command + "-" + stamp();
    s.dir = std::make_unique<eng::RunDir>(eng::RunDir::create(dir, command));
    s.manifest.command = command;
    s.manifest.exe = eng::self_exe();
    s.manifest.created = eng::iso_now();
    s.manifest.payload = std::move(payload);
    s.manifest.jobs = std::move(jobs);
    s.ctx.exe = s.manifest.exe;
    s.ctx.run_dir = s.dir->path();
    s.ctx.command = command;
    s.ctx.timeout_s = timeout_s;
    ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "DISABLE", 0);
    return s;
}

Session resume_session(const ExecFlags& f, const std::string& command, double timeout_s) {
    check_exec_flags(f);
    Session s;
    s.command = command;
    s.resume = true;
    s.dir = std::make_unique<eng::RunDir>(eng::RunDir::open(f.resume));
    s.manifest = s.dir->load();
    if (s.manifest.command != command && !(command == "sweep" && s.manifest.command == "table1"))
        throw UserError("--resume '" + f.resume + "': the run folder holds an imapsim " +
                        s.manifest.command + " run, not " + command + ": resume it with imapsim " +
                        s.manifest.command + " --resume " + f.resume);
    s.executor = make_executor(f, s.manifest.executor);
    s.manifest.exe = eng::self_exe();  // the binary that resumes runs the rest
    s.ctx.exe = s.manifest.exe;
    s.ctx.run_dir = s.dir->path();
    s.ctx.command = s.manifest.command;
    s.ctx.timeout_s = timeout_s;
    ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "DISABLE", 0);
    return s;
}

bool finish_session(Session& s, bool keep_needed, bool interrupted) {
    const std::string p = s.dir->path().string();
    if (s.dir->temporary() && !keep_needed && !interrupted && !s.resume) {
        s.dir->remove();
        return false;
    }
    if (interrupted)
        std::printf("  run folder kept in %s (continue with: imapsim %s --resume %s)\n", p.c_str(),
                    s.manifest.command.c_str(), p.c_str());
    else if (keep_needed && s.dir->temporary())
        std::printf("  logs of the failed runs kept in %s\n", p.c_str());
    else
        std::printf("  run folder %s\n", p.c_str());
    std::fflush(stdout);
    return true;
}

Printer::Printer(const std::string& unit, size_t total) : progress(unit, total) {}

}  // namespace imapsim
