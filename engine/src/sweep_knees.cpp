// The knees of a sweep's curves (find_knees): along a numeric, positive
// axis, each series' points of modeled time, where the log-log slope changes
// by more than kKneeSlopeChange; each knee explained in a sentence (the
// phases whose cycles change most on either side, the dominant phase) and
// labelled in words for the plot. Also the series of a plan's rows and the
// phase cycles of a run, which the reports and the plot share.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "imap/engine/sweep.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

using namespace detail;

namespace detail {

std::string series_label(const Plan& p, const Row& r, size_t xi) {
    std::string label;
    for (size_t i = 0; i < p.swept.size(); ++i)
        if (i != xi) label += (label.empty() ? "" : ", ") + p.swept[i].name + "=" + r.values[i];
    return label;
}

uint64_t phase_cycles(const RunResult& r, const std::string& n) {
    for (const auto& [k, c] : r.phases)
        if (k == n) return c;
    return 0;
}

}  // namespace detail

namespace {

struct SeriesPoints {
    std::string label;
    std::vector<const Row*> rows;  // ran, sorted by x
    std::vector<double> x;
};

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

}  // namespace imap::engine::sweep
