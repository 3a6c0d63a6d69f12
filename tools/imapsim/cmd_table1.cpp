// imapsim table1: the paper's grid on the modeled board (docs/whatif.md):
// 256 PEs at 40 MHz, ROI height 128, widths 32/64/128, D in 16/32/64/128
// with D <= width, the synthetic scene of width x 128. Runs on the sweep
// engine; prints modeled ms per cell with the paper's 85 ms beside the
// headline cell (128 wide, D = 64).
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli_common.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"
#include "sweep_engine.hpp"

namespace imapsim {

namespace {

constexpr int kWidths[] = {32, 64, 128};
constexpr int kLevels[] = {16, 32, 64, 128};
constexpr int kHeight = 128;
constexpr double kPaperHeadlineMs = 85.0;  // Kraft & Jonker's figure on the IMAP-VISION board

struct Table1Options {
    std::string csv, json, jobs;
    std::string model = kDefaultModel;
    uint64_t seed = 1;
};

}  // namespace

Subcommand register_table1(CLI::App& app) {
    auto o = std::make_shared<Table1Options>();
    CLI::App* sub = app.add_subcommand(
        "table1",
        "The paper's grid on the modeled board: 256 PEs, 40 MHz, ROI height 128, widths "
        "32/64/128, D 16/32/64/128 (D <= width); modeled ms per cell (docs/whatif.md)");
    sub->add_option("--csv", o->csv, "write width,D,modeled_ms,cycles here");
    sub->add_option("--json", o->json, "write every cell (cycles, phases, status) as JSON here");
    sub->add_option("--model", o->model, "model to run: " + model_names())->capture_default_str();
    sub->add_option("-j,--jobs", o->jobs, "cells run in parallel [default: one per core]");
    sub->add_option("--seed", o->seed, "synthetic scene seed")->capture_default_str();

    return {sub, [o]() {
                check_model_name(o->model);
                check_output_file("--csv", o->csv, false);
                check_output_file("--json", o->json, false);
                sweep::Spec s;
                s.command = "table1";
                s.model = o->model;
                s.input.seed = o->seed;
                if (!o->jobs.empty())
                    s.jobs = static_cast<unsigned>(parse_int_flag("-j", o->jobs, 1, 1024));
                std::string widths, levels;
                for (int w : kWidths)
                    widths += (widths.empty() ? "" : ",") + std::to_string(w) + "x" +
                              std::to_string(kHeight);
                for (int d : kLevels) levels += (levels.empty() ? "" : ",") + std::to_string(d);
                s.fixed = {sweep::make_axis("pes", "--pes", "256"),
                           sweep::make_axis("clock_mhz", "--clock-mhz", "40")};
                s.swept = {sweep::make_axis("roi_size", "--roi-size", widths),
                           sweep::make_axis("D", "--D", levels)};
                for (size_t wi = 0; wi < std::size(kWidths); ++wi)
                    for (size_t di = 0; di < std::size(kLevels); ++di)
                        if (kLevels[di] <= kWidths[wi]) s.points.push_back({wi, di});

                const sweep::Result r = sweep::run(s);

                // The grid: rows width, columns D.
                auto cell = [&](int w, int d) -> const sweep::Row* {
                    const std::string ws = std::to_string(w) + "x" + std::to_string(kHeight);
                    for (const sweep::Row& row : r.rows)
                        if (row.values[0] == ws && row.values[1] == std::to_string(d)) return &row;
                    return nullptr;
                };
                std::printf(
                    "\nTable 1 on the modeled board: modeled ms per frame (256 PEs at 40 MHz, "
                    "ROI height %d, bidir, vote on, model %s)\n",
                    kHeight, o->model.c_str());
                const std::string note = " [paper " + sweep::fmt("%g", kPaperHeadlineMs) + "]";
                auto emit = [](std::string line) {
                    line.erase(line.find_last_not_of(' ') + 1);
                    std::printf("%s\n", line.c_str());
                };
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
                        } else if (const sweep::Row* row = cell(w, d)) {
                            c = row->ran ? sweep::fmt("%.3f", row->modeled_ms)
                                         : std::string(sweep::status_name(row->status));
                            if (w == 128 && d == 64) extra = note;
                        } else {
                            c = "not run";
                        }
                        std::snprintf(b, sizeof b, "  %9s%-*s", c.c_str(),
                                      static_cast<int>(note.size()), extra.c_str());
                        line += b;
                    }
                    emit(line);
                }
                std::printf(
                    "  '-': D > ROI width (not a valid cell). Headline cell: ROI 128x128, D=64; "
                    "the paper reports %g ms for it on the real board.\n",
                    kPaperHeadlineMs);

                if (!o->csv.empty()) {
                    std::ostringstream c;
                    c << "width,D,modeled_ms,cycles\n";
                    for (int w : kWidths)
                        for (int d : kLevels) {
                            if (d > w) continue;
                            const sweep::Row* row = cell(w, d);
                            if (!row) continue;  // interrupted before it ran
                            c << w << "," << d << ","
                              << (row->ran ? sweep::fmt("%.6f", row->modeled_ms) : "") << ","
                              << (row->ran ? std::to_string(row->cycles) : "") << "\n";
                        }
                    imap::vision::write_text_atomic(o->csv, c.str());
                    std::printf("  csv -> %s\n", o->csv.c_str());
                }
                if (!o->json.empty()) {
                    nlohmann::json j = sweep::to_json(s, r);
                    j["paper_headline_ms"] = kPaperHeadlineMs;
                    j["headline_cell"] = {{"width", 128}, {"D", 64}};
                    if (const sweep::Row* row = cell(128, 64); row && row->ran)
                        j["headline_modeled_ms"] = row->modeled_ms;
                    imap::vision::write_text_atomic(o->json, j.dump(2) + "\n");
                    std::printf("  json -> %s\n", o->json.c_str());
                }
                std::fflush(stdout);
                return r.exit_code();
            }};
}

}  // namespace imapsim
