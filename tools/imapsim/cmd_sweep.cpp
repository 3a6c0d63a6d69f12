// imapsim sweep: the what-if explorer (docs/whatif.md). Every axis flag
// takes a comma list or a range (A..B, A..B:S, A..B*F); the sweep is the
// cartesian product of the swept axes. The engine (imap/engine/sweep.hpp)
// plans each point in-process and runs the ones that fit on an executor
// (local cores or a Slurm job array); this file parses the flags and prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "cli_common.hpp"
#include "engine_cli.hpp"
#include "imap/engine/plot.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/vision/image_io.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace v = imap::vision;
namespace eng = imap::engine;
namespace sw = imap::engine::sweep;

namespace {

struct SweepOptions {
    std::string csv, json, plot, plot_size = "900x600", x, y = "time";
    bool pareto = false;
    std::string model = kDefaultModel;
    std::string left, right, roi_size;
    uint64_t seed = 1;
    bool dry_run = false;
    AlgoFlags algo;
    MachineFlags machine;
    ExecFlags exec;
};

std::string norm_name(std::string s) {
    s.erase(0, s.find_first_not_of('-'));
    std::replace(s.begin(), s.end(), '-', '_');
    if (s == "roi" || s == "size") s = "roi_size";
    return s;
}

// The flags of the algorithm options that are not axes, as the child gets them.
std::vector<std::string> algo_child_args(const AlgoFlags& a) {
    std::vector<std::string> v = {"--seed-col", a.seed_col, "--seed-disp", a.seed_disp,
                                  "--vote",     a.vote,     "--frame",     a.frame};
    if (a.fill) v.push_back("--fill");
    return v;
}

void check_plot_size(const std::string& s) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 300 || h < 200 ||
        w > 4000 || h > 4000 || s.find_first_not_of("0123456789x") != std::string::npos)
        throw UserError("invalid value '" + s +
                        "' for --plot-size: expected WxH with W in 300..4000, H in 200..4000");
}

size_t x_index(const std::vector<sw::Axis>& swept, const std::string& x) {
    if (x.empty()) return 0;
    const std::string want = norm_name(x);
    std::string names;
    for (size_t i = 0; i < swept.size(); ++i) {
        if (swept[i].name == want) return i;
        names += (names.empty() ? "" : ", ") + swept[i].name;
    }
    throw UserError("invalid value '" + x + "' for --x: expected a swept axis (" +
                    (names.empty() ? std::string("none") : names) + ")");
}

}  // namespace

