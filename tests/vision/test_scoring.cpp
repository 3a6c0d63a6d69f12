// The scorer reproduces the published bad>1 percentages of the shared
// Middlebury scenes (scenes.json "reference_result_bad1").
#define BOOST_TEST_MODULE vision_scoring
#include <boost/test/unit_test.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "imap/vision/image_io.hpp"
#include "imap/vision/scene.hpp"
#include "imap/vision/score.hpp"
#include "imap/vision/synth.hpp"
#include "test_helpers.hpp"

namespace v = imap::vision;
using vision_test::TempDir;

namespace {
const std::string kData = std::string(IMAP_SHARED_DATA) + "/middlebury";

nlohmann::json catalog() {
    std::ifstream in(kData + "/scenes.json");
    BOOST_REQUIRE(in);
    nlohmann::json j;
    in >> j;
    return j;
}
}  // namespace

BOOST_AUTO_TEST_CASE(reference_results_reproduce_scenes_json) {
    const nlohmann::json j = catalog();
    const auto& ref = j.at("reference_result_bad1");
    int scenes = 0;
    for (const auto& [name, entry] : j.at("scenes").items()) {
        BOOST_TEST_CONTEXT("scene " << name) {
            const v::Scene sc = v::load_scene(kData + "/" + name);
            BOOST_TEST(sc.gt_scale == entry.at("gt_scale").get<double>());
            BOOST_TEST(sc.ndisp == entry.at("ndisp").get<int>());
            BOOST_TEST(sc.left.cols == entry.at("width").get<int>());
            BOOST_TEST(sc.left.rows == entry.at("height").get<int>());
            const cv::Mat res = v::load_grey8(kData + "/" + name + "/ref_result.png", "result");
            const v::BadScores b = v::score_bad(res, sc.gt_scale, sc);
            const auto& want = ref.at(name);
            BOOST_TEST_MESSAGE(name << ": nonocc " << b.nonocc << " all " << b.all << " disc "
                                    << b.disc);
            BOOST_TEST(std::abs(b.nonocc - want.at("nonocc").get<double>()) <= 0.005);
            BOOST_TEST(std::abs(b.all - want.at("all").get<double>()) <= 0.005);
            BOOST_TEST(std::abs(b.disc - want.at("disc").get<double>()) <= 0.005);
            ++scenes;
        }
    }
    BOOST_TEST(scenes == 4);
}

BOOST_AUTO_TEST_CASE(ground_truth_itself_scores_zero_and_delta_applies) {
    const v::Scene sc = v::load_scene(kData + "/teddy");
    cv::Mat exact;
    sc.gt.convertTo(exact, CV_32F, 1.0 / sc.gt_scale);
    v::BadScores b = v::score_bad(exact, 1.0, sc);
    BOOST_TEST(b.nonocc == 0.0);
    BOOST_TEST(b.all == 0.0);
    BOOST_TEST(b.disc == 0.0);
    b = v::score_bad(sc.gt, sc.gt_scale, sc);  // same map in the gt's own scale
    BOOST_TEST(b.all == 0.0);

    const cv::Mat off = exact + 1.5;  // 1.5 px off everywhere
    b = v::score_bad(off, 1.0, sc, 1.0);
    BOOST_TEST(b.nonocc == 100.0);
    BOOST_TEST(b.all == 100.0);
    BOOST_TEST(b.disc == 100.0);
    b = v::score_bad(off, 1.0, sc, 2.0);
    BOOST_TEST(b.all == 0.0);
    const cv::Mat one_off = exact + 1.0;  // exactly delta: not bad
    BOOST_TEST(v::score_bad(one_off, 1.0, sc, 1.0).all == 0.0);
}

BOOST_AUTO_TEST_CASE(only_mask_value_255_is_evaluated) {
    // disc.png holds other grey values (e.g. 128) that must not be evaluated:
    // a map that is wrong exactly there still scores 0 on disc.
    const v::Scene sc = v::load_scene(kData + "/tsukuba");
    BOOST_TEST_REQUIRE(cv::countNonZero((sc.disc != 0) & (sc.disc != 255)) > 0);
    cv::Mat d;
    sc.gt.convertTo(d, CV_32F, 1.0 / sc.gt_scale);
    d.setTo(200.0f, sc.disc != 255);
    BOOST_TEST(v::score_bad(d, 1.0, sc).disc == 0.0);
    BOOST_TEST(v::score_bad(d, 1.0, sc).all > 50.0);
}

