// imapsim regress from the outside: the quick suite passes with a valid JUnit
// report, --filter selects one case, and failing cases (a case table with
// impossible expectations) are reported with exit 1 and <failure> elements.
#define BOOST_TEST_MODULE cli_regress
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

namespace {

// The models the edge cases run on: all of the suite's by default.
#ifdef IMAP_TEST_REGRESS_MODELS
constexpr const char* kModels = IMAP_TEST_REGRESS_MODELS;
#else
constexpr const char* kModels = "";
#endif

using clitest::Result;
using clitest::run;

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imapsim-cli-regress-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// Removes the temp folder when the test program ends.
struct TmpCleanup {
    ~TmpCleanup() {
        std::error_code ec;
        fs::remove_all(
            fs::temp_directory_path() / ("imapsim-cli-regress-" + std::to_string(::getpid())), ec);
    }
} tmp_cleanup;

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t pos = s.find(what); pos != std::string::npos; pos = s.find(what, pos + 1)) ++n;
    return n;
}

// The last non-empty line of the output.
std::string last_line(const std::string& out) {
    std::string s = out;
    while (!s.empty() && s.back() == '\n') s.pop_back();
    const auto nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
}

// Value of attribute `attr` of the first element `<tag ` in the XML text.
std::string attr_of(const std::string& xml, const std::string& tag, const std::string& attr) {
    const auto t = xml.find("<" + tag + " ");
    if (t == std::string::npos) return "";
    const auto end = xml.find('>', t);
    const auto a = xml.find(" " + attr + "=\"", t);
    if (a == std::string::npos || a > end) return "";
    const auto b = a + attr.size() + 3;
    return xml.substr(b, xml.find('"', b) - b);
}

}  // namespace

