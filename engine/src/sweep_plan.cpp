// Planning a sweep (plan): every point of a Spec in point order, planned
// in-process: its algorithm and machine parameters checked, its ROI, the
// firmware's memory plan (what does not fit is an answer, with the memory
// it would need) and, when it fits, the job that runs it (`imapsim run`
// arguments); the fixed parameters of the report and the program's phase
// names. And the plan as JSON, the run folder's payload (to_json(Plan),
// plan_from_json).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "imap/engine/error.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;
using nlohmann::json;
using namespace detail;

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
        p.mode = *v == "single" ? g::Mode::Single : *v == "joint" ? g::Mode::Joint : g::Mode::Bidir;
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
    // every algorithm parameter the point was planned with: the child starts
    // from the paper preset, so the base's preset and A.9 options go too
    a.insert(a.end(), {"--D", std::to_string(p.D), "--km", std::to_string(p.km), "--kb",
                       std::to_string(p.kb), "--gb", std::to_string(p.gb), "--Wo",
                       std::to_string(p.Wo), "--Wd", std::to_string(p.Wd)});
    if (p.mode != g::Mode::Joint) a.insert(a.end(), {"--mode", g::to_string(p.mode)});
    std::istringstream options(g::options_string(p));  // "--mode joint --kc 4 ..."
    for (std::string w; options >> w;) a.push_back(w);
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

Status status_from_name(const std::string& s) {
    for (const auto& [k, n] : kStatusNames)
        if (s == n) return k;
    throw Error("sweep plan: unknown status '" + s + "'");
}

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

}  // namespace imap::engine::sweep
