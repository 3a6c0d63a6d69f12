#include "imap/engine/regress.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/values.hpp"

namespace imap::engine::regress {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- the case table --------------------------------------------------------

namespace {

const std::vector<std::string> kDefaultModels = {"core", "tlm", "rtl"};

template <class J>
std::vector<std::string> string_list(const J& j, const std::string& what) {
    std::vector<std::string> v;
    if (!j.is_array()) throw Error(what + ": expected an array of strings");
    for (const auto& e : j) {
        if (!e.is_string()) throw Error(what + ": expected an array of strings");
        v.push_back(e.template get<std::string>());
    }
    return v;
}

CaseTable load_cases_impl(const fs::path& file) {
    nlohmann::ordered_json doc;
    const std::string where = "case table " + file.string();
    std::string text;
    try {
        text = read_text_file(file);
    } catch (const Error&) {
        throw Error("cannot read case table " + file.string());
    }
    try {
        doc = nlohmann::ordered_json::parse(text, nullptr, true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": " + e.what());
    }
    if (!doc.is_object() || !doc.contains("cases") || !doc["cases"].is_array())
        throw Error(where + ": expected {\"cases\": [...]}");
    CaseTable t;
    for (const auto& [k, v] : doc.items()) {
        if (k == "cases") continue;
        if (k != "suites") throw Error(where + ": unknown key \"" + k + "\"");
        if (!v.is_object()) throw Error(where + ": suites must be an object");
        for (const auto& [suite, s] : v.items()) {
            if (suite != "quick" && suite != "full")
                throw Error(where + ": suite " + suite + " is not quick or full");
            if (!s.is_object() || !s.contains("models"))
                throw Error(where + ": suites." + suite + " needs \"models\"");
            t.suite_models[suite] =
                string_list(s["models"], where + ": suites." + suite + ".models");
        }
    }
    for (const auto& c : doc["cases"]) {
        if (!c.is_object() || !c.contains("name") || !c["name"].is_string())
            throw Error(where + ": every case needs a \"name\"");
        Case base;
        base.name = c["name"].get<std::string>();
        const std::string ctx = where + ", case " + base.name;
        for (const auto& [k, v] : c.items()) {
            if (k == "name" || k == "matrix" || k == "note") continue;
            if (k == "suite") {
                base.suite = v.get<std::string>();
                if (base.suite != "quick" && base.suite != "full")
                    throw Error(ctx + ": suite must be quick or full");
            } else if (k == "scene") {
                base.scene = v.get<std::string>();
            } else if (k == "args") {
                base.args = string_list(v, ctx + ": args");
            } else if (k == "models") {
                base.models = string_list(v, ctx + ": models");
            } else if (k == "expect") {
                const std::string e = v.get<std::string>();
                if (e != "pass" && e != "error")
                    throw Error(ctx + ": expect must be pass or error");
                base.expect_error = e == "error";
            } else if (k == "expect_message") {
                base.expect_message = v.get<std::string>();
            } else if (k == "expect_cycles") {
                base.expect_cycles = v.get<unsigned long long>();
            } else {
                throw Error(ctx + ": unknown key \"" + k + "\"");
            }
        }
        std::vector<Case> expanded = {base};
        if (c.contains("matrix")) {
            if (!c["matrix"].is_object()) throw Error(ctx + ": matrix must be an object");
            bool first = true;
            for (const auto& [flag, values] : c["matrix"].items()) {
                const auto vals = string_list(values, ctx + ": matrix " + flag);
                std::vector<Case> next;
                for (const Case& e : expanded)
                    for (const auto& val : vals) {
                        Case n = e;
                        n.name += (first ? "/" : ",") + flag.substr(flag.find_first_not_of('-')) +
                                  "=" + val;
                        n.args.push_back(flag);
                        n.args.push_back(val);
                        next.push_back(std::move(n));
                    }
                expanded = std::move(next);
                first = false;
            }
        }
        for (auto& e : expanded) t.cases.push_back(std::move(e));
    }
    std::map<std::string, int> seen;
    for (const Case& c : t.cases)
        if (seen[c.name]++) throw Error(where + ": duplicate case " + c.name);
    return t;
}

std::string safe_name(const std::string& name) {
    std::string s;
    for (char ch : name)
        s += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.' ? ch : '_';
    if (s.size() > 80) s.resize(80);
    return s;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

CaseTable load_cases(const fs::path& file) {
    try {
        return load_cases_impl(file);
    } catch (const nlohmann::json::exception& e) {  // a value of the wrong type
        throw Error("case table " + file.string() + ": " + e.what());
    }
}

// ---- the plan --------------------------------------------------------------

Plan plan(const CaseTable& t, const Selection& s) {
    Plan p;
    p.suite = s.suite;
    p.cases_file = s.cases_file;
    // Models: the suite's list (data) or --models, each one built here.
    std::vector<std::string> known = kDefaultModels;
    for (const auto& [suite, ms] : t.suite_models)
        for (const auto& m : ms)
            if (!contains(known, m)) known.push_back(m);
    std::vector<std::string> wanted = s.models;
    if (wanted.empty()) {
        const auto it = t.suite_models.find(s.suite);
        wanted = it != t.suite_models.end() ? it->second : kDefaultModels;
    }
    for (const std::string& m : wanted) {
        if (m.empty() || m == "golden") continue;  // golden: implicit in every run
        if (contains(s.built, m)) {
            if (!contains(p.models, m)) p.models.push_back(m);
        } else if (contains(known, m)) {
            p.notes.push_back("model " + m + " is not in this build, skipped");
        } else {
            std::string b;
            for (const auto& x : s.built) b += ", " + x;
            throw Error("invalid value '" + m +
                        "' for --models: expected a comma-separated list "
                        "of golden" +
                        b);
        }
    }
    if (p.models.empty()) {
        std::string b;
        for (const auto& x : s.built) b += (b.empty() ? "" : ", ") + x;
        throw Error("the selected models (" + command_line(wanted) +
                    ") include none built here (built: " + b + ")");
    }

    for (const Case& c : t.cases)
        if ((s.suite == "full" || c.suite == "quick") && c.name.find(s.filter) != std::string::npos)
            p.cases.push_back({c, {}, {}, ""});
    if (p.cases.empty())
        throw Error("no case of suite " + s.suite +
                    (s.filter.empty() ? "" : " matches --filter '" + s.filter + "'") + " in " +
                    s.cases_file);

    for (size_t i = 0; i < p.cases.size(); ++i) {
        Entry& e = p.cases[i];
        for (const auto& m : p.models)
            if (e.c.models.empty() || contains(e.c.models, m)) e.models.push_back(m);
        std::vector<std::string> scene_args;
        if (!e.c.scene.empty()) {
            const fs::path l = s.data / e.c.scene / "left.png",
                           r = s.data / e.c.scene / "right.png";
            std::error_code ec;
            if (s.data.empty() || !fs::exists(l, ec) || !fs::exists(r, ec)) {
                e.error = "scene " + e.c.scene + " not found under " +
                          (s.data.empty() ? std::string("(no data folder)") : s.data.string()) +
                          " (pass --data DIR)";
                continue;
            }
            scene_args = {"--left", l.string(), "--right", r.string()};
        }
        if (e.models.empty()) {
            e.error =
                "none of the case's models (" + command_line(e.c.models) + ") is selected or built";
            continue;
        }
        char idx[32];
        std::snprintf(idx, sizeof idx, "c%04zu-", i);
        for (const auto& m : e.models) {
            Job j;
            j.id = idx + safe_name(e.c.name) + "." + m;
            j.model = m;
            j.args = {"run", "--model", m};
            j.args.insert(j.args.end(), scene_args.begin(), scene_args.end());
            j.args.insert(j.args.end(), e.c.args.begin(), e.c.args.end());
            e.jobs.push_back(static_cast<int>(p.jobs.size()));
            p.jobs.push_back(std::move(j));
        }
    }
    return p;
}

json to_json(const Plan& p) {
    json j;
    j["kind"] = "regress-plan";
    j["suite"] = p.suite;
    j["cases_file"] = p.cases_file;
    j["models"] = p.models;
    j["notes"] = p.notes;
    json cs = json::array();
    for (const Entry& e : p.cases) {
        json c = {{"name", e.c.name},
                  {"suite", e.c.suite},
                  {"scene", e.c.scene},
                  {"args", e.c.args},
                  {"case_models", e.c.models},
                  {"expect_error", e.c.expect_error},
                  {"expect_message", e.c.expect_message},
                  {"models", e.models},
                  {"jobs", e.jobs},
                  {"error", e.error}};
        if (e.c.expect_cycles) c["expect_cycles"] = *e.c.expect_cycles;
        cs.push_back(c);
    }
    j["cases"] = cs;
    return j;
}

Plan plan_from_json(const json& j) {
    try {
        if (j.value("kind", std::string()) != "regress-plan")
            throw Error(
                "the run folder does not hold a regression (its plan is of another command)");
        Plan p;
        p.suite = j.at("suite").get<std::string>();
        p.cases_file = j.at("cases_file").get<std::string>();
        p.models = j.at("models").get<std::vector<std::string>>();
        p.notes = j.value("notes", std::vector<std::string>());
        for (const json& c : j.at("cases")) {
            Entry e;
            e.c.name = c.at("name").get<std::string>();
            e.c.suite = c.at("suite").get<std::string>();
            e.c.scene = c.at("scene").get<std::string>();
            e.c.args = c.at("args").get<std::vector<std::string>>();
            e.c.models = c.at("case_models").get<std::vector<std::string>>();
            e.c.expect_error = c.at("expect_error").get<bool>();
            e.c.expect_message = c.at("expect_message").get<std::string>();
            if (c.contains("expect_cycles"))
                e.c.expect_cycles = c["expect_cycles"].get<unsigned long long>();
            e.models = c.at("models").get<std::vector<std::string>>();
            e.jobs = c.at("jobs").get<std::vector<int>>();
            e.error = c.at("error").get<std::string>();
            p.cases.push_back(std::move(e));
        }
        return p;
    } catch (const json::exception& e) {
        throw Error(std::string("regression plan: ") + e.what());
    }
}

// ---- judging ---------------------------------------------------------------

namespace {

void fail(CaseOutcome& o, const std::string& type, const std::string& why) {
    if (o.passed) o.type = type;
    o.passed = false;
    o.reason += (o.reason.empty() ? "" : "; ") + why;
}

std::map<std::string, uint64_t> phase_map(const RunResult& r) {
    return {r.phases.begin(), r.phases.end()};
}

}  // namespace

CaseOutcome judge(const Entry& e, const std::vector<const RunResult*>& runs) {
    CaseOutcome o;
    if (!e.error.empty()) {
        fail(o, "input-error", e.error);
        return o;
    }
    for (size_t k = 0; k < runs.size(); ++k)
        if (!runs[k]) {
            o.not_run = true;
            o.passed = false;
            o.type = "not-run";
            o.reason = "not run (interrupted)";
        }
    if (o.not_run) {
        for (const RunResult* r : runs)
            if (r) o.wall_s += r->wall_s;
        return o;
    }
    const Case& c = e.c;
    for (size_t k = 0; k < runs.size(); ++k) {
        const RunResult& r = *runs[k];
        o.wall_s += r.wall_s;
        const std::string m = e.models[k] + ": ";
        switch (r.outcome) {
            case Outcome::TimedOut:
                fail(o, "timeout", m + describe(r));
                continue;
            case Outcome::Cancelled:
                fail(o, "cancelled", m + describe(r));
                continue;
            case Outcome::Interrupted:
                fail(o, "interrupted", m + describe(r));
                continue;
            case Outcome::Crashed:
                fail(o, "crash", m + describe(r));
                continue;
            default:
                break;
        }
        if (c.expect_error) {
            if (r.outcome != Outcome::InputError) {
                fail(o, "expected-error",
                     m + "expected an input error (exit 2), got " +
                         (r.exit_code >= 0 ? "exit " + std::to_string(r.exit_code) : describe(r)));
            } else if (!c.expect_message.empty() &&
                       r.message.find(c.expect_message) == std::string::npos) {
                fail(o, "expected-error",
                     m + "error message \"" + r.message + "\" lacks \"" + c.expect_message + "\"");
            }
            continue;
        }
        switch (r.outcome) {
            case Outcome::Ok:
                break;
            case Outcome::Mismatch:
                fail(o, "mismatch", m + describe(r));
                break;
            case Outcome::InputError:
                fail(o, "input-error", m + describe(r));
                break;
            case Outcome::Fault:
                fail(o, "fault", m + describe(r));
                break;
            default:
                fail(o, "error", m + describe(r));
        }
    }
    if (c.expect_error) return o;
    // Cross-model agreement on cycles and phases.
    const RunResult* ref = nullptr;
    std::string ref_model;
    for (size_t k = 0; k < runs.size(); ++k) {
        const RunResult& r = *runs[k];
        if (!r.has_report) continue;
        if (!ref) {
            ref = &r;
            ref_model = e.models[k];
            o.cycles = r.cycles;
            o.modeled_ms = r.modeled_ms;
            o.have_cycles = true;
            continue;
        }
        if (r.cycles != o.cycles)
            fail(o, "cycles",
                 "cycles differ: " + ref_model + " " + std::to_string(o.cycles) + ", " +
                     e.models[k] + " " + std::to_string(r.cycles));
        const auto pa = phase_map(*ref), pb = phase_map(r);
        if (pa != pb) {
            std::string which;
            for (const auto& [n, v] : pa) {
                const auto it = pb.find(n);
                if (it == pb.end() || it->second != v)
                    which += " " + n + " (" + ref_model + " " + std::to_string(v) + ", " +
                             e.models[k] + " " +
                             (it == pb.end() ? std::string("absent") : std::to_string(it->second)) +
                             ")";
            }
            for (const auto& [n, v] : pb)
                if (!pa.count(n)) which += " " + n + " (" + ref_model + " absent)";
            fail(o, "cycles", "phases differ:" + which);
        }
    }
    if (o.passed && c.expect_cycles && o.have_cycles && o.cycles != *c.expect_cycles)
        fail(o, "cycles",
             "cycles " + std::to_string(o.cycles) + ", expected " +
                 std::to_string(*c.expect_cycles));
    return o;
}

int Result::exit_code() const {
    if (interrupted) return kExitInterrupted;
    return failed ? kExitMismatch : kExitOk;
}

// ---- running ---------------------------------------------------------------

std::vector<std::string> header_lines(const Plan& p, const Executor* ex) {
    std::string ms;
    for (const auto& m : p.models) ms += (ms.empty() ? "" : ",") + m;
    char b[1024];
    std::snprintf(b, sizeof b, "imapsim regress: suite %s, %zu case%s, %zu run%s, models %s%s",
                  p.suite.c_str(), p.cases.size(), p.cases.size() == 1 ? "" : "s", p.jobs.size(),
                  p.jobs.size() == 1 ? "" : "s", ms.c_str(),
                  ex ? (", " + ex->describe()).c_str() : "");
    std::vector<std::string> out = {b, "  cases " + p.cases_file};
    for (const auto& n : p.notes) out.push_back("  note: " + n);
    std::snprintf(b, sizeof b, "%-44s %-14s %10s %10s %8s  %s", "case", "models", "cycles",
                  "modeled ms", "wall s", "result");
    out.push_back(b);
    return out;
}

std::string row_line(const Plan& p, size_t i, const CaseOutcome& o) {
    std::string cm;
    for (const auto& m : p.cases[i].models) cm += (cm.empty() ? "" : ",") + m;
    if (!p.cases[i].error.empty()) cm.clear();
    char b[4096];
    std::snprintf(b, sizeof b, "%-44s %-14s %10s %10s %8.2f  %s%s", p.cases[i].c.name.c_str(),
                  cm.empty() ? "-" : cm.c_str(),
                  o.have_cycles ? std::to_string(o.cycles).c_str() : "-",
                  o.have_cycles ? fmt("%.3f", o.modeled_ms).c_str() : "-", o.wall_s,
                  o.not_run  ? "NOT RUN (interrupted)"
                  : o.passed ? (p.cases[i].c.expect_error ? "PASS (error expected)" : "PASS")
                             : "FAIL: ",
                  o.passed || o.not_run ? "" : o.reason.c_str());
    return b;
}

Result run(const Plan& p, Executor& ex, RunDir& dir, Manifest& m, const ExecContext& ctx,
           Hooks& hooks, bool resume) {
    Result res;
    res.outcomes.resize(p.cases.size());
    res.runs.resize(p.jobs.size());
    std::vector<int> case_of(p.jobs.size(), -1);
    for (size_t i = 0; i < p.cases.size(); ++i)
        for (int j : p.cases[i].jobs) case_of[static_cast<size_t>(j)] = static_cast<int>(i);
    std::vector<bool> done(p.cases.size(), false);
    size_t printed = 0;
    auto judge_case = [&](size_t i) {
        std::vector<const RunResult*> rs;
        for (int j : p.cases[i].jobs) {
            const auto& r = res.runs[static_cast<size_t>(j)];
            rs.push_back(r ? &*r : nullptr);
        }
        res.outcomes[i] = judge(p.cases[i], rs);
    };
    auto complete = [&](size_t i) {
        for (int j : p.cases[i].jobs)
            if (!res.runs[static_cast<size_t>(j)]) return false;
        return true;
    };
    auto flush = [&]() {
        while (printed < p.cases.size() && done[printed]) {
            hooks.row(row_line(p, printed, res.outcomes[printed]));
            ++printed;
        }
    };
    for (size_t i = 0; i < p.cases.size(); ++i)
        if (p.cases[i].jobs.empty()) {
            judge_case(i);
            done[i] = true;
        }
    flush();
    ExecHooks eh;
    eh.stop_requested = hooks.stop_requested;
    eh.on_note = hooks.note;
    eh.on_status = hooks.status;
    eh.on_result = [&](size_t j, RunResult r) {
        res.runs[j] = std::move(r);
        const int c = case_of[j];
        if (c < 0) return;
        const size_t i = static_cast<size_t>(c);
        if (!done[i] && complete(i)) {
            judge_case(i);
            done[i] = true;
            flush();
        }
    };
    DriveOutcome d;
    if (!p.jobs.empty()) d = drive(dir, m, ex, ctx, eh, resume);
    res.interrupted = d.interrupted;
    res.reused = d.reused;
    res.wall_s = d.wall_s;
    for (size_t i = 0; i < p.cases.size(); ++i)
        if (!done[i]) {
            judge_case(i);  // not run: a job has no result
            done[i] = true;
        }
    flush();
    for (const CaseOutcome& o : res.outcomes) {
        if (o.not_run)
            ++res.not_run;
        else if (o.passed)
            ++res.passed;
        else
            ++res.failed;
    }
    if (res.not_run) res.interrupted = true;
    return res;
}

std::vector<std::string> failure_lines(const Plan& p, const Result& r, bool logs_kept) {
    std::vector<std::string> out;
    if (!r.failed) return out;
    out.push_back("");
    out.push_back("failures:");
    for (size_t i = 0; i < p.cases.size(); ++i) {
        const CaseOutcome& o = r.outcomes[i];
        if (o.passed || o.not_run) continue;
        out.push_back("  " + p.cases[i].c.name + ": " + o.reason);
        for (int j : p.cases[i].jobs) {
            const auto& run = r.runs[static_cast<size_t>(j)];
            if (!run) continue;
            out.push_back("    " + run->model + ": " + run->command);
            if (logs_kept && !run->log.empty()) out.push_back("      log " + run->log);
        }
    }
    return out;
}

std::vector<std::string> summary_lines(const Plan&, const Result& r) {
    std::vector<std::string> out;
    char b[256];
    std::snprintf(b, sizeof b, "total wall %.1f s", r.wall_s);
    out.push_back(b);
    if (r.reused) out.push_back(std::to_string(r.reused) + " run(s) taken from the run folder");
    if (r.not_run) out.push_back(std::to_string(r.not_run) + " case(s) not run (interrupted)");
    std::snprintf(b, sizeof b, "%zu passed, %zu failed", r.passed, r.failed);
    out.push_back(b);
    return out;
}

std::string xml_escape(const std::string& s) {
    std::string o;
    for (unsigned char c : s) {
        switch (c) {
            case '&':
                o += "&amp;";
                break;
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '"':
                o += "&quot;";
                break;
            case '\'':
                o += "&apos;";
                break;
            default:
                if (c < 0x20 && c != '\n' && c != '\t' && c != '\r')
                    o += '?';  // not allowed in XML 1.0
                else
                    o += static_cast<char>(c);
        }
    }
    return o;
}

std::string junit_xml(const Plan& p, const Result& r, const std::string& executor, bool logs_kept) {
    std::string ms;
    for (const auto& m : p.models) ms += (ms.empty() ? "" : ",") + m;
    std::ostringstream x;
    const size_t n = p.cases.size();
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    x << "<testsuites name=\"imapsim regress\" tests=\"" << n << "\" failures=\"" << r.failed
      << "\" errors=\"0\" skipped=\"" << r.not_run << "\" time=\"" << fmt("%.3f", r.wall_s)
      << "\">\n";
    x << "  <testsuite name=\"regress." << p.suite << "\" tests=\"" << n << "\" failures=\""
      << r.failed << "\" errors=\"0\" skipped=\"" << r.not_run << "\" time=\""
      << fmt("%.3f", r.wall_s) << "\" timestamp=\"" << iso_now() << "\">\n";
    x << "    <properties>\n      <property name=\"models\" value=\"" << xml_escape(ms)
      << "\"/>\n      <property name=\"cases\" value=\"" << xml_escape(p.cases_file)
      << "\"/>\n      <property name=\"executor\" value=\"" << xml_escape(executor)
      << "\"/>\n    </properties>\n";
    for (size_t i = 0; i < n; ++i) {
        const CaseOutcome& o = r.outcomes[i];
        x << "    <testcase classname=\"regress." << p.suite << "\" name=\""
          << xml_escape(p.cases[i].c.name) << "\" time=\"" << fmt("%.3f", o.wall_s) << "\">\n";
        std::string out;
        for (int j : p.cases[i].jobs) {
            const auto& run = r.runs[static_cast<size_t>(j)];
            const Job& job = p.jobs[static_cast<size_t>(j)];
            out += "$ " + (run && !run->command.empty() ? run->command : command_line(job.args)) +
                   "\n";
            if (!run) {
                out += "not run\n";
                continue;
            }
            out += run->exit_code >= 0 ? "exit " + std::to_string(run->exit_code) : describe(*run);
            if (run->has_report)
                out += ", cycles " + std::to_string(run->cycles) + ", modeled_ms " +
                       fmt("%.6g", run->modeled_ms);
            if (!run->where.empty() && run->where != "local") out += " (" + run->where + ")";
            out += "\n";
        }
        if (o.not_run) {
            x << "      <skipped message=\"" << xml_escape(o.reason) << "\"/>\n";
        } else if (!o.passed) {
            std::string detail = o.reason + "\n";
            for (int j : p.cases[i].jobs) {
                const auto& run = r.runs[static_cast<size_t>(j)];
                if (!run) continue;
                if (logs_kept && !run->log.empty())
                    detail += "--- " + run->model + " (" + run->log + "), last lines:\n" +
                              log_tail(run->log, 15);
                else
                    detail += "--- " + run->model + ": " + describe(*run) + "\n";
            }
            x << "      <failure type=\"" << xml_escape(o.type) << "\" message=\""
              << xml_escape(o.reason) << "\">" << xml_escape(detail) << "</failure>\n";
        }
        if (!out.empty()) x << "      <system-out>" << xml_escape(out) << "</system-out>\n";
        x << "    </testcase>\n";
    }
    x << "  </testsuite>\n</testsuites>\n";
    return x.str();
}

namespace {
// Milliseconds to the nanosecond, so that the JSON carries no float noise
// (7.22195, not 7.2219500000000005).
double ms_ns(double ms) {
    return std::round(ms * 1e6) / 1e6;
}
}  // namespace

json to_json(const Plan& p, const Result& r, const std::string& executor) {
    json s;
    s["suite"] = p.suite;
    s["models"] = p.models;
    s["cases_file"] = p.cases_file;
    s["executor"] = executor;
    s["passed"] = r.passed;
    s["failed"] = r.failed;
    s["not_run"] = r.not_run;
    s["interrupted"] = r.interrupted;
    s["wall_s"] = std::round(r.wall_s * 1000.0) / 1000.0;
    json arr = json::array();
    for (size_t i = 0; i < p.cases.size(); ++i) {
        const CaseOutcome& o = r.outcomes[i];
        json cj;
        cj["name"] = p.cases[i].c.name;
        cj["passed"] = o.passed;
        if (o.not_run) cj["not_run"] = true;
        cj["expect"] = p.cases[i].c.expect_error ? "error" : "pass";
        if (!o.passed) cj["reason"] = o.reason;
        if (o.have_cycles) {
            cj["cycles"] = o.cycles;
            cj["modeled_ms"] = ms_ns(o.modeled_ms);
        }
        cj["wall_s"] = std::round(o.wall_s * 1000.0) / 1000.0;
        json runs = json::object();
        for (int j : p.cases[i].jobs) {
            const auto& run = r.runs[static_cast<size_t>(j)];
            const Job& job = p.jobs[static_cast<size_t>(j)];
            json rj;
            if (!run) {
                rj["outcome"] = "not-run";
            } else {
                rj["outcome"] = outcome_name(run->outcome);
                rj["exit"] = run->exit_code;
                rj["wall_s"] = std::round(run->wall_s * 1000.0) / 1000.0;
                rj["command"] = run->command;
                if (run->has_report) {
                    rj["bit_exact"] = run->bit_exact;
                    rj["cycles"] = run->cycles;
                    rj["modeled_ms"] = ms_ns(run->modeled_ms);
                    json ph = json::object();
                    for (const auto& [n, c] : run->phases) ph[n] = c;
                    rj["phases"] = ph;
                }
            }
            runs[job.model] = rj;
        }
        cj["runs"] = runs;
        arr.push_back(cj);
    }
    s["cases"] = arr;
    return s;
}

}  // namespace imap::engine::regress
