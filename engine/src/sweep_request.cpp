// imapsim sweep's request: from the flags as given (Request) to the engine's
// Spec (axes in command-line order, fixed and swept; the base algorithm
// parameters; the input images, checked), and the outputs of a finished sweep.
#include "imap/engine/sweep_request.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "imap/engine/error.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/engine/plot.hpp"
#include "imap/vision/image_io.hpp"

namespace imap::engine::sweep {

namespace {

std::string norm_name(std::string s) {
    s.erase(0, s.find_first_not_of('-'));
    std::replace(s.begin(), s.end(), '-', '_');
    if (s == "roi" || s == "size") s = "roi_size";
    return s;
}

// The flags of the algorithm options that are not axes, as the child gets them.
std::vector<std::string> algo_child_args(const AlgoSettings& a) {
    std::vector<std::string> v = {"--seed-col", a.seed_col, "--seed-disp", a.seed_disp,
                                  "--vote",     a.vote,     "--frame",     a.frame};
    if (a.fill) v.push_back("--fill");
    return v;
}

// --camera ideal,ntsc,pixel-clock:5: an axis of camera_pixel_mhz.
std::string camera_axis(const std::string& camera) {
    std::string mhz;
    for (size_t a = 0; a < camera.size();) {
        size_t b = camera.find(',', a);
        if (b == std::string::npos) b = camera.size();
        mhz += (mhz.empty() ? "" : ",") + camera_pixel_mhz(camera.substr(a, b - a));
        a = b + 1;
    }
    return mhz;
}

// The axes of the request in command-line order (a name given twice refused).
std::vector<Axis> axes_of(const Request& r) {
    static const std::vector<std::pair<std::string, std::string>> names = {
        {"--pes", "pes"},
        {"--clock-mhz", "clock_mhz"},
        {"--mem-bytes", "mem_bytes"},
        {"--ext-bytes", "ext_bytes"},
        {"--camera", "camera_pixel_mhz"},
        {"--roi-size", "roi_size"},
        {"--D", "D"},
        {"--km", "km"},
        {"--kb", "kb"},
        {"--gb", "gb"},
        {"--Wo", "Wo"},
        {"--Wd", "Wd"},
        {"--mode", "mode"}};
    std::vector<Axis> axes;
    std::set<std::string> seen;
    for (const auto& [given, value] : r.axes) {
        std::string name, flag = given, text = value;
        const bool is_set = given == "--set";
        if (is_set) {
            const size_t eq = value.find('=');
            if (eq == std::string::npos || eq == 0)
                throw Error("invalid value '" + value +
                            "' for --set: expected NAME=VALUE or NAME=LIST");
            name = value.substr(0, eq);
            flag = "--set " + name;
            text = value.substr(eq + 1);
        } else {
            for (const auto& [f, n] : names)
                if (f == given) name = n;
            if (name.empty()) throw Error("not an axis flag: " + given);
            if (given == "--camera") text = camera_axis(value);
        }
        if (seen.count(name)) {
            bool same_flag = false;
            for (const Axis& a : axes) same_flag |= a.name == name && a.flag == flag;
            if (same_flag && !is_set) continue;
            throw Error(name + " is given twice (" + flag + " and another flag)");
        }
        seen.insert(name);
        axes.push_back(make_axis(name, flag, text));
    }
    return axes;
}

// The input images (checked) and the fixed ROI.
void input_of(const Request& r, bool has_roi, const golden::Roi& roi, Input* in) {
    if (r.left.empty() != r.right.empty()) throw Error("--left and --right must be given together");
    in->seed = r.seed;
    if (!r.left.empty()) {
        in->left = r.left;
        in->right = r.right;
        const cv::Mat L = vision::load_grey8(r.left, "left image");
        const cv::Mat R = vision::load_grey8(r.right, "right image");
        check_same_size(r.left, L.cols, L.rows, r.right, R.cols, R.rows);
        in->width = L.cols;
        in->height = L.rows;
        if (has_roi) {
            if (!r.roi_size.empty()) throw Error("--roi and --roi-size exclude each other");
            if (roi.x0 + roi.w > L.cols || roi.y0 + roi.h > L.rows)
                throw Error("--roi " + r.algo.roi + " lies outside the " + std::to_string(L.cols) +
                            "x" + std::to_string(L.rows) + " images");
            in->has_fixed_roi = true;
            in->roi = roi;
        }
    } else if (has_roi) {
        throw Error(
            "--roi needs --left/--right; the synthetic scene is generated at --roi-size WxH");
    }
}

}  // namespace

Spec build_spec(const Request& r) {
    Spec s;
    s.model = r.model;
    s.dry_run = r.dry_run;
    for (Axis& a : axes_of(r)) (a.values.size() > 1 ? s.swept : s.fixed).push_back(a);

    // The algorithm parameters that are not axes (validated now: errors
    // exit 2 before any run), and the fixed ones for the JSON report.
    AlgoSettings base = r.algo;
    base.D = base.km = base.kb = base.gb = base.Wo = base.Wd = "";
    base.mode = "bidir";
    golden::Roi roi;
    bool has_roi = false;
    s.base = algo_params(base, &roi, &has_roi);
    s.base_args = algo_child_args(r.algo);
    AlgoSettings fixed = base;
    for (const Axis& a : s.fixed) {
        const std::string& val = a.values.front();
        if (a.name == "D") fixed.D = val;
        if (a.name == "km") fixed.km = val;
        if (a.name == "kb") fixed.kb = val;
        if (a.name == "gb") fixed.gb = val;
        if (a.name == "Wo") fixed.Wo = val;
        if (a.name == "Wd") fixed.Wd = val;
        if (a.name == "mode") fixed.mode = val;
    }
    try {
        golden::Roi unused;
        bool has = false;
        s.fixed_algorithm = algo_params_json(algo_params(fixed, &unused, &has));
    } catch (const Error&) {
        // e.g. Wo < Wd with a fixed pair: every point says so
    }
    input_of(r, has_roi, roi, &s.input);
    if (r.plot && s.swept.empty())
        throw Error(
            "--plot needs a swept axis (a flag with two or more values, e.g. "
            "--pes 64,128,256)");
    x_index(s.swept, r.x);
    s.points = product(s.swept);
    return s;
}

size_t x_index(const std::vector<Axis>& swept, const std::string& x) {
    if (x.empty()) return 0;
    const std::string want = norm_name(x);
    std::string names;
    for (size_t i = 0; i < swept.size(); ++i) {
        if (swept[i].name == want) return i;
        names += (names.empty() ? "" : ", ") + swept[i].name;
    }
    throw Error("invalid value '" + x + "' for --x: expected a swept axis (" +
                (names.empty() ? std::string("none") : names) + ")");
}

void check_plot_size(const std::string& s) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 300 || h < 200 ||
        w > 4000 || h > 4000 || s.find_first_not_of("0123456789x") != std::string::npos)
        throw Error("invalid value '" + s +
                    "' for --plot-size: expected WxH with W in 300..4000, H in 200..4000");
}

