// The requests of imapsim's commands built from their flags, without a run:
// eval's checks (combinations refused with imapsim's messages, the default
// matchers, the --param-sets file and the mean rows), sweep's spec (axes in
// command-line order, fixed and swept, a name given twice, --x, --plot-size)
// and run's input (the synthetic scene's headline ROI, refused combinations).
#define BOOST_TEST_MODULE engine_requests
#include <boost/test/unit_test.hpp>
#include <fstream>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/eval_request.hpp"
#include "imap/engine/run_request.hpp"
#include "imap/engine/sweep_request.hpp"

namespace eng = imap::engine;
namespace ev = imap::engine::eval;
namespace sw = imap::engine::sweep;
namespace rn = imap::engine::run;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

// The message of the engine::Error `f` throws ("" when it throws none).
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const eng::Error& e) {
        BOOST_TEST(e.code() == eng::kExitInput);
        return e.what();
    }
    return "";
}

ev::Request eval_scene() {
    ev::Request r;
    r.scene = "some/scene";
    r.algo.frame = "left";
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(eval_refuses_bad_combinations) {
    ev::Request r;
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "give exactly one of --scene DIR or --all DATA_DIR");
    r = eval_scene();
    r.delta = -1;
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "invalid value for --delta: expected a number >= 0");
    r = eval_scene();
    r.gt_scale_given = true;
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "invalid value for --gt-scale: expected a number > 0");
    r = eval_scene();
    r.robustness = r.perturb_given = true;
    r.perturb = "gain=2";
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "--robustness runs its own list of perturbations: drop --perturb");
    r = eval_scene();
    r.tradeoff = true;
    r.param_sets = "sets.txt";
    BOOST_TEST(error_of([&] { ev::validate(r); }) == "give --tradeoff or --param-sets, not both");
    r = eval_scene();
    r.plot = "p.png";
    BOOST_TEST(error_of([&] { ev::validate(r); }) == "--plot needs --tradeoff");
    r = eval_scene();
    r.tradeoff = true;
    r.algo.km = "3";
    r.algo.given = {"--km"};
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "--tradeoff uses its own parameter sets: drop --km (only --D is accepted)");
    r = eval_scene();
    r.algo.frame = "cyc";
    r.algo.given = {"--frame"};
    BOOST_TEST(error_of([&] { ev::validate(r); }) ==
               "--frame cyc is not supported by eval: scoring uses the left frame");
}

BOOST_AUTO_TEST_CASE(eval_default_matchers) {
    ev::Request r = eval_scene();
    r.algo.D = "16";
    const ev::Checked c = ev::validate(r);
    BOOST_TEST(c.matchers == std::vector<std::string>{"golden"});
    BOOST_TEST(c.explicit_D);
    BOOST_TEST(c.p.D == 16);
    r.scene.clear();
    r.all = "some/data";
    BOOST_TEST(ev::validate(r).matchers.size() == 3u);  // golden, opencv-bm, opencv-sgbm
    r.algo.preset = "quality";
    BOOST_TEST(ev::label(r, "golden") == "golden:quality");
    BOOST_TEST(ev::label(r, "opencv-bm") == "opencv-bm");
}

BOOST_AUTO_TEST_CASE(eval_param_sets_file) {
    const auto path = (tmpdir() / "sets.txt").string();
    std::ofstream(path) << "# comment\n\n  --D 16 --km 3\n--kb 2\n";
    std::vector<std::pair<std::vector<std::string>, std::string>> seen;
    const auto sets =
        ev::read_param_sets(path, [&](const std::vector<std::string>& a, const std::string& where) {
            seen.emplace_back(a, where);
            return ev::ParamSet{};
        });
    BOOST_REQUIRE(sets.size() == 2u);
    BOOST_TEST(sets[0].line == 3);
    BOOST_TEST(sets[0].text == "--D 16 --km 3");
    BOOST_TEST(sets[1].line == 4);
    BOOST_TEST((seen[0].first == std::vector<std::string>{"--D", "16", "--km", "3"}));
    BOOST_TEST(seen[1].second == "--param-sets " + path + ":4: ");
    std::ofstream(path) << "# nothing\n";
    BOOST_TEST(error_of([&] { ev::read_param_sets(path, nullptr); }) ==
               "--param-sets '" + path + "': no parameter sets in it");
}

BOOST_AUTO_TEST_CASE(eval_mean_rows) {
    ev::Request r = eval_scene();
    std::vector<ev::Row> rows(4);
    const char* m[] = {"golden", "opencv-bm", "golden", "opencv-bm"};
    for (size_t i = 0; i < 4; ++i) {
        rows[i].matcher = m[i];
        rows[i].bad.nonocc = static_cast<double>(i);
        rows[i].ms = 10.0 * static_cast<double>(i);
    }
    const auto means = ev::mean_rows(r, rows, {"golden", "opencv-bm"}, 2);
    BOOST_REQUIRE(means.size() == 2u);
    BOOST_TEST(means[0].scene == "mean");
    BOOST_TEST(means[0].bad.nonocc == 1.0);  // (0 + 2) / 2
    BOOST_TEST(means[1].bad.nonocc == 2.0);  // (1 + 3) / 2
    BOOST_TEST(means[1].ms == 20.0);
    const auto j = ev::table_json(r, {rows[1]});
    BOOST_TEST(j[0]["matcher"] == "opencv-bm");
    BOOST_TEST(!j[0].contains("perturb"));
}

