// The regression engine without running anything: case tables (matrix
// expansion, suites and their models, errors), the selection of models and
// cases, judging a case from its models' results, and the reports.
#define BOOST_TEST_MODULE engine_regress
#include <boost/test/unit_test.hpp>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/regress.hpp"

namespace eng = imap::engine;
namespace rg = imap::engine::regress;
namespace fs = std::filesystem;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

fs::path table(const std::string& name, const std::string& text) {
    const fs::path p = tmpdir() / name;
    std::ofstream(p) << text;
    return p;
}

const char* kTable = R"({
  // comments are allowed
  "suites": {"quick": {"models": ["core", "tlm", "lockstep"]}, "full": {"models": ["core"]}},
  "cases": [
    {"name": "m", "suite": "quick", "args": ["--size", "32x16"],
     "matrix": {"--seed": ["1", "2"], "--mode": ["single", "bidir"]}},
    {"name": "only-tlm", "suite": "quick", "models": ["tlm"], "args": []},
    {"name": "err", "suite": "quick", "expect": "error", "expect_message": "out of range",
     "args": ["--D", "999"]},
    {"name": "full-only", "suite": "full", "args": [], "expect_cycles": 5},
    {"name": "scene", "suite": "full", "scene": "nowhere", "args": []}
  ]
})";

