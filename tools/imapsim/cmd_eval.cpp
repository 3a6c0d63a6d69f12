// imapsim eval: Middlebury-style scoring (SPEC A.8) of the golden reference
// and the OpenCV reference matchers on one scene or on every scene of a
// folder. Its flags and the printed tables; the checks of the flags and the
// rows are eval_request.hpp's, the scoring eval.hpp's (imap/engine/).
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/engine/eval.hpp"
#include "imap/engine/eval_request.hpp"
#include "imap/engine/plot.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/perturb.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;
namespace ev = imap::engine::eval;
namespace plot = imap::engine::plot;
using nlohmann::json;

namespace {
using EvalOptions = ev::Request;

// imapsim eval --tradeoff: every golden variant and the OpenCV matchers on
// every scene; one mean row each with the modeled time of the headline case.
int run_tradeoff(const EvalOptions& o, const std::vector<v::Scene>& scenes, int explicit_D) {
    const std::vector<ev::TradeoffRow> rows = ev::tradeoff(scenes, explicit_D, o.delta);
    char delta_txt[32];
    std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", o.delta);
    std::printf(
        "mean %s %% over %zu scene(s) (nonocc, all, disc; per-scene nonocc) and modeled ms "
        "of the headline case\n(128x128, D=64, 256 PEs, 40 MHz): fw = the firmware "
        "running the variant (measured: the paper's algorithm with --ad-max, --mode joint, "
        "--dissim bt, the census and the window), +A.9 = ESTIMATE of the options not in the "
        "firmware (none today); fw 'refused' = the firmware refuses the variant at the "
        "headline; fw uJ = energy per frame of the firmware's run ([A] energy model, "
        "docs/energy.md; the +A.9 estimate has none)\n\n",
        delta_txt, scenes.size());
    std::printf("%-16s %7s %7s %7s", "variant", "nonocc", "all", "disc");
    for (const auto& sc : scenes) std::printf(" %8.8s", sc.name.c_str());
    std::printf(" %8s %8s %9s %9s %8s\n", "fw ms", "+A.9 ms", "total ms", "fw uJ", "cpu ms");
    for (const ev::TradeoffRow& r : rows) {
        std::printf("%-16s %7.2f %7.2f %7.2f", r.name.c_str(), r.scores.mean.nonocc,
                    r.scores.mean.all, r.scores.mean.disc);
        for (const auto& b : r.scores.per_scene) std::printf(" %8.2f", b.nonocc);
        if (!r.golden)
            std::printf(" %8s %8s %9s %9s", "-", "-", "-", "-");
        else if (!r.model.ok())
            std::printf(" %8s %8.2f %9s %9s", "refused", r.model.est_ms(), "-", "-");
        else
            std::printf(" %8.2f %8.2f %9.2f %9.3f", r.model.fw_ms(), r.model.est_ms(),
                        r.model.total_ms(), r.model.fw_uj);
        std::printf(" %8.1f\n", r.scores.ms);
    }
    std::printf("\nvariants:\n");
    for (const ev::TradeoffRow& r : rows) {
        std::printf("  %-16s %s\n", r.name.c_str(), r.what.c_str());
        for (const auto& item : r.model.est.items)
            std::printf("  %-16s   est. %s\n", "", item.c_str());
    }

    if (!o.plot.empty())  // with its gnuplot script and data beside it
        plot::write_plot(ev::tradeoff_plot(rows, o.delta, scenes.size()), o.plot);
    if (!o.json.empty())
        v::write_text_atomic(o.json,
                             ev::tradeoff_json(rows, scenes, o.delta, o.perturb).dump(2) + "\n");
    return static_cast<int>(kExitOk);
}

// One line of --param-sets parsed like the command line's algorithm flags.
ev::ParamSet parse_param_set(std::vector<std::string> args, const std::string& where) {
    std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector
    CLI::App parser("param set");
    AlgoFlags f;
    add_algo_flags(&parser, f);
    try {
        parser.parse(args);
    } catch (const CLI::ParseError& e) {
        throw UserError(where + e.what());
    }
    if (!f.roi.empty() || f.fill || (f.given.count("--frame") && f.frame != "left"))
        throw UserError(where + "--roi, --fill and --frame are not accepted here");
    ev::ParamSet ps;
    g::Roi roi;
    bool has_roi = false;
    try {
        ps.p = parse_algo_flags(f, &roi, &has_roi);
    } catch (const UserError& e) {
        throw UserError(where + e.what());
    }
    ps.explicit_D = !f.D.empty();
    return ps;
}

// imapsim eval --param-sets: the golden with every set on every scene, one
// line per set (mean and per-scene nonocc); the scenes are loaded once.
int run_param_sets(const EvalOptions& o, const std::vector<ev::ParamSet>& sets,
                   const std::vector<v::Scene>& scenes) {
    char delta_txt[32];
    std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", o.delta);
    std::printf("%5s %7s %7s %7s", "set", "nonocc", "all", "disc");
    for (const auto& sc : scenes) std::printf(" %8.8s", sc.name.c_str());
    std::printf("  flags (mean %s %%; per-scene nonocc)\n", delta_txt);
    json arr = json::array();
    for (const ev::ParamSet& ps : sets) {
        const ev::Scores s = ev::score_all("golden", scenes, ps.p, ps.explicit_D, o.delta,
                                           "--param-sets line " + std::to_string(ps.line) + ", ");
        std::string cols;
        for (const v::BadScores& b : s.per_scene) {
            char c[32];
            std::snprintf(c, sizeof c, " %8.2f", b.nonocc);
            cols += c;
        }
        std::printf("%5d %7.2f %7.2f %7.2f%s  %s\n", ps.line, s.mean.nonocc, s.mean.all,
                    s.mean.disc, cols.c_str(), ps.text.c_str());
        std::fflush(stdout);
        arr.push_back(
            ev::param_set_json(ps.line, ps.text, ps.p, ps.explicit_D, s, scenes, o.delta));
    }
    if (!o.perturb.empty())
        for (auto& j : arr) j["perturb"] = o.perturb;
    if (!o.json.empty()) v::write_text_atomic(o.json, arr.dump(2) + "\n");
    return static_cast<int>(kExitOk);
}

// imapsim eval --robustness: every matcher on every scene under each
// condition (seed 1); one line per condition with each matcher's mean nonocc.
int run_robustness(const EvalOptions& o, const std::vector<v::Scene>& scenes,
                   const std::vector<std::string>& matchers, const std::vector<std::string>& labels,
                   const g::Params& p, bool explicit_D) {
    char delta_txt[32];
    std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", o.delta);
    std::printf("mean %s %% (nonocc) over %zu scene(s) under each perturbation (--perturb SPEC)\n",
                delta_txt, scenes.size());
    std::printf("%-24s", "condition");
    for (const auto& l : labels) std::printf(" %14s", l.c_str());
    std::printf("  perturb\n");
    json arr = json::array();
    for (const auto& [cond, spec] : ev::robustness_conditions()) {
        const ev::Condition c =
            ev::score_condition(cond, spec, scenes, matchers, labels, p, explicit_D, o.delta);
        std::printf("%-24s", cond.c_str());
        for (const double m : c.mean) std::printf(" %14.2f", m);
        std::printf("  %s\n", spec.empty() ? "-" : spec.c_str());
        std::fflush(stdout);
        arr.push_back(c.json);
    }
    if (!o.json.empty()) v::write_text_atomic(o.json, arr.dump(2) + "\n");
    return static_cast<int>(kExitOk);
}

}  // namespace

