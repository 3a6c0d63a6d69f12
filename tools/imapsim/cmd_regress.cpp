// imapsim regress: the regression suite (docs/regress.md). The engine
// (imap/engine/regress.hpp) runs every case x model as a job `imapsim run`
// on an executor (local cores or a Slurm job array); a case passes when every
// model's run is bit-exact with the golden (or, for an expected-error case,
// is refused with exit 2) and the models agree on cycles and phases. This
// file parses the flags and prints: the table, "N passed, M failed",
// --junit and --json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "engine_cli.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/regress.hpp"
#include "imap/vision/image_io.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace fs = std::filesystem;
namespace eng = imap::engine;
namespace rg = imap::engine::regress;

namespace {

fs::path first_existing(const std::vector<fs::path>& candidates) {
    for (const auto& c : candidates) {
        std::error_code ec;
        if (!c.empty() && fs::exists(c, ec)) return fs::weakly_canonical(c, ec);
    }
    return {};
}

fs::path default_cases(const fs::path& exe_dir) {
    std::vector<fs::path> c;
    // an installed binary's own table first (cmake --install: bin/imapsim
    // beside share/imapsim/regress/cases.json), then the source tree's
    c.push_back(exe_dir / "../share/imapsim/regress/cases.json");
#ifdef IMAP_REGRESS_CASES
    c.emplace_back(IMAP_REGRESS_CASES);
#endif
    c.push_back(exe_dir / "../tests/regress/cases.json");
    return first_existing(c);
}

fs::path default_data(const fs::path& exe_dir) {
    std::vector<fs::path> c;
#ifdef IMAP_SHARED_DATA
    c.emplace_back(fs::path(IMAP_SHARED_DATA) / "middlebury");
#endif
    c.push_back(exe_dir / "../../shared/data/middlebury");
    c.push_back(exe_dir / "../shared/data/middlebury");
    return first_existing(c);
}

// Models built into this binary, from model_names(): "tlm (...), rtl (...,
// ...), core (...)" -- names are split at the commas outside parentheses.
std::vector<std::string> built_models() {
    std::vector<std::string> out;
    const std::string s = model_names() + ",";
    std::string item;
    int depth = 0;
    for (char c : s) {
        if (c == '(') ++depth;
        if (c == ')') --depth;
        if (c == ',' && depth == 0) {
            const auto b = item.find_first_not_of(' ');
            if (b != std::string::npos) {
                const auto e = item.find_first_of(" (", b);
                out.push_back(item.substr(b, e == std::string::npos ? std::string::npos : e - b));
            }
            item.clear();
        } else {
            item += c;
        }
    }
    return out;
}

struct RegressOptions {
    std::string suite = "quick";
    std::string junit, json_out, models, filter, cases, data, work_dir;
    double timeout_s = 600;
    bool list = false;
    ExecFlags exec;
    std::string rtl_cache;  // --rtl-cache
};

}  // namespace

