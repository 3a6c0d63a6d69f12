// The Slurm executor against a real cluster: a private single-node Slurm
// cluster (munge, slurmctld, slurmd from Debian's packages, started by
// scripts/slurm-test-cluster.sh in a temporary folder) runs a sweep and the
// quick regression; their tables equal the local executor's (wall times
// aside). One task is cancelled and becomes a failed row with its reason;
// --resume runs only that point again; Ctrl-C cancels the array and leaves a
// valid partial report. The cluster is stopped at the end. If it does not
// come up, every test case fails (this test never skips).
#define BOOST_TEST_MODULE engine_slurm
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <thread>

#include "engine_test_util.hpp"

extern char** environ;

namespace fs = std::filesystem;
using enginetest::slurp;
using enginetest::tmpdir;
using nlohmann::json;

namespace {

struct Run {
    int code = -1;
    std::string out;
};

Run sh(const std::string& cmd) {
    Run r;
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    if (!p) return r;
    char buf[4096];
    size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    const int st = pclose(p);
    r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

Run imapsim(const std::string& args) {
    return sh(std::string(IMAPSIM_EXE) + " " + args);
}

// The cluster, for the whole test program.
struct Cluster {
    fs::path dir;
    bool up = false;
    std::string log;
    Cluster() {
        dir = tmpdir() / "cluster";
        const auto t0 = std::chrono::steady_clock::now();
        // --owner: if this program is killed (CTest's time limit), the
        // script's watchdog stops the daemons.
        const Run r = sh("bash " SLURM_CLUSTER_SCRIPT " start " + dir.string() + " --owner " +
                         std::to_string(::getpid()));
        log = r.out;
        up = r.code == 0;
        if (up) ::setenv("SLURM_CONF", (dir / "slurm.conf").c_str(), 1);
        std::printf("slurm test cluster: %s in %.1f s\n%s", up ? "up" : "DID NOT COME UP",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                    r.out.c_str());
    }
    ~Cluster() {
        if (fs::exists(dir / "slurm.conf")) {
            const Run r = sh("bash " SLURM_CLUSTER_SCRIPT " stop " + dir.string());
            std::printf("%s", r.out.c_str());
        }
        std::error_code ec;
        fs::remove_all(tmpdir(), ec);
    }
};
Cluster* g_cluster = nullptr;
struct ClusterFixture {
    Cluster c;
    ClusterFixture() { g_cluster = &c; }
    ~ClusterFixture() { g_cluster = nullptr; }
};

void require_cluster() {
    BOOST_REQUIRE_MESSAGE(g_cluster && g_cluster->up,
                          "the private Slurm cluster did not come up (it needs root and the "
                          "packages of scripts/install-deps.sh):\n"
                              << (g_cluster ? g_cluster->log : std::string()));
}

// CSV rows without the wall_s column (wall times differ between executors).
std::vector<std::string> csv_without_wall(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(text);
    std::vector<std::string> out;
    size_t wall = std::string::npos;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> f;
        std::string cur;
        bool q = false;
        for (char c : line) {
            if (c == '"') q = !q;
            if (c == ',' && !q) {
                f.push_back(cur);
                cur.clear();
            } else {
                cur += c;
            }
        }
        f.push_back(cur);
        if (wall == std::string::npos)
            for (size_t i = 0; i < f.size(); ++i)
                if (f[i] == "wall_s") wall = i;
        if (wall < f.size()) f.erase(f.begin() + static_cast<long>(wall));
        std::string joined;
        for (const auto& x : f) joined += x + "|";
        out.push_back(joined);
    }
    return out;
}

// A regression's JSON summary without what depends on the executor.
json regress_essentials(const json& s) {
    json out = json::array();
    for (const json& c : s.at("cases")) {
        json e = {{"name", c.at("name")}, {"passed", c.at("passed")}};
        if (c.contains("cycles")) e["cycles"] = c["cycles"];
        for (const auto& [m, r] : c.at("runs").items()) {
            json rr = {{"outcome", r.at("outcome")}, {"command", r.value("command", "")}};
            for (const char* k : {"cycles", "modeled_ms", "phases", "bit_exact", "exit"})
                if (r.contains(k)) rr[k] = r[k];
            e["runs"][m] = rr;
        }
        out.push_back(e);
    }
    return out;
}

json job_of(const fs::path& run_dir, int sub) {
    const fs::path f = run_dir / "slurm" / ("sub-" + std::to_string(sub)) / "submission.json";
    for (int i = 0; i < 600 && !fs::exists(f); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return fs::exists(f) ? json::parse(slurp(f)) : json();
}

// Starts a command in its own process group, output into `out`.
pid_t spawn(const std::vector<std::string>& args, const fs::path& out) {
    std::vector<std::string> a = args;
    std::vector<char*> av;
    for (auto& s : a) av.push_back(s.data());
    av.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    posix_spawnattr_t at;
    posix_spawnattr_init(&at);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&at, 0);
    pid_t pid = -1;
    posix_spawn(&pid, av[0], &fa, &at, av.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    return pid;
}

int wait_exit(pid_t pid) {
    int st = 0;
    ::waitpid(pid, &st, 0);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// The sweep of the tests: small points of the bare machine, some that do not fit.
const std::string kSweep = "sweep --model core --roi-size 32x16 --D 4..9 --mem-bytes 1024,60";

// The local executor's CSV of kSweep, run once for the whole test program.
const std::string& local_sweep_csv() {
    static const std::string csv = [] {
        const fs::path d = tmpdir();
        const Run local = imapsim(kSweep + " -j 2 --csv " + (d / "local.csv").string() +
                                  " --json " + (d / "local.json").string());
        BOOST_TEST_INFO(local.out);
        BOOST_REQUIRE_EQUAL(local.code, 0);
        return (d / "local.csv").string();
    }();
    return csv;
}

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(ClusterFixture);

BOOST_AUTO_TEST_CASE(sweep_equals_local) {
    require_cluster();
    const fs::path d = fs::path(local_sweep_csv()).parent_path();
    const auto t0 = std::chrono::steady_clock::now();
    const Run slurm =
        imapsim(kSweep + " --executor slurm --points-per-task 2 --poll 0.3 --run-dir " +
                (d / "sweep-run").string() + " --csv " + (d / "slurm.csv").string() + " --json " +
                (d / "slurm.json").string());
    BOOST_TEST_MESSAGE(
        "sweep through slurm: "
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s");
    BOOST_TEST_INFO(slurm.out);
    BOOST_REQUIRE_EQUAL(slurm.code, 0);
    BOOST_TEST(slurm.out.find("submitted job array") != std::string::npos);
    BOOST_TEST(
        (csv_without_wall(slurp(d / "local.csv")) == csv_without_wall(slurp(d / "slurm.csv"))));
    json a = json::parse(slurp(d / "local.json")), b = json::parse(slurp(d / "slurm.json"));
    for (json* j : {&a, &b}) {
        j->erase("wall_s");
        for (json& r : (*j)["rows"]) r.erase("wall_s");
    }
    BOOST_TEST(a == b);
    // 6 points that fit, 2 per task: 3 tasks, each with its result file.
    const json sub = job_of(d / "sweep-run", 1);
    BOOST_TEST(sub.at("tasks") == 3);
    for (int t = 0; t < 3; ++t)
        BOOST_TEST(fs::exists(d / "sweep-run" / "slurm" / "sub-1" /
                              ("task-" + std::to_string(t) + ".json")));
}

BOOST_AUTO_TEST_CASE(quick_regression_equals_local) {
    require_cluster();
    // The quick suite's eight synth-quick cases on the bare machine (the
    // fastest model; the whole suite on every model runs locally as
    // regress.quick): packed three per array task, so the array has full
    // and partial tasks.
    const fs::path d = tmpdir();
    const Run local =
        imapsim("regress --suite quick --filter synth-quick --models core -j 2 --json " +
                (d / "rl.json").string());
    BOOST_TEST_INFO(local.out);
    BOOST_REQUIRE_EQUAL(local.code, 0);
    const auto t0 = std::chrono::steady_clock::now();
    const Run slurm = imapsim(
        "regress --suite quick --filter synth-quick --models core --executor slurm "
        "--points-per-task 3 --poll 0.3 --run-dir " +
        (d / "regress-run").string() + " --json " + (d / "rs.json").string() + " --junit " +
        (d / "rs.xml").string());
    BOOST_TEST_MESSAGE(
        "quick regression (core) through slurm: "
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s");
    BOOST_TEST_INFO(slurm.out);
    BOOST_REQUIRE_EQUAL(slurm.code, 0);
    const json a = json::parse(slurp(d / "rl.json")), b = json::parse(slurp(d / "rs.json"));
    BOOST_TEST(a.at("passed") == 8);
    BOOST_TEST(a.at("passed") == b.at("passed"));
    BOOST_TEST(b.at("failed") == 0);
    BOOST_TEST(regress_essentials(a) == regress_essentials(b));
    BOOST_TEST(slurp(d / "rs.xml").find("slurm job ") != std::string::npos);  // where each ran
}

BOOST_AUTO_TEST_CASE(cancelled_task_is_a_failed_row_and_resume_runs_it) {
    require_cluster();
    const fs::path d = tmpdir(), run = d / "cancel-run";
    // One task at a time, so that the last one is still pending when it is cancelled.
    const pid_t pid =
        spawn({IMAPSIM_EXE,        "sweep",      "--model",    "core",
               "--roi-size",       "32x16",      "--D",        "4..9",
               "--mem-bytes",      "1024,60",    "--executor", "slurm",
               "--max-concurrent", "1",          "--poll",     "0.3",
               "--run-dir",        run.string(), "--csv",      (d / "cancel.csv").string()},
              d / "cancel.out");
    BOOST_REQUIRE(pid > 0);
    const json sub = job_of(run, 1);
    BOOST_REQUIRE_MESSAGE(!sub.is_null(), slurp(d / "cancel.out"));
    const std::string job = sub.at("job_id").get<std::string>();
    const int last = sub.at("tasks").get<int>() - 1;
    const Run c = sh("scancel " + job + "_" + std::to_string(last));
    BOOST_TEST(c.code == 0, c.out);
    const int code = wait_exit(pid);
    const std::string out = slurp(d / "cancel.out");
    BOOST_TEST_INFO(out);
    BOOST_TEST(code == 5);
    const auto rows = csv_without_wall(slurp(d / "cancel.csv"));
    size_t failed = 0, ok = 0;
    for (const std::string& r : rows) {
        if (r.find("|error|") != std::string::npos) {
            ++failed;
            BOOST_TEST(r.find("slurm: task " + std::to_string(last) + " of job " + job) !=
                           std::string::npos,
                       r);
            BOOST_TEST((r.find("cancelled") != std::string::npos), r);
        }
        ok += r.find("|ok|") != std::string::npos;
    }
    BOOST_TEST(failed == 1u);
    BOOST_TEST(ok == 5u);

    // Resume: only the cancelled point is submitted again; the table is the local one.
    const Run res = imapsim("sweep --resume " + run.string() + " --poll 0.3 --csv " +
                            (d / "resumed.csv").string());
    BOOST_TEST_INFO(res.out);
    BOOST_REQUIRE_EQUAL(res.code, 0);
    BOOST_TEST(res.out.find("5 of 6 runs have a result") != std::string::npos);
    const json sub2 = job_of(run, 2);
    BOOST_TEST(sub2.at("points") == 1);
    BOOST_TEST(
        (csv_without_wall(slurp(local_sweep_csv())) == csv_without_wall(slurp(d / "resumed.csv"))));
}

BOOST_AUTO_TEST_CASE(ctrl_c_cancels_the_array_and_leaves_a_partial_report) {
    require_cluster();
    const fs::path d = tmpdir(), run = d / "int-run";
    const pid_t pid = spawn({IMAPSIM_EXE,
                             "sweep",
                             "--model",
                             "core",
                             "--roi-size",
                             "32x16",
                             "--D",
                             "4..9",
                             "--executor",
                             "slurm",
                             "--max-concurrent",
                             "1",
                             "--poll",
                             "0.3",
                             "--run-dir",
                             run.string(),
                             "--csv",
                             (d / "int.csv").string(),
                             "--json",
                             (d / "int.json").string()},
                            d / "int.out");
    BOOST_REQUIRE(pid > 0);
    const json sub = job_of(run, 1);
    BOOST_REQUIRE(!sub.is_null());
    // Wait for the first point to finish, then Ctrl-C the driver's group.
    for (int i = 0; i < 600 && slurp(d / "int.out").find("ok, bit-exact") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    BOOST_REQUIRE(::kill(-pid, SIGINT) == 0);
    const int code = wait_exit(pid);
    const std::string out = slurp(d / "int.out");
    BOOST_TEST_INFO(out);
    BOOST_TEST(code == 130);
    BOOST_TEST(out.find("scancel " + sub.at("job_id").get<std::string>()) != std::string::npos);
    // The array left the queue.
    const Run q = sh("squeue --noheader --jobs=" + sub.at("job_id").get<std::string>() +
                     " --states=PENDING,RUNNING,COMPLETING");
    BOOST_TEST(q.out.find_first_not_of(" \n") == std::string::npos, q.out);
    // A valid partial report: finished rows, then the interrupted marker.
    const json j = json::parse(slurp(d / "int.json"));
    BOOST_TEST(j.at("interrupted").get<bool>());
    BOOST_TEST(j.at("points_finished").get<size_t>() + j.at("not_run").get<size_t>() == 6u);
    BOOST_TEST(j.at("points_finished").get<size_t>() >= 1u);
    const auto rows = csv_without_wall(slurp(d / "int.csv"));
    BOOST_TEST(rows.back().find("sweep-interrupted") != std::string::npos);
    // And it resumes to the full sweep.
    const Run res = imapsim("sweep --resume " + run.string() + " --poll 0.3");
    BOOST_TEST_INFO(res.out);
    BOOST_TEST(res.code == 0);
    BOOST_TEST(res.out.find("6 ran (6 bit-exact") != std::string::npos);
}