BOOST_AUTO_TEST_CASE(scene_folders_are_read_with_their_catalog) {
    const auto dirs = v::list_scene_dirs(kData);
    BOOST_TEST_REQUIRE(dirs.size() == 4u);
    BOOST_TEST(dirs[0] == kData + "/cones");
    BOOST_TEST(dirs[3] == kData + "/venus");

    const v::Scene sc = v::load_scene(kData + "/venus/");  // trailing slash
    BOOST_TEST(sc.name == "venus");
    BOOST_TEST(sc.gt_scale == 8.0);
    BOOST_TEST(sc.ndisp == 20);
    BOOST_TEST(!sc.default_masks);
    BOOST_TEST(sc.left.type() == CV_8UC1);  // colour converted

    const v::Scene o = v::load_scene(kData + "/venus", 4.0, 33);
    BOOST_TEST(o.gt_scale == 4.0);
    BOOST_TEST(o.ndisp == 33);
}

namespace {
template <class F>
std::string input_error(F&& f) {
    try {
        f();
    } catch (const v::InputError& e) {
        return e.what();
    }
    BOOST_FAIL("no InputError thrown");
    return {};
}
bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}
}  // namespace

BOOST_AUTO_TEST_CASE(scene_errors_name_the_problem) {
    TempDir t("scene");
    BOOST_TEST(contains(input_error([&] { v::load_scene(t.file("nope")); }), "not found"));

    // A synth folder: no catalog, no masks.
    const v::SynthScene s = v::make_synth_scene(1, 64, 32);
    const std::string dir = t.file("syn");
    std::filesystem::create_directory(dir);
    v::write_image_atomic(dir + "/left.png", s.left);
    v::write_image_atomic(dir + "/right.png", s.right);
    v::write_image_atomic(dir + "/gt.png", s.gt);
    const std::string m = input_error([&] { v::load_scene(dir); });
    BOOST_TEST(contains(m, dir));
    BOOST_TEST(contains(m, "scale"));
    BOOST_TEST(contains(input_error([&] { v::load_scene(dir, 1.0); }), "disparities"));

    const v::Scene sc = v::load_scene(dir, 1.0, s.max_disp + 1);
    BOOST_TEST(sc.default_masks);
    BOOST_TEST(cv::countNonZero(sc.all != 255) == 0);
    BOOST_TEST(v::score_bad(sc.gt, 1.0, sc).all == 0.0);

    // Catalog in the parent folder, keyed by the folder name.
    vision_test::write_file(t.file("scenes.json"),
                            R"({"scenes": {"syn": {"gt_scale": 1, "ndisp": 17}}})");
    const v::Scene c = v::load_scene(dir);
    BOOST_TEST(c.ndisp == 17);
    BOOST_TEST(v::list_scene_dirs(t.path().string()).size() == 1u);

    // One mask present, others missing: named.
    v::write_image_atomic(dir + "/nonocc.png", s.gt);
    BOOST_TEST(contains(input_error([&] { v::load_scene(dir); }), "all.png"));
    std::filesystem::remove(dir + "/nonocc.png");

    // Sizes that differ.
    v::write_image_atomic(dir + "/right.png", s.right(cv::Rect(0, 0, 60, 32)));
    const std::string sz = input_error([&] { v::load_scene(dir); });
    BOOST_TEST(contains(sz, "right.png is 60x32 but left.png is 64x32"));
    std::filesystem::remove(dir + "/right.png");
    BOOST_TEST(contains(input_error([&] { v::load_scene(dir); }), "right.png"));

    // Malformed catalog.
    vision_test::write_file(t.file("scenes.json"), "{ not json");
    BOOST_TEST(contains(input_error([&] { v::load_scene(dir); }), "scenes.json"));

    // Scoring a map of the wrong size.
    BOOST_TEST(
        contains(input_error([&] { v::score_bad(s.gt(cv::Rect(0, 0, 8, 8)), 1.0, sc); }), "8x8"));
}
