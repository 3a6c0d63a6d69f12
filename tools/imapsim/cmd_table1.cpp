// imapsim table1: the paper's grid on the modeled board (docs/whatif.md):
// 256 PEs at 40 MHz, ROI height 128, widths 32/64/128, D in 16/32/64/128
// with D <= width, the synthetic scene of width x 128. Runs on the sweep
// engine (any executor); prints modeled ms per cell with the paper's 85 ms
// beside the headline cell (128 wide, D = 64).
#include <cstdio>
#include <functional>
#include <memory>
#include <sstream>

#include "cli_common.hpp"
#include "engine_cli.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace sw = imap::engine::sweep;
using imap::engine::fmt;

namespace {

constexpr int kWidths[] = {32, 64, 128};
constexpr int kLevels[] = {16, 32, 64, 128};
constexpr int kHeight = 128;
constexpr double kPaperHeadlineMs = 85.0;  // Kraft & Jonker's figure on the IMAP-VISION board

struct Table1Options {
    std::string csv, json;
    std::string model = kDefaultModel;
    uint64_t seed = 1;
    ExecFlags exec;
};

}  // namespace

Subcommand register_table1(CLI::App& app) {
    auto o = std::make_shared<Table1Options>();
    CLI::App* sub = app.add_subcommand(
        "table1",
        "The paper's grid on the modeled board: 256 PEs, 40 MHz, ROI height 128, widths "
        "32/64/128, D 16/32/64/128 (D <= width); modeled ms and energy (uJ) per cell "
        "(docs/whatif.md)");
    sub->add_option("--csv", o->csv,
                    "write width,D,modeled_ms,cycles,dominant_phase,energy_uj here");
    sub->add_option("--json", o->json, "write every cell (cycles, phases, status) as JSON here");
    sub->add_option("--model", o->model, "model to run: " + model_names())->capture_default_str();
    sub->add_option("--seed", o->seed, "synthetic scene seed")->capture_default_str();
    add_exec_flags(sub, o->exec, "cells");

    return {sub, [o, sub]() {
                check_output_file("--csv", o->csv, false);
                check_output_file("--json", o->json, false);
                check_exec_flags(o->exec);
                sw::Plan plan;
                std::unique_ptr<Session> session;
                if (!o->exec.resume.empty()) {
                    for (const char* f : {"--model", "--seed"})
                        if (const CLI::Option* op = sub->get_option_no_throw(f); op && op->count())
                            throw UserError(std::string(f) +
                                            ": --resume takes the grid from the run folder");
                    session = std::make_unique<Session>(resume_session(o->exec, "table1", 0));
                    plan = sw::plan_from_json(session->manifest.payload);
                    plan.jobs = session->manifest.jobs;
                } else {
                    check_model_name(o->model);
                    sw::Spec s;
                    s.command = "table1";
                    s.model = o->model;
                    s.input.seed = o->seed;
                    std::string widths, levels;
                    for (int w : kWidths)
                        widths += (widths.empty() ? "" : ",") + std::to_string(w) + "x" +
                                  std::to_string(kHeight);
                    for (int d : kLevels) levels += (levels.empty() ? "" : ",") + std::to_string(d);
                    s.fixed = {sw::make_axis("pes", "--pes", "256"),
                               sw::make_axis("clock_mhz", "--clock-mhz", "40")};
                    s.swept = {sw::make_axis("roi_size", "--roi-size", widths),
                               sw::make_axis("D", "--D", levels)};
                    for (size_t wi = 0; wi < std::size(kWidths); ++wi)
                        for (size_t di = 0; di < std::size(kLevels); ++di)
                            if (kLevels[di] <= kWidths[wi]) s.points.push_back({wi, di});
                    const AlgoFlags defaults;
                    imap::golden::Roi roi;
                    bool has_roi = false;
                    s.base = parse_algo_flags(defaults, &roi, &has_roi);
                    s.fixed_algorithm = algo_params_json(s.base);
                    plan = sw::plan(s);
                    session = std::make_unique<Session>(
                        start_session(o->exec, "table1", sw::to_json(plan), plan.jobs, 0));
                }
                session->exec_keep = o->exec.keep;
                plan.y = sw::Metric::Energy;  // the rows' energy beside their time
                const sw::Result r = run_sweep_session(*session, plan, 1);

                // The grid: rows width, columns D.
                auto cell = [&](int w, int d) -> const sw::Row* {
                    const std::string ws = std::to_string(w) + "x" + std::to_string(kHeight);
                    for (const sw::Row& row : r.rows)
                        if (row.values[0] == ws && row.values[1] == std::to_string(d)) return &row;
                    return nullptr;
                };
                const std::string note = " [paper " + fmt("%g", kPaperHeadlineMs) + "]";
                auto emit = [](std::string line) {
                    line.erase(line.find_last_not_of(' ') + 1);
                    std::printf("%s\n", line.c_str());
                };
                // One grid of `value` (a ran cell's text; the paper's figure
                // beside the headline cell when `paper`).
                auto grid = [&](const std::function<std::string(const sw::Row&)>& value,
                                bool paper) {
                    std::string line = "ROI width";
                    for (int d : kLevels) {
                        char b[64];
                        std::snprintf(b, sizeof b, "  %9s%-*s", ("D=" + std::to_string(d)).c_str(),
                                      static_cast<int>(note.size()), "");
                        line += b;
                    }
                    emit(line);
                    for (int w : kWidths) {
                        char b[64];
                        std::snprintf(b, sizeof b, "%9d", w);
                        line = b;
                        for (int d : kLevels) {
                            std::string c, extra;
                            if (d > w) {
                                c = "-";
                            } else if (const sw::Row* row = cell(w, d)) {
                                c = row->ran() ? value(*row)
                                               : std::string(sw::status_name(row->status));
                                if (paper && w == 128 && d == 64) extra = note;
                            } else {
                                c = "not run";
                            }
                            std::snprintf(b, sizeof b, "  %9s%-*s", c.c_str(),
                                          static_cast<int>(note.size()), extra.c_str());
                            line += b;
                        }
                        emit(line);
                    }
                };
                std::printf(
                    "\nTable 1 on the modeled board: modeled ms per frame (256 PEs at 40 MHz, "
                    "ROI height %d, bidir, vote on, model %s)\n",
                    kHeight, plan.model.c_str());
                grid([](const sw::Row& row) { return fmt("%.3f", row.run->modeled_ms); }, true);
                std::printf(
                    "\nEnergy per frame (uJ) of the same cells ([A] 45 nm energy model, "
                    "docs/energy.md)\n");
                grid(
                    [](const sw::Row& row) {
                        return row.run->energy ? fmt("%.3f", row.run->energy->total_uj)
                                               : std::string("-");
                    },
                    false);
                std::printf(
                    "  '-': D > ROI width (not a valid cell). Headline cell: ROI 128x128, D=64; "
                    "the paper reports %g ms for it on the real board.\n",
                    kPaperHeadlineMs);

                if (!o->csv.empty()) {
                    std::ostringstream c;
                    c << "width,D,modeled_ms,cycles,dominant_phase,energy_uj\n";
                    for (int w : kWidths)
                        for (int d : kLevels) {
                            if (d > w) continue;
                            const sw::Row* row = cell(w, d);
                            if (!row) continue;  // interrupted before it ran
                            c << w << "," << d << ","
                              << (row->ran() ? fmt("%.6f", row->run->modeled_ms) : "") << ","
                              << (row->ran() ? std::to_string(row->run->cycles) : "") << ","
                              << (row->ran() ? row->run->dominant_phase() : "") << ","
                              << (row->ran() && row->run->energy
                                      ? fmt("%.6f", row->run->energy->total_uj)
                                      : "")
                              << "\n";
                        }
                    imap::vision::write_text_atomic(o->csv, c.str());
                    std::printf("  csv -> %s\n", o->csv.c_str());
                }
                if (!o->json.empty()) {
                    nlohmann::json j = sw::to_json(plan, r);
                    j["paper_headline_ms"] = kPaperHeadlineMs;
                    j["headline_cell"] = {{"width", 128}, {"D", 64}};
                    if (const sw::Row* row = cell(128, 64); row && row->ran()) {
                        j["headline_modeled_ms"] = row->run->modeled_ms;
                        if (row->run->energy) j["headline_energy_uj"] = row->run->energy->total_uj;
                    }
                    imap::vision::write_text_atomic(o->json, j.dump(2) + "\n");
                    std::printf("  json -> %s\n", o->json.c_str());
                }
                std::fflush(stdout);
                return r.exit_code(plan.dry_run);
            }};
}

}  // namespace imapsim