std::vector<std::string> write_outputs(const Outputs& o, const Plan& plan, const Result& r,
                                       size_t xi, std::string* warning) {
    std::vector<std::string> lines;
    warning->clear();
    if (!o.csv.empty()) {
        vision::write_text_atomic(o.csv, to_csv(plan, r));
        lines.push_back("  csv -> " + o.csv);
    }
    if (!o.json.empty()) {
        vision::write_text_atomic(o.json, to_json(plan, r).dump(2) + "\n");
        lines.push_back("  json -> " + o.json);
    }
    if (!o.plot.empty()) {
        plot::Figure f;
        f.width = std::atoi(o.plot_size.c_str());
        f.height = std::atoi(o.plot_size.substr(o.plot_size.find('x') + 1).c_str());
        if (o.pareto ? make_pareto_figure(plan, r, &f) : make_figure(plan, r, xi, &f)) {
            plot::write_plot(f, o.plot);
            lines.push_back("  plot -> " + o.plot + " (gnuplot script " +
                            plot::script_path(o.plot) + ", data " + plot::data_path(o.plot) + ")");
        } else {
            *warning = std::string("no point ran bit-exact") +
                       (o.pareto                 ? " with an energy"
                        : plan.y == Metric::Time ? ""
                        : plan.y == Metric::Area ? " with an area"
                                                 : " with an energy") +
                       ", " + o.plot + " not written";
        }
    }
    return lines;
}

}  // namespace imap::engine::sweep
