// imapsim eval's request: the checks of its flags (ranges, combinations;
// the messages imapsim prints), the --param-sets file, the scenes and the
// rows of the plain scoring table, from the flags as given (Request).
#include "imap/engine/eval_request.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "imap/engine/error.hpp"
#include "imap/engine/eval.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/engine/plot.hpp"
#include "imap/vision/matchers.hpp"

namespace imap::engine::eval {

Checked validate(const Request& r) {
    if (r.scene.empty() == r.all.empty())
        throw Error("give exactly one of --scene DIR or --all DATA_DIR");
    if (!std::isfinite(r.delta) || r.delta < 0)
        throw Error("invalid value for --delta: expected a number >= 0");
    if (r.gt_scale_given && !(std::isfinite(r.gt_scale) && r.gt_scale > 0))
        throw Error("invalid value for --gt-scale: expected a number > 0");
    Checked c;
    if (r.perturb_given) {
        try {
            c.pert = vision::parse_perturbation(r.perturb);
        } catch (const vision::PerturbSpecError& e) {
            throw Error("invalid value '" + e.item() + "' for --perturb: " + e.want());
        }
    }
    if (r.robustness) {
        if (r.perturb_given)
            throw Error("--robustness runs its own list of perturbations: drop --perturb");
        if (r.tradeoff || !r.param_sets.empty())
            throw Error("give one of --robustness, --tradeoff or --param-sets");
    }
    golden::Roi roi;
    bool has_roi = false;
    c.p = algo_params(r.algo, &roi, &has_roi);
    if (has_roi)
        throw Error("--roi is not supported by eval: scenes are scored over the whole image");
    if (r.algo.given.count("--frame") > 0 && c.p.frame != golden::Frame::Left)
        throw Error("--frame " + r.algo.frame +
                    " is not supported by eval: scoring uses the left frame");
    c.explicit_D = !r.algo.D.empty();
    if (!r.plot.empty() && !r.tradeoff) throw Error("--plot needs --tradeoff");
    if (!r.param_sets.empty()) {
        if (r.tradeoff) throw Error("give --tradeoff or --param-sets, not both");
        if (!r.matcher.empty() && r.matcher != "golden")
            throw Error("--param-sets scores the golden only: drop --matcher");
        for (const std::string& f : r.algo.given)
            if (f != "--D")
                throw Error("--param-sets takes the algorithm flags from its file: drop " + f +
                            " (only --D, the default of the sets without one, is accepted)");
        if (r.algo.fill) throw Error("--param-sets: drop --fill (it is implied)");
    }
    if (r.tradeoff) {
        if (!r.matcher.empty())
            throw Error("--tradeoff scores its own list of matchers: drop --matcher");
        for (const std::string& f : r.algo.given)
            if (f != "--D")
                throw Error("--tradeoff uses its own parameter sets: drop " + f +
                            " (only --D is accepted)");
        if (r.algo.fill) throw Error("--tradeoff uses its own parameter sets: drop --fill");
    }
    const std::string m = !r.matcher.empty() ? r.matcher : (r.all.empty() ? "golden" : "all");
    if (m == "all")
        c.matchers = vision::matcher_names();
    else
        c.matchers = {m};
    return c;
}

void check_outputs(const Request& r) {
    check_output_file("--json", r.json, false);
    if (!r.plot.empty()) {
        plot::check_plot_path("--plot", r.plot);
        check_output_file("--plot", r.plot, false);
    }
}

std::vector<ParamSet> read_param_sets(const std::string& path, const ParseSet& parse) {
    std::ifstream in(path);
    if (!in) throw Error("--param-sets '" + path + "': cannot read the file");
    std::vector<ParamSet> sets;
    std::string text;
    int line = 0;
    while (std::getline(in, text)) {
        ++line;
        const size_t b = text.find_first_not_of(" \t\r");
        if (b == std::string::npos || text[b] == '#') continue;
        std::istringstream is(text);
        std::vector<std::string> args;
        for (std::string w; is >> w;) args.push_back(w);
        ParamSet ps = parse(args, "--param-sets " + path + ":" + std::to_string(line) + ": ");
        ps.text = text.substr(b);
        ps.line = line;
        sets.push_back(ps);
    }
    if (sets.empty()) throw Error("--param-sets '" + path + "': no parameter sets in it");
    return sets;
}

std::vector<vision::Scene> load_scenes(const Request& r, const Checked& c) {
    const std::vector<std::string> dirs =
        r.all.empty() ? std::vector<std::string>{r.scene} : vision::list_scene_dirs(r.all);
    if (dirs.empty()) throw Error("no scene folders (with a left image) under '" + r.all + "'");
    std::vector<vision::Scene> scenes;
    for (const auto& d : dirs)
        scenes.push_back(vision::load_scene(d, r.gt_scale, c.explicit_D ? c.p.D : 0));
    return scenes;
}

std::string label(const Request& r, const std::string& matcher) {
    return matcher == "golden" && !r.algo.preset.empty() ? "golden:" + r.algo.preset : matcher;
}

std::vector<Row> score_table(const Request& r, const Checked& c,
                             const std::vector<vision::Scene>& scenes,
                             const std::function<void(const Row&)>& on_row) {
    std::vector<Row> rows;
    for (const auto& sc : scenes) {
        const golden::Params q = scene_params(c.p, c.explicit_D, sc);
        for (const auto& name : c.matchers) {
            const Score s = score_one(name, sc, q, r.delta);
            Row row{sc.name, label(r, name), q.D, s.bad, s.ms, matcher_params(name, q)};
            on_row(row);
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

std::vector<Row> mean_rows(const Request& r, const std::vector<Row>& rows,
                           const std::vector<std::string>& matchers, size_t nscenes) {
    std::vector<Row> means;
    for (const auto& name : matchers) {
        Row m{"mean", label(r, name), 0, {}, 0, {}};
        for (const auto& row : rows)
            if (row.matcher == m.matcher) {
                m.bad.nonocc += row.bad.nonocc / nscenes;
                m.bad.all += row.bad.all / nscenes;
                m.bad.disc += row.bad.disc / nscenes;
                m.ms += row.ms / nscenes;
            }
        means.push_back(m);
    }
    return means;
}

nlohmann::json table_json(const Request& r, const std::vector<Row>& rows) {
    nlohmann::json arr = nlohmann::json::array();
    for (const auto& row : rows)
        arr.push_back({{"scene", row.scene},
                       {"matcher", row.matcher},
                       {"nonocc", row.bad.nonocc},
                       {"all", row.bad.all},
                       {"disc", row.bad.disc},
                       {"ms", row.ms},
                       {"delta", r.delta},
                       {"params", row.params}});
    if (r.perturb_given)
        for (auto& j : arr) j["perturb"] = r.perturb;
    return arr;
}

}  // namespace imap::engine::eval