Subcommand register_regress(CLI::App& app) {
    auto o = std::make_shared<RegressOptions>();
    CLI::App* sub = app.add_subcommand(
        "regress",
        "Regression suite: every case x model as a child `imapsim run`, bit-exact vs golden and "
        "cycle agreement between models (docs/regress.md)");
    sub->add_option("--suite", o->suite, "quick (CI, about a minute) or full")
        ->check(CLI::IsMember({"quick", "full"}))
        ->capture_default_str();
    sub->add_option("--junit", o->junit, "write a JUnit XML report here");
    sub->add_option("--json", o->json_out, "write a JSON summary here");
    sub->add_option("--models", o->models,
                    "comma-separated models (golden is implicit; unbuilt models are skipped) "
                    "[default: the suite's models in the case table, of those built: " +
                        model_names() + "]");
    sub->add_option("--filter", o->filter, "only cases whose name contains this substring");
    sub->add_option("--cases", o->cases, "case table (JSON) [default: tests/regress/cases.json]");
    sub->add_option("--data", o->data,
                    "Middlebury data folder (tsukuba/, venus/, ...) [default: the shared data]");
    sub->add_option("--work-dir", o->work_dir, "the same as --run-dir (kept for old scripts)");
    sub->add_option("--timeout", o->timeout_s, "seconds before a child is killed")
        ->capture_default_str();
    sub->add_flag("--list", o->list, "list the selected cases and exit");
    add_exec_flags(sub, o->exec, "runs");
    add_rtl_cache_flag(sub, o->rtl_cache);

    return {
        sub, [o, sub]() {
            apply_rtl_cache_flag(o->rtl_cache);
            check_output_file("--junit", o->junit, false);  // before the suite, not after it
            check_output_file("--json", o->json_out, false);
            if (!o->work_dir.empty()) {
                if (!o->exec.run_dir.empty())
                    throw UserError("--work-dir and --run-dir are the same option: give one");
                o->exec.run_dir = o->work_dir;
            }
            check_exec_flags(o->exec);
            if (!(o->timeout_s >= 0))
                throw UserError("invalid value for --timeout: expected seconds >= 0");
            rg::Plan plan;
            std::unique_ptr<Session> session;
            if (!o->exec.resume.empty()) {
                for (const char* f : {"--suite", "--models", "--filter", "--cases", "--data"})
                    if (const CLI::Option* op = sub->get_option_no_throw(f); op && op->count())
                        throw UserError(std::string(f) +
                                        ": --resume takes the cases from the run folder");
                session =
                    std::make_unique<Session>(resume_session(o->exec, "regress", o->timeout_s));
                plan = rg::plan_from_json(session->manifest.payload);
                plan.jobs = session->manifest.jobs;
            } else {
                const fs::path exe_dir = fs::path(eng::self_exe()).parent_path();
                const fs::path cases_file =
                    o->cases.empty() ? default_cases(exe_dir) : fs::path(o->cases);
                if (cases_file.empty())
                    throw UserError(
                        "cannot find the case table tests/regress/cases.json; pass --cases FILE");
                const rg::CaseTable table = rg::load_cases(cases_file);
                rg::Selection sel;
                sel.suite = o->suite;
                sel.filter = o->filter;
                sel.built = built_models();
                sel.data = o->data.empty() ? default_data(exe_dir) : fs::path(o->data);
                sel.cases_file = cases_file.string();
                if (!o->models.empty()) {
                    std::stringstream ss(o->models);
                    std::string m;
                    while (std::getline(ss, m, ',')) sel.models.push_back(m);
                    if (sel.models.empty())
                        throw UserError("--models '" + o->models + "' names no model");
                }
                plan = rg::plan(table, sel);
                if (o->list) {
                    for (const rg::Entry& e : plan.cases) {
                        std::string ms;
                        for (const auto& m : e.models) ms += (ms.empty() ? "" : ",") + m;
                        std::printf("%-44s %-6s %-14s %s%s%s\n", e.c.name.c_str(),
                                    e.c.suite.c_str(), ms.c_str(),
                                    e.c.scene.empty() ? "" : ("scene " + e.c.scene + " ").c_str(),
                                    eng::command_line(e.c.args).c_str(),
                                    e.c.expect_error ? "  [expect error]" : "");
                    }
                    return static_cast<int>(kExitOk);
                }
                session = std::make_unique<Session>(
                    start_session(o->exec, "regress", rg::to_json(plan), plan.jobs, o->timeout_s));
            }
            for (const std::string& n : plan.notes)
                std::fprintf(stderr, "imapsim regress: %s\n", n.c_str());
            std::vector<std::string> head = rg::header_lines(plan, session->executor.get());
            if (!session->dir->temporary())
                head.insert(head.end() - 1, "  run folder " + session->dir->path().string());
            for (const std::string& l : head) std::printf("%s\n", l.c_str());
            std::fflush(stdout);

            interrupt::install();
            Printer pr("cases", plan.cases.size());
            rg::Hooks h;
            h.stop_requested = [] { return interrupt::requested(); };
            h.row = [&](const std::string& l) { pr.row(l); };
            h.note = [&](const std::string& l) { pr.note(l); };
            h.status = [&](const std::string& l) { pr.status(l); };
            const rg::Result r = rg::run(plan, *session->executor, *session->dir, session->manifest,
                                         session->ctx, h, session->resume);
            pr.progress.finish();

            // The run folder stays when a case failed, on --keep, --run-dir or
            // an interrupt; the reports name log files only when it stays.
            const bool keep = r.failed > 0 || o->exec.keep;
            const bool kept = session->dir->temporary() ? keep || r.interrupted : true;
            for (const std::string& l : rg::failure_lines(plan, r, kept))
                std::printf("%s\n", l.c_str());
            const std::string ex = session->executor->describe();
            if (!o->junit.empty())
                imap::vision::write_text_atomic(o->junit, rg::junit_xml(plan, r, ex, kept));
            if (!o->json_out.empty())
                imap::vision::write_text_atomic(o->json_out,
                                                rg::to_json(plan, r, ex).dump(2) + "\n");
            if (r.interrupted)
                std::printf("imapsim regress: interrupted (signal %d): partial results\n",
                            interrupt::signal_number());
            finish_session(*session, keep, r.interrupted);
            for (const std::string& l : rg::summary_lines(plan, r)) std::printf("%s\n", l.c_str());
            std::fflush(stdout);
            return r.exit_code();
        }};
}

}  // namespace imapsim