Subcommand register_eval(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* sub = app.add_subcommand(
        "eval",
        "Score matchers Middlebury-style (bad-delta % over nonocc/all/disc, left frame, after "
        "fill)");
    sub->add_option("--scene", o->scene,
                    "one scene folder (left.png, right.png, gt.png, masks; scenes.json in it or "
                    "its parent)");
    sub->add_option("--all", o->all, "score every scene folder under this folder, sorted by name");
    sub->add_option("--matcher", o->matcher,
                    "golden, opencv-bm, opencv-sgbm or all [default: golden with --scene, all "
                    "with --all]")
        ->check(CLI::IsMember({"golden", "opencv-bm", "opencv-sgbm", "all"}));
    sub->add_option("--json", o->json, "also write the rows as a JSON array to this file");
    sub->add_option("--delta", o->delta, "bad-pixel threshold in pixels")->capture_default_str();
    sub->add_option("--gt-scale", o->gt_scale,
                    "ground-truth scale (gt value / scale = disparity) [default: scenes.json]");
    sub->add_flag("--tradeoff", o->tradeoff,
                  "score every golden preset and option variant (docs/golden.md, "
                  "\"Trade-off\") and the OpenCV matchers; one mean row each with the modeled "
                  "time of the headline case (algorithm flags other than --D are refused)");
    sub->add_option("--plot", o->plot,
                    "with --tradeoff: PNG plot of the mean nonocc bad-delta against the modeled "
                    "time");
    sub->add_option("--param-sets", o->param_sets,
                    "score the golden with every parameter set of this file (one line of "
                    "algorithm flags each, e.g. '--preset quality --kc 3'); the scenes are "
                    "loaded once (tuning sweeps: scripts/tune-quality.sh)");
    sub->add_option("--perturb", o->perturb,
                    "perturb the images before every matcher: key=value[,key=value...] with "
                    "gain (0 < g <= 16, default 1) and offset (-255..255, default 0) on 'image' "
                    "(left|right|both, default right), Gaussian noise of standard deviation "
                    "noise (0..64, default 0) on 'noise-image' (default both) and seed (default "
                    "1), e.g. gain=0.8,offset=10 or noise=3,seed=2; integer arithmetic, the same "
                    "bytes on every CPU (docs/scoring.md)");
    sub->add_flag("--robustness", o->robustness,
                  "score the matchers under the standard perturbations (as recorded, right "
                  "x0.8+10, right x1.2-20, noise 3, noise 6, right x0.9+5 with noise 2; seed 1) "
                  "and print one line per condition with each matcher's mean nonocc");
    add_algo_flags(sub, o->algo);
    // Scores are taken in the left frame: that is eval's default and the
    // only frame it accepts, and its help says so.
    o->algo.frame = "left";
    sub->get_option("--frame")->description(
        "output frame: left only (scenes are scored in the left frame) [default: left]");
    sub->footer(
        "--D defaults to the scene's ndisp (scenes.json). Scenes are scored over the whole "
        "image in the left frame after the fill post-step, so --roi and --frame cyc/right are "
        "refused and --fill is implied.");

    return {sub, [o, sub]() {
                o->gt_scale_given = sub->count("--gt-scale") > 0;
                o->perturb_given = sub->count("--perturb") > 0;
                const ev::Checked c = ev::validate(*o);
                std::vector<ev::ParamSet> sets;
                if (!o->param_sets.empty())
                    sets = ev::read_param_sets(o->param_sets, parse_param_set);
                ev::check_outputs(*o);  // fail before the work, not after it
                std::vector<v::Scene> scenes = ev::load_scenes(*o, c);
                if (o->perturb_given) {  // the same perturbed pair goes to every matcher
                    for (auto& sc : scenes) v::perturb_pair(sc.left, sc.right, c.pert);
                    o->perturb = v::to_string(c.pert);
                    std::printf("perturbation: %s\n", o->perturb.c_str());
                }
                if (o->robustness) {
                    std::vector<std::string> labels;
                    for (const auto& name : c.matchers) labels.push_back(ev::label(*o, name));
                    return run_robustness(*o, scenes, c.matchers, labels, c.p, c.explicit_D);
                }
                if (o->tradeoff) return run_tradeoff(*o, scenes, c.explicit_D ? c.p.D : 0);
                if (!sets.empty()) return run_param_sets(*o, sets, scenes);

                int wscene = 5;
                for (const auto& sc : scenes)
                    wscene = std::max(wscene, static_cast<int>(sc.name.size()));
                char delta_txt[32];
                std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", o->delta);
                std::printf("%-*s  %-14s %6s %7s %7s %7s %10s\n", wscene, "scene", "matcher", "D",
                            (std::string(delta_txt) + " nonocc").c_str(), "all", "disc", "time ms");
                const int wfirst = static_cast<int>(std::string(delta_txt).size()) + 7;
                const std::vector<ev::Row> rows =
                    ev::score_table(*o, c, scenes, [&](const ev::Row& r) {
                        std::printf("%-*s  %-14s %6d %*.2f %7.2f %7.2f %10.1f\n", wscene,
                                    r.scene.c_str(), r.matcher.c_str(), r.D, wfirst, r.bad.nonocc,
                                    r.bad.all, r.bad.disc, r.ms);
                        std::fflush(stdout);
                    });
                if (scenes.size() > 1)
                    for (const ev::Row& m : ev::mean_rows(*o, rows, c.matchers, scenes.size()))
                        std::printf("%-*s  %-14s %6s %*.2f %7.2f %7.2f %10.1f\n", wscene, "mean",
                                    m.matcher.c_str(), "", wfirst, m.bad.nonocc, m.bad.all,
                                    m.bad.disc, m.ms);
                if (!o->json.empty())
                    v::write_text_atomic(o->json, ev::table_json(*o, rows).dump(2) + "\n");
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
