// imapsim sweep: the what-if explorer (docs/whatif.md). Every axis flag
// takes a comma list or a range (A..B, A..B:S, A..B*F); the sweep is the
// cartesian product of the swept axes. The engine (imap/engine/sweep.hpp)
// plans each point in-process and runs the ones that fit on an executor
// (local cores or a Slurm job array); the spec is built from the flags by
// sweep_request.hpp; this file gathers the flags and prints.
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "engine_cli.hpp"
#include "imap/engine/plot.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/engine/sweep_request.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"

namespace imapsim {

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
    std::string rtl_cache;  // --rtl-cache
};

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
    add_rtl_cache_flag(sub, o->rtl_cache);

    return {
        sub, [o, sub]() {
            apply_rtl_cache_flag(o->rtl_cache);
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
                sw::check_plot_size(o->plot_size);
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
                sw::Request rq{{},       o->algo,     o->model, o->dry_run,       o->left,
                               o->right, o->roi_size, o->seed,  !o->plot.empty(), o->x};
                const std::map<std::string, const std::string*> text = {
                    {"--pes", &o->machine.pes},
                    {"--clock-mhz", &o->machine.clock_mhz},
                    {"--mem-bytes", &o->machine.mem_bytes},
                    {"--ext-bytes", &o->machine.ext_bytes},
                    {"--camera", &o->machine.camera},
                    {"--roi-size", &o->roi_size},
                    {"--D", &o->algo.D},
                    {"--km", &o->algo.km},
                    {"--kb", &o->algo.kb},
                    {"--gb", &o->algo.gb},
                    {"--Wo", &o->algo.Wo},
                    {"--Wd", &o->algo.Wd},
                    {"--mode", &o->algo.mode}};
                size_t set_k = 0;  // axes in command-line order
                for (const CLI::Option* op : sub->parse_order())
                    if (op->get_name() == "--set" && set_k < o->machine.sets.size())
                        rq.axes.emplace_back("--set", o->machine.sets[set_k++]);
                    else if (auto it = text.find(op->get_name()); it != text.end())
                        rq.axes.emplace_back(it->first, *it->second);
                plan = sw::plan(sw::build_spec(rq));
                ExecFlags ex = o->exec;
                if (plan.dry_run) ex = ExecFlags{};  // nothing runs: no executor, no run folder
                session = std::make_unique<Session>(
                    start_session(ex, "sweep", sw::to_json(plan), plan.jobs, 0));
            }
            if (!o->plot.empty() && plan.swept.empty())
                throw UserError("--plot needs a swept axis");
            const size_t xi = sw::x_index(plan.swept, o->x);
            plan.y = *metric;
            session->exec_keep = o->exec.keep;
            const sw::Result r = run_sweep_session(*session, plan, xi);
            if (o->pareto && !plan.dry_run)
                for (const std::string& l : sw::pareto_lines(plan, r))
                    std::printf("%s\n", l.c_str());
            std::string warning;
            for (const std::string& l : sw::write_outputs(
                     {o->csv, o->json, o->plot, o->plot_size, o->pareto}, plan, r, xi, &warning))
                std::printf("%s\n", l.c_str());
            if (!warning.empty())
                std::fprintf(stderr, "imapsim sweep: warning: %s\n", warning.c_str());
            std::fflush(stdout);
            return r.exit_code(plan.dry_run);
        }};
}

}  // namespace imapsim
