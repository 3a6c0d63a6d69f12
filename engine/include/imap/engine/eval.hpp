// Scoring matchers Middlebury-style (imapsim eval, SPEC A.8): a matcher on
// every scene (bad-delta % over nonocc / all / disc, left frame, after the
// fill), the quality trade-off of the golden variants against the modeled
// time of the headline case, parameter sets, and robustness under the
// standard perturbations. Results and their JSON; printing is imapsim's.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "imap/engine/plot.hpp"
#include "imap/golden/estimate.hpp"
#include "imap/golden/params.hpp"
#include "imap/vision/scene.hpp"
#include "imap/vision/score.hpp"

namespace imap::engine::eval {

// The parameters a matcher ran with, as the JSON rows carry them.
nlohmann::json matcher_params(const std::string& name, const golden::Params& p);

// The parameters scene `sc` is scored with: D = p.D when explicit_D, else
// the scene's ndisp; the left frame.
golden::Params scene_params(const golden::Params& p, bool explicit_D, const vision::Scene& sc);

// One matcher on one scene (p as scene_params gives it): the scores and
// the matcher's wall time. Error "<context>scene 'NAME'<suffix>: ..." when the
// parameters do not fit the scene.
struct Score {
    vision::BadScores bad;
    double ms = 0;
};
Score score_one(const std::string& matcher, const vision::Scene& sc, const golden::Params& q,
                double delta, const std::string& context = "", const std::string& suffix = "");

// One matcher on every scene: per scene and the means (scores, wall ms).
struct Scores {
    std::vector<vision::BadScores> per_scene;
    vision::BadScores mean;
    double ms = 0;
};
Scores score_all(const std::string& matcher, const std::vector<vision::Scene>& scenes,
                 const golden::Params& p, bool explicit_D, double delta,
                 const std::string& context = "", const std::string& suffix = "");

// Modeled cycles of the headline case (synthetic scene seed 1, 160x128, ROI
// 16,0,128x128, D = 64, the default machine: 256 PEs at 40 MHz) for the
// part of `p` the firmware runs (firmware_part), measured on the machine
// core; the A.9 options the firmware does not run come on top as an estimate.
struct Modeled {
    int64_t fw_cycles = -1;  // measured; -1 when the firmware refuses it
    double fw_uj = 0;        // its energy per frame (docs/energy.md), from the same run
    golden::OptionCost est;  // estimated: the A.9 options not in the firmware
    double clock_mhz = 40;
    bool ok() const { return fw_cycles >= 0; }
    double fw_ms() const { return static_cast<double>(fw_cycles) / (clock_mhz * 1e3); }
    double est_ms() const { return static_cast<double>(est.cycles) / (clock_mhz * 1e3); }
    double total_ms() const { return fw_ms() + est_ms(); }
};
Modeled modeled_headline(const golden::Params& p);

// eval --tradeoff: every golden variant (golden::tradeoff_variants) and the
// OpenCV matchers on every scene; explicit_D > 0 overrides the scenes' D.
struct TradeoffRow {
    std::string name, what;
    bool golden = false;
    golden::Params p;
    Scores scores;
    Modeled model;  // golden rows only
};
std::vector<TradeoffRow> tradeoff(const std::vector<vision::Scene>& scenes, int explicit_D,
                                  double delta);
// The mean nonocc against the modeled time, with the Pareto front and the
// OpenCV matchers as lines.
plot::Figure tradeoff_plot(const std::vector<TradeoffRow>& rows, double delta, size_t nscenes);
nlohmann::json tradeoff_json(const std::vector<TradeoffRow>& rows,
                             const std::vector<vision::Scene>& scenes, double delta,
                             const std::string& perturb);

// One row of eval --param-sets: line `line` of the file (`text`) scored.
nlohmann::json param_set_json(int line, const std::string& text, const golden::Params& p,
                              bool explicit_D, const Scores& s,
                              const std::vector<vision::Scene>& scenes, double delta);

// The conditions of eval --robustness (docs/golden.md, "Robustness"):
// (label, perturbation spec; "" = as recorded).
const std::vector<std::pair<std::string, std::string>>& robustness_conditions();
// Every matcher on every scene under one condition: each matcher's mean
// nonocc and the condition's JSON row.
struct Condition {
    std::vector<double> mean;  // per matcher
    nlohmann::json json;
};
Condition score_condition(const std::string& name, const std::string& spec,
                          const std::vector<vision::Scene>& scenes,
                          const std::vector<std::string>& matchers,
                          const std::vector<std::string>& labels, const golden::Params& p,
                          bool explicit_D, double delta);

}  // namespace imap::engine::eval
