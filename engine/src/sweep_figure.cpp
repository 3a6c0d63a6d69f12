// The sweep's figures (plot::Figure, drawn by gnuplot): make_figure, the
// plan's metric against a swept axis (numeric, log or categorical x), one
// series per combination of the other axes, with the machine's bound, the
// real-time lines and the knees for time; and the Pareto view (--pareto):
// the Pareto-optimal rows by time and energy, their listing and the figure
// of energy against time.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "imap/engine/sweep.hpp"
#include "imap/isa/config.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

namespace isa = imap::isa;
using namespace detail;

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
        // The series' name (the other swept axes' values) names its bound;
        // with x the only swept axis it is empty, and the legend then tells
        // the achieved curve from the bound.
        const std::string series = f->series[i].label;
        if (series.empty()) f->series[i].label = "achieved (firmware)";
        f->series.push_back({(series.empty() ? std::string() : series + ": ") + "machine bound",
                             bound_x[i], bound_y[i], static_cast<int>(i)});
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