eng::RunResult ran(const std::string& model, uint64_t cycles,
                   std::vector<std::pair<std::string, uint64_t>> phases = {{"forward", 1}}) {
    eng::RunResult r;
    r.model = model;
    r.outcome = eng::Outcome::Ok;
    r.exit_code = 0;
    r.has_report = true;
    r.bit_exact = true;
    r.cycles = cycles;
    r.modeled_ms = static_cast<double>(cycles) / 40000.0;
    r.phases = std::move(phases);
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(matrix_and_suites) {
    const rg::CaseTable t = rg::load_cases(table("t.json", kTable));
    BOOST_REQUIRE_EQUAL(t.cases.size(), 8u);
    BOOST_TEST(t.cases[0].name == "m/seed=1,mode=single");
    BOOST_TEST(t.cases[3].name == "m/seed=2,mode=bidir");
    BOOST_TEST((t.cases[3].args ==
                std::vector<std::string>{"--size", "32x16", "--seed", "2", "--mode", "bidir"}));
    BOOST_TEST((t.suite_models.at("quick") == std::vector<std::string>{"core", "tlm", "lockstep"}));

    // The suite's models (data) intersected with the built ones.
    rg::Selection s;
    s.suite = "quick";
    s.built = {"tlm", "core"};
    s.cases_file = "t.json";
    const rg::Plan p = rg::plan(t, s);
    BOOST_TEST((p.models == std::vector<std::string>{"core", "tlm"}));
    BOOST_REQUIRE_EQUAL(p.notes.size(), 1u);
    BOOST_TEST(p.notes[0].find("lockstep") != std::string::npos);
    BOOST_REQUIRE_EQUAL(p.cases.size(), 6u);  // quick only
    BOOST_TEST((p.cases[4].models == std::vector<std::string>{"tlm"}));
    BOOST_TEST(p.jobs.size() == 4u * 2u + 1u + 2u);
    const eng::Job& j = p.jobs[static_cast<size_t>(p.cases[0].jobs[1])];
    BOOST_TEST(j.model == "tlm");
    BOOST_TEST((j.args == std::vector<std::string>{"run", "--model", "tlm", "--size", "32x16",
                                                   "--seed", "1", "--mode", "single"}));
    // The plan survives the run folder.
    rg::Plan back = rg::plan_from_json(rg::to_json(p));
    BOOST_TEST(rg::to_json(back) == rg::to_json(p));

    // The full suite takes its own models; a missing scene fails its case.
    s.suite = "full";
    s.data = tmpdir();
    const rg::Plan f = rg::plan(t, s);
    BOOST_TEST((f.models == std::vector<std::string>{"core"}));
    BOOST_TEST(f.cases.size() == 8u);
    BOOST_TEST(f.cases[7].error.find("scene nowhere not found") == 0u);
    BOOST_TEST(f.cases[7].jobs.empty());
    BOOST_TEST(!rg::judge(f.cases[7], {}).passed);

    // --models: unknown names are refused, known unbuilt ones skipped.
    s.models = {"core", "nosuch"};
    BOOST_CHECK_THROW(rg::plan(t, s), eng::Error);
    s.models = {"lockstep"};
    BOOST_CHECK_THROW(rg::plan(t, s), eng::Error);  // nothing built remains
    s.models = {};
    s.filter = "no-case-is-called-this";
    BOOST_CHECK_THROW(rg::plan(t, s), eng::Error);
}

BOOST_AUTO_TEST_CASE(bad_tables_name_the_problem) {
    const std::pair<const char*, const char*> bad[] = {
        {R"({"cases": [{"args": []}]})", "needs a \"name\""},
        {R"({"cases": [{"name": "a", "suite": "nightly"}]})", "suite must be quick or full"},
        {R"({"cases": [{"name": "a", "colour": 1}]})", "unknown key \"colour\""},
        {R"({"cases": [{"name": "a"}, {"name": "a"}]})", "duplicate case a"},
        {R"({"cases": [], "suites": {"quick": {}}})", "needs \"models\""},
        {R"({"cases": [{"name": "a", "args": "x"}]})", "expected an array of strings"},
        {R"({"cases": [{"name": "a", "expect_cycles": "many"}]})", "case table"},
        {R"([1, 2])", "expected {\"cases\""},
    };
    int k = 0;
    for (const auto& [text, msg] : bad) {
        const fs::path f = table("bad" + std::to_string(k++) + ".json", text);
        BOOST_TEST_CONTEXT(text) {
            try {
                rg::load_cases(f);
                BOOST_ERROR("accepted");
            } catch (const eng::Error& e) {
                BOOST_TEST(std::string(e.what()).find(msg) != std::string::npos, e.what());
                BOOST_TEST(std::string(e.what()).find(f.string()) != std::string::npos);
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(judging) {
    rg::Entry e;
    e.c.name = "x";
    e.models = {"core", "tlm"};
    e.jobs = {0, 1};
    eng::RunResult a = ran("core", 100), b = ran("tlm", 100);
    BOOST_TEST(rg::judge(e, {&a, &b}).passed);
    BOOST_TEST(rg::judge(e, {&a, &b}).cycles == 100u);

    b.cycles = 101;
    rg::CaseOutcome o = rg::judge(e, {&a, &b});
    BOOST_TEST(!o.passed);
    BOOST_TEST(o.type == "cycles");
    BOOST_TEST(o.reason == "cycles differ: core 100, tlm 101");

    b = ran("tlm", 100, {{"forward", 2}});
    o = rg::judge(e, {&a, &b});
    BOOST_TEST(o.reason == "phases differ: forward (core 1, tlm 2)");

    b.outcome = eng::Outcome::Cancelled;
    b.has_report = false;
    b.message = "slurm: task 3 of job 9 was cancelled (CANCELLED) while it ran";
    o = rg::judge(e, {&a, &b});
    BOOST_TEST(o.type == "cancelled");
    BOOST_TEST(o.reason == "tlm: slurm: task 3 of job 9 was cancelled (CANCELLED) while it ran");

    o = rg::judge(e, {&a, nullptr});
    BOOST_TEST(o.not_run);
    BOOST_TEST(!o.passed);

    // Expected errors: exit 2 with the message, nothing else.
    rg::Entry err = e;
    err.c.expect_error = true;
    err.c.expect_message = "out of range";
    eng::RunResult i1, i2;
    i1.model = "core";
    i1.outcome = eng::Outcome::InputError;
    i1.exit_code = 2;
    i1.message = "parameter D = 999 is out of range";
    i2 = i1;
    i2.model = "tlm";
    BOOST_TEST(rg::judge(err, {&i1, &i2}).passed);
    i2.message = "something else";
    BOOST_TEST(rg::judge(err, {&i1, &i2}).reason ==
               "tlm: error message \"something else\" lacks \"out of range\"");
    const eng::RunResult ok = ran("tlm", 5);
    BOOST_TEST(rg::judge(err, {&i1, &ok}).reason ==
               "tlm: expected an input error (exit 2), got exit 0");

    // Pinned cycles.
    rg::Entry pin = e;
    pin.c.expect_cycles = 7;
    a = ran("core", 100);
    b = ran("tlm", 100);
    BOOST_TEST(rg::judge(pin, {&a, &b}).reason == "cycles 100, expected 7");
}

BOOST_AUTO_TEST_CASE(junit_counts_and_skips) {
    rg::Plan p;
    p.suite = "quick";
    p.cases_file = "cases.json";
    p.models = {"core"};
    for (int i = 0; i < 3; ++i) {
        rg::Entry e;
        e.c.name = "case<" + std::to_string(i) + ">";
        e.models = {"core"};
        e.jobs = {i};
        p.cases.push_back(e);
        p.jobs.push_back({"j" + std::to_string(i), "core", {"run", "--model", "core"}});
    }
    rg::Result r;
    r.runs = {ran("core", 288878), std::nullopt, ran("core", 2)};
    r.runs[0]->modeled_ms =
        288878 / (40.0 * 1e6) * 1e3;  // as the models compute it: 7.2219500000000005
    r.runs[2]->outcome = eng::Outcome::Mismatch;
    r.runs[2]->bit_exact = false;
    r.runs[2]->differing_pixels = 1;
    for (size_t i = 0; i < 3; ++i) {
        std::vector<const eng::RunResult*> rs = {r.runs[i] ? &*r.runs[i] : nullptr};
        r.outcomes.push_back(rg::judge(p.cases[i], rs));
    }
    r.passed = 1;
    r.not_run = 1;
    r.failed = 1;
    r.interrupted = true;
    const std::string x = rg::junit_xml(p, r, "local, -j 2", false);
    BOOST_TEST(x.find("tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"1\"") !=
               std::string::npos);
    BOOST_TEST(x.find("name=\"case&lt;0&gt;\"") != std::string::npos);
    BOOST_TEST(x.find("<skipped message=\"not run (interrupted)\"/>") != std::string::npos);
    BOOST_TEST(x.find("<failure type=\"mismatch\"") != std::string::npos);
    BOOST_TEST(x.find("value=\"local, -j 2\"") != std::string::npos);
    BOOST_TEST(r.exit_code() == 130);
    const auto s = rg::to_json(p, r, "local");
    BOOST_TEST(s["not_run"] == 1);
    BOOST_TEST(s["cases"][1]["runs"]["core"]["outcome"] == "not-run");
    // No float noise in the JSON.
    BOOST_TEST(s["cases"][0]["modeled_ms"].dump() == "7.22195");
    BOOST_TEST(s["cases"][0]["runs"]["core"]["modeled_ms"].dump() == "7.22195");
    BOOST_TEST(rg::xml_escape(std::string("a\x01&\"")) == "a?&amp;&quot;");
}
