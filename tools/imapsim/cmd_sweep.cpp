// imapsim sweep: the what-if explorer (docs/whatif.md). Every axis flag
// takes a comma list or a range (A..B, A..B:S, A..B*F); the sweep is the
// cartesian product of the swept axes. Each point is planned in-process
// (what does not fit is a row, not an error) and run on a model as a child
// `imapsim run --report`; table on stdout, --csv, --json, --plot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>

#include "cli_common.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"
#include "plot.hpp"
#include "sweep_engine.hpp"

namespace imapsim {

namespace v = imap::vision;
using sweep::Axis;
using sweep::AxisKind;

namespace {

struct SweepOptions {
    std::string csv, json, plot, plot_size = "900x600", x;
    std::string jobs;
    std::string model = kDefaultModel;
    std::string left, right, roi_size;
    uint64_t seed = 1;
    bool dry_run = false;
    AlgoFlags algo;
    MachineFlags machine;
};

std::string norm_name(std::string s) {
    s.erase(0, s.find_first_not_of('-'));
    std::replace(s.begin(), s.end(), '-', '_');
    if (s == "roi" || s == "size") s = "roi_size";
    return s;
}

std::string axis_label(const Axis& a) {
    if (a.name == "pes") return "PEs";
    if (a.name == "clock_mhz") return "clock (MHz)";
    if (a.name == "mem_bytes") return "local memory per PE (bytes)";
    if (a.name == "ext_bytes") return "external memory per PE (bytes)";
    if (a.name == "D") return "disparity levels D";
    if (a.name == "mode") return "mode";
    return a.name + (a.kind == AxisKind::Machine && a.name != "indirect" ? " (cycles)" : "");
}

// The plot of modeled frame time against one swept axis, one series per
// combination of the other swept axes.
void write_plot(const sweep::Spec& s, const sweep::Result& r, const SweepOptions& o) {
    size_t xi = 0;
    if (!o.x.empty()) {
        const std::string want = norm_name(o.x);
        bool found = false;
        for (size_t i = 0; i < s.swept.size(); ++i)
            if (s.swept[i].name == want) {
                xi = i;
                found = true;
            }
        if (!found) throw UserError("internal: --x axis vanished", kExitInternal);
    }
    const Axis& ax = s.swept[xi];
    plot::Figure f;
    const int pw = std::atoi(o.plot_size.c_str());
    const int ph = std::atoi(o.plot_size.substr(o.plot_size.find('x') + 1).c_str());
    f.width = pw;
    f.height = ph;

    // x positions of the axis values.
    std::vector<double> xv(ax.values.size());
    f.xlabel = axis_label(ax);
    bool categorical = false;
    if (ax.kind == AxisKind::RoiSize) {
        std::vector<int> ws, hs;
        for (const std::string& val : ax.values) {
            ws.push_back(std::atoi(val.c_str()));
            hs.push_back(std::atoi(val.substr(val.find('x') + 1).c_str()));
        }
        const bool same_h = std::all_of(hs.begin(), hs.end(), [&](int h) { return h == hs[0]; });
        const bool same_w = std::all_of(ws.begin(), ws.end(), [&](int w) { return w == ws[0]; });
        for (size_t i = 0; i < xv.size(); ++i)
            xv[i] = same_h ? ws[i] : same_w ? hs[i] : static_cast<double>(ws[i]) * hs[i];
        f.xlabel = same_h   ? "ROI width (pixels), height " + std::to_string(hs[0])
                   : same_w ? "ROI height (lines), width " + std::to_string(ws[0])
                            : "ROI pixels (W x H)";
    } else {
        for (size_t i = 0; i < xv.size(); ++i) {
            xv[i] = sweep::numeric_value(ax, ax.values[i]);
            if (std::isnan(xv[i])) categorical = true;
        }
    }
    if (categorical)
        for (size_t i = 0; i < xv.size(); ++i) {
            xv[i] = static_cast<double>(i);
            f.xcategories.emplace_back(xv[i], ax.values[i]);
        }
    const double xmin = *std::min_element(xv.begin(), xv.end());
    const double xmax = *std::max_element(xv.begin(), xv.end());
    f.logx = !categorical && xmin > 0 && (ax.name == "pes" || xmax / xmin > 8);
    if (!categorical && xv.size() <= 16) f.xticks = xv;  // tick at the swept values

    // Series.
    std::map<std::string, size_t> series_of;
    size_t not_fit = 0, failed = 0;
    double ymin = INFINITY, ymax = 0;
    for (const sweep::Row& row : r.rows) {
        if (row.status != sweep::Status::Ok) {
            (row.status == sweep::Status::DoesNotFit || row.status == sweep::Status::CannotRun
                 ? not_fit
                 : failed)++;
            continue;
        }
        std::string label;
        for (size_t i = 0; i < s.swept.size(); ++i)
            if (i != xi)
                label += (label.empty() ? "" : ", ") + s.swept[i].name + "=" + row.values[i];
        auto it = series_of.find(label);
        if (it == series_of.end()) {
            it = series_of.emplace(label, f.series.size()).first;
            f.series.push_back({label, {}, {}});
        }
        const size_t vi = static_cast<size_t>(
            std::find(ax.values.begin(), ax.values.end(), row.values[xi]) - ax.values.begin());
        f.series[it->second].x.push_back(xv[vi]);
        f.series[it->second].y.push_back(row.modeled_ms);
        ymin = std::min(ymin, row.modeled_ms);
        ymax = std::max(ymax, row.modeled_ms);
    }
    if (f.series.empty()) {
        std::fprintf(stderr, "imapsim sweep: warning: no point ran bit-exact, %s not written\n",
                     o.plot.c_str());
        return;
    }
    f.hlines = {{100.0, "real time, 10 fps (100 ms)"}, {40.0, "video rate, 25 fps (40 ms)"}};
    f.logy = ymin > 0 && std::max(ymax, 100.0) / std::min(ymin, 40.0) > 20;
    std::string note;
    if (not_fit)
        note = std::to_string(not_fit) + " point" + (not_fit == 1 ? "" : "s") + " that do" +
               (not_fit == 1 ? "es" : "") + " not fit / cannot run not shown";
    if (failed)
        note += (note.empty() ? "" : "; ") + std::to_string(failed) + " failed point" +
                (failed == 1 ? "" : "s") + " not shown";
    if (r.interrupted)
        note += (note.empty() ? "" : "; ") + std::string("interrupted: ") +
                std::to_string(r.not_run) + " points not run";
    f.note = note;
    f.title = "Modeled frame time vs " + f.xlabel.substr(0, f.xlabel.find(',')) +
              " (imapsim sweep, model " + s.model + ")";
    std::string sub;
    for (const Axis& a : s.fixed) sub += (sub.empty() ? "" : ", ") + a.name + "=" + a.values[0];
    if (s.input.left.empty() &&
        std::none_of(s.fixed.begin(), s.fixed.end(),
                     [](const Axis& a) { return a.name == "roi_size"; }) &&
        std::none_of(s.swept.begin(), s.swept.end(),
                     [](const Axis& a) { return a.name == "roi_size"; }))
        sub += (sub.empty() ? "" : ", ") + std::string("roi_size=128x128");
    sub =
        (s.input.left.empty() ? "synthetic scene" : s.input.left) + (sub.empty() ? "" : "; " + sub);
    if (sub.size() > 120) sub = sub.substr(0, 117) + "...";
    f.subtitle = sub;
    f.ylabel = "modeled frame time (ms)";
    v::write_image_atomic(o.plot, plot::render(f));
    std::printf("  plot -> %s\n", o.plot.c_str());
}

}  // namespace

Subcommand register_sweep(CLI::App& app) {
    auto o = std::make_shared<SweepOptions>();
    CLI::App* sub = app.add_subcommand(
        "sweep",
        "What-if explorer: run the firmware over a grid of machine and algorithm parameters "
        "(docs/whatif.md). Axis flags (--pes --clock-mhz --mem-bytes --ext-bytes --set NAME=... "
        "--roi-size --D --mode --km --kb --gb --Wo --Wd) take a comma list or a range A..B, "
        "A..B:S (step S) or A..B*F (factor F), e.g. --pes 8..1024*2; the sweep is their product");
    sub->add_option("--csv", o->csv, "write the rows as CSV here");
    sub->add_option("--json", o->json, "write the rows and the fixed parameters as JSON here");
    sub->add_option("--plot", o->plot, "draw modeled frame time against --x into this PNG");
    sub->add_option("--plot-size", o->plot_size, "plot size WxH")->capture_default_str();
    sub->add_option("--x", o->x, "plot x axis: a swept axis (default: the first on the line)");
    sub->add_option("-j,--jobs", o->jobs, "points run in parallel [default: one per core]");
    sub->add_option("--model", o->model, "model to run: " + model_names())->capture_default_str();
    sub->add_option("--left", o->left, "left image (default: the synthetic scene)");
    sub->add_option("--right", o->right, "right image");
    sub->add_option("--seed", o->seed, "synthetic scene seed")->capture_default_str();
    sub->add_option("--roi-size", o->roi_size,
                    "ROI sizes WxH, comma list (synthetic scene: generated at this size; "
                    "images: centred) [default: 128x128 / whole image]");
    sub->add_flag("--dry-run", o->dry_run, "plan every point, run none (memory answers only)");
    add_algo_flags(sub, o->algo);
    add_machine_flags(sub, o->machine);

    return {
        sub, [o, sub]() {
            check_model_name(o->model);
            sweep::Spec s;
            s.model = o->model;
            s.dry_run = o->dry_run;
            if (!o->jobs.empty())
                s.jobs = static_cast<unsigned>(parse_int_flag("-j", o->jobs, 1, 1024));

            // Axes in command-line order.
            std::map<const CLI::Option*, std::pair<std::string, const std::string*>> opts;
            auto reg = [&](const char* flag, const std::string& name, const std::string& val) {
                if (const CLI::Option* op = sub->get_option_no_throw(flag)) opts[op] = {name, &val};
            };
            reg("--pes", "pes", o->machine.pes);
            reg("--clock-mhz", "clock_mhz", o->machine.clock_mhz);
            reg("--mem-bytes", "mem_bytes", o->machine.mem_bytes);
            reg("--ext-bytes", "ext_bytes", o->machine.ext_bytes);
            reg("--roi-size", "roi_size", o->roi_size);
            reg("--D", "D", o->algo.D);
            reg("--km", "km", o->algo.km);
            reg("--kb", "kb", o->algo.kb);
            reg("--gb", "gb", o->algo.gb);
            reg("--Wo", "Wo", o->algo.Wo);
            reg("--Wd", "Wd", o->algo.Wd);
            reg("--mode", "mode", o->algo.mode);
            const CLI::Option* set_opt = sub->get_option_no_throw("--set");
            std::vector<Axis> axes;
            std::set<std::string> seen;
            size_t set_k = 0;
            for (const CLI::Option* op : sub->parse_order()) {
                std::string name, flag, text;
                if (op == set_opt) {
                    if (set_k >= o->machine.sets.size()) continue;
                    const std::string& st = o->machine.sets[set_k++];
                    const size_t eq = st.find('=');
                    if (eq == std::string::npos || eq == 0)
                        throw UserError("invalid value '" + st +
                                        "' for --set: expected NAME=VALUE or NAME=LIST");
                    name = st.substr(0, eq);
                    flag = "--set " + name;
                    text = st.substr(eq + 1);
                } else {
                    auto it = opts.find(op);
                    if (it == opts.end()) continue;
                    name = it->second.first;
                    flag = op->get_name();
                    text = *it->second.second;
                }
                if (seen.count(name)) {
                    bool same_flag = false;
                    for (const Axis& a : axes) same_flag |= a.name == name && a.flag == flag;
                    if (same_flag && op != set_opt) continue;
                    throw UserError(name + " is given twice (" + flag + " and another flag)");
                }
                seen.insert(name);
                axes.push_back(sweep::make_axis(name, flag, text));
            }
            for (Axis& a : axes) (a.values.size() > 1 ? s.swept : s.fixed).push_back(a);

            // The fixed algorithm flags (validated now: errors exit 2 before any run).
            AlgoFlags fixed_algo = o->algo;
            fixed_algo.D = fixed_algo.km = fixed_algo.kb = fixed_algo.gb = fixed_algo.Wo =
                fixed_algo.Wd = "";
            fixed_algo.mode = "bidir";
            imap::golden::Roi roi;
            bool has_roi = false;
            parse_algo_flags(fixed_algo, &roi, &has_roi);
            s.algo = o->algo;

            // Input.
            if (o->left.empty() != o->right.empty())
                throw UserError("--left and --right must be given together");
            s.input.seed = o->seed;
            if (!o->left.empty()) {
                s.input.left = o->left;
                s.input.right = o->right;
                s.input.L = v::load_grey8(o->left, "left image");
                s.input.R = v::load_grey8(o->right, "right image");
                if (s.input.L.size() != s.input.R.size())
                    throw UserError(
                        "left and right images differ in size: " + std::to_string(s.input.L.cols) +
                        "x" + std::to_string(s.input.L.rows) + " vs " +
                        std::to_string(s.input.R.cols) + "x" + std::to_string(s.input.R.rows));
                if (has_roi) {
                    if (!o->roi_size.empty())
                        throw UserError("--roi and --roi-size exclude each other");
                    if (roi.x0 + roi.w > s.input.L.cols || roi.y0 + roi.h > s.input.L.rows)
                        throw UserError("--roi " + o->algo.roi + " lies outside the " +
                                        std::to_string(s.input.L.cols) + "x" +
                                        std::to_string(s.input.L.rows) + " images");
                    s.input.has_fixed_roi = true;
                    s.input.roi_x0 = roi.x0;
                    s.input.roi_y0 = roi.y0;
                    s.input.roi_w = roi.w;
                    s.input.roi_h = roi.h;
                }
            } else if (has_roi) {
                throw UserError(
                    "--roi needs --left/--right; the synthetic scene is generated at "
                    "--roi-size WxH");
            }

            // Outputs (checked before the run).
            check_output_file("--csv", o->csv, false);
            check_output_file("--json", o->json, false);
            check_output_file("--plot", o->plot, true);
            if (!o->plot.empty()) {
                int w = 0, h = 0;
                char x = 0;
                if (std::sscanf(o->plot_size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' ||
                    w < 300 || h < 200 || w > 4000 || h > 4000 ||
                    o->plot_size.find_first_not_of("0123456789x") != std::string::npos)
                    throw UserError("invalid value '" + o->plot_size +
                                    "' for --plot-size: expected WxH with W in 300..4000, H "
                                    "in 200..4000");
                if (s.swept.empty())
                    throw UserError(
                        "--plot needs a swept axis (a flag with two or more values, e.g. "
                        "--pes 64,128,256)");
            }
            if (!o->x.empty()) {
                const std::string want = norm_name(o->x);
                std::string names;
                bool found = false;
                for (const Axis& a : s.swept) {
                    found |= a.name == want;
                    names += (names.empty() ? "" : ", ") + a.name;
                }
                if (!found)
                    throw UserError("invalid value '" + o->x +
                                    "' for --x: expected a swept axis (" +
                                    (names.empty() ? std::string("none") : names) + ")");
            }
            s.points = sweep::product(s.swept);

            const sweep::Result r = sweep::run(s);
            if (!o->csv.empty()) {
                v::write_text_atomic(o->csv, sweep::to_csv(s, r));
                std::printf("  csv -> %s\n", o->csv.c_str());
            }
            if (!o->json.empty()) {
                v::write_text_atomic(o->json, sweep::to_json(s, r).dump(2) + "\n");
                std::printf("  json -> %s\n", o->json.c_str());
            }
            if (!o->plot.empty()) write_plot(s, r, *o);
            std::fflush(stdout);
            return r.exit_code();
        }};
}

}  // namespace imapsim
