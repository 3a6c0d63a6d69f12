// The regression suite of `imapsim regress` (docs/regress.md): a case table
// (JSON) of `imapsim run` argument sets, each run on every selected model as
// a job; a case passes when every model's run is bit-exact with the golden
// (or, for an expected-error case, is refused with exit 2) and the models
// agree on cycles and phases. Which models a suite runs is data: the case
// table's "suites" entry, intersected with the models built.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "imap/engine/executor.hpp"
#include "imap/engine/result.hpp"
#include "imap/engine/run_dir.hpp"

namespace imap::engine::regress {

struct Case {
    std::string name;
    std::string suite = "full";  // "quick" or "full" (quick cases also run in full)
    std::string scene;           // Middlebury folder under the data folder, or empty (synthetic)
    std::vector<std::string> args;
    std::vector<std::string> models;  // empty: every selected model
    bool expect_error = false;
    std::string expect_message;
    std::optional<unsigned long long> expect_cycles;
};

struct CaseTable {
    std::vector<Case> cases;
    // "suites": {"quick": {"models": [...]}, "full": {...}}: the models each
    // suite runs by default (empty map: core, tlm, rtl).
    std::map<std::string, std::vector<std::string>> suite_models;
};

// Parses a case table; a case with a "matrix" expands into one case per
// combination of the listed flag values. engine::Error naming the file and
// the case for anything malformed.
CaseTable load_cases(const std::filesystem::path& file);

struct Selection {
    std::string suite = "quick";
    std::string filter;               // substring of the case name
    std::vector<std::string> models;  // --models (empty: the suite's)
    std::vector<std::string> built;   // models this imapsim has
    std::filesystem::path data;       // Middlebury data folder (may be empty)
    std::string cases_file;           // for the reports
};

struct Entry {
    Case c;
    std::vector<std::string> models;  // the models it runs
    std::vector<int> jobs;            // indices into Plan::jobs, one per model
    std::string error;                // set up failure (scene missing, no model): fails the case
};

struct Plan {
    std::string suite, cases_file;
    std::vector<std::string> models;  // selected, in run order
    std::vector<std::string> notes;   // "model rtl is not in this build, skipped"
    std::vector<Entry> cases;
    std::vector<Job> jobs;
};

// Selects the cases and builds the jobs. engine::Error when nothing is
// selected or a model name is unknown.
Plan plan(const CaseTable& t, const Selection& s);

nlohmann::json to_json(const Plan& p);
Plan plan_from_json(const nlohmann::json& j);  // jobs come from the manifest

struct CaseOutcome {
    bool passed = true;
    bool not_run = false;  // interrupted before every model had run
    std::string reason;    // "; "-joined reasons of the failure
    std::string type;      // JUnit failure type (mismatch, cycles, timeout, cancelled, ...)
    unsigned long long cycles = 0;
    double modeled_ms = 0, wall_s = 0;
    bool have_cycles = false;
};

// Judges one case from its models' results (nullptr: the run did not finish).
CaseOutcome judge(const Entry& e, const std::vector<const RunResult*>& runs);

struct Result {
    std::vector<CaseOutcome> outcomes;           // per case
    std::vector<std::optional<RunResult>> runs;  // per job
    size_t passed = 0, failed = 0, not_run = 0, reused = 0;
    bool interrupted = false;
    double wall_s = 0;
    // 130 interrupted, 1 if a case failed, else 0.
    int exit_code() const;
};

struct Hooks {
    std::function<bool()> stop_requested = [] { return false; };
    std::function<void(const std::string&)> row = [](const std::string&) {};
    std::function<void(const std::string&)> note = [](const std::string&) {};
    std::function<void(const std::string&)> status = [](const std::string&) {};
};

std::vector<std::string> header_lines(const Plan& p, const Executor* ex);
std::string row_line(const Plan& p, size_t i, const CaseOutcome& o);

// Runs the plan's jobs (resume: only those without a definitive result),
// judges each case when its last model finishes and prints its row in case
// order.
Result run(const Plan& p, Executor& ex, RunDir& dir, Manifest& m, const ExecContext& ctx,
           Hooks& hooks, bool resume);

// The failure details (per failed case: reason, each model's command and
// log) and the summary lines ("N passed, M failed" last).
std::vector<std::string> failure_lines(const Plan& p, const Result& r, bool logs_kept);
std::vector<std::string> summary_lines(const Plan& p, const Result& r);

// JUnit XML: one testcase per case, <failure> with the reason and the
// logs' last lines, <skipped> for cases an interrupt left unrun. Log files
// are named only when `logs_kept` (the run folder stays).
std::string junit_xml(const Plan& p, const Result& r, const std::string& executor, bool logs_kept);
nlohmann::json to_json(const Plan& p, const Result& r, const std::string& executor);

std::string xml_escape(const std::string& s);

}  // namespace imap::engine::regress
