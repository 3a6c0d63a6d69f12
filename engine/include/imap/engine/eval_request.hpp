// The request of `imapsim eval` (SPEC A.8) as its flags give it: the checks
// of their ranges and combinations (the messages imapsim prints), the
// parameter sets of --param-sets, the scenes, and the rows of the plain
// scoring table with their means and JSON. Printing is imapsim's.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "imap/engine/flag_values.hpp"
#include "imap/golden/params.hpp"
#include "imap/vision/perturb.hpp"
#include "imap/vision/scene.hpp"
#include "imap/vision/score.hpp"

namespace imap::engine::eval {

// The flags of imapsim eval, as given.
struct Request {
    std::string scene, all, matcher, json, plot, param_sets, perturb;
    bool tradeoff = false, robustness = false;
    double delta = 1.0;
    double gt_scale = 0;
    bool gt_scale_given = false, perturb_given = false;
    AlgoSettings algo;  // algo.given: the algorithm flags seen
};

// What the checked request runs with.
struct Checked {
    golden::Params p;
    bool explicit_D = false;
    vision::Perturbation pert;          // when r.perturb_given
    std::vector<std::string> matchers;  // --matcher (all: every matcher)
};

// Checks the flags' ranges and combinations (engine::Error with imapsim's
// message, exit 2) before any file is read.
Checked validate(const Request& r);
// Then the output files (--json, --plot): refused before the work.
void check_outputs(const Request& r);

// One parameter set of --param-sets: the text of its line and its parameters.
struct ParamSet {
    std::string text;
    int line = 0;
    golden::Params p;
    bool explicit_D = false;
};
// Reads --param-sets FILE: one set of flags per line ('#' starts a comment
// line); `parse` turns a line's words (in command-line order) into its set,
// its errors prefixed with `where` ("--param-sets FILE:LINE: ").
using ParseSet =
    std::function<ParamSet(const std::vector<std::string>& args, const std::string& where)>;
std::vector<ParamSet> read_param_sets(const std::string& path, const ParseSet& parse);

// The scenes of --scene or --all (all loaded first: a bad folder fails
// before minutes of matching).
std::vector<vision::Scene> load_scenes(const Request& r, const Checked& c);

// The row label of a matcher: the golden names its preset (golden:quality).
std::string label(const Request& r, const std::string& matcher);

// One row of the plain table: a matcher on a scene.
struct Row {
    std::string scene, matcher;
    int D = 0;
    vision::BadScores bad;
    double ms = 0;
    nlohmann::json params;
};
// Every matcher on every scene, in order; `on_row` sees each row as it is done.
std::vector<Row> score_table(const Request& r, const Checked& c,
                             const std::vector<vision::Scene>& scenes,
                             const std::function<void(const Row&)>& on_row);
// The mean row of each matcher over the scenes (D unused).
std::vector<Row> mean_rows(const Request& r, const std::vector<Row>& rows,
                           const std::vector<std::string>& matchers, size_t nscenes);
// The rows as the --json array ("perturb" when r.perturb_given).
nlohmann::json table_json(const Request& r, const std::vector<Row>& rows);

}  // namespace imap::engine::eval