// Runs a planned sweep (new or resumed), prints it and writes the outputs;
// shared by sweep and table1. Returns the result; `exit` its exit code.
sw::Result run_sweep_session(Session& s, const sw::Plan& plan, size_t xi) {
    std::vector<std::string> head =
        sw::header_lines(plan, plan.dry_run ? nullptr : s.executor.get());
    if (!plan.dry_run && !s.dir->temporary())
        head.insert(head.end() - 1, "  run folder " + s.dir->path().string());
    for (const std::string& l : head) std::printf("%s\n", l.c_str());
    std::fflush(stdout);
    interrupt::install();
    Printer pr("points", plan.rows.size());
    sw::Hooks h;
    h.stop_requested = [] { return interrupt::requested(); };
    h.row = [&](const std::string& l) { pr.row(l); };
    h.note = [&](const std::string& l) { pr.note(l); };
    h.status = [&](const std::string& l) { pr.status(l); };
    sw::Result r = sw::run(plan, *s.executor, *s.dir, s.manifest, s.ctx, h, s.resume, xi);
    pr.progress.finish();
    if (r.interrupted)
        std::printf("imapsim %s: interrupted (signal %d): partial results\n", plan.command.c_str(),
                    interrupt::signal_number());
    for (const std::string& l : sw::summary_lines(plan, r)) std::printf("%s\n", l.c_str());
    const bool keep = r.count(sw::Status::Error) || r.count(sw::Status::Mismatch) || s.exec_keep;
    if (finish_session(s, keep, r.interrupted)) r.logs = s.dir->path().string();
    std::fflush(stdout);
    return r;
}

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
    sub->add_option("--plot", o->plot,
                    "plot modeled frame time against --x into this .png or .svg (gnuplot; the "
                    ".gp script and .dat data are written beside it)");
    sub->add_option("--plot-size", o->plot_size, "plot size WxH")->capture_default_str();
    sub->add_option("--x", o->x,
                    "plot x axis and the axis knees are looked for along: a swept axis "
                    "(default: the first on the line)");
    sub->add_option("--y", o->y,
                    std::string("what the table highlights (a column and the least point) and "
                                "the plot's y axis: ") +
                        sw::kMetricNames +
                        " (energy per frame uJ, average power mW, energy x delay uJ*ms, area "
                        "cells; docs/whatif.md)")
        ->capture_default_str();
    sub->add_flag("--pareto", o->pareto,
                  "list the Pareto-optimal points by modeled time and energy per frame; with "
                  "--plot, draw time against energy (area as the point size) instead of --y");
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
    add_exec_flags(sub, o->exec, "points");

    return {
        sub, [o, sub]() {
            // Outputs (checked before the run).
            const std::optional<sw::Metric> metric = sw::metric_from_name(o->y);
            if (!metric)
                throw UserError("invalid value '" + o->y + "' for --y: expected one of " +
                                sw::kMetricNames);
            check_output_file("--csv", o->csv, false);
            check_output_file("--json", o->json, false);
            if (!o->plot.empty()) {
                eng::plot::check_plot_path("--plot", o->plot);
                check_output_file("--plot", o->plot, false);
                check_plot_size(o->plot_size);
            }
            check_exec_flags(o->exec);

            sw::Plan plan;
            std::unique_ptr<Session> session;
            if (!o->exec.resume.empty()) {
                for (const char* f :
                     {"--pes",       "--clock-mhz", "--mem-bytes", "--ext-bytes", "--set",
                      "--roi-size",  "--D",         "--km",        "--kb",        "--gb",
                      "--Wo",        "--Wd",        "--mode",      "--left",      "--right",
                      "--roi",       "--seed",      "--model",     "--dry-run",   "--seed-col",
                      "--seed-disp", "--vote",      "--frame",     "--fill"})
                    if (const CLI::Option* op = sub->get_option_no_throw(f); op && op->count())
                        throw UserError(std::string(f) +
                                        ": --resume takes the sweep from the run folder; give "
                                        "only outputs and executor options with it");
                session = std::make_unique<Session>(resume_session(o->exec, "sweep", 0));
                plan = sw::plan_from_json(session->manifest.payload);
                plan.jobs = session->manifest.jobs;
            } else {
                check_model_name(o->model);
                sw::Spec s;
                s.model = o->model;
                s.dry_run = o->dry_run;

                // Axes in command-line order.
                std::map<const CLI::Option*, std::pair<std::string, const std::string*>> opts;
                auto reg = [&](const char* flag, const std::string& name, const std::string& val) {
                    if (const CLI::Option* op = sub->get_option_no_throw(flag))
                        opts[op] = {name, &val};
                };
                reg("--pes", "pes", o->machine.pes);
                reg("--clock-mhz", "clock_mhz", o->machine.clock_mhz);
                reg("--mem-bytes", "mem_bytes", o->machine.mem_bytes);
                reg("--ext-bytes", "ext_bytes", o->machine.ext_bytes);
                // --camera ideal,ntsc,pixel-clock:5: an axis of camera_pixel_mhz
                std::string camera_mhz;
                for (size_t a = 0; a < o->machine.camera.size();) {
                    size_t b = o->machine.camera.find(',', a);
                    if (b == std::string::npos) b = o->machine.camera.size();
                    camera_mhz += (camera_mhz.empty() ? "" : ",") +
                                  camera_pixel_mhz(o->machine.camera.substr(a, b - a));
                    a = b + 1;
                }
                reg("--camera", "camera_pixel_mhz", camera_mhz);
                reg("--roi-size", "roi_size", o->roi_size);
                reg("--D", "D", o->algo.D);
                reg("--km", "km", o->algo.km);
                reg("--kb", "kb", o->algo.kb);
                reg("--gb", "gb", o->algo.gb);
                reg("--Wo", "Wo", o->algo.Wo);
                reg("--Wd", "Wd", o->algo.Wd);
                reg("--mode", "mode", o->algo.mode);
                const CLI::Option* set_opt = sub->get_option_no_throw("--set");
                std::vector<sw::Axis> axes;
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
                        for (const sw::Axis& a : axes)
                            same_flag |= a.name == name && a.flag == flag;
                        if (same_flag && op != set_opt) continue;
                        throw UserError(name + " is given twice (" + flag + " and another flag)");
                    }
                    seen.insert(name);
                    axes.push_back(sw::make_axis(name, flag, text));
                }
                for (sw::Axis& a : axes) (a.values.size() > 1 ? s.swept : s.fixed).push_back(a);

                // The algorithm parameters that are not axes (validated now: errors
                // exit 2 before any run), and the fixed ones for the JSON report.
                AlgoFlags base = o->algo;
                base.D = base.km = base.kb = base.gb = base.Wo = base.Wd = "";
                base.mode = "bidir";
                imap::golden::Roi roi;
                bool has_roi = false;
                s.base = parse_algo_flags(base, &roi, &has_roi);
                s.base_args = algo_child_args(o->algo);
                AlgoFlags fixed = base;
                for (const sw::Axis& a : s.fixed) {
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
                    imap::golden::Roi unused;
                    bool has = false;
                    s.fixed_algorithm = algo_params_json(parse_algo_flags(fixed, &unused, &has));
                } catch (const UserError&) {
                    // e.g. Wo < Wd with a fixed pair: every point says so
                }

                // Input.
                if (o->left.empty() != o->right.empty())
                    throw UserError("--left and --right must be given together");
                s.input.seed = o->seed;
                if (!o->left.empty()) {
                    s.input.left = o->left;
                    s.input.right = o->right;
                    const cv::Mat L = v::load_grey8(o->left, "left image");
                    const cv::Mat R = v::load_grey8(o->right, "right image");
                    check_same_size(o->left, L.cols, L.rows, o->right, R.cols, R.rows);
                    s.input.width = L.cols;
                    s.input.height = L.rows;
                    if (has_roi) {
                        if (!o->roi_size.empty())
                            throw UserError("--roi and --roi-size exclude each other");
                        if (roi.x0 + roi.w > L.cols || roi.y0 + roi.h > L.rows)
                            throw UserError("--roi " + o->algo.roi + " lies outside the " +
                                            std::to_string(L.cols) + "x" + std::to_string(L.rows) +
                                            " images");
                        s.input.has_fixed_roi = true;
                        s.input.roi = roi;
                    }
                } else if (has_roi) {
                    throw UserError(
                        "--roi needs --left/--right; the synthetic scene is generated at "
                        "--roi-size WxH");
                }
                if (!o->plot.empty() && s.swept.empty())
                    throw UserError(
                        "--plot needs a swept axis (a flag with two or more values, e.g. "
                        "--pes 64,128,256)");
                x_index(s.swept, o->x);
                s.points = sw::product(s.swept);
                plan = sw::plan(s);
                ExecFlags ex = o->exec;
                if (plan.dry_run) ex = ExecFlags{};  // nothing runs: no executor, no run folder
                session = std::make_unique<Session>(
                    start_session(ex, "sweep", sw::to_json(plan), plan.jobs, 0));
            }
            if (!o->plot.empty() && plan.swept.empty())
                throw UserError("--plot needs a swept axis");
            const size_t xi = x_index(plan.swept, o->x);
            plan.y = *metric;
            session->exec_keep = o->exec.keep;
            const sw::Result r = run_sweep_session(*session, plan, xi);
            if (o->pareto && !plan.dry_run)
                for (const std::string& l : sw::pareto_lines(plan, r))
                    std::printf("%s\n", l.c_str());

            if (!o->csv.empty()) {
                v::write_text_atomic(o->csv, sw::to_csv(plan, r));
                std::printf("  csv -> %s\n", o->csv.c_str());
            }
            if (!o->json.empty()) {
                v::write_text_atomic(o->json, sw::to_json(plan, r).dump(2) + "\n");
                std::printf("  json -> %s\n", o->json.c_str());
            }
            if (!o->plot.empty()) {
                eng::plot::Figure f;
                f.width = std::atoi(o->plot_size.c_str());
                f.height = std::atoi(o->plot_size.substr(o->plot_size.find('x') + 1).c_str());
                if (o->pareto ? sw::make_pareto_figure(plan, r, &f)
                              : sw::make_figure(plan, r, xi, &f)) {
                    eng::plot::write_plot(f, o->plot);
                    std::printf("  plot -> %s (gnuplot script %s, data %s)\n", o->plot.c_str(),
                                eng::plot::script_path(o->plot).c_str(),
                                eng::plot::data_path(o->plot).c_str());
                } else {
                    std::fprintf(stderr,
                                 "imapsim sweep: warning: no point ran bit-exact%s, %s not "
                                 "written\n",
                                 o->pareto                     ? " with an energy"
                                 : *metric == sw::Metric::Time ? ""
                                 : *metric == sw::Metric::Area ? " with an area"
                                                               : " with an energy",
                                 o->plot.c_str());
                }
            }
            std::fflush(stdout);
            return r.exit_code(plan.dry_run);
        }};
}

}  // namespace imapsim
