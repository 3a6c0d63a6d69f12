// What a sweep prints: the metrics --y chooses (names, values, their text),
// the table's header lines and one line per row (swept values, cycles,
// time, the metric, fps, efficiency, memory, area, dominant phase, wall
// time, result, the mark of a clock above the design's Fmax), and the
// summary lines (counts, the points above the Fmax, knees, the least point
// of the metric).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "imap/engine/sweep.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

using namespace detail;

// ---- metrics ----------------------------------------------------------------------------

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

}  // namespace

namespace detail {

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

}  // namespace detail

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

bool clock_above_fmax(const Row& r) {
    return r.ran() && r.run->design_fmax && r.run->design_fmax->clock_above;
}

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
    if (clock_above_fmax(r))
        result += fmt(" [clock > design Fmax %.1f MHz]", r.run->design_fmax->mhz);
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
    // Points whose clock the design does not reach (docs/rtl.md, "Place and
    // route (iCE40)"): modeled, but not a clock this design was shown to run at.
    const Row* above = nullptr;
    size_t n_above = 0;
    for (const Row& row : r.rows)
        if (clock_above_fmax(row)) {
            ++n_above;
            if (!above) above = &row;
        }
    if (above) {
        const DesignFmax& f = *above->run->design_fmax;
        std::snprintf(b, sizeof b,
                      "  %zu point%s with the clock above the design's Fmax (%.1f MHz on %s, "
                      "docs/rtl.md), marked [clock > design Fmax]",
                      n_above, n_above == 1 ? "" : "s", f.mhz, f.technology.c_str());
        out.push_back(b);
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

}  // namespace imap::engine::sweep
