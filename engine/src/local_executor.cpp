#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <thread>

#include "imap/engine/executor.hpp"
#include "imap/engine/process.hpp"

namespace imap::engine {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

json to_json(const Job& j) {
    return {{"id", j.id}, {"model", j.model}, {"args", j.args}};
}

Job job_from_json(const json& j) {
    Job r;
    r.id = j.at("id").get<std::string>();
    r.model = j.at("model").get<std::string>();
    r.args = j.at("args").get<std::vector<std::string>>();
    return r;
}

fs::path job_log(const fs::path& run_dir, const std::string& id) {
    return run_dir / "points" / (id + ".log");
}

fs::path job_report(const fs::path& run_dir, const std::string& id) {
    return run_dir / "points" / (id + ".report.json");
}

std::vector<std::string> job_argv(const std::string& exe, const Job& j, const fs::path& run_dir) {
    std::vector<std::string> a = {exe};
    a.insert(a.end(), j.args.begin(), j.args.end());
    a.insert(a.end(), {"--report", job_report(run_dir, j.id).string()});
    return a;
}

std::string job_command(const std::string& exe, const Job& j) {
    std::vector<std::string> a = {exe};
    a.insert(a.end(), j.args.begin(), j.args.end());
    return command_line(a);
}

LocalExecutor::LocalExecutor(unsigned parallel)
    : parallel_(parallel ? parallel : std::max(1u, std::thread::hardware_concurrency())) {}

std::string LocalExecutor::describe() const {
    return "local, -j " + std::to_string(parallel_);
}

json LocalExecutor::options_json() const {
    return {{"executor", "local"}, {"jobs", parallel_}};
}

namespace {

struct Running {
    size_t job = 0;
    pid_t pid = -1;
    Clock::time_point start;
    bool term_sent = false, timed_out = false;
};

}  // namespace

bool LocalExecutor::run(const std::vector<Job>& jobs, const std::vector<size_t>& todo,
                        const ExecContext& ctx, ExecHooks& hooks) {
    std::vector<Running> running;
    size_t next = 0;
    bool stopping = false;
    auto finish = [&](const Running& r, bool started, int st) {
        const Job& j = jobs[r.job];
        const double wall = std::chrono::duration<double>(Clock::now() - r.start).count();
        RunResult res = read_child(j.model, started, st, job_report(ctx.run_dir, j.id).string(),
                                   job_log(ctx.run_dir, j.id).string(), wall,
                                   r.term_sent && !r.timed_out, r.timed_out);
        if (r.timed_out)
            res.message = "timed out after " + std::to_string(static_cast<long>(ctx.timeout_s)) +
                          " s (--timeout)";
        res.command = job_command(ctx.exe, j);
        hooks.on_result(r.job, std::move(res));
    };
    while (true) {
        if (!stopping && hooks.stop_requested()) {
            stopping = true;
            for (Running& r : running)
                if (!r.term_sent) {
                    ::kill(r.pid, SIGTERM);
                    r.term_sent = true;
                }
        }
        while (!stopping && running.size() < parallel_ && next < todo.size()) {
            Running r;
            r.job = todo[next++];
            r.start = Clock::now();
            const Job& j = jobs[r.job];
            std::error_code ec;
            fs::remove(job_report(ctx.run_dir, j.id), ec);
            r.pid = spawn_logged(job_argv(ctx.exe, j, ctx.run_dir),
                                 job_log(ctx.run_dir, j.id).string());
            if (r.pid < 0)
                finish(r, false, 0);
            else
                running.push_back(r);
        }
        if (running.empty() && (stopping || next >= todo.size())) break;
        bool any = false;
        for (size_t k = 0; k < running.size();) {
            Running& r = running[k];
            int st = 0;
            const pid_t w = ::waitpid(r.pid, &st, WNOHANG);
            if (w < 0 && errno == ECHILD) {  // reaped elsewhere: no status to read
                RunResult res;
                res.model = jobs[r.job].model;
                res.message = "lost track of the child process";
                res.command = job_command(ctx.exe, jobs[r.job]);
                hooks.on_result(r.job, std::move(res));
                running.erase(running.begin() + static_cast<long>(k));
                any = true;
                continue;
            }
            if (w == r.pid) {
                finish(r, true, st);
                running.erase(running.begin() + static_cast<long>(k));
                any = true;
                continue;
            }
            if (ctx.timeout_s > 0 && !r.timed_out &&
                std::chrono::duration<double>(Clock::now() - r.start).count() > ctx.timeout_s) {
                ::kill(r.pid, SIGKILL);
                r.timed_out = true;
            }
            ++k;
        }
        if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return stopping;
}

}  // namespace imap::engine
