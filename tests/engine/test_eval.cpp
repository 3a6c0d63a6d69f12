// engine.eval: scoring through the library (eval.hpp) on tiny synthetic
// scenes: the means over scenes against the scores of each scene taken
// directly from the vision library, the error naming the scene, a
// robustness condition, the Pareto front of the trade-off plot on
// hand-made rows, and the headline's modeled cycles against a model run.
#define BOOST_TEST_MODULE engine_eval
#include <boost/test/unit_test.hpp>

#include "imap/engine/error.hpp"
#include "imap/engine/eval.hpp"
#include "imap/engine/models.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/matchers.hpp"
#include "imap/vision/synth.hpp"

namespace e = imap::engine;
namespace ev = imap::engine::eval;
namespace g = imap::golden;
namespace v = imap::vision;

namespace {

v::Scene tiny_scene(uint64_t seed, const std::string& name) {
    const v::SynthScene s = v::make_synth_scene(seed, 48, 16);
    v::Scene sc;
    sc.name = name;
    sc.left = s.left;
    sc.right = s.right;
    sc.gt = s.gt;
    sc.gt_scale = 1;
    sc.ndisp = s.max_disp + 1;
    sc.default_masks = true;
    sc.nonocc = cv::Mat(s.left.size(), CV_8UC1, cv::Scalar(255));
    sc.all = sc.nonocc.clone();
    sc.disc = sc.nonocc.clone();
    return sc;
}

// The scores of `matcher` on `sc`, straight from the vision library.
v::BadScores direct(const std::string& matcher, const v::Scene& sc, int D, double delta) {
    g::Params q;
    q.D = D;
    q.frame = g::Frame::Left;
    double secs = 0;
    return v::score_bad(v::run_matcher(matcher, sc, q, &secs), 1.0, sc, delta);
}

}  // namespace

BOOST_AUTO_TEST_CASE(means_over_scenes) {
    const std::vector<v::Scene> scenes = {tiny_scene(1, "a"), tiny_scene(2, "b")};
    const ev::Scores s = ev::score_all("golden", scenes, g::Params{}, false, 1.0);
    BOOST_REQUIRE(s.per_scene.size() == 2u);
    const v::BadScores a = direct("golden", scenes[0], scenes[0].ndisp, 1.0);
    const v::BadScores b = direct("golden", scenes[1], scenes[1].ndisp, 1.0);
    BOOST_TEST(s.per_scene[0].nonocc == a.nonocc);
    BOOST_TEST(s.per_scene[1].disc == b.disc);
    BOOST_TEST(s.mean.nonocc == (a.nonocc + b.nonocc) / 2, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s.mean.all == (a.all + b.all) / 2, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s.mean.disc == (a.disc + b.disc) / 2, boost::test_tools::tolerance(1e-12));
    // An explicit D is every scene's.
    g::Params p;
    p.D = 4;
    const ev::Scores d4 = ev::score_all("golden", scenes, p, true, 2.0);
    BOOST_TEST(d4.per_scene[1].nonocc == direct("golden", scenes[1], 4, 2.0).nonocc);
    BOOST_TEST(ev::scene_params(p, false, scenes[0]).D == scenes[0].ndisp);
    BOOST_TEST(ev::scene_params(p, true, scenes[0]).D == 4);
}

BOOST_AUTO_TEST_CASE(an_error_names_the_scene) {
    const std::vector<v::Scene> scenes = {tiny_scene(1, "tiny")};
    g::Params p;
    p.D = 200;  // wider than the scene
    try {
        ev::score_all("golden", scenes, p, true, 1.0, "line 3, ", ", variant x");
        BOOST_FAIL("expected an engine::Error");
    } catch (const e::Error& err) {
        BOOST_TEST(std::string(err.what()).rfind("line 3, scene 'tiny', variant x: ", 0) == 0);
    }
}

BOOST_AUTO_TEST_CASE(a_robustness_condition) {
    const std::vector<v::Scene> scenes = {tiny_scene(1, "a")};
    const ev::Condition c = ev::score_condition("as recorded", "", scenes, {"golden"}, {"golden"},
                                                g::Params{}, false, 1.0);
    BOOST_REQUIRE(c.mean.size() == 1u);
    BOOST_TEST(c.mean[0] == direct("golden", scenes[0], scenes[0].ndisp, 1.0).nonocc);
    BOOST_TEST(c.json.at("perturb").is_null());
    BOOST_TEST(c.json.at("nonocc").at("golden").get<double>() == c.mean[0]);
    BOOST_TEST(ev::robustness_conditions().size() == 6u);
}

BOOST_AUTO_TEST_CASE(pareto_front_of_hand_made_rows) {
    // (ms, nonocc): A (1, 9), B (2, 5), C (3, 7) dominated by B, D (4, 1).
    std::vector<ev::TradeoffRow> rows;
    const double pts[4][2] = {{1, 9}, {2, 5}, {3, 7}, {4, 1}};
    for (int i = 0; i < 4; ++i) {
        ev::TradeoffRow r;
        r.name = std::string(1, static_cast<char>('A' + i));
        r.golden = true;
        r.model.clock_mhz = 1;  // fw_ms = cycles / 1000
        r.model.fw_cycles = static_cast<int64_t>(pts[i][0] * 1000);
        r.scores.mean.nonocc = pts[i][1];
        rows.push_back(r);
    }
    ev::TradeoffRow cv;
    cv.name = "opencv-bm";
    cv.scores.mean.nonocc = 3;
    rows.push_back(cv);
    const e::plot::Figure f = ev::tradeoff_plot(rows, 1.0, 2);
    BOOST_REQUIRE(f.series.size() == 5u);  // the front, then A..D
    BOOST_TEST(f.series[0].label == "Pareto front");
    BOOST_TEST(f.series[0].x == std::vector<double>({1, 2, 4}), boost::test_tools::per_element());
    BOOST_TEST(f.series[0].y == std::vector<double>({9, 5, 1}), boost::test_tools::per_element());
    BOOST_REQUIRE(f.hlines.size() == 1u);
    BOOST_TEST(f.hlines[0].y == 3.0);
}

BOOST_AUTO_TEST_CASE(headline_cycles_are_a_model_runs) {
    const ev::Modeled m = ev::modeled_headline(g::Params{});
    BOOST_REQUIRE(m.ok());
    const v::SynthScene sc = v::make_synth_scene(1, 160, 128);
    g::Params p;
    p.D = 64;
    const e::ModelRun run = e::run_model("core", p, {16, 0, 128, 128}, v::view_of(sc.left),
                                         v::view_of(sc.right), imap::isa::MachineConfig{});
    BOOST_TEST(static_cast<uint64_t>(m.fw_cycles) == run.result.cycles);
    BOOST_TEST(m.fw_uj == run.energy.frame.total_pj * 1e-6);
    BOOST_TEST(m.est.cycles == 0);  // the paper's algorithm: nothing estimated
}
