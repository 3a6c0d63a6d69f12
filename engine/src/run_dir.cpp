#include "imap/engine/run_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>

#include "imap/engine/error.hpp"

namespace imap::engine {

namespace fs = std::filesystem;
using nlohmann::json;

std::string iso_now() {
    const std::time_t t = std::time(nullptr);
    char b[32];
    std::tm tm{};
    ::gmtime_r(&t, &tm);
    std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%S", &tm);
    return b;
}

void write_file_atomic(const fs::path& p, const std::string& text) {
    const fs::path tmp =
        p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()));
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw Error("cannot write " + p.string() + ": " + std::strerror(errno), kExitInput);
        }
    }
    std::error_code ec;
    fs::rename(tmp, p, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error("cannot write " + p.string() + ": " + ec.message(), kExitInput);
    }
}

std::string read_text_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw Error("cannot read " + p.string() + ": " + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

RunDir::RunDir(RunDir&& o) noexcept
    : path_(std::move(o.path_)), temporary_(o.temporary_), lock_fd_(o.lock_fd_) {
    o.lock_fd_ = -1;
}

RunDir& RunDir::operator=(RunDir&& o) noexcept {
    if (this != &o) {
        if (lock_fd_ >= 0) ::close(lock_fd_);
        path_ = std::move(o.path_);
        temporary_ = o.temporary_;
        lock_fd_ = o.lock_fd_;
        o.lock_fd_ = -1;
    }
    return *this;
}

RunDir::~RunDir() {
    if (lock_fd_ >= 0) ::close(lock_fd_);
}

void RunDir::lock() {
    const fs::path lf = path_ / "run.lock";
    lock_fd_ = ::open(lf.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0)
        throw Error("run folder " + path_.string() + ": cannot create " + lf.string() + ": " +
                    std::strerror(errno));
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
        throw Error("run folder " + path_.string() +
                    " is in use by another imapsim (run.lock is held): wait for it to end");
}

RunDir RunDir::create(const std::string& dir, const std::string& command) {
    RunDir d;
    std::error_code ec;
    if (dir.empty()) {
        std::string tmpl =
            (fs::temp_directory_path() / ("imapsim-" + command + "-XXXXXX")).string();
        if (!::mkdtemp(tmpl.data()))
            throw Error("cannot create a run folder under " + fs::temp_directory_path().string() +
                            ": " + std::strerror(errno),
                        kExitInternal);
        d.path_ = tmpl;
        d.temporary_ = true;
    } else {
        d.path_ = fs::absolute(dir, ec).lexically_normal();
        if (fs::exists(d.path_, ec)) {
            if (!fs::is_directory(d.path_, ec))
                throw Error("--run-dir '" + dir + "': exists and is not a folder");
            if (fs::exists(d.path_ / "run.json", ec))
                throw Error("--run-dir '" + dir +
                            "' already holds a run: continue it with --resume " + dir +
                            ", or choose a new folder");
            if (!fs::is_empty(d.path_, ec))
                throw Error("--run-dir '" + dir + "': the folder is not empty; choose a new one");
        }
        fs::create_directories(d.path_, ec);
        if (ec) throw Error("--run-dir '" + dir + "': cannot create it (" + ec.message() + ")");
    }
    for (const char* sub : {"points", "results"}) {
        fs::create_directories(d.path_ / sub, ec);
        if (ec)
            throw Error("run folder " + d.path_.string() + ": cannot create " + sub + "/ (" +
                        ec.message() + ")");
    }
    d.lock();
    return d;
}

RunDir RunDir::open(const std::string& dir) {
    RunDir d;
    std::error_code ec;
    d.path_ = fs::absolute(dir, ec).lexically_normal();
    if (!fs::is_directory(d.path_, ec)) throw Error("--resume '" + dir + "': no such folder");
    if (!fs::exists(d.path_ / "run.json", ec))
        throw Error("--resume '" + dir + "': not a run folder (no run.json in it)");
    for (const char* sub : {"points", "results"}) fs::create_directories(d.path_ / sub, ec);
    d.lock();
    return d;
}

void RunDir::save(const Manifest& m) const {
    json j;
    j["format"] = m.format;
    j["command"] = m.command;
    j["exe"] = m.exe;
    j["created"] = m.created;
    j["executor"] = m.executor;
    json jobs = json::array();
    for (const Job& job : m.jobs) jobs.push_back(to_json(job));
    j["jobs"] = jobs;
    j["payload"] = m.payload;
    write_file_atomic(path_ / "run.json", j.dump(1) + "\n");
}

Manifest RunDir::load() const {
    return read_manifest(path_);
}

Manifest read_manifest(const fs::path& run_dir) {
    const fs::path f = run_dir / "run.json";
    try {
        const json j = json::parse(read_text_file(f));
        Manifest m;
        m.format = j.at("format").get<int>();
        if (m.format != kManifestFormat)
            throw Error(f.string() + ": manifest format " + std::to_string(m.format) +
                        ", this imapsim reads format " + std::to_string(kManifestFormat));
        m.command = j.at("command").get<std::string>();
        m.exe = j.at("exe").get<std::string>();
        m.created = j.value("created", std::string());
        m.executor = j.value("executor", json::object());
        for (const json& job : j.at("jobs")) m.jobs.push_back(job_from_json(job));
        m.payload = j.at("payload");
        return m;
    } catch (const json::exception& e) {
        throw Error(f.string() + ": not a valid run manifest (" + e.what() + ")");
    }
}

void RunDir::store(const Job& j, const RunResult& r) const {
    write_file_atomic(path_ / "results" / (j.id + ".json"), to_json(r).dump(1) + "\n");
}

std::vector<std::optional<RunResult>> RunDir::results(const std::vector<Job>& jobs) const {
    std::map<std::string, size_t> index;
    for (size_t i = 0; i < jobs.size(); ++i) index[jobs[i].id] = i;
    std::vector<std::optional<RunResult>> out(jobs.size());
    std::error_code ec;
    // Slurm task result files first (older), then the driver's own store.
    const fs::path slurm = path_ / "slurm";
    if (fs::is_directory(slurm, ec)) {
        std::vector<fs::path> files;
        for (const auto& sub : fs::directory_iterator(slurm, ec)) {
            if (!sub.is_directory()) continue;
            for (const auto& f : fs::directory_iterator(sub.path(), ec)) {
                const std::string n = f.path().filename().string();
                if (n.rfind("task-", 0) == 0 && f.path().extension() == ".json")
                    files.push_back(f.path());
            }
        }
        std::sort(files.begin(), files.end());
        for (const fs::path& f : files) {
            try {
                const json t = json::parse(read_text_file(f));
                for (const json& e : t.at("results")) {
                    const auto it = index.find(e.at("id").get<std::string>());
                    if (it == index.end()) continue;
                    RunResult r = result_from_json(e.at("result"));
                    if (!out[it->second] || is_definitive(r.outcome))
                        out[it->second] = std::move(r);
                }
            } catch (const std::exception&) {
                // a half-written or foreign file: its jobs are simply not known
            }
        }
    }
    for (size_t i = 0; i < jobs.size(); ++i) {
        const fs::path f = path_ / "results" / (jobs[i].id + ".json");
        if (!fs::exists(f, ec)) continue;
        try {
            RunResult r = result_from_json(json::parse(read_text_file(f)));
            if (!out[i] || is_definitive(r.outcome) || !is_definitive(out[i]->outcome))
                out[i] = std::move(r);
        } catch (const std::exception&) {
        }
    }
    return out;
}

void RunDir::remove() {
    if (lock_fd_ >= 0) {
        ::close(lock_fd_);
        lock_fd_ = -1;
    }
    std::error_code ec;
    fs::remove_all(path_, ec);
}

DriveOutcome drive(const RunDir& dir, Manifest& m, Executor& ex, const ExecContext& ctx,
                   ExecHooks& hooks, bool resume) {
    const auto t0 = std::chrono::steady_clock::now();
    DriveOutcome out;
    out.results.resize(m.jobs.size());
    std::vector<size_t> todo;
    if (resume) {
        auto prior = dir.results(m.jobs);
        for (size_t i = 0; i < m.jobs.size(); ++i) {
            if (prior[i] && is_definitive(prior[i]->outcome)) {
                out.results[i] = prior[i];
                ++out.reused;
            } else {
                todo.push_back(i);
            }
        }
    } else {
        for (size_t i = 0; i < m.jobs.size(); ++i) todo.push_back(i);
    }
    m.executor = ex.options_json();
    dir.save(m);
    if (resume)
        hooks.on_note("resume: " + std::to_string(out.reused) + " of " +
                      std::to_string(m.jobs.size()) + " runs have a result in the run folder; " +
                      std::to_string(todo.size()) + " to run");
    for (size_t i = 0; i < m.jobs.size(); ++i)
        if (out.results[i]) hooks.on_result(i, *out.results[i]);
    ExecHooks inner = hooks;
    inner.on_result = [&](size_t i, RunResult r) {
        dir.store(m.jobs[i], r);
        out.results[i] = r;
        hooks.on_result(i, std::move(r));
    };
    if (!todo.empty()) out.interrupted = ex.run(m.jobs, todo, ctx, inner);
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace imap::engine
