#include "imap/engine/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "imap/engine/error.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"

namespace imap::engine::sweep {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;
using nlohmann::json;

// ---- axes -------------------------------------------------------------------------

namespace {

bool parse_wxh(const std::string& v, int* w, int* h) {
    const size_t x = v.find('x');
    if (x == std::string::npos) return false;
    long long a = 0, b = 0;
    if (!parse_uint_text(v.substr(0, x), &a) || !parse_uint_text(v.substr(x + 1), &b)) return false;
    if (a > 1000000 || b > 1000000) return false;
    *w = static_cast<int>(a);
    *h = static_cast<int>(b);
    return true;
}

struct AlgoInt {
    const char* name;
    long long lo, hi;
    int g::Params::*field;
};
const AlgoInt kAlgoInts[] = {
    {"D", 1, g::kMaxLevels, &g::Params::D},   {"km", 0, g::kMaxWeight, &g::Params::km},
    {"kb", 0, g::kMaxWeight, &g::Params::kb}, {"gb", 0, 255, &g::Params::gb},
    {"Wo", 0, g::kMaxWeight, &g::Params::Wo}, {"Wd", 0, g::kMaxWeight, &g::Params::Wd}};

const isa::ParamInfo* machine_param(const std::vector<isa::ParamInfo>& list, const std::string& n) {
    for (const isa::ParamInfo& pi : list)
        if (pi.name == n) return &pi;
    return nullptr;
}

ValueType machine_type(const isa::ParamInfo& pi) {
    if (pi.range.find('|') != std::string::npos) return ValueType::Text;
    if (pi.name == "clock_mhz" || pi.group == "energy" || pi.group == "board" ||
        pi.range.find('.') != pi.range.rfind("..") ||
        pi.range.find("exclusive") != std::string::npos)
        return ValueType::Real;
    return ValueType::Int;
}

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
                throw Error("invalid value '" + v + "' in " + flag +
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
                throw Error("invalid value '" + v + "' in " + flag +
                            ": expected single, bidir or single,bidir");
        return a;
    }
    for (const AlgoInt& r : kAlgoInts)
        if (name == r.name) {
            a.kind = AxisKind::Algo;
            a.values = parse_value_list(flag, text, ValueType::Int);
            for (const std::string& v : a.values) {
                long long x = 0;
                parse_uint_text(v, &x);
                if (x < r.lo || x > r.hi)
                    throw Error("value " + v + " for " + flag + " is out of range (allowed: " +
                                std::to_string(r.lo) + ".." + std::to_string(r.hi) + ")");
            }
            return a;
        }
    // A machine or cost parameter.
    a.kind = AxisKind::Machine;
    const isa::MachineConfig probe;
    const std::vector<isa::ParamInfo> list = probe.list();
    const isa::ParamInfo* pi = machine_param(list, name);
    if (!pi) {
        std::string names;
        for (const isa::ParamInfo& p : list) names += (names.empty() ? "" : ", ") + p.name;
        throw Error("unknown machine parameter '" + name + "' in " + flag + " (known: " + names +
                    ")");
    }
    a.values = parse_value_list(flag, text, machine_type(*pi));
    for (const std::string& v : a.values) {
        isa::MachineConfig c;
        try {
            c.set(name, v);
        } catch (const std::exception& e) {
            throw Error(flag + ": " + e.what());
        }
    }
    return a;
}

double numeric_value(const Axis& a, const std::string& v) {
    if (a.kind == AxisKind::RoiSize || a.name == "mode") return NAN;
    double d = 0;
    return parse_real_text(v, &d) ? d : NAN;
}

std::string Input::describe() const {
    if (left.empty())
        return "synthetic scene seed " + std::to_string(seed) + " (generated at the ROI size)";
    std::string d =
        left + " + " + right + " (" + std::to_string(width) + "x" + std::to_string(height) + ")";
    if (has_fixed_roi)
        d += ", ROI " + std::to_string(roi.x0) + "," + std::to_string(roi.y0) + "," +
             std::to_string(roi.w) + "," + std::to_string(roi.h);
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
        throw Error("the sweep has " +
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

namespace {

constexpr std::pair<Status, const char*> kStatusNames[] = {
    {Status::Ok, "ok"},
    {Status::Mismatch, "mismatch"},
    {Status::DoesNotFit, "does-not-fit"},
    {Status::CannotRun, "cannot-run"},
    {Status::Planned, "fits-not-run"},
    {Status::Error, "error"},
    {Status::Interrupted, "interrupted"},
};

Status status_from_name(const std::string& s) {
    for (const auto& [k, n] : kStatusNames)
        if (s == n) return k;
    throw Error("sweep plan: unknown status '" + s + "'");
}

}  // namespace

const char* status_name(Status s) {
    for (const auto& [k, n] : kStatusNames)
        if (k == s) return n;
    return "?";
}

size_t Result::count(Status s) const {
    return static_cast<size_t>(
        std::count_if(rows.begin(), rows.end(), [s](const Row& r) { return r.status == s; }));
}

int Result::exit_code(bool dry_run) const {
    if (interrupted) return kExitInterrupted;
    if (count(Status::Error)) return kExitItemErrors;
    if (dry_run ? count(Status::Planned) == 0 : ran() == 0) return kExitItemErrors;
    if (count(Status::Mismatch)) return kExitMismatch;
    return kExitOk;
}

// ---- planning a point -------------------------------------------------------------

namespace {

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

struct Prepared {
    Row row;
    std::vector<std::string> args;  // the job's imapsim arguments (empty: not runnable)
    std::vector<std::string> phases;
};

std::string machine_flag(const std::string& n) {
    if (n == "pes" || n == "clock_mhz" || n == "mem_bytes" || n == "ext_bytes") {
        std::string f = "--" + n;
        std::replace(f.begin(), f.end(), '_', '-');
        return f;
    }
    return "";
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

    // Algorithm parameters: the base, then the axes.
    g::Params p = s.base;
    for (const AlgoInt& r : kAlgoInts)
        if (const std::string* v = value_of(s, pt, r.name)) p.*(r.field) = std::atoi(v->c_str());
    if (const std::string* v = value_of(s, pt, "mode"))
        p.mode = *v == "single" ? g::Mode::Single : g::Mode::Bidir;
    try {
        g::validate_params(p);
    } catch (const g::ParamError& e) {
        return cannot(e.what());
    }

    // Machine parameters.
    isa::MachineConfig cfg;
    std::vector<std::pair<std::string, std::string>> machine;  // name, value (for the child)
    try {
        auto add = [&](const Axis& a, const std::string& v) {
            if (a.kind != AxisKind::Machine) return;
            machine.emplace_back(a.name, v);
            cfg.set(a.name, v);
        };
        for (const Axis& a : s.fixed) add(a, a.values.front());
        for (size_t i = 0; i < s.swept.size(); ++i) add(s.swept[i], s.swept[i].values[pt[i]]);
        cfg.validate();
    } catch (const std::exception& e) {
        return cannot(e.what());
    }

    // The ROI and the image size.
    g::Roi roi;
    int img_w = 0, img_h = 0;
    const std::string* rs = value_of(s, pt, "roi_size");
    int rw = 128, rh = 128;
    if (rs) parse_wxh(*rs, &rw, &rh);
    if (s.input.left.empty()) {
        roi = {0, 0, rw, rh};
        img_w = rw;
        img_h = rh;
    } else {
        img_w = s.input.width;
        img_h = s.input.height;
        if (s.input.has_fixed_roi) {
            roi = s.input.roi;
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

    // The job's command line.
    std::vector<std::string>& a = pr.args;
    a = {"run", "--model", s.model};
    const std::string roi_txt = std::to_string(roi.x0) + "," + std::to_string(roi.y0) + "," +
                                std::to_string(roi.w) + "," + std::to_string(roi.h);
    if (s.input.left.empty())
        a.insert(a.end(), {"--seed", std::to_string(s.input.seed), "--size",
                           std::to_string(rw) + "x" + std::to_string(rh), "--roi", roi_txt});
    else
        a.insert(a.end(), {"--left", s.input.left, "--right", s.input.right, "--roi", roi_txt});
    for (const char* n : {"D", "km", "kb", "gb", "Wo", "Wd", "mode"})
        if (const std::string* v = value_of(s, pt, n))
            a.insert(a.end(), {std::string("--") + n, *v});
    a.insert(a.end(), s.base_args.begin(), s.base_args.end());
    for (const auto& [n, v] : machine) {
        const std::string f = machine_flag(n);
        if (!f.empty())
            a.insert(a.end(), {f, v});
        else
            a.insert(a.end(), {"--set", n + "=" + v});
    }
    row.status = Status::Planned;
    return pr;
}

std::string job_id(size_t point) {
    char b[32];
    std::snprintf(b, sizeof b, "p%05zu", point);
    return b;
}

}  // namespace

Plan plan(const Spec& s) {
    Plan pl;
    pl.command = s.command;
    pl.model = s.model;
    pl.dry_run = s.dry_run;
    pl.input = s.input.describe();
    pl.synthetic = s.input.left.empty();
    pl.swept = s.swept;
    pl.fixed = s.fixed;
    const std::vector<std::vector<size_t>> points = s.points.empty() ? product(s.swept) : s.points;
    if (points.size() > kMaxPoints)
        throw Error("the sweep has " + std::to_string(points.size()) + " points; at most " +
                    std::to_string(kMaxPoints) + " are allowed");

    // The fixed parameters of the JSON report: everything not swept.
    std::set<std::string> swept_names;
    for (const Axis& a : s.swept) swept_names.insert(a.name);
    json fixed;
    json alg = s.fixed_algorithm;
    for (const std::string& n : swept_names) alg.erase(n);
    fixed["algorithm"] = alg;
    isa::MachineConfig cfg;
    for (const Axis& a : s.fixed)
        if (a.kind == AxisKind::Machine) {
            try {
                cfg.set(a.name, a.values.front());
            } catch (const std::exception&) {
            }
        }
    json mach = machine_params_json(cfg);
    for (const std::string& n : swept_names) mach.erase(n);
    fixed["machine"] = mach;
    if (!swept_names.count("roi_size")) {
        const Axis* rs = nullptr;
        for (const Axis& a : s.fixed)
            if (a.name == "roi_size") rs = &a;
        if (s.input.left.empty())
            fixed["roi_size"] = rs ? rs->values.front() : std::string("128x128");
        else if (s.input.has_fixed_roi)
            fixed["roi"] = {s.input.roi.x0, s.input.roi.y0, s.input.roi.w, s.input.roi.h};
        else if (rs)
            fixed["roi_size"] = rs->values.front() + " (centred)";
        else
            fixed["roi"] = "whole image";
    }
    pl.fixed_params = fixed;

    for (size_t k = 0; k < points.size(); ++k) {
        Prepared pr = prepare(s, points[k], pl.phase_names.empty());
        if (pl.phase_names.empty() && !pr.phases.empty()) pl.phase_names = pr.phases;
        if (!pr.args.empty()) {
            if (s.dry_run) {
                pr.row.message = "fits: " + std::to_string(pr.row.local_bytes) + " bytes local + " +
                                 std::to_string(pr.row.ext_bytes) + " bytes external per PE";
            } else {
                pr.row.job = static_cast<int>(pl.jobs.size());
                pl.jobs.push_back({job_id(k), s.model, pr.args});
            }
        }
        pl.rows.push_back(std::move(pr.row));
    }
    // Phase names in program order, without duplicates (a phase may recur).
    std::vector<std::string> uniq;
    for (const std::string& n : pl.phase_names)
        if (std::find(uniq.begin(), uniq.end(), n) == uniq.end()) uniq.push_back(n);
    pl.phase_names = uniq;
    return pl;
}

// ---- plan as JSON (the run folder's payload) ------------------------------------------

namespace {

const char* kind_name(AxisKind k) {
    return k == AxisKind::Machine ? "machine" : k == AxisKind::RoiSize ? "roi_size" : "algorithm";
}

AxisKind kind_from(const std::string& s) {
    if (s == "machine") return AxisKind::Machine;
    if (s == "roi_size") return AxisKind::RoiSize;
    if (s == "algorithm") return AxisKind::Algo;
    throw Error("sweep plan: unknown axis kind '" + s + "'");
}

json axes_json(const std::vector<Axis>& axes) {
    json a = json::array();
    for (const Axis& x : axes)
        a.push_back({{"name", x.name},
                     {"flag", x.flag},
                     {"kind", kind_name(x.kind)},
                     {"values", x.values}});
    return a;
}

std::vector<Axis> axes_from(const json& j) {
    std::vector<Axis> out;
    for (const json& x : j)
        out.push_back({x.at("name").get<std::string>(), x.at("flag").get<std::string>(),
                       kind_from(x.at("kind").get<std::string>()),
                       x.at("values").get<std::vector<std::string>>()});
    return out;
}

}  // namespace

json to_json(const Plan& p) {
    json j;
    j["kind"] = "sweep-plan";
    j["command"] = p.command;
    j["model"] = p.model;
    j["dry_run"] = p.dry_run;
    j["input"] = p.input;
    j["synthetic"] = p.synthetic;
    j["swept"] = axes_json(p.swept);
    j["fixed_axes"] = axes_json(p.fixed);
    j["fixed"] = p.fixed_params;
    j["phase_names"] = p.phase_names;
    json rows = json::array();
    for (const Row& r : p.rows) {
        json o = {{"values", r.values}, {"status", status_name(r.status)}};
        if (!r.message.empty()) o["message"] = r.message;
        if (r.local_bytes >= 0) o["local_bytes"] = r.local_bytes;
        if (r.ext_bytes >= 0) o["ext_bytes"] = r.ext_bytes;
        if (r.job >= 0) o["job"] = r.job;
        rows.push_back(o);
    }
    j["rows"] = rows;
    return j;
}

Plan plan_from_json(const json& j) {
    try {
        if (j.value("kind", std::string()) != "sweep-plan")
            throw Error("the run folder does not hold a sweep (its plan is of another command)");
        Plan p;
        p.command = j.at("command").get<std::string>();
        p.model = j.at("model").get<std::string>();
        p.dry_run = j.at("dry_run").get<bool>();
        p.input = j.at("input").get<std::string>();
        p.synthetic = j.at("synthetic").get<bool>();
        p.swept = axes_from(j.at("swept"));
        p.fixed = axes_from(j.at("fixed_axes"));
        p.fixed_params = j.at("fixed");
        p.phase_names = j.at("phase_names").get<std::vector<std::string>>();
        for (const json& o : j.at("rows")) {
            Row r;
            r.values = o.at("values").get<std::vector<std::string>>();
            r.status = status_from_name(o.at("status").get<std::string>());
            r.message = o.value("message", std::string());
            r.local_bytes = o.value("local_bytes", int64_t{-1});
            r.ext_bytes = o.value("ext_bytes", int64_t{-1});
            r.job = o.value("job", -1);
            if (r.values.size() != p.swept.size())
                throw Error("sweep plan: a row has the wrong size");
            p.rows.push_back(std::move(r));
        }
        return p;
    } catch (const json::exception& e) {
        throw Error(std::string("sweep plan: ") + e.what());
    }
}

// ---- the table on stdout --------------------------------------------------------------

namespace {

std::vector<size_t> value_widths(const Plan& p) {
    std::vector<size_t> w;
    for (const Axis& a : p.swept) {
        size_t n = a.name.size();
        for (const auto& v : a.values) n = std::max(n, v.size());
        w.push_back(n);
    }
    return w;
}

std::string dominant_text(const RunResult& r) {
    const std::string d = r.dominant_phase();
    if (d.empty()) return "-";
    char b[64];
    std::snprintf(b, sizeof b, "%s %.0f%%", d.c_str(), 100.0 * r.dominant_share());
    return b;
}

}  // namespace

const char* metric_name(Metric m) {
    switch (m) {
        case Metric::Time:
            return "time";
        case Metric::Energy:
            return "energy";
        case Metric::Power:
            return "power";
        case Metric::Edp:
            return "edp";
        case Metric::Area:
            return "area";
    }
    return "?";
}

std::optional<Metric> metric_from_name(const std::string& s) {
    for (Metric m : {Metric::Time, Metric::Energy, Metric::Power, Metric::Edp, Metric::Area})
        if (s == metric_name(m)) return m;
    return std::nullopt;
}

double metric_value(const Row& r, Metric m) {
    if (!r.ran()) return NAN;
    const RunResult& x = *r.run;
    switch (m) {
        case Metric::Time:
            return x.modeled_ms;
        case Metric::Energy:
            return x.energy ? x.energy->total_uj : NAN;
        case Metric::Power:
            return x.energy ? x.energy->power_mw : NAN;
        case Metric::Edp:
            return x.energy ? x.energy->total_uj * x.modeled_ms : NAN;
        case Metric::Area:
            return x.area ? static_cast<double>(x.area->cells) : NAN;
    }
    return NAN;
}

namespace {

// The column --y adds to the table (energy, power, edp; time and area have
// theirs already): its heading and the value's text.
const char* metric_column(Metric m) {
    switch (m) {
        case Metric::Energy:
            return "energy uJ";
        case Metric::Power:
            return "power mW";
        case Metric::Edp:
            return "EDP uJ*ms";
        default:
            return nullptr;
    }
}

std::string metric_text(Metric m, double v) {
    if (std::isnan(v)) return "-";
    switch (m) {
        case Metric::Time:
            return fmt("%.3f ms", v);
        case Metric::Energy:
            return fmt("%.3f uJ", v);
        case Metric::Power:
            return fmt("%.3f mW", v);
        case Metric::Edp:
            return fmt("%.3f uJ*ms", v);
        case Metric::Area:
            return fmt("%.2f Mcells", v / 1e6);
    }
    return "-";
}

// "pes=256, D=64": a row's swept values (the whole point when nothing is swept).
std::string point_text(const Plan& p, const Row& r) {
    std::string t;
    for (size_t i = 0; i < p.swept.size() && i < r.values.size(); ++i)
        t += (t.empty() ? "" : ", ") + p.swept[i].name + "=" + r.values[i];
    return t.empty() ? std::string("the point") : t;
}

}  // namespace

std::vector<std::string> header_lines(const Plan& p, const Executor* ex) {
    std::vector<std::string> out;
    std::string sizes;
    for (const Axis& a : p.swept)
        sizes += (sizes.empty() ? "" : " x ") + a.name + " " + std::to_string(a.values.size());
    char b[512];
    std::snprintf(
        b, sizeof b, "imapsim %s: %zu point%s%s, %s, model %s%s", p.command.c_str(), p.rows.size(),
        p.rows.size() == 1 ? "" : "s", sizes.empty() ? "" : (" (" + sizes + ")").c_str(),
        p.dry_run ? "plan only (--dry-run)" : (std::to_string(p.jobs.size()) + " to run").c_str(),
        p.model.c_str(), ex && !p.dry_run ? (", " + ex->describe()).c_str() : "");
    out.push_back(b);
    out.push_back("  input: " + p.input);
    std::string fixed;
    for (const Axis& a : p.fixed) fixed += (fixed.empty() ? "" : ", ") + a.name + "=" + a.values[0];
    if (!fixed.empty()) out.push_back("  fixed: " + fixed);
    std::string h;
    const std::vector<size_t> w = value_widths(p);
    for (size_t i = 0; i < p.swept.size(); ++i) {
        std::snprintf(b, sizeof b, "%*s  ", static_cast<int>(w[i]), p.swept[i].name.c_str());
        h += b;
    }
    std::snprintf(b, sizeof b, "%10s %10s ", "cycles", "modeled ms");
    h += b;
    if (const char* col = metric_column(p.y)) {
        std::snprintf(b, sizeof b, "%10s ", col);
        h += b;
    }
    std::snprintf(b, sizeof b, "%8s %5s %8s %8s  %-17s %7s  %s", "fps", "eff", "local B", "Mcells",
                  "dominant phase", "wall s", "result");
    out.push_back(h + b);
    return out;
}

std::string row_line(const Plan& p, const Row& r) {
    const std::vector<size_t> w = value_widths(p);
    std::string l;
    char b[512];
    for (size_t i = 0; i < r.values.size() && i < w.size(); ++i) {
        std::snprintf(b, sizeof b, "%*s  ", static_cast<int>(w[i]), r.values[i].c_str());
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
    const bool ran = r.ran();
    std::snprintf(b, sizeof b, "%10s %10s ", ran ? std::to_string(r.run->cycles).c_str() : "-",
                  ran ? fmt("%.3f", r.run->modeled_ms).c_str() : "-");
    l += b;
    if (metric_column(p.y)) {
        const double v = metric_value(r, p.y);
        std::snprintf(b, sizeof b, "%10s ", std::isnan(v) ? "-" : fmt("%.3f", v).c_str());
        l += b;
    }
    std::snprintf(
        b, sizeof b, "%8s %5s %8s %8s  %-17s %7s  ", ran ? fmt("%.2f", r.fps()).c_str() : "-",
        ran && r.run->bound_cycles > 0 ? fmt("%.0f%%", 100.0 * r.run->efficiency()).c_str() : "-",
        r.local_bytes >= 0 ? std::to_string(r.local_bytes).c_str() : "-",
        ran && r.run->area ? fmt("%.2f", r.run->area->cells / 1e6).c_str() : "-",
        ran ? dominant_text(*r.run).c_str() : "-",
        r.run && r.run->wall_s > 0 ? fmt("%.2f", r.run->wall_s).c_str() : "-");
    return l + b + result;
}

// ---- running --------------------------------------------------------------------------

namespace {

void apply(Row& row, RunResult r) {
    switch (r.outcome) {
        case Outcome::Ok:
            row.status = Status::Ok;
            row.message.clear();
            break;
        case Outcome::Mismatch:
            row.status = Status::Mismatch;
            row.message = describe(r);
            break;
        case Outcome::Interrupted:
            row.status = Status::Interrupted;
            row.message = describe(r);
            break;
        default:
            row.status = Status::Error;
            row.message = describe(r);
    }
    row.run = std::move(r);
}

}  // namespace

Result run(const Plan& p, Executor& ex, RunDir& dir, Manifest& m, const ExecContext& ctx,
           Hooks& hooks, bool resume, size_t x_axis) {
    Result res;
    res.total = p.rows.size();
    std::vector<Row> rows = p.rows;
    std::vector<bool> done(rows.size(), false);
    std::vector<size_t> row_of(p.jobs.size(), 0);
    for (size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].job >= 0 && static_cast<size_t>(rows[i].job) < row_of.size())
            row_of[static_cast<size_t>(rows[i].job)] = i;
        else
            done[i] = true;
    }
    size_t printed = 0;
    auto flush = [&]() {
        while (printed < rows.size() && done[printed]) hooks.row(row_line(p, rows[printed++]));
    };
    flush();
    ExecHooks eh;
    eh.stop_requested = hooks.stop_requested;
    eh.on_note = hooks.note;
    eh.on_status = hooks.status;
    eh.on_result = [&](size_t j, RunResult r) {
        const size_t i = row_of[j];
        apply(rows[i], std::move(r));
        done[i] = true;
        flush();
    };
    DriveOutcome d;
    if (!p.jobs.empty()) {
        d = drive(dir, m, ex, ctx, eh, resume);
    }
    res.interrupted = d.interrupted;
    res.reused = d.reused;
    res.wall_s = d.wall_s;
    // What finished after an interrupt (points that never ran are left out).
    for (size_t i = printed; i < rows.size(); ++i)
        if (done[i]) hooks.row(row_line(p, rows[i]));
    for (size_t i = 0; i < rows.size(); ++i) {
        if (done[i])
            res.rows.push_back(std::move(rows[i]));
        else
            ++res.not_run;
    }
    if (res.not_run) res.interrupted = true;
    // Phase names: the program's order, then any other name a report gave.
    res.phase_names = p.phase_names;
    for (const Row& r : res.rows)
        if (r.run)
            for (const auto& [n, c] : r.run->phases)
                if (std::find(res.phase_names.begin(), res.phase_names.end(), n) ==
                    res.phase_names.end())
                    res.phase_names.push_back(n);
    if (x_axis < p.swept.size()) {
        res.x_axis = p.swept[x_axis].name;
        res.knees = find_knees(p, res.rows, x_axis);
    }
    return res;
}

std::vector<std::string> summary_lines(const Plan& p, const Result& r) {
    std::vector<std::string> out;
    char b[1024];
    std::string s;
    std::snprintf(b, sizeof b, "%zu point%s: ", r.total, r.total == 1 ? "" : "s");
    s = b;
    if (p.dry_run)
        std::snprintf(b, sizeof b, "%zu fit%s", r.count(Status::Planned),
                      r.count(Status::Planned) == 1 ? "s" : "");
    else
        std::snprintf(b, sizeof b, "%zu ran (%zu bit-exact, %zu not bit-exact)", r.ran(),
                      r.count(Status::Ok), r.count(Status::Mismatch));
    s += b;
    std::snprintf(b, sizeof b, ", %zu do%s not fit, %zu cannot run, %zu error%s",
                  r.count(Status::DoesNotFit), r.count(Status::DoesNotFit) == 1 ? "es" : "",
                  r.count(Status::CannotRun), r.count(Status::Error),
                  r.count(Status::Error) == 1 ? "" : "s");
    s += b;
    if (r.interrupted) {
        std::snprintf(b, sizeof b, ", %zu interrupted, %zu not run (%s interrupted)",
                      r.count(Status::Interrupted), r.not_run, p.command.c_str());
        s += b;
    }
    if (r.reused) {
        std::snprintf(b, sizeof b, ", %zu taken from the run folder", r.reused);
        s += b;
    }
    std::snprintf(b, sizeof b, "; wall %.1f s", r.wall_s);
    out.push_back(s + b);
    if (!r.interrupted) {
        if (p.dry_run && r.count(Status::Planned) == 0)
            out.push_back(
                "  nothing fits: no point can run (every point does not fit or cannot "
                "run)");
        else if (!p.dry_run && r.ran() == 0)
            out.push_back(r.count(Status::Error)
                              ? "  nothing ran: every point that fits failed"
                              : "  nothing ran: no point can run (every point does not fit or "
                                "cannot run)");
    }
    for (const Knee& k : r.knees) out.push_back("  " + k.explanation);
    // --y other than time: the point with the least of it.
    if (p.y != Metric::Time) {
        const Row* best = nullptr;
        for (const Row& row : r.rows) {
            const double v = metric_value(row, p.y);
            if (row.status == Status::Ok && !std::isnan(v) &&
                (!best || v < metric_value(*best, p.y)))
                best = &row;
        }
        if (best)
            out.push_back("  least " + std::string(metric_name(p.y)) + ": " + point_text(p, *best) +
                          ", " + metric_text(p.y, metric_value(*best, p.y)) + " (" +
                          metric_text(Metric::Time, best->run->modeled_ms) + ")");
        else
            out.push_back("  least " + std::string(metric_name(p.y)) +
                          ": no bit-exact point reports it");
    }
    return out;
}

// ---- knees --------------------------------------------------------------------------

namespace {

struct SeriesPoints {
    std::string label;
    std::vector<const Row*> rows;  // ran, sorted by x
    std::vector<double> x;
};

std::string series_label(const Plan& p, const Row& r, size_t xi) {
    std::string label;
    for (size_t i = 0; i < p.swept.size(); ++i)
        if (i != xi) label += (label.empty() ? "" : ", ") + p.swept[i].name + "=" + r.values[i];
    return label;
}

std::vector<SeriesPoints> series_of(const Plan& p, const std::vector<Row>& rows, size_t xi,
                                    const std::vector<double>& xv) {
    std::vector<SeriesPoints> out;
    std::map<std::string, size_t> index;
    const Axis& ax = p.swept[xi];
    for (const Row& r : rows) {
        if (r.status != Status::Ok) continue;
        const std::string label = series_label(p, r, xi);
        auto it = index.find(label);
        if (it == index.end()) {
            it = index.emplace(label, out.size()).first;
            out.push_back({label, {}, {}});
        }
        const size_t vi = static_cast<size_t>(
            std::find(ax.values.begin(), ax.values.end(), r.values[xi]) - ax.values.begin());
        out[it->second].rows.push_back(&r);
        out[it->second].x.push_back(vi < xv.size() ? xv[vi] : NAN);
    }
    for (SeriesPoints& s : out) {
        std::vector<size_t> ord(s.rows.size());
        for (size_t i = 0; i < ord.size(); ++i) ord[i] = i;
        std::sort(ord.begin(), ord.end(), [&](size_t a, size_t b) { return s.x[a] < s.x[b]; });
        SeriesPoints t{s.label, {}, {}};
        for (size_t i : ord) {
            t.rows.push_back(s.rows[i]);
            t.x.push_back(s.x[i]);
        }
        s = t;
    }
    return out;
}

uint64_t phase_cycles(const RunResult& r, const std::string& n) {
    for (const auto& [k, c] : r.phases)
        if (k == n) return c;
    return 0;
}

// The phase whose cycles change most from a to b, and its relative change.
std::pair<std::string, double> driver(const RunResult& a, const RunResult& b) {
    std::set<std::string> names;
    for (const auto& [n, c] : a.phases) names.insert(n);
    for (const auto& [n, c] : b.phases) names.insert(n);
    std::string best;
    double delta = 0;
    for (const std::string& n : names) {
        const double d =
            static_cast<double>(phase_cycles(b, n)) - static_cast<double>(phase_cycles(a, n));
        if (std::fabs(d) > std::fabs(delta)) {
            delta = d;
            best = n;
        }
    }
    if (best.empty()) return {"", 0};
    const double base = static_cast<double>(phase_cycles(a, best));
    return {best, base > 0 ? delta / base : (delta > 0 ? INFINITY : 0)};
}

// An axis value in words for a plot label: "64 PEs", "80 MHz", "D = 64".
std::string axis_value_words(const Axis& a, const std::string& v) {
    if (a.name == "pes") return v + " PEs";
    if (a.name == "clock_mhz") return v + " MHz";
    if (a.name == "mem_bytes" || a.name == "ext_bytes") return v + " B per PE";
    if (a.name == "roi_size") return "ROI " + v;
    return a.name + " = " + v;
}

std::string pct(double f) {
    if (std::isinf(f)) return "from 0";
    char b[32];
    std::snprintf(b, sizeof b, "%+.0f%%", 100.0 * f);
    return b;
}

// "falls 43%" / "grows 12%" / "grows from 0".
std::string change_words(double f) {
    if (std::isinf(f)) return "grows from 0";
    char b[48];
    std::snprintf(b, sizeof b, "%s %.0f%%", f < 0 ? "falls" : "grows", 100.0 * std::fabs(f));
    return b;
}

}  // namespace

std::vector<Knee> find_knees(const Plan& p, const std::vector<Row>& rows, size_t xi) {
    std::vector<Knee> out;
    if (xi >= p.swept.size()) return out;
    const Axis& ax = p.swept[xi];
    std::vector<double> xv;
    for (const std::string& v : ax.values) xv.push_back(numeric_value(ax, v));
    if (ax.kind == AxisKind::RoiSize) {
        xv.clear();
        for (const std::string& v : ax.values) {
            int w = 0, h = 0;
            parse_wxh(v, &w, &h);
            xv.push_back(static_cast<double>(w) * h);
        }
    }
    for (double x : xv)
        if (!(x > 0)) return out;  // knees on numeric, positive axes only
    for (const SeriesPoints& s : series_of(p, rows, xi, xv)) {
        if (s.rows.size() < 3) continue;
        std::vector<double> slope;
        for (size_t i = 0; i + 1 < s.rows.size(); ++i) {
            const double y0 = s.rows[i]->run->modeled_ms, y1 = s.rows[i + 1]->run->modeled_ms;
            const double dx = std::log(s.x[i + 1]) - std::log(s.x[i]);
            slope.push_back(dx > 0 && y0 > 0 && y1 > 0 ? (std::log(y1) - std::log(y0)) / dx : 0);
        }
        size_t best = 0;
        double change = 0;
        for (size_t i = 1; i < slope.size(); ++i) {
            const double c = slope[i] - slope[i - 1];
            if (std::fabs(c) > std::fabs(change)) {
                change = c;
                best = i;
            }
        }
        if (std::fabs(change) < kKneeSlopeChange) continue;
        const RunResult& a = *s.rows[best - 1]->run;
        const RunResult& k = *s.rows[best]->run;
        const RunResult& c = *s.rows[best + 1]->run;
        Knee kn;
        kn.series = s.label;
        kn.x = s.rows[best]->values[xi];
        kn.xv = s.x[best];
        kn.y_ms = k.modeled_ms;
        kn.slope_before = slope[best - 1];
        kn.slope_after = slope[best];
        const auto [pb, fb] = driver(a, k);
        const auto [pa, fa] = driver(k, c);
        kn.phase_before = pb;
        kn.phase_after = pa;
        const std::string xa = s.rows[best - 1]->values[xi], xc = s.rows[best + 1]->values[xi];
        auto seg = [&](const std::string& from, const std::string& to, const RunResult& r0,
                       const RunResult& r1, const std::string& ph, double f) {
            std::string t =
                from + " -> " + to + ": time " + pct(r1.modeled_ms / r0.modeled_ms - 1.0);
            if (!ph.empty())
                t += " (" + ph + " " + pct(f) + ")";
            else
                t += " (cycles unchanged)";
            return t;
        };
        const std::string da = a.dominant_phase(), dc = c.dominant_phase();
        kn.explanation =
            "knee at " + ax.name + "=" + kn.x +
            (s.label.empty() ? std::string() : " [" + s.label + "]") + ": " +
            seg(xa, kn.x, a, k, pb, fb) + "; " + seg(kn.x, xc, k, c, pa, fa) +
            (da != dc ? "; dominant phase " + da + " -> " + dc : "; dominant phase " + dc);
        // The plot's label in words: what the time does beyond the knee and
        // which phase makes it do so.
        const double after = c.modeled_ms / k.modeled_ms - 1.0;
        const std::string where = "beyond " + axis_value_words(ax, kn.x);
        const bool flat = std::fabs(after) < 0.05;
        std::string what = flat ? "flat " + where : where + " the time " + change_words(after);
        if (!pa.empty()) what += std::string(flat ? ":" : ",") + " " + pa + " " + change_words(fa);
        if (da != dc) what += " (" + dc + " dominates)";
        kn.label = what;
        out.push_back(kn);
    }
    return out;
}

// ---- CSV and JSON -----------------------------------------------------------------------

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string to_csv(const Plan& p, const Result& r) {
    std::ostringstream o;
    std::vector<std::string> head;
    for (const Axis& a : p.swept) head.push_back(a.name);
    for (const char* c : {"cycles", "modeled_ms", "fps", "status", "message", "bit_exact", "wall_s",
                          "local_bytes_per_pe", "ext_bytes_per_pe", "dominant_phase",
                          "dominant_share", "area_cells", "area_memory_bits"})
        head.push_back(c);
    for (const std::string& ph : r.phase_names) head.push_back("phase_" + ph);
    head.push_back("bound_cycles");
    head.push_back("efficiency");
    // The phases with a machine bound in some row (docs/firmware.md 11).
    std::vector<std::string> bounded;
    for (const std::string& ph : r.phase_names)
        for (const Row& row : r.rows)
            if (row.ran() && row.run->bound_of(ph) > 0) {
                bounded.push_back(ph);
                break;
            }
    for (const std::string& ph : bounded) head.push_back("bound_" + ph);
    // Energy of the frame and average power over its modeled time
    // (docs/energy.md), after every other column so that their positions stay.
    head.push_back("energy_uj");
    head.push_back("power_mw");
    head.push_back("edp");  // energy x delay, uJ x ms
    auto emit = [&](const std::vector<std::string>& cells) {
        for (size_t i = 0; i < cells.size(); ++i) o << (i ? "," : "") << csv_field(cells[i]);
        o << "\n";
    };
    emit(head);
    for (const Row& row : r.rows) {
        const bool ran = row.ran();
        std::vector<std::string> c = row.values;
        c.push_back(ran ? std::to_string(row.run->cycles) : "");
        c.push_back(ran ? fmt("%.6f", row.run->modeled_ms) : "");
        c.push_back(ran ? fmt("%.4f", row.fps()) : "");
        c.push_back(status_name(row.status));
        c.push_back(row.message);
        c.push_back(ran ? (row.run->bit_exact ? "yes" : "no") : "");
        c.push_back(row.run && row.run->wall_s > 0 ? fmt("%.3f", row.run->wall_s) : "");
        c.push_back(row.local_bytes >= 0 ? std::to_string(row.local_bytes) : "");
        c.push_back(row.ext_bytes >= 0 ? std::to_string(row.ext_bytes) : "");
        c.push_back(ran ? row.run->dominant_phase() : "");
        c.push_back(ran ? fmt("%.4f", row.run->dominant_share()) : "");
        c.push_back(ran && row.run->area ? std::to_string(row.run->area->cells) : "");
        c.push_back(ran && row.run->area ? std::to_string(row.run->area->memory_bits) : "");
        for (const std::string& ph : r.phase_names)
            c.push_back(ran ? std::to_string(phase_cycles(*row.run, ph)) : "");
        const bool bd = ran && row.run->bound_cycles > 0;
        c.push_back(bd ? std::to_string(row.run->bound_cycles) : "");
        c.push_back(bd ? fmt("%.4f", row.run->efficiency()) : "");
        for (const std::string& ph : bounded) {
            const uint64_t b = ran ? row.run->bound_of(ph) : 0;
            c.push_back(b > 0 ? std::to_string(b) : "");
        }
        const bool en = ran && row.run->energy.has_value();
        c.push_back(en ? fmt("%.6f", row.run->energy->total_uj) : "");
        c.push_back(en ? fmt("%.6f", row.run->energy->power_mw) : "");
        c.push_back(en ? fmt("%.6f", metric_value(row, Metric::Edp)) : "");
        emit(c);
    }
    if (r.interrupted) {
        std::vector<std::string> c(head.size());
        c[p.swept.size() + 3] = p.command + "-interrupted";
        c[p.swept.size() + 4] = p.command + " interrupted: " + std::to_string(r.not_run) + " of " +
                                std::to_string(r.total) + " points did not run";
        emit(c);
    }
    return o.str();
}

json to_json(const Plan& p, const Result& r) {
    json j;
    j["command"] = "imapsim " + p.command;
    j["model"] = p.model;
    j["dry_run"] = p.dry_run;
    j["input"] = p.input;
    json sw = json::array();
    for (const Axis& a : p.swept)
        sw.push_back({{"name", a.name}, {"flag", a.flag}, {"values", a.values}});
    j["swept"] = sw;
    j["fixed"] = p.fixed_params;
    j["points_total"] = r.total;
    j["points_finished"] = r.rows.size();
    j["interrupted"] = r.interrupted;
    j["not_run"] = r.not_run;
    if (r.interrupted)
        j["interrupt_message"] = p.command + " interrupted: " + std::to_string(r.not_run) + " of " +
                                 std::to_string(r.total) + " points did not run";
    json counts;
    for (const auto& [st, n] : kStatusNames) counts[n] = r.count(st);
    j["counts"] = counts;
    j["wall_s"] = r.wall_s;
    j["exit_code"] = r.exit_code(p.dry_run);
    j["phase_names"] = r.phase_names;
    json knees = json::array();
    for (const Knee& k : r.knees)
        knees.push_back({{"axis", r.x_axis},
                         {"series", k.series},
                         {"at", k.x},
                         {"modeled_ms", k.y_ms},
                         {"slope_before", k.slope_before},
                         {"slope_after", k.slope_after},
                         {"phase_before", k.phase_before},
                         {"phase_after", k.phase_after},
                         {"explanation", k.explanation},
                         {"label", k.label}});
    j["knees"] = knees;
    json rows = json::array();
    for (const Row& row : r.rows) {
        json o;
        json pt = json::object();
        for (size_t i = 0; i < p.swept.size(); ++i) pt[p.swept[i].name] = row.values[i];
        o["point"] = pt;
        o["status"] = status_name(row.status);
        if (!row.message.empty()) o["message"] = row.message;
        if (row.ran()) {
            const RunResult& rr = *row.run;
            o["cycles"] = rr.cycles;
            o["modeled_ms"] = rr.modeled_ms;
            o["fps"] = row.fps();
            o["bit_exact"] = rr.bit_exact;
            json ph = json::object();
            for (const auto& [n, c] : rr.phases) ph[n] = c;
            o["phases"] = ph;
            o["dominant_phase"] = rr.dominant_phase();
            o["dominant_share"] = rr.dominant_share();
            if (rr.area)
                o["area"] = {{"cells", rr.area->cells}, {"memory_bits", rr.area->memory_bits}};
            if (rr.bound_cycles > 0) {
                json bd = json::object();
                for (const auto& [n, c] : rr.bounds) bd[n] = c;
                o["bounds"] = bd;
                o["bound_cycles"] = rr.bound_cycles;
                o["efficiency"] = rr.efficiency();
            }
            if (rr.energy) {
                o["energy"] = energy_json(*rr.energy);
                o["edp"] = metric_value(row, Metric::Edp);
            }
        }
        if (row.run && row.run->wall_s > 0) o["wall_s"] = row.run->wall_s;
        if (row.local_bytes >= 0) o["local_bytes_per_pe"] = row.local_bytes;
        if (row.ext_bytes >= 0) o["ext_bytes_per_pe"] = row.ext_bytes;
        if (row.run && !row.run->command.empty()) o["command"] = row.run->command;
        rows.push_back(o);
    }
    j["rows"] = rows;
    return j;
}

// ---- the plot ---------------------------------------------------------------------------

namespace {

std::string axis_label(const Axis& a) {
    if (a.name == "pes") return "PEs";
    if (a.name == "clock_mhz") return "clock (MHz)";
    if (a.name == "mem_bytes") return "local memory per PE (bytes)";
    if (a.name == "ext_bytes") return "external memory per PE (bytes)";
    if (a.name == "D") return "disparity levels D";
    if (a.name == "mode") return "mode";
    if (a.kind == AxisKind::Machine) {
        const isa::MachineConfig probe;
        for (const isa::ParamInfo& pi : probe.list())
            if (pi.name == a.name && !pi.unit.empty()) return a.name + " (" + pi.unit + ")";
    }
    return a.name;
}

// The input and the fixed parameters, for a plot's subtitle.
std::string figure_subtitle(const Plan& p) {
    std::string sub;
    for (const Axis& a : p.fixed) sub += (sub.empty() ? "" : ", ") + a.name + "=" + a.values[0];
    if (p.synthetic &&
        std::none_of(p.fixed.begin(), p.fixed.end(),
                     [](const Axis& a) { return a.name == "roi_size"; }) &&
        std::none_of(p.swept.begin(), p.swept.end(),
                     [](const Axis& a) { return a.name == "roi_size"; }))
        sub += (sub.empty() ? "" : ", ") + std::string("roi_size=128x128");
    sub =
        (p.synthetic ? std::string("synthetic scene") : p.input) + (sub.empty() ? "" : "; " + sub);
    if (sub.size() > 120) sub = sub.substr(0, 117) + "...";
    return sub;
}

}  // namespace

bool make_figure(const Plan& p, const Result& r, size_t xi, plot::Figure* f) {
    if (xi >= p.swept.size()) return false;
    const Axis& ax = p.swept[xi];

    // x positions of the axis values.
    std::vector<double> xv(ax.values.size());
    f->xlabel = axis_label(ax);
    bool categorical = false;
    if (ax.kind == AxisKind::RoiSize) {
        std::vector<int> ws, hs;
        for (const std::string& val : ax.values) {
            int w = 0, h = 0;
            parse_wxh(val, &w, &h);
            ws.push_back(w);
            hs.push_back(h);
        }
        const bool same_h = std::all_of(hs.begin(), hs.end(), [&](int h) { return h == hs[0]; });
        const bool same_w = std::all_of(ws.begin(), ws.end(), [&](int w) { return w == ws[0]; });
        for (size_t i = 0; i < xv.size(); ++i) xv[i] = same_h ? ws[i] : hs[i];
        // Sizes that differ in both: one labelled tick per size (W x H), so
        // that 64x32 and 32x64 do not share an x.
        categorical = !same_h && !same_w;
        f->xlabel = same_h   ? "ROI width (pixels), height " + std::to_string(hs[0])
                    : same_w ? "ROI height (lines), width " + std::to_string(ws[0])
                             : "ROI size (W x H)";
    } else {
        for (size_t i = 0; i < xv.size(); ++i) {
            xv[i] = numeric_value(ax, ax.values[i]);
            if (std::isnan(xv[i])) categorical = true;
        }
    }
    if (categorical)
        for (size_t i = 0; i < xv.size(); ++i) {
            xv[i] = static_cast<double>(i);
            f->xcategories.emplace_back(xv[i], ax.values[i]);
        }
    const double xmin = *std::min_element(xv.begin(), xv.end());
    const double xmax = *std::max_element(xv.begin(), xv.end());
    f->logx = !categorical && xmin > 0 && (ax.name == "pes" || xmax / xmin > 8);
    if (!categorical && xv.size() <= 16) f->xticks = xv;  // tick at the swept values

    // Series.
    std::map<std::string, size_t> series_index;
    std::map<size_t, std::vector<double>> bound_x, bound_y;  // per achieved series
    size_t not_fit = 0, failed = 0, no_value = 0;
    const Metric m = p.y;
    const bool time = m == Metric::Time;
    double ymin = INFINITY, ymax = 0;
    for (const Row& row : r.rows) {
        if (row.status != Status::Ok) {
            (row.status == Status::DoesNotFit || row.status == Status::CannotRun ? not_fit
                                                                                 : failed)++;
            continue;
        }
        const double yv = metric_value(row, m);
        if (std::isnan(yv)) {
            ++no_value;
            continue;
        }
        const std::string label = series_label(p, row, xi);
        auto it = series_index.find(label);
        if (it == series_index.end()) {
            it = series_index.emplace(label, f->series.size()).first;
            f->series.push_back({label, {}, {}});
        }
        const size_t vi = static_cast<size_t>(
            std::find(ax.values.begin(), ax.values.end(), row.values[xi]) - ax.values.begin());
        f->series[it->second].x.push_back(xv[vi]);
        f->series[it->second].y.push_back(yv);
        ymin = std::min(ymin, yv);
        ymax = std::max(ymax, yv);
        // The machine's bound at this point (same clock, so the same ms per cycle).
        if (time && row.run->bound_cycles > 0) {
            const double ms = row.run->modeled_ms * row.run->efficiency();
            bound_x[it->second].push_back(xv[vi]);
            bound_y[it->second].push_back(ms);
            ymin = std::min(ymin, ms);
        }
    }
    if (f->series.empty()) return false;
    const size_t achieved = f->series.size();
    for (size_t i = 0; i < achieved; ++i) {
        if (bound_x[i].empty()) continue;
        if (f->series[i].label.empty()) f->series[i].label = "achieved (firmware)";
        const std::string l =
            f->series[i].label == "achieved (firmware)" ? std::string() : f->series[i].label;
        f->series.push_back({(l.empty() ? std::string() : l + ": ") + "machine bound", bound_x[i],
                             bound_y[i], static_cast<int>(i)});
    }
    if (time) {
        f->hlines = {{100.0, "real time, 10 fps (100 ms)"}, {40.0, "video rate, 25 fps (40 ms)"}};
        f->logy = ymin > 0 && std::max(ymax, 100.0) / std::min(ymin, 40.0) > 20;
    } else {
        f->logy = ymin > 0 && ymax / ymin > 20;
    }
    std::string note;
    if (not_fit)
        note = std::to_string(not_fit) + " point" + (not_fit == 1 ? "" : "s") + " that do" +
               (not_fit == 1 ? "es" : "") + " not fit / cannot run not shown";
    if (failed)
        note += (note.empty() ? "" : "; ") + std::to_string(failed) + " failed point" +
                (failed == 1 ? "" : "s") + " not shown";
    if (no_value)
        note += (note.empty() ? "" : "; ") + std::to_string(no_value) + " point" +
                (no_value == 1 ? "" : "s") + " without " +
                (m == Metric::Area ? "an area (no yosys in the run's build)" : "an energy") +
                " not shown";
    if (r.interrupted)
        note += (note.empty() ? "" : "; ") + std::string("interrupted: ") +
                std::to_string(r.not_run) + " points not run";
    f->note = note;
    for (const Knee& k : r.knees) {
        if (!time || r.x_axis != ax.name) continue;
        double x = k.xv;
        if (ax.kind == AxisKind::RoiSize) {
            const size_t vi = static_cast<size_t>(
                std::find(ax.values.begin(), ax.values.end(), k.x) - ax.values.begin());
            if (vi < xv.size()) x = xv[vi];
        }
        f->annotations.push_back({x, k.y_ms, k.label});
    }
    static const std::map<Metric, std::pair<const char*, const char*>> kY = {
        {Metric::Time, {"Modeled frame time", "modeled frame time (ms)"}},
        {Metric::Energy, {"Energy per frame", "energy per frame (uJ; [A] energy model)"}},
        {Metric::Power, {"Average power", "average power over the frame (mW; [A] energy model)"}},
        {Metric::Edp, {"Energy x delay", "energy x delay per frame (uJ x ms)"}},
        {Metric::Area, {"Area", "area (yosys generic cells)"}}};
    f->title = std::string(kY.at(m).first) + " vs " + f->xlabel.substr(0, f->xlabel.find(',')) +
               " (imapsim " + p.command + ", model " + p.model + ")";
    f->subtitle = figure_subtitle(p);
    f->ylabel = kY.at(m).second;
    return true;
}

// ---- Pareto view: time against energy -------------------------------------------------

namespace {
// A row that counts as a design point of the Pareto view.
bool pareto_candidate(const Row& r) {
    return r.status == Status::Ok && r.ran() && r.run->energy.has_value();
}
}  // namespace

std::vector<size_t> pareto_rows(const std::vector<Row>& rows) {
    std::vector<size_t> out;
    for (size_t i = 0; i < rows.size(); ++i) {
        if (!pareto_candidate(rows[i])) continue;
        const double ti = rows[i].run->modeled_ms, ei = rows[i].run->energy->total_uj;
        bool dominated = false;
        for (size_t j = 0; j < rows.size() && !dominated; ++j) {
            if (j == i || !pareto_candidate(rows[j])) continue;
            const double tj = rows[j].run->modeled_ms, ej = rows[j].run->energy->total_uj;
            dominated = tj <= ti && ej <= ei && (tj < ti || ej < ei);
        }
        if (!dominated) out.push_back(i);
    }
    return out;
}

std::vector<std::string> pareto_lines(const Plan& p, const Result& r) {
    std::vector<std::string> out;
    size_t n = 0;
    for (const Row& row : r.rows) n += pareto_candidate(row);
    if (n == 0) {
        out.push_back("  Pareto (time, energy): no point ran bit-exact with an energy");
        return out;
    }
    std::vector<size_t> front = pareto_rows(r.rows);
    std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
        return r.rows[a].run->modeled_ms < r.rows[b].run->modeled_ms;
    });
    out.push_back(
        "  Pareto-optimal (no other point both at most as slow and at most as much "
        "energy): " +
        std::to_string(front.size()) + " of " + std::to_string(n) + " point" + (n == 1 ? "" : "s") +
        ", fastest first");
    for (size_t i : front) {
        const Row& row = r.rows[i];
        std::string l = "    " + point_text(p, row) + ": " +
                        metric_text(Metric::Time, row.run->modeled_ms) + ", " +
                        metric_text(Metric::Energy, row.run->energy->total_uj) + ", " +
                        metric_text(Metric::Power, row.run->energy->power_mw);
        if (row.run->area) l += ", " + metric_text(Metric::Area, metric_value(row, Metric::Area));
        out.push_back(l);
    }
    return out;
}

bool make_pareto_figure(const Plan& p, const Result& r, plot::Figure* f) {
    std::vector<size_t> pts;
    for (size_t i = 0; i < r.rows.size(); ++i)
        if (pareto_candidate(r.rows[i])) pts.push_back(i);
    if (pts.empty()) return false;
    const bool sized = std::all_of(pts.begin(), pts.end(), [&](size_t i) {
        return r.rows[i].run->area && r.rows[i].run->area->cells > 0;
    });
    double amax = 0, xmin = INFINITY, xmax = 0, ymin = INFINITY, ymax = 0;
    for (size_t i : pts) {
        const RunResult& x = *r.rows[i].run;
        if (sized) amax = std::max(amax, static_cast<double>(x.area->cells));
        xmin = std::min(xmin, x.modeled_ms);
        xmax = std::max(xmax, x.modeled_ms);
        ymin = std::min(ymin, x.energy->total_uj);
        ymax = std::max(ymax, x.energy->total_uj);
    }
    plot::Series all;
    all.label = sized ? "design points (size: area)" : "design points";
    all.scatter = true;
    for (size_t i : pts) {
        const RunResult& x = *r.rows[i].run;
        all.x.push_back(x.modeled_ms);
        all.y.push_back(x.energy->total_uj);
        // point size 1..4, its area proportional to the cells
        if (sized) all.size.push_back(1.0 + 3.0 * std::sqrt(x.area->cells / amax));
    }
    f->series.push_back(all);
    std::vector<size_t> front = pareto_rows(r.rows);
    std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
        return r.rows[a].run->modeled_ms < r.rows[b].run->modeled_ms;
    });
    plot::Series line;
    line.label =
        "Pareto front (" + std::to_string(front.size()) + " of " + std::to_string(pts.size()) + ")";
    line.bound_of = 0;  // dashed, in the points' colour, without markers
    for (size_t i : front) {
        const Row& row = r.rows[i];
        line.x.push_back(row.run->modeled_ms);
        line.y.push_back(row.run->energy->total_uj);
        f->annotations.push_back({row.run->modeled_ms, row.run->energy->total_uj,
                                  p.swept.empty() ? std::string() : point_text(p, row)});
    }
    f->series.push_back(line);
    f->logx = xmin > 0 && xmax / xmin > 20;
    f->logy = ymin > 0 && ymax / ymin > 20;
    f->key = "below horizontal";  // points can be anywhere in the plot area
    std::string note =
        sized ? "point size: area (yosys cells), largest " + fmt("%.2f", amax / 1e6) + " Mcells"
              : "no area in the results (no yosys in the run's build): points "
                "the same size";
    const size_t left_out = r.rows.size() - pts.size();
    if (left_out)
        note += "; " + std::to_string(left_out) + " point" + (left_out == 1 ? "" : "s") +
                " not run bit-exact with an energy not shown";
    f->title = "Energy per frame vs modeled frame time, Pareto-optimal points circled (imapsim " +
               p.command + ", model " + p.model + ")";
    // under the title: the bottom-left corner is where the Pareto points lie
    f->subtitle = figure_subtitle(p) + "\n" + note;
    f->xlabel = "modeled frame time (ms)";
    f->ylabel = "energy per frame (uJ; [A] energy model)";
    return true;
}

}  // namespace imap::engine::sweep
