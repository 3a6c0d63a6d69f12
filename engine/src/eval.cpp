// Scoring matchers (eval.hpp): one matcher on one scene or every scene, the
// trade-off of the golden variants against the headline's modeled time,
// parameter sets and robustness conditions, and their JSON rows.
#include "imap/engine/eval.hpp"

#include <algorithm>
#include <cstdio>

#include "imap/engine/error.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/energy.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/matchers.hpp"
#include "imap/vision/perturb.hpp"
#include "imap/vision/synth.hpp"

namespace imap::engine::eval {

namespace g = imap::golden;
namespace v = imap::vision;
using nlohmann::json;

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

g::Params scene_params(const g::Params& p, bool explicit_D, const v::Scene& sc) {
    g::Params q = p;
    if (!explicit_D) q.D = sc.ndisp;
    q.frame = g::Frame::Left;
    return q;
}

Score score_one(const std::string& matcher, const v::Scene& sc, const g::Params& q, double delta,
                const std::string& context, const std::string& suffix) {
    double secs = 0;
    cv::Mat disp;
    try {
        disp = v::run_matcher(matcher, sc, q, &secs);
    } catch (const g::ParamError& e) {
        throw Error(context + "scene '" + sc.name + "'" + suffix + ": " + e.what());
    }
    return {v::score_bad(disp, 1.0, sc, delta), secs * 1e3};
}

Scores score_all(const std::string& matcher, const std::vector<v::Scene>& scenes,
                 const g::Params& p, bool explicit_D, double delta, const std::string& context,
                 const std::string& suffix) {
    Scores s;
    const double n = static_cast<double>(scenes.size());
    for (const v::Scene& sc : scenes) {
        const Score one =
            score_one(matcher, sc, scene_params(p, explicit_D, sc), delta, context, suffix);
        s.per_scene.push_back(one.bad);
        s.mean.nonocc += one.bad.nonocc / n;
        s.mean.all += one.bad.all / n;
        s.mean.disc += one.bad.disc / n;
        s.ms += one.ms / n;
    }
    return s;
}

Modeled modeled_headline(const g::Params& p) {
    static const v::SynthScene sc = v::make_synth_scene(1, 160, 128);
    const g::Roi roi{16, 0, 128, 128};
    const isa::MachineConfig cfg;
    g::Params q = p;
    q.D = 64;
    q.frame = g::Frame::Cyclopean;
    Modeled m;
    m.clock_mhz = cfg.clock_mhz;
    m.est = g::estimate_options(q, roi.w, /*in_firmware=*/true);
    try {
        const g::Params pp = firmware::firmware_part(q);
        const firmware::FramePlan plan = firmware::plan_frame(pp, roi, cfg);
        const isa::Program prog = firmware::assemble_frame(pp, plan);
        const firmware::FrameResult r =
            firmware::run_frame_core(plan, prog, v::view_of(sc.left), v::view_of(sc.right), cfg);
        m.fw_cycles = static_cast<int64_t>(r.cycles);
        m.fw_uj = isa::energy_of(r.stats, r.cycles, cfg).total_pj * 1e-6;
    } catch (const std::exception&) {
        m.fw_cycles = -1;  // refused (does not fit): shown as "-"
    }
    return m;
}

std::vector<TradeoffRow> tradeoff(const std::vector<v::Scene>& scenes, int explicit_D,
                                  double delta) {
    std::vector<TradeoffRow> rows;
    for (const auto& var : g::tradeoff_variants()) {
        TradeoffRow r;
        r.name = var.name;
        r.what = var.what;
        r.golden = true;
        r.p = var.p;
        rows.push_back(r);
    }
    for (const char* name : {"opencv-bm", "opencv-sgbm"}) {
        TradeoffRow r;
        r.name = name;
        r.what = "OpenCV reference matcher (docs/scoring.md)";
        rows.push_back(r);
    }
    for (TradeoffRow& r : rows) {
        g::Params q = r.golden ? r.p : g::Params{};
        if (explicit_D > 0) q.D = explicit_D;
        r.scores = score_all(r.golden ? "golden" : r.name, scenes, q, explicit_D > 0, delta, "",
                             ", variant " + r.name);
        if (r.golden) r.model = modeled_headline(r.p);
    }
    return rows;
}

plot::Figure tradeoff_plot(const std::vector<TradeoffRow>& rows, double delta, size_t nscenes) {
    char delta_txt[32];
    std::snprintf(delta_txt, sizeof delta_txt, "bad>%g", delta);
    plot::Figure f;
    f.title = "Mean " + std::string(delta_txt) + " (nonocc) against modeled time, headline case";
    f.subtitle =
        "ms = firmware (paper + ad-max + joint, measured) + other A.9 options (estimate); " +
        std::to_string(nscenes) + " scene(s)";
    f.xlabel = "modeled ms per frame (128x128, D=64, 256 PEs, 40 MHz; partly estimated)";
    f.ylabel = "mean " + std::string(delta_txt) + " % (nonocc)";
    std::vector<std::pair<double, double>> pts;
    for (const TradeoffRow& r : rows) {
        if (!r.golden || !r.model.ok()) continue;
        f.series.push_back({r.name, {r.model.total_ms()}, {r.scores.mean.nonocc}});
        pts.push_back({r.model.total_ms(), r.scores.mean.nonocc});
    }
    // Pareto front: no other point is both faster and better.
    std::sort(pts.begin(), pts.end());
    plot::Series front{"Pareto front", {}, {}};
    double best = 1e300;
    for (const auto& [x, y] : pts)
        if (y < best) {
            best = y;
            front.x.push_back(x);
            front.y.push_back(y);
        }
    if (front.x.size() > 1) f.series.insert(f.series.begin(), front);
    for (const TradeoffRow& r : rows)
        if (!r.golden) {
            char lab[64];
            std::snprintf(lab, sizeof lab, "%s %.2f%% (not on the machine)", r.name.c_str(),
                          r.scores.mean.nonocc);
            f.hlines.push_back({r.scores.mean.nonocc, lab});
        }
    f.note = "video rate: 40 ms";
    f.width = 1000;
    f.height = 650;
    return f;
}

json tradeoff_json(const std::vector<TradeoffRow>& rows, const std::vector<v::Scene>& scenes,
                   double delta, const std::string& perturb) {
    json arr = json::array();
    for (const TradeoffRow& r : rows) {
        const v::BadScores& m = r.scores.mean;
        json j = {{"variant", r.name}, {"what", r.what}, {"nonocc", m.nonocc},
                  {"all", m.all},      {"disc", m.disc}, {"cpu_ms", r.scores.ms},
                  {"delta", delta}};
        json per = json::object();
        for (size_t i = 0; i < scenes.size(); ++i)
            per[scenes[i].name] = {{"nonocc", r.scores.per_scene[i].nonocc},
                                   {"all", r.scores.per_scene[i].all},
                                   {"disc", r.scores.per_scene[i].disc}};
        j["scenes"] = per;
        if (r.golden) {
            json prm = algo_params_json(r.p);
            prm.erase("D");
            j["params"] = prm;
            j["fw_cycles_measured"] = r.model.fw_cycles;
            j["a9_cycles_estimate"] = r.model.est.cycles;
            j["a9_local_bytes_estimate"] = r.model.est.local_bytes;
            j["modeled_ms"] = r.model.ok() ? json(r.model.total_ms()) : json(nullptr);
            j["fw_energy_uj"] = r.model.ok() ? json(r.model.fw_uj) : json(nullptr);
        }
        if (!perturb.empty()) j["perturb"] = perturb;
        arr.push_back(j);
    }
    return arr;
}

json param_set_json(int line, const std::string& text, const g::Params& p, bool explicit_D,
                    const Scores& s, const std::vector<v::Scene>& scenes, double delta) {
    json per = json::object();
    for (size_t i = 0; i < scenes.size(); ++i) {
        const v::BadScores& b = s.per_scene[i];
        per[scenes[i].name] = {{"nonocc", b.nonocc}, {"all", b.all}, {"disc", b.disc}};
    }
    json prm = algo_params_json(p);
    if (!explicit_D) prm.erase("D");
    return {{"line", line},      {"flags", text},       {"params", prm},  {"nonocc", s.mean.nonocc},
            {"all", s.mean.all}, {"disc", s.mean.disc}, {"delta", delta}, {"scenes", per}};
}

const std::vector<std::pair<std::string, std::string>>& robustness_conditions() {
    static const std::vector<std::pair<std::string, std::string>> c = {
        {"as recorded", ""},
        {"right x0.8 + 10", "gain=0.8,offset=10"},
        {"right x1.2 - 20", "gain=1.2,offset=-20"},
        {"noise 3", "noise=3"},
        {"noise 6", "noise=6"},
        {"right x0.9 + 5, noise 2", "gain=0.9,offset=5,noise=2"},
    };
    return c;
}

Condition score_condition(const std::string& name, const std::string& spec,
                          const std::vector<v::Scene>& scenes,
                          const std::vector<std::string>& matchers,
                          const std::vector<std::string>& labels, const g::Params& p,
                          bool explicit_D, double delta) {
    const v::Perturbation pert = spec.empty() ? v::Perturbation{} : v::parse_perturbation(spec);
    std::vector<v::Scene> perturbed;
    for (const v::Scene& orig : scenes) {
        v::Scene sc = orig;
        sc.left = orig.left.clone();
        sc.right = orig.right.clone();
        v::perturb_pair(sc.left, sc.right, pert);
        perturbed.push_back(sc);
    }
    Condition c;
    json per = json::object();
    json means = json::object();
    for (size_t i = 0; i < matchers.size(); ++i) {
        const Scores s = score_all(matchers[i], perturbed, p, explicit_D, delta);
        c.mean.push_back(s.mean.nonocc);
        means[labels[i]] = s.mean.nonocc;
        for (size_t k = 0; k < perturbed.size(); ++k)
            per[labels[i]][perturbed[k].name] = s.per_scene[k].nonocc;
    }
    c.json = {{"condition", name},
              {"perturb", spec.empty() ? json(nullptr) : json(v::to_string(pert))},
              {"nonocc", means},
              {"scenes", per},
              {"delta", delta}};
    return c;
}

}  // namespace imap::engine::eval
