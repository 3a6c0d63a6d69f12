// imapsim eval: Middlebury-style scoring (SPEC A.8) of the golden reference
// and the OpenCV reference matchers on one scene or on every scene of a folder.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/matchers.hpp"
#include "imap/vision/scene.hpp"
#include "imap/vision/score.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;
using nlohmann::json;

namespace {
struct EvalOptions {
    std::string scene, all, matcher, json;
    double delta = 1.0;
    double gt_scale = 0;
    AlgoFlags algo;
};

struct Row {
    std::string scene, matcher;
    v::BadScores bad;
    double ms = 0;
    json params;
};

json matcher_params(const std::string& name, const g::Params& p) {
    if (name == "golden") {
        json j = algo_params_json(p);
        j["frame"] = "left";
        j["fill"] = true;
        return j;
    }
    const v::OpenCvSettings s = v::opencv_settings(name, p.D);
    json j = {{"D", p.D},
              {"numDisparities", s.num_disparities},
              {"blockSize", s.block_size},
              {"preFilterCap", s.pre_filter_cap},
              {"uniquenessRatio", s.uniqueness_ratio},
              {"disp12MaxDiff", s.disp12_max_diff},
              {"threads", 1},
              {"fill", true}};
    if (name == "opencv-bm") {
        j["textureThreshold"] = s.texture_threshold;
    } else {
        j["P1"] = s.p1;
        j["P2"] = s.p2;
        j["speckleWindowSize"] = s.speckle_window;
        j["speckleRange"] = s.speckle_range;
        j["mode"] = "MODE_SGBM";
    }
    return j;
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
    add_algo_flags(sub, o->algo);
    sub->footer(
        "--D defaults to the scene's ndisp (scenes.json). Scenes are scored over the whole "
        "image in the left frame after the fill post-step, so --roi and --frame cyc/right are "
        "refused and --fill is implied.");

    return {
        sub, [o, sub]() {
            if (o->scene.empty() == o->all.empty())
                throw UserError("give exactly one of --scene DIR or --all DATA_DIR");
            if (!std::isfinite(o->delta) || o->delta < 0)
                throw UserError("invalid value for --delta: expected a number >= 0");
            if (sub->count("--gt-scale") > 0 && !(std::isfinite(o->gt_scale) && o->gt_scale > 0))
                throw UserError("invalid value for --gt-scale: expected a number > 0");
            g::Roi roi;
            bool has_roi = false;
            const g::Params p = parse_algo_flags(o->algo, &roi, &has_roi);
            if (has_roi)
                throw UserError(
                    "--roi is not supported by eval: scenes are scored over the "
                    "whole image");
            if (sub->count("--frame") > 0 && p.frame != g::Frame::Left)
                throw UserError("--frame " + o->algo.frame +
                                " is not supported by eval: scoring uses the left frame");
            const bool explicit_D = !o->algo.D.empty();

            std::vector<std::string> matchers;
            const std::string m =
                !o->matcher.empty() ? o->matcher : (o->all.empty() ? "golden" : "all");
            if (m == "all")
                matchers = v::matcher_names();
            else
                matchers = {m};

            check_output_file("--json", o->json, false);  // fail before the work, not after it

            const std::vector<std::string> dirs =
                o->all.empty() ? std::vector<std::string>{o->scene} : v::list_scene_dirs(o->all);
            if (dirs.empty())
                throw UserError("no scene folders (with a left image) under '" + o->all + "'");

            // Load every scene first: a bad folder fails before minutes of matching.
            std::vector<v::Scene> scenes;
            for (const auto& d : dirs)
                scenes.push_back(v::load_scene(d, o->gt_scale, explicit_D ? p.D : 0));

            int wscene = 5;
            for (const auto& sc : scenes)
                wscene = std::max(wscene, static_cast<int>(sc.name.size()));
            char delta_txt[32];
            std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", o->delta);
            std::printf("%-*s  %-12s %6s %7s %7s %7s %10s\n", wscene, "scene", "matcher", "D",
                        (std::string(delta_txt) + " nonocc").c_str(), "all", "disc", "time ms");
            const char* fmt = "%-*s  %-12s %6d %*.2f %7.2f %7.2f %10.1f\n";
            const int wfirst = static_cast<int>(std::string(delta_txt).size()) + 7;

            std::vector<Row> rows;
            for (const auto& sc : scenes) {
                g::Params q = p;
                if (!explicit_D) q.D = sc.ndisp;
                q.frame = g::Frame::Left;
                for (const auto& name : matchers) {
                    double secs = 0;
                    cv::Mat disp;
                    try {
                        disp = v::run_matcher(name, sc, q, &secs);
                    } catch (const g::ParamError& e) {
                        throw UserError("scene '" + sc.name + "': " + e.what());
                    }
                    Row r{sc.name, name, v::score_bad(disp, 1.0, sc, o->delta), secs * 1e3,
                          matcher_params(name, q)};
                    std::printf(fmt, wscene, r.scene.c_str(), r.matcher.c_str(), q.D, wfirst,
                                r.bad.nonocc, r.bad.all, r.bad.disc, r.ms);
                    std::fflush(stdout);
                    rows.push_back(std::move(r));
                }
            }
            if (scenes.size() > 1) {
                for (const auto& name : matchers) {
                    v::BadScores mean;
                    double ms = 0;
                    for (const auto& r : rows)
                        if (r.matcher == name) {
                            mean.nonocc += r.bad.nonocc / scenes.size();
                            mean.all += r.bad.all / scenes.size();
                            mean.disc += r.bad.disc / scenes.size();
                            ms += r.ms / scenes.size();
                        }
                    std::printf("%-*s  %-12s %6s %*.2f %7.2f %7.2f %10.1f\n", wscene, "mean",
                                name.c_str(), "", wfirst, mean.nonocc, mean.all, mean.disc, ms);
                }
            }

            if (!o->json.empty()) {
                json arr = json::array();
                for (const auto& r : rows)
                    arr.push_back({{"scene", r.scene},
                                   {"matcher", r.matcher},
                                   {"nonocc", r.bad.nonocc},
                                   {"all", r.bad.all},
                                   {"disc", r.bad.disc},
                                   {"ms", r.ms},
                                   {"delta", o->delta},
                                   {"params", r.params}});
                v::write_text_atomic(o->json, arr.dump(2) + "\n");
            }
            return static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
