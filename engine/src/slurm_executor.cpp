#include "imap/engine/slurm_executor.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/run_dir.hpp"

namespace imap::engine {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// ---- options ---------------------------------------------------------------------

namespace {

bool only(const std::string& s, const char* allowed) {
    return !s.empty() && s.find_first_not_of(allowed) == std::string::npos;
}

}  // namespace

void SlurmOptions::validate() const {
    if (!partition.empty() &&
        !only(partition, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.,-"))
        throw Error("invalid value '" + partition +
                    "' for --partition: expected a partition name (letters, digits, _ . -; a comma "
                    "list for several)");
    if (!time_limit.empty() && !only(time_limit, "0123456789:-"))
        throw Error("invalid value '" + time_limit +
                    "' for --time-limit: expected a Slurm time: MM, MM:SS, HH:MM:SS or D-HH:MM:SS");
    if (!mem_per_task.empty()) {
        const size_t d = mem_per_task.find_first_not_of("0123456789");
        if (d == 0 || (d != std::string::npos &&
                       (d + 1 != mem_per_task.size() ||
                        std::string("KMGTkmgt").find(mem_per_task[d]) == std::string::npos)))
            throw Error("invalid value '" + mem_per_task +
                        "' for --mem-per-task: expected a size such as 2000 (MB), 512M or 4G");
    }
    if (cpus_per_task < 1 || cpus_per_task > 1024)
        throw Error("value " + std::to_string(cpus_per_task) +
                    " for --cpus-per-task is out of range (allowed: 1..1024)");
    if (points_per_task < 1 || points_per_task > 100000)
        throw Error("value " + std::to_string(points_per_task) +
                    " for --points-per-task is out of range (allowed: 1..100000)");
    if (!(poll_s > 0 && poll_s <= 3600))
        throw Error("invalid value for --poll: expected seconds in (0, 3600]");
}

json to_json(const SlurmOptions& o) {
    return {{"executor", "slurm"},
            {"partition", o.partition},
            {"time_limit", o.time_limit},
            {"cpus_per_task", o.cpus_per_task},
            {"mem_per_task", o.mem_per_task},
            {"max_concurrent", o.max_concurrent},
            {"points_per_task", o.points_per_task},
            {"sbatch_args", o.sbatch_args},
            {"poll_s", o.poll_s}};
}

SlurmOptions slurm_options_from_json(const json& j) {
    SlurmOptions o;
    o.partition = j.value("partition", std::string());
    o.time_limit = j.value("time_limit", std::string());
    o.cpus_per_task = j.value("cpus_per_task", 1u);
    o.mem_per_task = j.value("mem_per_task", std::string());
    o.max_concurrent = j.value("max_concurrent", 0u);
    o.points_per_task = j.value("points_per_task", 1u);
    o.sbatch_args = j.value("sbatch_args", std::vector<std::string>());
    o.poll_s = j.value("poll_s", 2.0);
    return o;
}

SlurmExecutor::SlurmExecutor(SlurmOptions o) : o_(std::move(o)) {
    o_.validate();
}

std::string SlurmExecutor::describe() const {
    std::string d = "slurm";
    d += o_.partition.empty() ? ", default partition" : ", partition " + o_.partition;
    d += ", " + std::to_string(o_.points_per_task) + " point" +
         (o_.points_per_task == 1 ? "" : "s") + " per task, " + std::to_string(o_.cpus_per_task) +
         " CPU" + (o_.cpus_per_task == 1 ? "" : "s") + " per task";
    if (!o_.time_limit.empty()) d += ", time limit " + o_.time_limit;
    if (!o_.mem_per_task.empty()) d += ", memory " + o_.mem_per_task;
    if (o_.max_concurrent) d += ", at most " + std::to_string(o_.max_concurrent) + " at a time";
    return d;
}

json SlurmExecutor::options_json() const {
    return to_json(o_);
}

void SlurmExecutor::check_available() {
    for (const char* c : {"sbatch", "squeue", "scancel"})
        if (!on_path(c))
            throw Error(std::string("--executor slurm: ") + c +
                        " is not on PATH (run on a Slurm submit host, or load its module)");
}

fs::path submission_dir(const fs::path& run_dir, int sub) {
    return run_dir / "slurm" / ("sub-" + std::to_string(sub));
}
fs::path task_result_file(const fs::path& run_dir, int sub, int task) {
    return submission_dir(run_dir, sub) / ("task-" + std::to_string(task) + ".json");
}
fs::path task_status_file(const fs::path& run_dir, int sub, int task) {
    return submission_dir(run_dir, sub) / ("task-" + std::to_string(task) + ".status");
}
fs::path task_log_file(const fs::path& run_dir, int sub, int task) {
    return submission_dir(run_dir, sub) / ("task-" + std::to_string(task) + ".out");
}

// ---- talking to Slurm ---------------------------------------------------------------

namespace {

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
    size_t b = s.find_first_not_of(" \n");
    return b == std::string::npos ? "" : s.substr(b);
}

std::string last_line(const std::string& s) {
    const std::string t = trim(s);
    const size_t nl = t.rfind('\n');
    return nl == std::string::npos ? t : t.substr(nl + 1);
}

struct TaskState {
    std::string state, reason, node;
};

// States of the array's tasks as squeue lists them (finished tasks stay
// listed for MinJobAge). nullopt when squeue failed.
std::optional<std::map<int, TaskState>> squeue_states(const std::string& job) {
    const Captured c = run_capture({"squeue", "--noheader", "--array", "--states=all",
                                    "--jobs=" + job, "--format=%K|%T|%r|%N"},
                                   60);
    std::map<int, TaskState> out;
    if (c.exit_code != 0) {
        // The whole array left the queue (older than MinJobAge): nothing listed.
        if (c.output.find("Invalid job id") != std::string::npos) return out;
        return std::nullopt;
    }
    std::istringstream in(c.output);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ls(line);
        std::string x;
        while (std::getline(ls, x, '|')) f.push_back(trim(x));
        if (f.size() < 2 || f[0].empty() ||
            f[0].find_first_not_of("0123456789") != std::string::npos)
            continue;
        TaskState t;
        t.state = f[1];
        if (f.size() > 2) t.reason = f[2];
        if (f.size() > 3) t.node = f[3];
        out[std::atoi(f[0].c_str())] = t;
    }
    return out;
}

bool is_active(const std::string& st) {
    return st == "PENDING" || st == "RUNNING" || st == "CONFIGURING" || st == "COMPLETING" ||
           st == "SUSPENDED" || st == "REQUEUED" || st == "RESIZING" || st == "SIGNALING" ||
           st == "STAGE_OUT" || st == "REQUEUE_HOLD" || st == "REQUEUE_FED" || st == "STOPPED";
}

// The final state from accounting (sacct), when the cluster has it.
std::optional<std::string> sacct_state(const std::string& job, int task) {
    if (!on_path("sacct")) return std::nullopt;
    const Captured c = run_capture({"sacct", "--noheader", "--parsable2", "--allocations",
                                    "--jobs=" + job + "_" + std::to_string(task), "--format=State"},
                                   60);
    if (c.exit_code != 0) return std::nullopt;
    const std::string s = trim(c.output);
    if (s.empty()) return std::nullopt;
    std::string first = s.substr(0, s.find('\n'));
    first = first.substr(0, first.find(' '));  // "CANCELLED by 0" -> CANCELLED
    return first.empty() ? std::nullopt : std::optional<std::string>(first);
}

// The final state from a jobcomp/filetxt log the cluster writes (when this
// host can read it).
std::optional<std::string> jobcomp_state(const std::string& job, int task) {
    static std::optional<std::string> loc;
    static bool looked = false;
    if (!looked) {
        looked = true;
        const Captured c = run_capture({"scontrol", "show", "config"}, 60);
        if (c.exit_code == 0 && c.output.find("jobcomp/filetxt") != std::string::npos) {
            std::istringstream in(c.output);
            std::string line;
            while (std::getline(in, line))
                if (line.rfind("JobCompLoc", 0) == 0) {
                    const size_t eq = line.find('=');
                    if (eq != std::string::npos) loc = trim(line.substr(eq + 1));
                }
        }
    }
    if (!loc) return std::nullopt;
    std::ifstream in(*loc);
    std::string line;
    std::optional<std::string> st;
    const std::string a = "ArrayJobId=" + job + " ",
                      t = "ArrayTaskId=" + std::to_string(task) + " ";
    while (std::getline(in, line)) {
        if (line.find(a) == std::string::npos || line.find(t) == std::string::npos) continue;
        const size_t k = line.find("JobState=");
        if (k != std::string::npos) st = line.substr(k + 9, line.find(' ', k) - k - 9);
    }
    return st;
}

// The line of a task's Slurm log that says why it ended ("slurmstepd: error:
// *** JOB 49 ON node1 CANCELLED AT ... ***").
std::string slurm_log_reason(const fs::path& log) {
    std::ifstream in(log);
    std::string line, found;
    while (std::getline(in, line))
        if (line.find("***") != std::string::npos && line.find("slurmstepd") != std::string::npos)
            found = trim(line);
    return found;
}

struct Track {
    int task = 0;
    std::vector<size_t> jobs;    // indices into the job vector
    std::set<size_t> forwarded;  // jobs whose result was handed on
    std::string last_state;      // as last seen in squeue
    std::string node;
    bool final = false;
    int absent_polls = 0;
    std::optional<Clock::time_point> ended;  // when squeue first showed it finished or gone
};

struct TaskFile {
    bool complete = false;
    std::map<std::string, RunResult> results;
};

std::optional<TaskFile> read_task_file(const fs::path& f) {
    std::error_code ec;
    if (!fs::exists(f, ec)) return std::nullopt;
    try {
        const json j = json::parse(read_text_file(f));
        TaskFile t;
        t.complete = j.value("complete", false);
        for (const json& e : j.at("results"))
            t.results[e.at("id").get<std::string>()] = result_from_json(e.at("result"));
        return t;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace

// ---- the driver -----------------------------------------------------------------------

bool SlurmExecutor::run(const std::vector<Job>& jobs, const std::vector<size_t>& todo,
                        const ExecContext& ctx, ExecHooks& hooks) {
    check_available();
    const fs::path slurm_dir = ctx.run_dir / "slurm";
    std::error_code ec;
    fs::create_directories(slurm_dir, ec);

    // Earlier submissions of this run folder must have left the queue.
    int sub = 1;
    for (const auto& e : fs::directory_iterator(slurm_dir, ec)) {
        const std::string n = e.path().filename().string();
        if (n.rfind("sub-", 0) != 0) continue;
        sub = std::max(sub, std::atoi(n.c_str() + 4) + 1);
        try {
            const json s = json::parse(read_text_file(e.path() / "submission.json"));
            const std::string old = s.at("job_id").get<std::string>();
            if (const auto st = squeue_states(old))
                for (const auto& [k, t] : *st)
                    if (is_active(t.state))
                        throw Error("job array " + old + " of this run folder (" + n +
                                    ") is still in the queue: wait for it to end or cancel it "
                                    "(scancel " +
                                    old + "), then resume");
        } catch (const Error&) {
            throw;
        } catch (const std::exception&) {
        }
    }
    const fs::path sd = submission_dir(ctx.run_dir, sub);
    fs::create_directories(sd, ec);
    if (ec) throw Error("cannot create " + sd.string() + ": " + ec.message());

    // Pack the points into tasks.
    std::vector<Track> tracks;
    json tasks = json::array();
    for (size_t i = 0; i < todo.size(); i += o_.points_per_task) {
        Track t;
        t.task = static_cast<int>(tracks.size());
        json ids = json::array();
        for (size_t k = i; k < std::min(todo.size(), i + o_.points_per_task); ++k) {
            t.jobs.push_back(todo[k]);
            ids.push_back(jobs[todo[k]].id);
        }
        tasks.push_back(ids);
        tracks.push_back(std::move(t));
    }
    write_file_atomic(sd / "tasks.json", json{{"submission", sub},
                                              {"command", ctx.command},
                                              {"timeout_s", ctx.timeout_s},
                                              {"cpus_per_task", o_.cpus_per_task},
                                              {"tasks", tasks}}
                                                 .dump(1) +
                                             "\n");
    const fs::path script = sd / "task.sh";
    write_file_atomic(script,
                      "#!/bin/sh\n"
                      "# One task of an imapsim job array (docs/cluster.md): runs the points of\n"
                      "# task $SLURM_ARRAY_TASK_ID listed in tasks.json beside this script.\n"
                      "exec " +
                          shell_quote(ctx.exe) + " run-task --run-dir " +
                          shell_quote(ctx.run_dir.string()) + " --submission " +
                          std::to_string(sub) + " --task \"$SLURM_ARRAY_TASK_ID\"\n");
    ::chmod(script.c_str(), 0755);

    std::vector<std::string> sb = {"sbatch", "--parsable"};
    std::string array = "--array=0-" + std::to_string(tracks.size() - 1);
    if (o_.max_concurrent) array += "%" + std::to_string(o_.max_concurrent);
    sb.push_back(array);
    sb.push_back("--job-name=imapsim-" + ctx.command);
    sb.push_back("--output=" + (sd / "task-%a.out").string());
    sb.push_back("--chdir=" + ctx.run_dir.string());
    sb.push_back("--cpus-per-task=" + std::to_string(o_.cpus_per_task));
    if (!o_.partition.empty()) sb.push_back("--partition=" + o_.partition);
    if (!o_.time_limit.empty()) sb.push_back("--time=" + o_.time_limit);
    if (!o_.mem_per_task.empty()) sb.push_back("--mem=" + o_.mem_per_task);
    sb.insert(sb.end(), o_.sbatch_args.begin(), o_.sbatch_args.end());
    sb.push_back(script.string());
    const Captured c = run_capture(sb, 120);
    std::string job;
    {
        std::istringstream in(c.output);
        std::string line;
        while (std::getline(in, line)) {
            line = trim(line);
            const std::string id = line.substr(0, line.find(';'));
            if (!id.empty() && id.find_first_not_of("0123456789") == std::string::npos) job = id;
        }
    }
    if (c.exit_code != 0 || job.empty())
        throw Error(
            "--executor slurm: sbatch refused the job array (" +
            (c.exit_code >= 0 ? "exit " + std::to_string(c.exit_code) : std::string("killed")) +
            "): " + (trim(c.output).empty() ? "(no output)" : last_line(c.output)) +
            "; command: " + command_line(sb));
    write_file_atomic(sd / "submission.json", json{{"job_id", job},
                                                   {"submitted", iso_now()},
                                                   {"tasks", tracks.size()},
                                                   {"points", todo.size()},
                                                   {"sbatch", command_line(sb)}}
                                                      .dump(1) +
                                                  "\n");
    hooks.on_note("submitted job array " + job + ": " + std::to_string(tracks.size()) + " task" +
                  (tracks.size() == 1 ? "" : "s") + " for " + std::to_string(todo.size()) +
                  " point" + (todo.size() == 1 ? "" : "s") + "; task logs in " + sd.string());

    const auto grace = std::chrono::duration<double>(o_.result_grace_s);
    auto forward = [&](Track& t, size_t j, RunResult r) {
        if (t.forwarded.count(j)) return;
        t.forwarded.insert(j);
        hooks.on_result(j, std::move(r));
    };
    // Hands on what the task's result file holds: definitive results at
    // once, all of them when the task wrote its last word.
    auto collect = [&](Track& t, bool all) {
        const auto f = read_task_file(task_result_file(ctx.run_dir, sub, t.task));
        if (!f) return false;
        for (size_t j : t.jobs) {
            const auto it = f->results.find(jobs[j].id);
            if (it == f->results.end()) continue;
            if (all || f->complete || is_definitive(it->second.outcome)) forward(t, j, it->second);
        }
        return f->complete;
    };
    // The task ended without finishing: its other points fail with the reason.
    auto fail_rest = [&](Track& t, const std::string& state) {
        collect(t, false);
        const std::string who = "slurm: task " + std::to_string(t.task) + " of job " + job;
        const bool started = fs::exists(task_status_file(ctx.run_dir, sub, t.task), ec);
        const std::string log_reason = slurm_log_reason(task_log_file(ctx.run_dir, sub, t.task));
        Outcome o = Outcome::Failed;
        std::string why;
        if (state == "CANCELLED" || state == "PREEMPTED" || state == "REVOKED") {
            o = Outcome::Cancelled;
            why = who + " was cancelled (" + state + ") " +
                  (started ? "while it ran" : "before it started");
        } else if (state == "TIMEOUT" || state == "DEADLINE") {
            o = Outcome::TimedOut;
            why = who + " reached its time limit (" + state +
                  (o_.time_limit.empty() ? "" : ", --time-limit " + o_.time_limit) + ")";
        } else if (state.empty()) {
            o = Outcome::Cancelled;
            why = who + " left the queue without a result (" +
                  (started ? "stopped while it ran" : "cancelled before it started") + ")";
        } else if (state == "COMPLETED") {
            why = who + " completed without writing its results (see " +
                  task_log_file(ctx.run_dir, sub, t.task).string() + ")";
        } else {
            why = who + " ended " + state + (t.node.empty() ? "" : " on " + t.node);
        }
        if (!log_reason.empty()) why += ": " + log_reason;
        for (size_t j : t.jobs) {
            if (t.forwarded.count(j)) continue;
            RunResult r;
            r.model = jobs[j].model;
            r.outcome = o;
            r.message = why;
            r.where = "slurm job " + job + "_" + std::to_string(t.task) +
                      (t.node.empty() ? "" : " on " + t.node);
            r.command = job_command(ctx.exe, jobs[j]);
            const fs::path lg = job_log(ctx.run_dir, jobs[j].id);
            if (fs::exists(lg, ec)) r.log = lg.string();
            forward(t, j, std::move(r));
        }
        t.final = true;
    };
    auto final_state = [&](Track& t) -> std::string {
        if (!t.last_state.empty() && !is_active(t.last_state)) return t.last_state;
        if (const auto s = sacct_state(job, t.task)) return *s;
        if (const auto s = jobcomp_state(job, t.task)) return *s;
        return "";
    };
    auto sleep_poll = [&]() {
        const auto until = Clock::now() + std::chrono::duration<double>(o_.poll_s);
        while (Clock::now() < until && !hooks.stop_requested())
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
    };

    bool stopped = false;
    while (true) {
        if (hooks.stop_requested()) {
            stopped = true;
            hooks.on_note("interrupted: cancelling job array " + job + " (scancel " + job + ")");
            run_capture({"scancel", job}, 60);
            const auto until = Clock::now() + std::chrono::duration<double>(o_.cancel_wait_s);
            bool active = true;
            while (active && Clock::now() < until) {
                active = false;
                if (const auto st = squeue_states(job))
                    for (const auto& [k, s] : *st) active |= is_active(s.state);
                else
                    active = true;
                if (active) std::this_thread::sleep_for(std::chrono::milliseconds(200));
            }
            if (active)
                hooks.on_note("job array " + job + " is still in the queue after " +
                              std::to_string(static_cast<int>(o_.cancel_wait_s)) +
                              " s; its results are collected by --resume");
            // What finished is kept; what did not has no result (not run).
            for (Track& t : tracks)
                if (!t.final) {
                    const auto f = read_task_file(task_result_file(ctx.run_dir, sub, t.task));
                    if (f)
                        for (size_t j : t.jobs) {
                            const auto it = f->results.find(jobs[j].id);
                            if (it != f->results.end() && is_definitive(it->second.outcome))
                                forward(t, j, it->second);
                        }
                }
            break;
        }
        const auto st = squeue_states(job);
        size_t pending = 0, running = 0, finished = 0;
        for (Track& t : tracks) {
            if (t.final) {
                ++finished;
                continue;
            }
            if (collect(t, false)) {
                t.final = true;
                ++finished;
                continue;
            }
            if (!st) continue;  // squeue failed this time: look again next poll
            const auto it = st->find(t.task);
            if (it != st->end()) {
                t.last_state = it->second.state;
                if (!it->second.node.empty() && it->second.node != "(null)")
                    t.node = it->second.node;
                t.absent_polls = 0;
                if (is_active(t.last_state)) {
                    (t.last_state == "PENDING" ? pending : running)++;
                    continue;
                }
            } else if (++t.absent_polls < 2) {
                ++pending;
                continue;
            }
            // Finished or gone without a complete result file.
            if (!t.ended) t.ended = Clock::now();
            const std::string fs_state = final_state(t);
            const bool wait_more =
                (fs_state == "COMPLETED" && Clock::now() - *t.ended < grace) ||
                (fs_state != "COMPLETED" &&
                 Clock::now() - *t.ended < std::chrono::duration<double>(o_.poll_s * 1.5));
            if (wait_more) {
                ++running;
                continue;
            }
            fail_rest(t, fs_state);
            ++finished;
        }
        hooks.on_status("job " + job + ": " + std::to_string(pending) + " pending, " +
                        std::to_string(running) + " running, " + std::to_string(finished) + "/" +
                        std::to_string(tracks.size()) + " tasks done");
        if (finished == tracks.size()) break;
        sleep_poll();
    }
    return stopped;
}

// ---- the task -----------------------------------------------------------------------

int run_task(const fs::path& run_dir, int sub, int task, unsigned parallel,
             std::function<bool()> stop_requested) {
    const Manifest m = read_manifest(run_dir);
    const fs::path sd = submission_dir(run_dir, sub);
    json tj;
    try {
        tj = json::parse(read_text_file(sd / "tasks.json"));
    } catch (const json::exception& e) {
        throw Error((sd / "tasks.json").string() + ": " + e.what());
    }
    const json& list = tj.at("tasks");
    if (task < 0 || static_cast<size_t>(task) >= list.size())
        throw Error("--task " + std::to_string(task) + " is out of range (allowed: 0.." +
                    std::to_string(list.size() - 1) + ")");
    std::map<std::string, size_t> index;
    for (size_t i = 0; i < m.jobs.size(); ++i) index[m.jobs[i].id] = i;
    std::vector<size_t> todo;
    for (const json& id : list[static_cast<size_t>(task)]) {
        const auto it = index.find(id.get<std::string>());
        if (it == index.end())
            throw Error("task " + std::to_string(task) + ": unknown job " + id.dump());
        todo.push_back(it->second);
    }
    if (parallel == 0) {
        const char* c = std::getenv("SLURM_CPUS_PER_TASK");
        parallel = c && std::atoi(c) > 0 ? static_cast<unsigned>(std::atoi(c)) : 1;
    }
    char host[256] = "";
    ::gethostname(host, sizeof host - 1);
    const char* aj = std::getenv("SLURM_ARRAY_JOB_ID");
    const std::string where =
        std::string("slurm job ") + (aj ? aj : "?") + "_" + std::to_string(task) + " on " + host;
    const fs::path status = task_status_file(run_dir, sub, task);
    const std::string started =
        "running " + where + " pid " + std::to_string(::getpid()) + " since " + iso_now() + "\n";
    write_file_atomic(status, started);

    json results = json::array();
    auto write = [&](bool complete, bool stopped) {
        json j = {{"task", task},         {"submission", sub},  {"where", where},
                  {"complete", complete}, {"stopped", stopped}, {"results", results}};
        write_file_atomic(task_result_file(run_dir, sub, task), j.dump(1) + "\n");
    };
    write(false, false);
    ExecContext ctx;
    ctx.exe = m.exe;
    ctx.run_dir = run_dir;
    ctx.command = tj.value("command", std::string());
    ctx.timeout_s = tj.value("timeout_s", 0.0);
    ExecHooks hooks;
    hooks.stop_requested = stop_requested;
    hooks.on_result = [&](size_t j, RunResult r) {
        r.where = where;
        results.push_back({{"id", m.jobs[j].id}, {"result", to_json(r)}});
        write(false, false);
    };
    LocalExecutor local(parallel);
    const bool stopped = local.run(m.jobs, todo, ctx, hooks);
    write(!stopped, stopped);
    write_file_atomic(status, started + (stopped ? "stopped " : "finished ") + iso_now() + "\n");
    return stopped ? kExitInterrupted : kExitOk;
}

}  // namespace imap::engine
