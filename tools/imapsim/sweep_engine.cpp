#include "sweep_engine.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "child.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"
#include "progress.hpp"

extern char** environ;

namespace imapsim::sweep {

namespace fs = std::filesystem;
namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// ---- value lists and ranges ---------------------------------------------------

namespace {

constexpr size_t kMaxValues = kMaxPoints;  // per range, before the product check

[[noreturn]] void bad_list(const std::string& flag, const std::string& text, ValueType type,
                           const std::string& why) {
    std::string expect =
        type == ValueType::Text
            ? "expected a comma list of values, e.g. a,b,c"
            : "expected a comma list of values and ranges A..B (step 1), A..B:S (step S) or "
              "A..B*F (factor F), e.g. 8,16,64 or 8..1024*2";
    throw UserError("invalid value '" + text + "' for " + flag + ": " + why + "; " + expect);
}

bool parse_i64(const std::string& s, long long* out) {
    if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
        return false;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (errno != 0 || *end != '\0') return false;
    *out = v;
    return true;
}

bool parse_real(const std::string& s, double* out) {
    if (s.empty() || s.find_first_not_of("0123456789.eE+-") != std::string::npos) return false;
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (errno != 0 || *end != '\0' || !std::isfinite(v)) return false;
    *out = v;
    return true;
}

std::string real_text(double v) {
    return fmt("%.10g", v);
}

// "A..B", "A..B:S" or "A..B*F" split into its texts (op 0, ':' or '*').
struct RangeText {
    std::string a, b, step;
    char op = 0;
};

RangeText split_range(const std::string& item) {
    RangeText r;
    const size_t dots = item.find("..");
    r.a = item.substr(0, dots);
    r.b = item.substr(dots + 2);
    const size_t k = r.b.find_first_of(":*");
    if (k != std::string::npos) {
        r.op = r.b[k];
        r.step = r.b.substr(k + 1);
        r.b.resize(k);
    }
    return r;
}

void expand_int_range(const std::string& flag, const std::string& text, const std::string& item,
                      std::vector<std::string>& out) {
    const RangeText r = split_range(item);
    long long a = 0, b = 0, s = 1;
    const char op = r.op;
    if (!parse_i64(r.a, &a) || !parse_i64(r.b, &b) || (op && !parse_i64(r.step, &s)))
        bad_list(flag, text, ValueType::Int, "'" + item + "' is not a range of integers");
    if (a > b) bad_list(flag, text, ValueType::Int, "range '" + item + "' has A > B");
    if (op == '*') {
        if (s < 2) bad_list(flag, text, ValueType::Int, "factor in '" + item + "' must be >= 2");
        if (a < 1)
            bad_list(flag, text, ValueType::Int, "geometric range '" + item + "' needs A >= 1");
        for (long long v = a;; v *= s) {
            out.push_back(std::to_string(v));
            if (v > b / s) break;
        }
    } else {
        if (s < 1) bad_list(flag, text, ValueType::Int, "step in '" + item + "' must be >= 1");
        if ((b - a) / s + 1 > static_cast<long long>(kMaxValues))
            bad_list(
                flag, text, ValueType::Int,
                "range '" + item + "' has more than " + std::to_string(kMaxValues) + " values");
        for (long long v = a; v <= b; v += s) {
            out.push_back(std::to_string(v));
            if (v > b - s) break;
        }
    }
}

void expand_real_range(const std::string& flag, const std::string& text, const std::string& item,
                       std::vector<std::string>& out) {
    const RangeText r = split_range(item);
    double a = 0, b = 0, s = 1;
    const char op = r.op;
    if (!parse_real(r.a, &a) || !parse_real(r.b, &b) || (op && !parse_real(r.step, &s)))
        bad_list(flag, text, ValueType::Real, "'" + item + "' is not a range of numbers");
    if (a > b) bad_list(flag, text, ValueType::Real, "range '" + item + "' has A > B");
    const double tol = 1e-9 * std::max(1.0, std::fabs(b));
    if (op == '*') {
        if (!(s > 1)) bad_list(flag, text, ValueType::Real, "factor in '" + item + "' must be > 1");
        if (!(a > 0))
            bad_list(flag, text, ValueType::Real, "geometric range '" + item + "' needs A > 0");
        for (int i = 0;; ++i) {
            const double v = a * std::pow(s, i);
            if (v > b + tol) break;
            out.push_back(real_text(v));
        }
    } else {
        if (!(s > 0)) bad_list(flag, text, ValueType::Real, "step in '" + item + "' must be > 0");
        if ((b - a) / s + 1 > static_cast<double>(kMaxValues))
            bad_list(
                flag, text, ValueType::Real,
                "range '" + item + "' has more than " + std::to_string(kMaxValues) + " values");
        for (long long i = 0;; ++i) {
            const double v = a + static_cast<double>(i) * s;
            if (v > b + tol) break;
            out.push_back(real_text(v));
        }
    }
}

}  // namespace

std::vector<std::string> parse_value_list(const std::string& flag, const std::string& text,
                                          ValueType type) {
    if (text.empty()) bad_list(flag, text, type, "empty list");
    std::vector<std::string> out;
    std::string item;
    std::stringstream ss(text);
    std::vector<std::string> items;
    while (std::getline(ss, item, ',')) items.push_back(item);
    if (text.back() == ',') items.push_back("");
    for (const std::string& it : items) {
        if (it.empty()) bad_list(flag, text, type, "empty item");
        if (it.find("..") != std::string::npos) {
            if (type == ValueType::Text)
                bad_list(flag, text, type, "ranges (A..B) need a numeric parameter");
            if (type == ValueType::Int)
                expand_int_range(flag, text, it, out);
            else
                expand_real_range(flag, text, it, out);
        } else if (type == ValueType::Int) {
            long long v = 0;
            if (!parse_i64(it, &v)) bad_list(flag, text, type, "'" + it + "' is not an integer");
            out.push_back(std::to_string(v));
        } else if (type == ValueType::Real) {
            double v = 0;
            if (!parse_real(it, &v)) bad_list(flag, text, type, "'" + it + "' is not a number");
            out.push_back(real_text(v));
        } else {
            out.push_back(it);
        }
        if (out.size() > kMaxValues)
            bad_list(flag, text, type, "more than " + std::to_string(kMaxValues) + " values");
    }
    std::set<std::string> seen;
    for (const std::string& v : out)
        if (!seen.insert(v).second)
            throw UserError("invalid value '" + text + "' for " + flag + ": value " + v +
                            " appears twice");
    return out;
}

// ---- axes -------------------------------------------------------------------------

namespace {

bool parse_wxh(const std::string& v, int* w, int* h) {
    const size_t x = v.find('x');
    if (x == std::string::npos) return false;
    long long a = 0, b = 0;
    if (!parse_i64(v.substr(0, x), &a) || !parse_i64(v.substr(x + 1), &b)) return false;
    if (a > 1000000 || b > 1000000) return false;
    *w = static_cast<int>(a);
    *h = static_cast<int>(b);
    return true;
}

struct AlgoRange {
    const char* name;
    long long lo, hi;
};
const AlgoRange kAlgoInts[] = {{"D", 1, g::kMaxLevels},  {"km", 0, g::kMaxWeight},
                               {"kb", 0, g::kMaxWeight}, {"gb", 0, 255},
                               {"Wo", 0, g::kMaxWeight}, {"Wd", 0, g::kMaxWeight}};

}  // namespace

Axis make_axis(const std::string& name, const std::string& flag, const std::string& text) {
    Axis a;
    a.name = name;
    a.flag = flag;
    if (name == "roi_size") {
        a.kind = AxisKind::RoiSize;
        a.values = parse_value_list(flag, text, ValueType::Text);
        for (const std::string& v : a.values) {
            int w = 0, h = 0;
            if (!parse_wxh(v, &w, &h) || w < 2 || h < 1 || w > 4096 || h > 4096)
                throw UserError("invalid value '" + v + "' in " + flag +
                                ": expected WxH with W in 2..4096, H in 1..4096 (a comma list, "
                                "e.g. 64x64,128x128)");
        }
        return a;
    }
    if (name == "mode") {
        a.kind = AxisKind::Algo;
        a.values = parse_value_list(flag, text, ValueType::Text);
        for (const std::string& v : a.values)
            if (v != "single" && v != "bidir")
                throw UserError("invalid value '" + v + "' in " + flag +
                                ": expected single, bidir or single,bidir");
        return a;
    }
    for (const AlgoRange& r : kAlgoInts)
        if (name == r.name) {
            a.kind = AxisKind::Algo;
            a.values = parse_value_list(flag, text, ValueType::Int);
            for (const std::string& v : a.values) parse_int_flag(flag, v, r.lo, r.hi);
            return a;
        }
    // A machine or cost parameter.
    a.kind = AxisKind::Machine;
    isa::MachineConfig probe;
    bool known = false;
    std::string names;
    for (const isa::ParamInfo& pi : probe.list()) {
        known |= pi.name == name;
        names += (names.empty() ? "" : ", ") + pi.name;
    }
    if (!known)
        throw UserError("unknown machine parameter '" + name + "' in " + flag +
                        " (known: " + names + ")");
    const ValueType t = name == "clock_mhz"  ? ValueType::Real
                        : name == "indirect" ? ValueType::Text
                                             : ValueType::Int;
    a.values = parse_value_list(flag, text, t);
    for (const std::string& v : a.values) {
        isa::MachineConfig c;
        try {
            c.set(name, v);
        } catch (const std::exception& e) {
            throw UserError(flag + ": " + e.what());
        }
    }
    return a;
}

double numeric_value(const Axis& a, const std::string& v) {
    if (a.kind == AxisKind::RoiSize || a.name == "mode" || a.name == "indirect") return NAN;
    double d = 0;
    return parse_real(v, &d) ? d : NAN;
}

std::string Input::describe() const {
    if (left.empty())
        return "synthetic scene seed " + std::to_string(seed) + " (generated at the ROI size)";
    std::string d =
        left + " + " + right + " (" + std::to_string(L.cols) + "x" + std::to_string(L.rows) + ")";
    if (has_fixed_roi)
        d += ", ROI " + std::to_string(roi_x0) + "," + std::to_string(roi_y0) + "," +
             std::to_string(roi_w) + "," + std::to_string(roi_h);
    return d;
}

std::vector<std::vector<size_t>> product(const std::vector<Axis>& swept) {
    size_t n = 1;
    std::string sizes;
    bool too_many = false;
    for (const Axis& a : swept) {
        sizes += (sizes.empty() ? "" : " x ") + a.name + " " + std::to_string(a.values.size());
        if (a.values.size() > 0 && n > kMaxPoints * 10 / a.values.size()) too_many = true;
        n *= a.values.size();
        if (n > kMaxPoints) too_many = true;
    }
    if (too_many)
        throw UserError("the sweep has " +
                        (n > kMaxPoints * 10
                             ? std::string("more than ") + std::to_string(kMaxPoints * 10)
                             : std::to_string(n)) +
                        " points (" + sizes + "); at most " + std::to_string(kMaxPoints) +
                        " are allowed: use fewer values or coarser steps");
    std::vector<std::vector<size_t>> pts;
    std::vector<size_t> idx(swept.size(), 0);
    for (size_t k = 0; k < n; ++k) {
        pts.push_back(idx);
        for (size_t i = swept.size(); i-- > 0;) {  // the last axis varies fastest
            if (++idx[i] < swept[i].values.size()) break;
            idx[i] = 0;
        }
    }
    return pts;
}

const char* status_name(Status s) {
    switch (s) {
        case Status::Ok:
            return "ok";
        case Status::Mismatch:
            return "mismatch";
        case Status::DoesNotFit:
            return "does-not-fit";
        case Status::CannotRun:
            return "cannot-run";
        case Status::Planned:
            return "fits-not-run";
        case Status::Error:
            return "error";
        case Status::Interrupted:
            return "interrupted";
    }
    return "?";
}

size_t Result::count(Status s) const {
    return static_cast<size_t>(
        std::count_if(rows.begin(), rows.end(), [s](const Row& r) { return r.status == s; }));
}

int Result::exit_code() const {
    if (interrupted) return kExitInterrupted;
    if (count(Status::Error)) return kExitItemErrors;
    if (count(Status::Mismatch)) return kExitMismatch;
    return kExitOk;
}

// ---- planning a point -------------------------------------------------------------

namespace {

struct Prepared {
    Row row;
    bool runnable = false;
    std::vector<std::string> args;  // child arguments after the binary
    std::vector<std::string> phases;
};

const std::string* value_of(const Spec& s, const std::vector<size_t>& pt, const std::string& name) {
    for (size_t i = 0; i < s.swept.size(); ++i)
        if (s.swept[i].name == name) return &s.swept[i].values[pt[i]];
    for (const Axis& a : s.fixed)
        if (a.name == name) return &a.values.front();
    return nullptr;
}

bool plans(const g::Params& p, const g::Roi& roi, const isa::MachineConfig& cfg,
           fw::FramePlan* out = nullptr) {
    try {
        fw::FramePlan fp = fw::plan_frame(p, roi, cfg);
        if (out) *out = fp;
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

Prepared prepare(const Spec& s, const std::vector<size_t>& pt, bool want_phases) {
    Prepared pr;
    Row& row = pr.row;
    for (size_t i = 0; i < s.swept.size(); ++i) row.values.push_back(s.swept[i].values[pt[i]]);
    auto cannot = [&](const std::string& why) {
        row.status = Status::CannotRun;
        row.message = why;
        return pr;
    };

    AlgoFlags af = s.algo;
    af.roi.clear();
    auto algo_val = [&](const char* name, std::string& dst) {
        if (const std::string* v = value_of(s, pt, name)) dst = *v;
    };
    algo_val("D", af.D);
    algo_val("km", af.km);
    algo_val("kb", af.kb);
    algo_val("gb", af.gb);
    algo_val("Wo", af.Wo);
    algo_val("Wd", af.Wd);
    algo_val("mode", af.mode);
    MachineFlags mf;
    std::vector<std::pair<std::string, std::string>> machine;  // name, value (for the child)
    auto add_machine = [&](const Axis& a, const std::string& v) {
        if (a.kind != AxisKind::Machine) return;
        machine.emplace_back(a.name, v);
        if (a.name == "pes")
            mf.pes = v;
        else if (a.name == "clock_mhz")
            mf.clock_mhz = v;
        else if (a.name == "mem_bytes")
            mf.mem_bytes = v;
        else if (a.name == "ext_bytes")
            mf.ext_bytes = v;
        else
            mf.sets.push_back(a.name + "=" + v);
    };
    for (const Axis& a : s.fixed) add_machine(a, a.values.front());
    for (size_t i = 0; i < s.swept.size(); ++i) add_machine(s.swept[i], s.swept[i].values[pt[i]]);

    g::Params p;
    isa::MachineConfig cfg;
    try {
        g::Roi unused;
        bool has = false;
        p = parse_algo_flags(af, &unused, &has);
        cfg = parse_machine_flags(mf);
    } catch (const UserError& e) {
        return cannot(e.what());
    }

    // The ROI and the image size.
    g::Roi roi;
    int img_w = 0, img_h = 0;
    const std::string* rs = value_of(s, pt, "roi_size");
    int rw = 128, rh = 128;
    if (rs) {
        const size_t x = rs->find('x');
        rw = std::atoi(rs->substr(0, x).c_str());
        rh = std::atoi(rs->substr(x + 1).c_str());
    }
    if (s.input.left.empty()) {
        roi = {0, 0, rw, rh};
        img_w = rw;
        img_h = rh;
    } else {
        img_w = s.input.L.cols;
        img_h = s.input.L.rows;
        if (s.input.has_fixed_roi) {
            roi = {s.input.roi_x0, s.input.roi_y0, s.input.roi_w, s.input.roi_h};
        } else if (rs) {
            if (rw > img_w || rh > img_h)
                return cannot("ROI " + *rs + " is larger than the " + std::to_string(img_w) + "x" +
                              std::to_string(img_h) + " images");
            roi = {(img_w - rw) / 2, (img_h - rh) / 2, rw, rh};
        } else {
            roi = {0, 0, img_w, img_h};
        }
    }
    try {
        g::validate(p, roi, img_w, img_h);
    } catch (const g::ParamError& e) {
        return cannot(e.what());
    }

    // The memory plan: what does not fit is an answer.
    fw::FramePlan plan;
    try {
        plan = fw::plan_frame(p, roi, cfg);
    } catch (const std::exception& e) {  // FirmwareError, ParamError, ConfigError
        isa::MachineConfig big = cfg;
        big.mem_bytes = 1u << 20;
        big.ext_bytes = 1u << 24;
        fw::FramePlan bp;
        if (!plans(p, roi, big, &bp)) return cannot(e.what());
        // Smallest local memory that plans (the plan is monotonic in it).
        uint32_t lo = 1, hi = big.mem_bytes;
        while (lo < hi) {
            const uint32_t mid = lo + (hi - lo) / 2;
            isa::MachineConfig c = big;
            c.mem_bytes = mid;
            if (plans(p, roi, c))
                hi = mid;
            else
                lo = mid + 1;
        }
        row.local_bytes = lo;
        row.ext_bytes = bp.ext_needed;
        std::string why;
        if (lo > cfg.mem_bytes)
            why = "needs " + std::to_string(lo) + " bytes of local memory per PE (have " +
                  std::to_string(cfg.mem_bytes) + ")";
        if (bp.ext_needed > static_cast<int64_t>(cfg.ext_bytes))
            why += (why.empty() ? "needs " : " and ") + std::to_string(bp.ext_needed) +
                   " bytes of external memory per PE (have " + std::to_string(cfg.ext_bytes) + ")";
        if (why.empty()) return cannot(e.what());
        row.status = Status::DoesNotFit;
        row.message = "does not fit: " + why;
        return pr;
    }
    row.local_bytes = plan.mem_needed;
    row.ext_bytes = plan.ext_needed;
    if (want_phases) {
        try {
            pr.phases = fw::assemble_frame(p, plan).phases;
        } catch (const std::exception&) {
        }
    }

    // The child's command line.
    pr.runnable = true;
    std::vector<std::string>& a = pr.args;
    a = {"run", "--model", s.model};
    const std::string roi_txt = std::to_string(roi.x0) + "," + std::to_string(roi.y0) + "," +
                                std::to_string(roi.w) + "," + std::to_string(roi.h);
    if (s.input.left.empty())
        a.insert(a.end(), {"--seed", std::to_string(s.input.seed), "--size",
                           std::to_string(rw) + "x" + std::to_string(rh), "--roi", roi_txt});
    else
        a.insert(a.end(), {"--left", s.input.left, "--right", s.input.right, "--roi", roi_txt});
    for (const char* n : {"D", "km", "kb", "gb", "Wo", "Wd"})
        if (const std::string* v = value_of(s, pt, n))
            a.insert(a.end(), {std::string("--") + n, *v});
    a.insert(a.end(), {"--mode", af.mode, "--seed-col", af.seed_col, "--seed-disp", af.seed_disp,
                       "--vote", af.vote, "--frame", af.frame});
    if (af.fill) a.push_back("--fill");
    for (const auto& [n, v] : machine) {
        if (n == "pes" || n == "clock_mhz" || n == "mem_bytes" || n == "ext_bytes") {
            std::string f = "--" + n;
            std::replace(f.begin(), f.end(), '_', '-');
            a.insert(a.end(), {f, v});
        } else {
            a.insert(a.end(), {"--set", n + "=" + v});
        }
    }
    return pr;
}

// ---- children ------------------------------------------------------------------------

struct Job {
    size_t point = 0;
    std::vector<std::string> argv;
    fs::path log, report;
    pid_t pid = -1;
    Clock::time_point start;
};

bool spawn(Job& j) {
    j.start = Clock::now();
    j.pid = spawn_logged(j.argv, j.log.string());
    return j.pid > 0;
}

// The "imapsim: error: ..." (or last non-empty) line of a child's log.
std::string log_error(const fs::path& log) {
    std::string m = child_log_message(log.string());
    if (m.rfind("error: ", 0) == 0) m = m.substr(7);
    return m.empty() ? "(no output)" : m;
}

void finish(const Job& j, int status, bool spawned, Row& row) {
    row.wall_s = std::chrono::duration<double>(Clock::now() - j.start).count();
    row.status = Status::Error;
    if (!spawned) {
        row.message = log_error(j.log);
        return;
    }
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        if (sig == SIGINT || sig == SIGTERM) {
            row.status = Status::Interrupted;
            row.message = std::string("stopped by signal ") + std::to_string(sig) + " (" +
                          strsignal(sig) + ")";
        } else {
            row.message = std::string("killed by signal ") + std::to_string(sig) + " (" +
                          strsignal(sig) + ")";
        }
        return;
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == kExitInterrupted) {
        row.status = Status::Interrupted;
        row.message = "stopped (exit 130)";
        return;
    }
    json rep;
    std::error_code ec;
    if ((code == kExitOk || code == kExitMismatch) && fs::exists(j.report, ec)) {
        try {
            std::ifstream in(j.report);
            rep = json::parse(in);
        } catch (const std::exception&) {
            rep = nullptr;
        }
    }
    if (!rep.is_object() || !rep.contains("cycles")) {
        switch (code) {
            case kExitInput:
                row.message = "input error (exit 2): " + log_error(j.log);
                break;
            case kExitFault:
                row.message = "machine fault (exit 3): " + log_error(j.log);
                break;
            default:
                row.message = "exit " + std::to_string(code) + (code <= 1 ? ", no report" : "") +
                              ": " + log_error(j.log);
        }
        return;
    }
    try {
        row.ran = true;
        row.cycles = rep.at("cycles").get<uint64_t>();
        row.modeled_ms = rep.at("modeled_ms").get<double>();
        row.fps = row.modeled_ms > 0 ? 1000.0 / row.modeled_ms : 0.0;
        row.bit_exact = rep.value("bit_exact", false);
        for (const auto& [k, v] : rep.at("phases").items())
            row.phases.emplace_back(k, v.get<uint64_t>());
    } catch (const std::exception& e) {
        row.ran = false;
        row.message = std::string("unreadable report: ") + e.what();
        return;
    }
    if (row.bit_exact && code == kExitOk) {
        row.status = Status::Ok;
    } else if (!row.bit_exact) {
        row.status = Status::Mismatch;
        row.message = "not bit-exact vs golden: " + rep.value("differing_pixels", json()).dump() +
                      " pixels differ";
        if (rep.contains("first_difference")) {
            const json& f = rep["first_difference"];
            row.message += ", first at (" + f.value("x", json()).dump() + "," +
                           f.value("y", json()).dump() + ")";
        }
    } else {
        row.message = "bit-exact report but exit " + std::to_string(code);
    }
}

// ---- the table on stdout ------------------------------------------------------------

struct Table {
    std::vector<size_t> widths;
    std::string header(const Spec& s) const {
        std::string h;
        for (size_t i = 0; i < s.swept.size(); ++i) {
            char b[256];
            std::snprintf(b, sizeof b, "%*s  ", static_cast<int>(widths[i]),
                          s.swept[i].name.c_str());
            h += b;
        }
        char b[256];
        std::snprintf(b, sizeof b, "%10s %10s %8s %8s %7s  %s", "cycles", "modeled ms", "fps",
                      "local B", "wall s", "result");
        return h + b;
    }
    std::string line(const Row& r) const {
        std::string l;
        for (size_t i = 0; i < r.values.size(); ++i) {
            char b[256];
            std::snprintf(b, sizeof b, "%*s  ", static_cast<int>(widths[i]), r.values[i].c_str());
            l += b;
        }
        std::string result;
        switch (r.status) {
            case Status::Ok:
                result = "ok, bit-exact";
                break;
            case Status::Mismatch:
                result = "NOT BIT-EXACT: " + r.message;
                break;
            case Status::DoesNotFit:
                result = r.message;
                break;
            case Status::CannotRun:
                result = "cannot run: " + r.message;
                break;
            case Status::Planned:
                result = "fits (not run)";
                break;
            case Status::Error:
                result = "ERROR: " + r.message;
                break;
            case Status::Interrupted:
                result = "interrupted: " + r.message;
                break;
        }
        char b[512];
        std::snprintf(b, sizeof b, "%10s %10s %8s %8s %7s  ",
                      r.ran ? std::to_string(r.cycles).c_str() : "-",
                      r.ran ? fmt("%.3f", r.modeled_ms).c_str() : "-",
                      r.ran ? fmt("%.2f", r.fps).c_str() : "-",
                      r.local_bytes >= 0 ? std::to_string(r.local_bytes).c_str() : "-",
                      r.wall_s > 0 ? fmt("%.2f", r.wall_s).c_str() : "-");
        return l + b + result;
    }
};

}  // namespace

// ---- running the sweep -------------------------------------------------------------------

Result run(const Spec& s) {
    interrupt::install();
    const auto t0 = Clock::now();
    const std::vector<std::vector<size_t>> points = s.points.empty() ? product(s.swept) : s.points;
    Result res;
    res.total = points.size();

    // Plan every point in-process.
    std::vector<Prepared> prep;
    prep.reserve(points.size());
    bool have_phases = false;
    for (const auto& pt : points) {
        prep.push_back(prepare(s, pt, !have_phases));
        if (!prep.back().phases.empty() && !have_phases) {
            have_phases = true;
            for (const std::string& n : prep.back().phases) res.phase_names.push_back(n);
        }
    }

    unsigned par = s.jobs ? s.jobs : std::max(1u, std::thread::hardware_concurrency());
    const std::string exe = self_exe();
    fs::path work;
    std::vector<Job> jobs;
    for (size_t i = 0; i < prep.size(); ++i) {
        if (!prep[i].runnable) continue;
        if (s.dry_run) {
            prep[i].row.status = Status::Planned;
            prep[i].row.message = "fits: " + std::to_string(prep[i].row.local_bytes) +
                                  " bytes local + " + std::to_string(prep[i].row.ext_bytes) +
                                  " bytes external per PE";
            continue;
        }
        if (work.empty()) {
            std::string tmpl =
                (fs::temp_directory_path() / ("imapsim-" + s.command + "-XXXXXX")).string();
            if (!::mkdtemp(tmpl.data()))
                throw UserError("cannot create a work folder under " +
                                    fs::temp_directory_path().string() + ": " +
                                    std::strerror(errno),
                                kExitInternal);
            work = tmpl;
        }
        Job j;
        j.point = i;
        j.log = work / ("point-" + std::to_string(i) + ".log");
        j.report = work / ("point-" + std::to_string(i) + ".json");
        j.argv.push_back(exe);
        j.argv.insert(j.argv.end(), prep[i].args.begin(), prep[i].args.end());
        j.argv.insert(j.argv.begin() + 4, {"--report", j.report.string()});
        prep[i].row.command = command_line(j.argv);
        jobs.push_back(std::move(j));
    }

    // Header.
    Table t;
    for (size_t i = 0; i < s.swept.size(); ++i) {
        size_t w = s.swept[i].name.size();
        for (const auto& v : s.swept[i].values) w = std::max(w, v.size());
        t.widths.push_back(w);
    }
    std::string sizes;
    for (const Axis& a : s.swept)
        sizes += (sizes.empty() ? "" : " x ") + a.name + " " + std::to_string(a.values.size());
    std::printf(
        "imapsim %s: %zu point%s%s, %s, model %s, -j %u\n", s.command.c_str(), points.size(),
        points.size() == 1 ? "" : "s", sizes.empty() ? "" : (" (" + sizes + ")").c_str(),
        s.dry_run ? "plan only (--dry-run)" : (std::to_string(jobs.size()) + " to run").c_str(),
        s.model.c_str(), par);
    std::printf("  input: %s\n", s.input.describe().c_str());
    std::string fixed;
    for (const Axis& a : s.fixed) fixed += (fixed.empty() ? "" : ", ") + a.name + "=" + a.values[0];
    if (!fixed.empty()) std::printf("  fixed: %s\n", fixed.c_str());
    std::printf("%s\n", t.header(s).c_str());
    std::fflush(stdout);

    // Run.
    std::vector<bool> done(prep.size(), false);
    for (size_t i = 0; i < prep.size(); ++i) done[i] = !prep[i].runnable || s.dry_run;
    std::vector<bool> started(prep.size(), false);
    size_t printed = 0;
    {
        Progress prog("points", prep.size());
        auto flush = [&]() {
            while (printed < prep.size() && done[printed]) prog.step(t.line(prep[printed++].row));
        };
        flush();
        std::map<pid_t, size_t> running;  // pid -> job
        size_t next = 0;
        bool noted = false;
        while (true) {
            if (interrupt::requested()) {
                if (!noted) {
                    noted = true;
                    res.interrupted = true;
                    prog.note("imapsim " + s.command + ": interrupted (signal " +
                              std::to_string(interrupt::signal_number()) +
                              "): starting no more points; waiting for " +
                              std::to_string(running.size()) + " running");
                }
            } else {
                while (running.size() < par && next < jobs.size()) {
                    Job& j = jobs[next++];
                    started[j.point] = true;
                    if (spawn(j)) {
                        running[j.pid] = next - 1;
                    } else {
                        finish(j, 0, false, prep[j.point].row);
                        done[j.point] = true;
                    }
                }
                flush();
            }
            if (running.empty() && (next == jobs.size() || res.interrupted)) break;
            if (running.empty()) continue;
            int st = 0;
            const pid_t pid = ::waitpid(-1, &st, 0);
            if (pid < 0) {
                if (errno == EINTR) continue;
                // No children left that we know of: record the rest as errors.
                for (const auto& [p, k] : running) {
                    prep[jobs[k].point].row.status = Status::Error;
                    prep[jobs[k].point].row.message = "lost track of the child process";
                    done[jobs[k].point] = true;
                }
                running.clear();
                continue;
            }
            const auto it = running.find(pid);
            if (it == running.end()) continue;
            const Job& j = jobs[it->second];
            running.erase(it);
            finish(j, st, true, prep[j.point].row);
            done[j.point] = true;
            flush();
        }
        // What finished after an interrupt (points that never started are left out).
        for (size_t i = printed; i < prep.size(); ++i)
            if (done[i]) prog.step(t.line(prep[i].row));
        prog.finish();
    }

    for (size_t i = 0; i < prep.size(); ++i) {
        if (done[i])
            res.rows.push_back(std::move(prep[i].row));
        else
            ++res.not_run;
    }
    // Phase names: the program's order, then any other name a report gave.
    for (const Row& r : res.rows)
        for (const auto& [n, c] : r.phases)
            if (std::find(res.phase_names.begin(), res.phase_names.end(), n) ==
                res.phase_names.end())
                res.phase_names.push_back(n);
    res.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();

    // Summary.
    const size_t ran = res.count(Status::Ok) + res.count(Status::Mismatch);
    std::printf("%zu point%s: ", res.total, res.total == 1 ? "" : "s");
    if (s.dry_run)
        std::printf("%zu fit%s", res.count(Status::Planned),
                    res.count(Status::Planned) == 1 ? "s" : "");
    else
        std::printf("%zu ran (%zu bit-exact, %zu not bit-exact)", ran, res.count(Status::Ok),
                    res.count(Status::Mismatch));
    std::printf(", %zu do%s not fit, %zu cannot run, %zu error%s", res.count(Status::DoesNotFit),
                res.count(Status::DoesNotFit) == 1 ? "es" : "", res.count(Status::CannotRun),
                res.count(Status::Error), res.count(Status::Error) == 1 ? "" : "s");
    if (res.interrupted)
        std::printf(", %zu interrupted, %zu not run (sweep interrupted)",
                    res.count(Status::Interrupted), res.not_run);
    std::printf("; wall %.1f s\n", res.wall_s);
    if (!work.empty()) {
        std::error_code ec;
        if (res.count(Status::Error) || res.count(Status::Mismatch)) {
            res.logs = work.string();
            std::printf("  logs of the failed points kept in %s\n", work.c_str());
        } else {
            fs::remove_all(work, ec);
        }
    }
    std::fflush(stdout);
    return res;
}

// ---- CSV and JSON -----------------------------------------------------------------------

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string to_csv(const Spec& s, const Result& r) {
    std::ostringstream o;
    std::vector<std::string> head;
    for (const Axis& a : s.swept) head.push_back(a.name);
    for (const char* c : {"cycles", "modeled_ms", "fps", "status", "message", "bit_exact", "wall_s",
                          "local_bytes_per_pe", "ext_bytes_per_pe"})
        head.push_back(c);
    for (const std::string& p : r.phase_names) head.push_back("phase_" + p);
    auto emit = [&](const std::vector<std::string>& cells) {
        for (size_t i = 0; i < cells.size(); ++i) o << (i ? "," : "") << csv_field(cells[i]);
        o << "\n";
    };
    emit(head);
    for (const Row& row : r.rows) {
        std::vector<std::string> c = row.values;
        c.push_back(row.ran ? std::to_string(row.cycles) : "");
        c.push_back(row.ran ? fmt("%.6f", row.modeled_ms) : "");
        c.push_back(row.ran ? fmt("%.4f", row.fps) : "");
        c.push_back(status_name(row.status));
        c.push_back(row.message);
        c.push_back(row.ran ? (row.bit_exact ? "yes" : "no") : "");
        c.push_back(row.wall_s > 0 ? fmt("%.3f", row.wall_s) : "");
        c.push_back(row.local_bytes >= 0 ? std::to_string(row.local_bytes) : "");
        c.push_back(row.ext_bytes >= 0 ? std::to_string(row.ext_bytes) : "");
        for (const std::string& p : r.phase_names) {
            std::string v;
            if (row.ran) {
                v = "0";
                for (const auto& [n, cyc] : row.phases)
                    if (n == p) v = std::to_string(cyc);
            }
            c.push_back(v);
        }
        emit(c);
    }
    if (r.interrupted) {
        std::vector<std::string> c(head.size());
        c[s.swept.size() + 3] = "sweep-interrupted";
        c[s.swept.size() + 4] = "sweep interrupted: " + std::to_string(r.not_run) + " of " +
                                std::to_string(r.total) + " points did not run";
        emit(c);
    }
    return o.str();
}

json to_json(const Spec& s, const Result& r) {
    json j;
    j["command"] = "imapsim " + s.command;
    j["model"] = s.model;
    j["dry_run"] = s.dry_run;
    j["input"] = s.input.describe();
    json sw = json::array();
    for (const Axis& a : s.swept)
        sw.push_back({{"name", a.name}, {"flag", a.flag}, {"values", a.values}});
    j["swept"] = sw;

    // Fixed parameters: everything not swept, as resolved for the run.
    std::set<std::string> swept_names;
    for (const Axis& a : s.swept) swept_names.insert(a.name);
    json fixed;
    AlgoFlags af = s.algo;
    af.roi.clear();
    af.D = af.km = af.kb = af.gb = af.Wo = af.Wd = "";  // lists: the axes say
    af.mode = "bidir";
    isa::MachineConfig cfg;
    for (const Axis& a : s.fixed) {
        const std::string& v = a.values.front();
        if (a.name == "D") af.D = v;
        if (a.name == "km") af.km = v;
        if (a.name == "kb") af.kb = v;
        if (a.name == "gb") af.gb = v;
        if (a.name == "Wo") af.Wo = v;
        if (a.name == "Wd") af.Wd = v;
        if (a.name == "mode") af.mode = v;
        if (a.kind == AxisKind::Machine) {
            try {
                cfg.set(a.name, v);
            } catch (const std::exception&) {
            }
        }
    }
    try {
        g::Roi unused;
        bool has = false;
        json alg = algo_params_json(parse_algo_flags(af, &unused, &has));
        for (const std::string& n : swept_names) alg.erase(n);
        fixed["algorithm"] = alg;
    } catch (const std::exception&) {
    }
    json mach = json::object();
    for (const isa::ParamInfo& pi : cfg.list())
        if (!swept_names.count(pi.name)) mach[pi.name] = pi.value;
    fixed["machine"] = mach;
    if (!swept_names.count("roi_size")) {
        const Axis* rs = nullptr;
        for (const Axis& a : s.fixed)
            if (a.name == "roi_size") rs = &a;
        if (s.input.left.empty())
            fixed["roi_size"] = rs ? rs->values.front() : std::string("128x128");
        else if (s.input.has_fixed_roi)
            fixed["roi"] = {s.input.roi_x0, s.input.roi_y0, s.input.roi_w, s.input.roi_h};
        else if (rs)
            fixed["roi_size"] = rs->values.front() + " (centred)";
        else
            fixed["roi"] = "whole image";
    }
    j["fixed"] = fixed;

    j["points_total"] = r.total;
    j["points_finished"] = r.rows.size();
    j["interrupted"] = r.interrupted;
    j["not_run"] = r.not_run;
    if (r.interrupted)
        j["interrupt_message"] = "sweep interrupted: " + std::to_string(r.not_run) + " of " +
                                 std::to_string(r.total) + " points did not run";
    json counts;
    for (Status st : {Status::Ok, Status::Mismatch, Status::DoesNotFit, Status::CannotRun,
                      Status::Planned, Status::Error, Status::Interrupted})
        counts[status_name(st)] = r.count(st);
    j["counts"] = counts;
    j["wall_s"] = r.wall_s;
    j["exit_code"] = r.exit_code();
    j["phase_names"] = r.phase_names;
    json rows = json::array();
    for (const Row& row : r.rows) {
        json o;
        json pt = json::object();
        for (size_t i = 0; i < s.swept.size(); ++i) pt[s.swept[i].name] = row.values[i];
        o["point"] = pt;
        o["status"] = status_name(row.status);
        if (!row.message.empty()) o["message"] = row.message;
        if (row.ran) {
            o["cycles"] = row.cycles;
            o["modeled_ms"] = row.modeled_ms;
            o["fps"] = row.fps;
            o["bit_exact"] = row.bit_exact;
            json ph = json::object();
            for (const auto& [n, c] : row.phases) ph[n] = c;
            o["phases"] = ph;
        }
        if (row.wall_s > 0) o["wall_s"] = row.wall_s;
        if (row.local_bytes >= 0) o["local_bytes_per_pe"] = row.local_bytes;
        if (row.ext_bytes >= 0) o["ext_bytes_per_pe"] = row.ext_bytes;
        if (!row.command.empty()) o["command"] = row.command;
        rows.push_back(o);
    }
    j["rows"] = rows;
    return j;
}

}  // namespace imapsim::sweep