BOOST_AUTO_TEST_CASE(sweep_spec_axes_in_order) {
    sw::Request r;
    r.axes = {{"--D", "16,32"}, {"--pes", "8"}, {"--set", "ring_hop=1,2"}};
    const sw::Spec s = sw::build_spec(r);
    BOOST_REQUIRE(s.swept.size() == 2u);
    BOOST_TEST(s.swept[0].name == "D");
    BOOST_TEST(s.swept[1].name == "ring_hop");
    BOOST_TEST(s.swept[1].flag == "--set ring_hop");
    BOOST_REQUIRE(s.fixed.size() == 1u);
    BOOST_TEST(s.fixed[0].name == "pes");
    BOOST_TEST(s.points.size() == 4u);
}

BOOST_AUTO_TEST_CASE(sweep_spec_refusals) {
    sw::Request r;
    r.axes = {{"--pes", "8,16"}, {"--set", "pes=4"}};
    BOOST_TEST(error_of([&] { sw::build_spec(r); }) ==
               "pes is given twice (--set pes and another flag)");
    r.axes = {{"--set", "ring_hop"}};
    BOOST_TEST(error_of([&] { sw::build_spec(r); }) ==
               "invalid value 'ring_hop' for --set: expected NAME=VALUE or NAME=LIST");
    r.axes = {{"--pes", "8"}};
    r.plot = true;
    BOOST_TEST(error_of([&] { sw::build_spec(r); }) ==
               "--plot needs a swept axis (a flag with two or more values, e.g. --pes "
               "64,128,256)");
    r.plot = false;
    r.algo.roi = "0,0,8,8";
    BOOST_TEST(error_of([&] { sw::build_spec(r); }) ==
               "--roi needs --left/--right; the synthetic scene is generated at --roi-size WxH");
    r.algo.roi.clear();
    r.left = "l.png";
    BOOST_TEST(error_of([&] { sw::build_spec(r); }) == "--left and --right must be given together");
}

BOOST_AUTO_TEST_CASE(sweep_x_and_plot_size) {
    sw::Request r;
    r.axes = {{"--pes", "8,16"}, {"--km", "2,3"}};
    const sw::Spec s = sw::build_spec(r);
    BOOST_TEST(sw::x_index(s.swept, "") == 0u);
    BOOST_TEST(sw::x_index(s.swept, "--km") == 1u);
    BOOST_TEST(error_of([&] { sw::x_index(s.swept, "D"); }) ==
               "invalid value 'D' for --x: expected a swept axis (pes, km)");
    BOOST_TEST(error_of([&] { sw::check_plot_size("900x600"); }) == "");
    BOOST_TEST(error_of([&] { sw::check_plot_size("200x600"); }) ==
               "invalid value '200x600' for --plot-size: expected WxH with W in 300..4000, H in "
               "200..4000");
}

BOOST_AUTO_TEST_CASE(run_input_synthetic_and_refusals) {
    rn::Request r;
    imap::golden::Params p;
    imap::golden::Roi roi;
    const auto none = [](const std::string&) {};
    const rn::Input in = rn::load_input(r, &p, &roi, false, none);
    BOOST_TEST(in.source == "synthetic scene seed 1 160x128");
    BOOST_TEST(in.L.cols == 160);
    BOOST_TEST((roi.x0 == 16 && roi.y0 == 0 && roi.w == 128 && roi.h == 128));  // headline ROI
    BOOST_TEST(!in.gt.empty());
    r.size = "64x48";
    rn::load_input(r, &p, &roi, false, none);
    BOOST_TEST((roi.x0 == 0 && roi.w == 64 && roi.h == 48));  // whole image
    r.size = "1x1";
    BOOST_TEST(error_of([&] { rn::load_input(r, &p, &roi, false, none); }) ==
               "invalid value '1x1' for --size: expected WxH with W in 2..4096, H in 1..4096");
    r = rn::Request{};
    r.gt_scale = "2";
    BOOST_TEST(error_of([&] { rn::load_input(r, &p, &roi, false, none); }) ==
               "--gt-scale needs --scene or --gt");
    r = rn::Request{};
    r.scene = "s";
    r.left = "l.png";
    r.right = "r.png";
    BOOST_TEST(error_of([&] { rn::load_input(r, &p, &roi, false, none); }) ==
               "give either --scene DIR or --left/--right, not both");
    r = rn::Request{};
    r.gt = "gt.png";
    BOOST_TEST(error_of([&] { rn::load_input(r, &p, &roi, false, none); }) ==
               "--gt needs --left and --right (--scene has its own)");
}