// The whole quick suite runs as its own CTest entry (regress.quick); here a
// slice of it (the edge cases, every model) proves the reports.
BOOST_AUTO_TEST_CASE(quick_suite_passes_with_junit_and_json) {
    const fs::path d = tmpdir();
    const fs::path xml = d / "quick.xml", js = d / "quick.json";
    const Result r = run("regress --suite quick --filter edge- -j 2 " + std::string(kModels) +
                         "--junit " + xml.string() + " --json " + js.string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    const nlohmann::json s = nlohmann::json::parse(slurp(js));
    const size_t n = s["cases"].size();
    BOOST_TEST(n >= 8u);
    BOOST_TEST(s["passed"].get<size_t>() == n);
    BOOST_TEST(s["failed"].get<size_t>() == 0u);
    BOOST_TEST(last_line(r.out) == std::to_string(n) + " passed, 0 failed");

    const std::string x = slurp(xml);
    BOOST_TEST(x.rfind("<?xml version=\"1.0\"", 0) == 0u);
    BOOST_TEST(attr_of(x, "testsuite", "tests") == std::to_string(n));
    BOOST_TEST(attr_of(x, "testsuite", "failures") == "0");
    BOOST_TEST(attr_of(x, "testsuites", "tests") == std::to_string(n));
    BOOST_TEST(count(x, "<testcase ") == n);
    BOOST_TEST(count(x, "</testcase>") == n);
    BOOST_TEST(count(x, "<failure") == 0u);
    BOOST_TEST(x.find("</testsuites>") != std::string::npos);
    // Every model that ran agrees on the cycles (a case reports one number).
    for (const auto& c : s["cases"]) {
        BOOST_TEST_CONTEXT(c["name"]) {
            BOOST_TEST(!c["runs"].empty());
            for (const auto& [model, run] : c["runs"].items())
                if (c["expect"] == "pass") BOOST_TEST(run["cycles"] == c["cycles"]);
        }
    }
}

BOOST_AUTO_TEST_CASE(filter_selects_one_case) {
    const fs::path d = tmpdir();
    const fs::path xml = d / "one.xml";
    const Result r = run("regress --filter edge-pes8 --models core --junit " + xml.string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(last_line(r.out) == "1 passed, 0 failed");
    const std::string x = slurp(xml);
    BOOST_TEST(attr_of(x, "testsuite", "tests") == "1");
    BOOST_TEST(count(x, "<testcase ") == 1u);
    BOOST_TEST(x.find("name=\"edge-pes8\"") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(failing_cases_are_reported) {
    const fs::path d = tmpdir();
    const fs::path cases = d / "bad-cases.json", xml = d / "bad.xml", js = d / "bad.json";
    std::ofstream(cases) << R"({
  // one good case and three that must fail, each for its own reason
  "cases": [
    {"name": "good", "suite": "quick", "args": ["--size", "32x16", "--D", "8"]},
    {"name": "wrong-cycles", "suite": "quick", "args": ["--size", "32x16", "--D", "8"],
     "expect_cycles": 1},
    {"name": "error-not-raised", "suite": "quick", "expect": "error",
     "args": ["--size", "32x16", "--D", "8"]},
    {"name": "unexpected-input-error", "suite": "full", "args": ["--size", "32x16", "--D", "99"]}
  ]
})";
    const Result r =
        run("regress --suite full -j 2 --cases " + cases.string() + " --junit " + xml.string() +
            " --json " + js.string() + " --work-dir " + (d / "work").string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 1);
    BOOST_TEST(last_line(r.out) == "1 passed, 3 failed");
    const std::string x = slurp(xml);
    BOOST_TEST(attr_of(x, "testsuite", "tests") == "4");
    BOOST_TEST(attr_of(x, "testsuite", "failures") == "3");
    BOOST_TEST(count(x, "<failure ") == 3u);
    BOOST_TEST(x.find("expected 1") != std::string::npos);
    BOOST_TEST(x.find("expected an input error (exit 2), got exit 0") != std::string::npos);
    BOOST_TEST(x.find("input error (exit 2): parameter D = 99") != std::string::npos);
    const nlohmann::json s = nlohmann::json::parse(slurp(js));
    BOOST_TEST(s["failed"] == 3);
    BOOST_TEST(s["cases"][0]["passed"] == true);
    BOOST_TEST(s["cases"][1]["passed"] == false);

    // --suite quick leaves the full-only case out.
    const Result q = run("regress --suite quick --cases " + cases.string() + " --work-dir " +
                         (d / "work-quick").string());
    BOOST_TEST_INFO(q.out);
    BOOST_TEST(q.code == 1);
    BOOST_TEST(last_line(q.out) == "1 passed, 2 failed");
    // The failing run's log is kept and named in the report.
    BOOST_TEST(fs::exists(d / "work"));
    BOOST_TEST(x.find((d / "work").string()) != std::string::npos);
}

// A passing suite with a temporary run folder removes it: then neither the
// output nor the JUnit report may name anything in it (issue: the report
// pointed at logs that were deleted).
BOOST_AUTO_TEST_CASE(reports_name_only_what_is_kept) {
    const fs::path d = tmpdir();
    const fs::path xml = d / "kept.xml", js = d / "kept.json";
    const Result r = run("regress --filter edge-pes8 --models core --junit " + xml.string() +
                         " --json " + js.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    const std::string tmp = (fs::temp_directory_path() / "imapsim-regress-").string();
    for (const std::string& text : {r.out, slurp(xml), slurp(js)}) {
        for (size_t p = text.find(tmp); p != std::string::npos; p = text.find(tmp, p + 1)) {
            const size_t e = text.find_first_of(" \n\"<'", p);
            const std::string path = text.substr(p, e == std::string::npos ? e : e - p);
            BOOST_TEST_INFO("named: " << path);
            BOOST_TEST(fs::exists(path));
        }
    }
    // The reproduction command is in the report: it runs as it stands.
    const nlohmann::json s = nlohmann::json::parse(slurp(js));
    const std::string cmd = s["cases"][0]["runs"]["core"]["command"].get<std::string>();
    BOOST_TEST(cmd.find("--report") == std::string::npos);
    BOOST_TEST(cmd.find(" run --model core") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(missing_scene_data_fails_the_case) {
    const fs::path d = tmpdir();
    const Result r =
        run("regress --filter mb-tsukuba-roi --models core --data /nonexistent-dir "
            "--work-dir " +
            (d / "work-nodata").string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 1);
    BOOST_TEST(r.out.find("scene tsukuba not found") != std::string::npos);
    BOOST_TEST(last_line(r.out) == "0 passed, 1 failed");
}

BOOST_AUTO_TEST_CASE(bad_flags_are_input_errors) {
    Result r = run("regress --models core,nosuchmodel");
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("nosuchmodel") != std::string::npos);
    r = run("regress --filter no-case-has-this-name");
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("no case") != std::string::npos);
    r = run("regress --cases /nonexistent/cases.json");
    BOOST_TEST(r.code == 2);
    r = run("regress --suite huge");
    BOOST_TEST(r.code == 2);
}

BOOST_AUTO_TEST_CASE(list_shows_the_cases) {
    const Result r = run("regress --suite full --list");
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(r.out.find("edge-pes320") != std::string::npos);
    BOOST_TEST(r.out.find("mb-whole-teddy") != std::string::npos);
    BOOST_TEST(r.out.find("[expect error]") != std::string::npos);
}
