// imapsim regress: the regression suite (docs/regress.md). Every case x model
// runs as a child process `imapsim run --model M --report R.json ...` (SystemC
// elaborates once per process), up to -j children at a time. A case passes
// when every model's run is bit-exact with the golden (or, for an
// expected-error case, is refused with exit 2) and the models agree on cycles
// and phases. Prints a table and "N passed, M failed"; --junit / --json.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child.hpp"
#include "cli_common.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"

extern char** environ;

namespace imapsim {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using Clock = std::chrono::steady_clock;

// ---- the case table --------------------------------------------------------

struct Case {
    std::string name;
    std::string suite = "full";  // "quick" or "full"
    std::string scene;           // Middlebury folder under --data, or empty (synthetic)
    std::vector<std::string> args;
    std::vector<std::string> models;  // empty: every selected model
    bool expect_error = false;
    std::string expect_message;
    std::optional<unsigned long long> expect_cycles;
};

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw UserError("cannot read case table " + p.string());
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

template <class J>
std::vector<std::string> string_list(const J& j, const std::string& what) {
    std::vector<std::string> v;
    if (!j.is_array()) throw UserError(what + ": expected an array of strings");
    for (const auto& e : j) {
        if (!e.is_string()) throw UserError(what + ": expected an array of strings");
        v.push_back(e.template get<std::string>());
    }
    return v;
}

// Parses the case table; a case with a "matrix" expands into one case per
// combination of the listed flag values.
std::vector<Case> load_cases_impl(const fs::path& file) {
    nlohmann::ordered_json doc;
    try {
        doc = nlohmann::ordered_json::parse(read_file(file), nullptr, true,
                                            /*ignore_comments=*/true);
    } catch (const nlohmann::json::exception& e) {
        throw UserError("case table " + file.string() + ": " + e.what());
    }
    if (!doc.is_object() || !doc.contains("cases") || !doc["cases"].is_array())
        throw UserError("case table " + file.string() + ": expected {\"cases\": [...]}");
    std::vector<Case> out;
    for (const auto& c : doc["cases"]) {
        const std::string where = "case table " + file.string();
        if (!c.is_object() || !c.contains("name") || !c["name"].is_string())
            throw UserError(where + ": every case needs a \"name\"");
        Case base;
        base.name = c["name"].get<std::string>();
        const std::string ctx = where + ", case " + base.name;
        for (const auto& [k, v] : c.items()) {
            if (k == "name" || k == "matrix" || k == "note") continue;
            if (k == "suite") {
                base.suite = v.get<std::string>();
                if (base.suite != "quick" && base.suite != "full")
                    throw UserError(ctx + ": suite must be quick or full");
            } else if (k == "scene") {
                base.scene = v.get<std::string>();
            } else if (k == "args") {
                base.args = string_list(v, ctx + ": args");
            } else if (k == "models") {
                base.models = string_list(v, ctx + ": models");
            } else if (k == "expect") {
                const std::string e = v.get<std::string>();
                if (e != "pass" && e != "error")
                    throw UserError(ctx + ": expect must be pass or error");
                base.expect_error = e == "error";
            } else if (k == "expect_message") {
                base.expect_message = v.get<std::string>();
            } else if (k == "expect_cycles") {
                base.expect_cycles = v.get<unsigned long long>();
            } else {
                throw UserError(ctx + ": unknown key \"" + k + "\"");
            }
        }
        std::vector<Case> expanded = {base};
        if (c.contains("matrix")) {
            if (!c["matrix"].is_object()) throw UserError(ctx + ": matrix must be an object");
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
        for (auto& e : expanded) out.push_back(std::move(e));
    }
    std::map<std::string, int> seen;
    for (const Case& c : out)
        if (seen[c.name]++)
            throw UserError("case table " + file.string() + ": duplicate case " + c.name);
    return out;
}

std::vector<Case> load_cases(const fs::path& file) {
    try {
        return load_cases_impl(file);
    } catch (const nlohmann::json::exception& e) {  // a value of the wrong type
        throw UserError("case table " + file.string() + ": " + e.what());
    }
}

// ---- locating the binary, the case table and the data ------------------------

std::string self_path() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        throw UserError("cannot find the imapsim binary (/proc/self/exe): " + ec.message(),
                        kExitInternal);
    return p.string();
}

fs::path first_existing(const std::vector<fs::path>& candidates) {
    for (const auto& c : candidates) {
        std::error_code ec;
        if (!c.empty() && fs::exists(c, ec)) return fs::weakly_canonical(c, ec);
    }
    return {};
}

fs::path default_cases(const fs::path& exe_dir) {
    std::vector<fs::path> c;
#ifdef IMAP_REGRESS_CASES
    c.emplace_back(IMAP_REGRESS_CASES);
#endif
    c.push_back(exe_dir / "../tests/regress/cases.json");
    c.push_back(exe_dir / "../share/imapsim/regress/cases.json");
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

// ---- running children ---------------------------------------------------------

struct Job {
    size_t case_idx = 0;
    std::string model;
    std::vector<std::string> argv;
    fs::path log, report;
    pid_t pid = -1;
    Clock::time_point start;
    double wall_s = 0;
    int exit_code = -1;  // -1: killed by a signal / did not start
    int signal = 0;
    bool timed_out = false;
    bool started = false, finished = false;
    json rep;  // parsed report (null if none)
};

void spawn(Job& j) {
    j.started = true;
    j.start = Clock::now();
    j.pid = spawn_logged(j.argv, j.log.string());
    if (j.pid < 0) {
        j.finished = true;
        j.exit_code = -1;
    }
}

void finish(Job& j, int status) {
    j.finished = true;
    j.wall_s = std::chrono::duration<double>(Clock::now() - j.start).count();
    if (WIFEXITED(status)) {
        j.exit_code = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        j.exit_code = -1;
        j.signal = WTERMSIG(status);
    }
    std::error_code ec;
    if (fs::exists(j.report, ec)) {
        try {
            j.rep = json::parse(read_file(j.report));
        } catch (const std::exception&) {
            j.rep = nullptr;
        }
    }
}

std::string log_tail(const fs::path& log, size_t max_lines) {
    std::ifstream in(log);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
    std::string out;
    for (size_t i = lines.size() > max_lines ? lines.size() - max_lines : 0; i < lines.size(); ++i)
        out += lines[i] + "\n";
    return out;
}

// ---- judging a case -------------------------------------------------------------

struct Outcome {
    bool passed = true;
    std::string reason;  // first line: the summary; more lines: details
    std::string type;    // JUnit failure type
    unsigned long long cycles = 0;
    double modeled_ms = 0, wall_s = 0;
    bool have_cycles = false;
};

void fail(Outcome& o, const std::string& type, const std::string& why) {
    if (o.passed) o.type = type;
    o.passed = false;
    o.reason += (o.reason.empty() ? "" : "; ") + why;
}

Outcome judge(const Case& c, const std::vector<const Job*>& jobs) {
    Outcome o;
    for (const Job* j : jobs) {
        o.wall_s += j->wall_s;
        const std::string m = j->model + ": ";
        if (j->timed_out) {
            fail(o, "timeout", m + "timed out after " + std::to_string(j->wall_s) + " s");
            continue;
        }
        if (j->exit_code < 0) {
            fail(o, "crash",
                 m + (j->signal ? "killed by signal " + std::to_string(j->signal) + " (" +
                                      strsignal(j->signal) + ")"
                                : "did not run: " + child_log_message(j->log.string())));
            continue;
        }
        if (c.expect_error) {
            if (j->exit_code != kExitInput) {
                fail(o, "expected-error",
                     m + "expected an input error (exit 2), got exit " +
                         std::to_string(j->exit_code));
            } else {
                const std::string e = child_log_message(j->log.string());
                if (!c.expect_message.empty() && e.find(c.expect_message) == std::string::npos)
                    fail(o, "expected-error",
                         m + "error message \"" + e + "\" lacks \"" + c.expect_message + "\"");
            }
            continue;
        }
        switch (j->exit_code) {
            case kExitOk:
            case kExitMismatch:
                break;
            case kExitInput:
                fail(o, "input-error",
                     m + "input error (exit 2): " + child_log_message(j->log.string()));
                continue;
            case kExitFault:
                fail(o, "fault",
                     m + "machine fault (exit 3): " + child_log_message(j->log.string()));
                continue;
            default:
                fail(o, "error",
                     m + "exit " + std::to_string(j->exit_code) + ": " +
                         child_log_message(j->log.string()));
                continue;
        }
        if (!j->rep.is_object()) {
            fail(o, "error", m + "no report written (exit " + std::to_string(j->exit_code) + ")");
            continue;
        }
        if (!j->rep.value("bit_exact", false)) {
            std::string why = m + "not bit-exact vs golden";
            if (j->rep.contains("differing_pixels"))
                why += ": " + j->rep["differing_pixels"].dump() + " pixels differ";
            if (j->rep.contains("first_difference")) {
                const json& f = j->rep["first_difference"];
                why += ", first at (" + f.value("x", json()).dump() + "," +
                       f.value("y", json()).dump() + "): model " + f.value("model", json()).dump() +
                       ", golden " + f.value("golden", json()).dump();
            }
            fail(o, "mismatch", why);
        } else if (j->exit_code != kExitOk) {
            fail(o, "error", m + "bit-exact report but exit " + std::to_string(j->exit_code));
        }
    }
    if (c.expect_error) return o;
    // Cross-model agreement on cycles and phases.
    const Job* ref = nullptr;
    for (const Job* j : jobs) {
        if (!j->rep.is_object() || !j->rep.contains("cycles")) continue;
        if (!ref) {
            ref = j;
            o.cycles = j->rep["cycles"].get<unsigned long long>();
            o.modeled_ms = j->rep.value("modeled_ms", 0.0);
            o.have_cycles = true;
            continue;
        }
        const auto cy = j->rep["cycles"].get<unsigned long long>();
        if (cy != o.cycles)
            fail(o, "cycles",
                 "cycles differ: " + ref->model + " " + std::to_string(o.cycles) + ", " + j->model +
                     " " + std::to_string(cy));
        const json pa = ref->rep.value("phases", json::object());
        const json pb = j->rep.value("phases", json::object());
        if (pa != pb) {
            std::string which;
            for (const auto& [k, v] : pa.items())
                if (!pb.contains(k) || pb[k] != v)
                    which += " " + k + " (" + ref->model + " " + v.dump() + ", " + j->model + " " +
                             (pb.contains(k) ? pb[k].dump() : std::string("absent")) + ")";
            for (const auto& [k, v] : pb.items())
                if (!pa.contains(k)) which += " " + k + " (" + ref->model + " absent)";
            fail(o, "cycles", "phases differ:" + which);
        }
    }
    if (o.passed && c.expect_cycles && o.have_cycles && o.cycles != *c.expect_cycles)
        fail(o, "cycles",
             "cycles " + std::to_string(o.cycles) + ", expected " +
                 std::to_string(*c.expect_cycles));
    return o;
}

// ---- reports ---------------------------------------------------------------------

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

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

std::string iso_now() {
    const std::time_t t = std::time(nullptr);
    char b[32];
    std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
    return b;
}

struct RegressOptions {
    std::string suite = "quick";
    std::string junit, json_out, models, filter, cases, data, work_dir;
    unsigned jobs = 0;
    double timeout_s = 600;
    bool keep = false, list = false;
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
                    "[default: every built model: " +
                        model_names() + "]");
    sub->add_option("-j,--jobs", o->jobs, "parallel children [default: number of cores]");
    sub->add_option("--filter", o->filter, "only cases whose name contains this substring");
    sub->add_option("--cases", o->cases, "case table (JSON) [default: tests/regress/cases.json]");
    sub->add_option("--data", o->data,
                    "Middlebury data folder (tsukuba/, venus/, ...) [default: the shared data]");
    sub->add_option("--work-dir", o->work_dir,
                    "folder for the children's logs and reports [default: a new temp folder]");
    sub->add_option("--timeout", o->timeout_s, "seconds before a child is killed")
        ->capture_default_str();
    sub->add_flag("--keep", o->keep, "keep logs and reports even when everything passes");
    sub->add_flag("--list", o->list, "list the selected cases and exit");

    return {
        sub, [o]() {
            const std::string exe = self_path();
            const fs::path exe_dir = fs::path(exe).parent_path();

            // Models.
            const std::vector<std::string> built = built_models();
            std::vector<std::string> models;
            if (o->models.empty()) {
                // core first: it is the fastest and the reference for cycle
                // comparisons. Other built models (e.g. lockstep, a debugging aid)
                // run only when named in --models.
                for (const char* m : {"core", "tlm", "rtl"})
                    if (std::find(built.begin(), built.end(), m) != built.end())
                        models.push_back(m);
            } else {
                std::stringstream ss(o->models);
                std::string m;
                while (std::getline(ss, m, ',')) {
                    if (m.empty() || m == "golden") continue;  // golden: implicit in every run
                    if (std::find(built.begin(), built.end(), m) != built.end()) {
                        if (std::find(models.begin(), models.end(), m) == models.end())
                            models.push_back(m);
                    } else if (m == "core" || m == "tlm" || m == "rtl") {
                        std::fprintf(stderr,
                                     "imapsim regress: model %s is not in this build, "
                                     "skipped\n",
                                     m.c_str());
                    } else {
                        throw UserError("invalid value '" + m +
                                        "' for --models: expected a comma-separated list of "
                                        "golden, " +
                                        model_names());
                    }
                }
                if (models.empty())
                    throw UserError("--models '" + o->models +
                                    "' selects no model built here (built: " + model_names() + ")");
            }

            // Cases.
            const fs::path cases_file =
                o->cases.empty() ? default_cases(exe_dir) : fs::path(o->cases);
            if (cases_file.empty())
                throw UserError(
                    "cannot find the case table tests/regress/cases.json; pass --cases FILE");
            std::vector<Case> all = load_cases(cases_file);
            std::vector<Case> cases;
            for (auto& c : all)
                if ((o->suite == "full" || c.suite == "quick") &&
                    c.name.find(o->filter) != std::string::npos)
                    cases.push_back(c);
            if (cases.empty())
                throw UserError("no case of suite " + o->suite +
                                (o->filter.empty() ? "" : " matches --filter '" + o->filter + "'") +
                                " in " + cases_file.string());

            const fs::path data = o->data.empty() ? default_data(exe_dir) : fs::path(o->data);
            check_output_file("--junit", o->junit, false);  // before the suite, not after it
            check_output_file("--json", o->json_out, false);

            // Jobs.
            std::vector<std::vector<std::string>> case_models(cases.size());
            for (size_t i = 0; i < cases.size(); ++i)
                for (const auto& m : models)
                    if (cases[i].models.empty() ||
                        std::find(cases[i].models.begin(), cases[i].models.end(), m) !=
                            cases[i].models.end())
                        case_models[i].push_back(m);

            if (o->list) {
                for (size_t i = 0; i < cases.size(); ++i) {
                    std::string ms;
                    for (const auto& m : case_models[i]) ms += (ms.empty() ? "" : ",") + m;
                    std::printf(
                        "%-44s %-6s %-14s %s%s%s\n", cases[i].name.c_str(), cases[i].suite.c_str(),
                        ms.c_str(),
                        cases[i].scene.empty() ? "" : ("scene " + cases[i].scene + " ").c_str(),
                        command_line(cases[i].args).c_str(),
                        cases[i].expect_error ? "  [expect error]" : "");
                }
                return static_cast<int>(kExitOk);
            }

            fs::path work;
            if (o->work_dir.empty()) {
                std::string tmpl = (fs::temp_directory_path() / "imapsim-regress-XXXXXX").string();
                if (!::mkdtemp(tmpl.data()))
                    throw UserError("cannot create a temp folder: " +
                                    std::string(std::strerror(errno)));
                work = tmpl;
            } else {
                work = o->work_dir;
                std::error_code ec;
                fs::create_directories(work, ec);
                if (ec)
                    throw UserError("cannot create --work-dir " + work.string() + ": " +
                                    ec.message());
            }
            ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "DISABLE", 0);

            std::vector<Job> jobs;
            std::vector<std::vector<size_t>> case_jobs(cases.size());
            std::vector<std::string> case_error(cases.size());
            for (size_t i = 0; i < cases.size(); ++i) {
                const Case& c = cases[i];
                std::vector<std::string> scene_args;
                if (!c.scene.empty()) {
                    const fs::path l = data / c.scene / "left.png",
                                   r = data / c.scene / "right.png";
                    std::error_code ec;
                    if (data.empty() || !fs::exists(l, ec) || !fs::exists(r, ec)) {
                        case_error[i] =
                            "scene " + c.scene + " not found under " +
                            (data.empty() ? std::string("(no data folder)") : data.string()) +
                            " (pass --data DIR)";
                        continue;
                    }
                    scene_args = {"--left", l.string(), "--right", r.string()};
                }
                if (case_models[i].empty()) {
                    case_error[i] = "none of the case's models (" + command_line(c.models) +
                                    ") is selected or built";
                    continue;
                }
                std::string safe;
                for (char ch : c.name)
                    safe += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.'
                                ? ch
                                : '_';
                for (const auto& m : case_models[i]) {
                    Job j;
                    j.case_idx = i;
                    j.model = m;
                    j.log = work / (std::to_string(i) + "-" + safe + "." + m + ".log");
                    j.report = work / (std::to_string(i) + "-" + safe + "." + m + ".json");
                    std::error_code ec;
                    fs::remove(j.report, ec);
                    j.argv = {exe, "run", "--model", m, "--report", j.report.string()};
                    j.argv.insert(j.argv.end(), scene_args.begin(), scene_args.end());
                    j.argv.insert(j.argv.end(), c.args.begin(), c.args.end());
                    case_jobs[i].push_back(jobs.size());
                    jobs.push_back(std::move(j));
                }
            }

            unsigned par = o->jobs;
            if (par == 0) par = std::max(1u, std::thread::hardware_concurrency());
            const bool tty = ::isatty(STDOUT_FILENO);
            std::string ms;
            for (const auto& m : models) ms += (ms.empty() ? "" : ",") + m;
            std::printf("imapsim regress: suite %s, %zu case%s, %zu run%s, models %s, -j %u\n",
                        o->suite.c_str(), cases.size(), cases.size() == 1 ? "" : "s", jobs.size(),
                        jobs.size() == 1 ? "" : "s", ms.c_str(), par);
            std::printf("  cases %s, logs %s\n", cases_file.string().c_str(),
                        work.string().c_str());
            std::printf("%-44s %-14s %10s %10s %8s  %s\n", "case", "models", "cycles", "modeled ms",
                        "wall s", "result");
            std::fflush(stdout);

            // Run: start children in case order, print rows in case order.
            const auto t0 = Clock::now();
            std::vector<Outcome> outcomes(cases.size());
            std::vector<bool> done(cases.size(), false);
            size_t next_job = 0, running = 0, printed = 0, jobs_done = 0, passed = 0, failed = 0;
            auto case_complete = [&](size_t i) {
                for (size_t k : case_jobs[i])
                    if (!jobs[k].finished) return false;
                return true;
            };
            auto print_ready = [&]() {
                while (printed < cases.size() && done[printed]) {
                    const size_t i = printed++;
                    const Outcome& oc = outcomes[i];
                    std::string cm;
                    for (size_t k : case_jobs[i]) cm += (cm.empty() ? "" : ",") + jobs[k].model;
                    if (tty) std::printf("\r\033[K");
                    std::printf(
                        "%-44s %-14s %10s %10s %8.2f  %s%s\n", cases[i].name.c_str(),
                        cm.empty() ? "-" : cm.c_str(),
                        oc.have_cycles ? std::to_string(oc.cycles).c_str() : "-",
                        oc.have_cycles ? fmt("%.3f", oc.modeled_ms).c_str() : "-", oc.wall_s,
                        oc.passed ? (cases[i].expect_error ? "PASS (error expected)" : "PASS")
                                  : "FAIL: ",
                        oc.passed ? "" : oc.reason.c_str());
                }
            };
            auto mark_done = [&](size_t i) {
                if (done[i]) return;
                std::vector<const Job*> js;
                for (size_t k : case_jobs[i]) js.push_back(&jobs[k]);
                outcomes[i] = case_error[i].empty() ? judge(cases[i], js) : Outcome{};
                if (!case_error[i].empty()) fail(outcomes[i], "input-error", case_error[i]);
                done[i] = true;
                (outcomes[i].passed ? passed : failed)++;
            };
            for (size_t i = 0; i < cases.size(); ++i)
                if (case_jobs[i].empty()) mark_done(i);
            print_ready();
            auto last_progress = Clock::now() - std::chrono::seconds(1);
            while (jobs_done < jobs.size()) {
                while (running < par && next_job < jobs.size()) {
                    spawn(jobs[next_job]);
                    if (jobs[next_job].finished) {
                        ++jobs_done;
                        if (case_complete(jobs[next_job].case_idx))
                            mark_done(jobs[next_job].case_idx);
                    } else {
                        ++running;
                    }
                    ++next_job;
                }
                bool any = false;
                for (auto& j : jobs) {
                    if (!j.started || j.finished) continue;
                    int st = 0;
                    const pid_t r = ::waitpid(j.pid, &st, WNOHANG);
                    if (r == j.pid) {
                        finish(j, st);
                    } else if (r == 0 && o->timeout_s > 0 &&
                               std::chrono::duration<double>(Clock::now() - j.start).count() >
                                   o->timeout_s) {
                        ::kill(j.pid, SIGKILL);
                        ::waitpid(j.pid, &st, 0);
                        finish(j, st);
                        j.timed_out = true;
                    } else {
                        continue;
                    }
                    any = true;
                    --running;
                    ++jobs_done;
                    if (case_complete(j.case_idx)) mark_done(j.case_idx);
                }
                if (any) print_ready();
                if (tty && Clock::now() - last_progress > std::chrono::milliseconds(200)) {
                    last_progress = Clock::now();
                    std::printf("\r\033[K[%zu/%zu runs, %zu passed, %zu failed, %.0f s]", jobs_done,
                                jobs.size(), passed, failed,
                                std::chrono::duration<double>(Clock::now() - t0).count());
                    std::fflush(stdout);
                }
                if (!any && jobs_done < jobs.size())
                    std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
            for (size_t i = 0; i < cases.size(); ++i) mark_done(i);
            print_ready();
            const double total_s = std::chrono::duration<double>(Clock::now() - t0).count();
            if (tty) std::printf("\r\033[K");

            // Failure details.
            if (failed) {
                std::printf("\nfailures:\n");
                for (size_t i = 0; i < cases.size(); ++i) {
                    if (outcomes[i].passed) continue;
                    std::printf("  %s: %s\n", cases[i].name.c_str(), outcomes[i].reason.c_str());
                    for (size_t k : case_jobs[i])
                        std::printf("    %s: %s\n      log %s\n", jobs[k].model.c_str(),
                                    command_line(jobs[k].argv).c_str(), jobs[k].log.c_str());
                }
            }

            // JUnit.
            if (!o->junit.empty()) {
                std::ostringstream x;
                x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
                x << "<testsuites name=\"imapsim regress\" tests=\"" << cases.size()
                  << "\" failures=\"" << failed << "\" errors=\"0\" time=\"" << fmt("%.3f", total_s)
                  << "\">\n";
                x << "  <testsuite name=\"regress." << o->suite << "\" tests=\"" << cases.size()
                  << "\" failures=\"" << failed << "\" errors=\"0\" skipped=\"0\" time=\""
                  << fmt("%.3f", total_s) << "\" timestamp=\"" << iso_now() << "\">\n";
                x << "    <properties>\n      <property name=\"models\" value=\"" << xml_escape(ms)
                  << "\"/>\n      <property name=\"cases\" value=\""
                  << xml_escape(cases_file.string()) << "\"/>\n    </properties>\n";
                for (size_t i = 0; i < cases.size(); ++i) {
                    const Outcome& oc = outcomes[i];
                    x << "    <testcase classname=\"regress." << o->suite << "\" name=\""
                      << xml_escape(cases[i].name) << "\" time=\"" << fmt("%.3f", oc.wall_s)
                      << "\">\n";
                    std::string out;
                    for (size_t k : case_jobs[i]) {
                        const Job& j = jobs[k];
                        out +=
                            "$ " + command_line(j.argv) + "\nexit " + std::to_string(j.exit_code);
                        if (j.rep.is_object() && j.rep.contains("cycles"))
                            out += ", cycles " + j.rep["cycles"].dump() + ", modeled_ms " +
                                   j.rep.value("modeled_ms", json()).dump();
                        out += "\n";
                    }
                    if (!oc.passed) {
                        std::string detail = oc.reason + "\n";
                        for (size_t k : case_jobs[i])
                            detail += "--- " + jobs[k].model + " (" + jobs[k].log.string() +
                                      "), last lines:\n" + log_tail(jobs[k].log, 15);
                        x << "      <failure type=\"" << xml_escape(oc.type) << "\" message=\""
                          << xml_escape(oc.reason) << "\">" << xml_escape(detail) << "</failure>\n";
                    }
                    if (!out.empty())
                        x << "      <system-out>" << xml_escape(out) << "</system-out>\n";
                    x << "    </testcase>\n";
                }
                x << "  </testsuite>\n</testsuites>\n";
                imap::vision::write_text_atomic(o->junit, x.str());
            }

            // JSON summary.
            if (!o->json_out.empty()) {
                json s;
                s["suite"] = o->suite;
                s["models"] = models;
                s["cases_file"] = cases_file.string();
                s["passed"] = passed;
                s["failed"] = failed;
                s["wall_s"] = total_s;
                s["jobs"] = par;
                json arr = json::array();
                for (size_t i = 0; i < cases.size(); ++i) {
                    const Outcome& oc = outcomes[i];
                    json cj;
                    cj["name"] = cases[i].name;
                    cj["passed"] = oc.passed;
                    cj["expect"] = cases[i].expect_error ? "error" : "pass";
                    if (!oc.passed) cj["reason"] = oc.reason;
                    if (oc.have_cycles) {
                        cj["cycles"] = oc.cycles;
                        cj["modeled_ms"] = oc.modeled_ms;
                    }
                    cj["wall_s"] = oc.wall_s;
                    json runs = json::object();
                    for (size_t k : case_jobs[i]) {
                        const Job& j = jobs[k];
                        json r;
                        r["exit"] = j.exit_code;
                        r["wall_s"] = j.wall_s;
                        r["command"] = command_line(j.argv);
                        if (j.rep.is_object()) {
                            for (const char* key : {"bit_exact", "cycles", "modeled_ms", "phases"})
                                if (j.rep.contains(key)) r[key] = j.rep[key];
                        }
                        runs[j.model] = r;
                    }
                    cj["runs"] = runs;
                    arr.push_back(cj);
                }
                s["cases"] = arr;
                imap::vision::write_text_atomic(o->json_out, s.dump(2) + "\n");
            }

            if (failed == 0 && !o->keep && o->work_dir.empty()) {
                std::error_code ec;
                fs::remove_all(work, ec);
            } else {
                std::printf("logs and reports kept in %s\n", work.string().c_str());
            }
            std::printf("total wall %.1f s\n", total_s);
            std::printf("%zu passed, %zu failed\n", passed, failed);
            std::fflush(stdout);
            return failed ? static_cast<int>(kExitMismatch) : static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
