// The local executor, the run folder and resume, against a fake `imapsim run`
// (fake_imapsim): every way a child can end becomes the right RunResult, at
// most -j children run at once, a timeout kills, a stop leaves unstarted jobs
// without a result, and drive(..., resume) re-runs only what has no
// definitive result.
#define BOOST_TEST_MODULE engine_executor
#include <sys/wait.h>

#include <atomic>
#include <boost/test/unit_test.hpp>
#include <map>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/executor.hpp"
#include "imap/engine/result.hpp"
#include "imap/engine/run_dir.hpp"

namespace eng = imap::engine;
namespace fs = std::filesystem;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

eng::Job job(const std::string& id, std::vector<std::string> extra) {
    eng::Job j{id, "fake", {"run", "--model", "fake"}};
    j.args.insert(j.args.end(), extra.begin(), extra.end());
    return j;
}

struct Collected {
    std::map<size_t, eng::RunResult> results;
    eng::ExecHooks hooks() {
        eng::ExecHooks h;
        h.on_result = [this](size_t i, eng::RunResult r) { results[i] = std::move(r); };
        return h;
    }
};

eng::ExecContext context(const fs::path& dir) {
    eng::ExecContext c;
    c.exe = FAKE_IMAPSIM;
    c.run_dir = dir;
    c.command = "test";
    return c;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_ending_becomes_its_result) {
    eng::RunDir dir = eng::RunDir::create((tmpdir() / "endings").string(), "test");
    const std::vector<eng::Job> jobs = {
        job("ok", {"--cycles", "4000"}),
        job("mismatch", {"--mismatch"}),
        job("input", {"--exit", "2", "--message", "parameter D = 99 is out of range"}),
        job("fault", {"--exit", "3", "--message", "machine fault: watchdog"}),
        job("internal", {"--exit", "4", "--message", "internal error: oops"}),
        job("noreport", {"--no-report"}),
        job("killed", {"--kill"}),
    };
    eng::LocalExecutor ex(3);
    Collected c;
    eng::ExecHooks h = c.hooks();
    const bool stopped = ex.run(jobs, {0, 1, 2, 3, 4, 5, 6}, context(dir.path()), h);
    BOOST_TEST(!stopped);
    BOOST_REQUIRE_EQUAL(c.results.size(), jobs.size());
    const eng::RunResult& ok = c.results[0];
    BOOST_TEST(ok.outcome == eng::Outcome::Ok);
    BOOST_TEST(ok.cycles == 4000u);
    BOOST_TEST(ok.modeled_ms == 0.1, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(ok.dominant_phase() == "forward");
    BOOST_TEST(ok.dominant_share() == 0.75, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(ok.command.find("--report") == std::string::npos);
    BOOST_TEST(ok.command.find("run --model fake --cycles 4000") != std::string::npos);
    BOOST_TEST(fs::exists(ok.log));
    BOOST_TEST(c.results[1].outcome == eng::Outcome::Mismatch);
    BOOST_TEST(eng::describe(c.results[1]) ==
               "not bit-exact vs golden: 3 pixels differ, first at (4,5): model 7, golden 6");
    BOOST_TEST(c.results[2].outcome == eng::Outcome::InputError);
    BOOST_TEST(eng::describe(c.results[2]) ==
               "input error (exit 2): parameter D = 99 is out of range");
    BOOST_TEST(c.results[3].outcome == eng::Outcome::Fault);
    BOOST_TEST(eng::describe(c.results[3]) == "machine fault (exit 3): machine fault: watchdog");
    BOOST_TEST(c.results[4].outcome == eng::Outcome::Failed);
    BOOST_TEST(eng::describe(c.results[4]) == "exit 4: internal error: oops");
    BOOST_TEST(c.results[5].outcome == eng::Outcome::Failed);
    BOOST_TEST(eng::describe(c.results[5]).find("exit 0, no report") == 0u);
    BOOST_TEST(c.results[6].outcome == eng::Outcome::Crashed);
    BOOST_TEST(c.results[6].signal == 9);
    BOOST_TEST(eng::describe(c.results[6]).find("killed by signal 9") == 0u);
}

BOOST_AUTO_TEST_CASE(results_survive_json) {
    eng::RunResult r;
    r.model = "tlm";
    r.outcome = eng::Outcome::Mismatch;
    r.exit_code = 1;
    r.has_report = true;
    r.bit_exact = false;
    r.differing_pixels = 12;
    r.first_difference = eng::FirstDifference{1, 2, 3, 4};
    r.cycles = 99;
    r.modeled_ms = 0.5;
    r.phases = {{"video_in", 5}, {"forward", 90}, {"backtrack", 4}};
    r.area = eng::Area{1234, 8192};
    eng::Energy e;
    e.total_uj = 3.5;
    e.dynamic_uj = 3;
    e.static_uj = 0.5;
    e.power_mw = 7;
    e.by_class = {{"alu", 1.25}, {"load", 1.75}, {"static_pe", 0.5}};
    e.events = {{"alu_lanes", 41}, {"load_lanes", 4}};
    e.events_source = "isa";
    r.energy = e;
    r.wall_s = 1.5;
    r.where = "slurm job 3_1 on node";
    r.command = "imapsim run";
    const eng::RunResult b = eng::result_from_json(eng::to_json(r));
    BOOST_TEST(eng::to_json(b) == eng::to_json(r));
    BOOST_TEST((b.phases == r.phases));  // order kept
    BOOST_TEST(b.area->memory_bits == 8192u);
    BOOST_REQUIRE(b.energy.has_value());
    BOOST_TEST(b.energy->total_uj == 3.5);
    BOOST_TEST(b.energy->power_mw == 7.0);
    BOOST_TEST(b.energy->events.size() == 2u);
    BOOST_TEST(b.energy->events_source == "isa");
    BOOST_CHECK_THROW(eng::result_from_json({{"model", "x"}, {"outcome", "nonsense"}}),
                      std::exception);
}

BOOST_AUTO_TEST_CASE(at_most_j_at_once) {
    eng::RunDir dir = eng::RunDir::create((tmpdir() / "par").string(), "test");
    const fs::path marker = dir.path() / "marker";
    std::vector<eng::Job> jobs;
    std::vector<size_t> todo;
    for (int i = 0; i < 6; ++i) {
        jobs.push_back(
            job("j" + std::to_string(i), {"--sleep", "0.3", "--marker", marker.string()}));
        todo.push_back(static_cast<size_t>(i));
    }
    eng::LocalExecutor ex(2);
    Collected c;
    eng::ExecHooks h = c.hooks();
    ex.run(jobs, todo, context(dir.path()), h);
    BOOST_TEST(c.results.size() == 6u);
    int now = 0, most = 0;
    std::istringstream in(enginetest::slurp(marker));
    for (std::string l; std::getline(in, l);) {
        now += l == "start" ? 1 : -1;
        most = std::max(most, now);
    }
    BOOST_TEST(most == 2);
    BOOST_TEST(now == 0);
}

BOOST_AUTO_TEST_CASE(timeout_kills_the_child) {
    eng::RunDir dir = eng::RunDir::create((tmpdir() / "timeout").string(), "test");
    const std::vector<eng::Job> jobs = {job("slow", {"--sleep", "30"})};
    eng::LocalExecutor ex(1);
    eng::ExecContext ctx = context(dir.path());
    ctx.timeout_s = 0.3;
    Collected c;
    eng::ExecHooks h = c.hooks();
    const auto t0 = std::chrono::steady_clock::now();
    ex.run(jobs, {0}, ctx, h);
    BOOST_TEST(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 10);
    BOOST_REQUIRE_EQUAL(c.results.size(), 1u);
    BOOST_TEST(c.results[0].outcome == eng::Outcome::TimedOut);
    BOOST_TEST(eng::describe(c.results[0]).find("timed out") == 0u);
    BOOST_TEST(!eng::is_definitive(c.results[0].outcome));
}

BOOST_AUTO_TEST_CASE(stop_leaves_unstarted_jobs_without_result) {
    eng::RunDir dir = eng::RunDir::create((tmpdir() / "stop").string(), "test");
    std::vector<eng::Job> jobs;
    for (int i = 0; i < 5; ++i) jobs.push_back(job("s" + std::to_string(i), {"--sleep", "20"}));
    eng::LocalExecutor ex(1);
    Collected c;
    eng::ExecHooks h = c.hooks();
    const auto t0 = std::chrono::steady_clock::now();
    h.stop_requested = [&] {
        return std::chrono::steady_clock::now() - t0 > std::chrono::milliseconds(300);
    };
    const bool stopped = ex.run(jobs, {0, 1, 2, 3, 4}, context(dir.path()), h);
    BOOST_TEST(stopped);
    BOOST_REQUIRE_EQUAL(c.results.size(), 1u);  // the running one, stopped
    BOOST_TEST(c.results[0].outcome == eng::Outcome::Interrupted);
}

BOOST_AUTO_TEST_CASE(drive_stores_and_resume_reruns_only_what_failed) {
    const fs::path where = tmpdir() / "resume";
    std::vector<eng::Job> jobs = {job("a", {"--cycles", "10"}), job("b", {"--exit", "4"}),
                                  job("c", {"--exit", "2"}), job("d", {"--kill"})};
    {
        eng::RunDir dir = eng::RunDir::create(where.string(), "test");
        eng::Manifest m;
        m.command = "test";
        m.exe = FAKE_IMAPSIM;
        m.payload = {{"anything", 1}};
        m.jobs = jobs;
        eng::LocalExecutor ex(2);
        Collected c;
        eng::ExecHooks h = c.hooks();
        const eng::DriveOutcome d = eng::drive(dir, m, ex, context(dir.path()), h, false);
        BOOST_TEST(!d.interrupted);
        BOOST_TEST(d.reused == 0u);
        BOOST_TEST(c.results.size() == 4u);
        // A second driver cannot take the folder while this one holds it.
        BOOST_CHECK_THROW(eng::RunDir::open(where.string()), eng::Error);
        // Neither can a new run.
        BOOST_CHECK_THROW(eng::RunDir::create(where.string(), "test"), eng::Error);
    }
    // Resume: a (ok) and c (input error) are definitive and kept; b (exit 4)
    // and d (killed) run again, now "fixed" in the manifest.
    eng::RunDir dir = eng::RunDir::open(where.string());
    eng::Manifest m = dir.load();
    BOOST_TEST(m.payload["anything"] == 1);
    BOOST_REQUIRE_EQUAL(m.jobs.size(), 4u);
    m.jobs[1] = job("b", {"--cycles", "20"});
    m.jobs[3] = job("d", {"--cycles", "30"});
    eng::LocalExecutor ex(2);
    Collected c;
    std::vector<size_t> order;
    eng::ExecHooks h = c.hooks();
    h.on_result = [&](size_t i, eng::RunResult r) {
        order.push_back(i);
        c.results[i] = std::move(r);
    };
    const eng::DriveOutcome d = eng::drive(dir, m, ex, context(dir.path()), h, true);
    BOOST_TEST(d.reused == 2u);
    BOOST_REQUIRE_EQUAL(order.size(), 4u);
    BOOST_TEST(order[0] == 0u);  // the kept ones first, in job order
    BOOST_TEST(order[1] == 2u);
    BOOST_TEST(c.results[0].cycles == 10u);
    BOOST_TEST(c.results[1].cycles == 20u);
    BOOST_TEST(c.results[2].outcome == eng::Outcome::InputError);
    BOOST_TEST(c.results[3].cycles == 30u);
    // Everything is in the folder now.
    const auto stored = dir.results(m.jobs);
    for (const auto& r : stored) BOOST_TEST(r.has_value());
}

BOOST_AUTO_TEST_CASE(run_folder_errors) {
    BOOST_CHECK_THROW(eng::RunDir::open((tmpdir() / "no-such").string()), eng::Error);
    const fs::path f = tmpdir() / "a-file";
    std::ofstream(f) << "x";
    BOOST_CHECK_THROW(eng::RunDir::create(f.string(), "test"), eng::Error);
    const fs::path full = tmpdir() / "full";
    fs::create_directories(full);
    std::ofstream(full / "other") << "x";
    BOOST_CHECK_THROW(eng::RunDir::create(full.string(), "test"), eng::Error);
    // A temporary folder is made and removed.
    eng::RunDir t = eng::RunDir::create("", "test");
    BOOST_TEST(t.temporary());
    const fs::path p = t.path();
    BOOST_TEST(fs::is_directory(p / "points"));
    t.remove();
    BOOST_TEST(!fs::exists(p));
}
