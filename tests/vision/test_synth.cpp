// The synthetic scene is deterministic and its ground truth is exact in the
// convention of SPEC A.1: left pixel x + d shows what right pixel x shows.
#define BOOST_TEST_MODULE vision_synth
#include <boost/test/unit_test.hpp>
#include <set>

#include "imap/vision/synth.hpp"
#include "test_helpers.hpp"

namespace v = imap::vision;

namespace {

bool same(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

// FNV-1a over the pixels, row by row.
uint64_t fnv1a(const cv::Mat& m) {
    uint64_t h = 1469598103934665603ull;
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) h = (h ^ m.at<uint8_t>(y, x)) * 1099511628211ull;
    return h;
}

}  // namespace

BOOST_AUTO_TEST_CASE(same_seed_same_bytes_different_seed_different_scene) {
    const v::SynthScene a = v::make_synth_scene(7, 160, 128);
    const v::SynthScene b = v::make_synth_scene(7, 160, 128);
    BOOST_TEST(same(a.left, b.left));
    BOOST_TEST(same(a.right, b.right));
    BOOST_TEST(same(a.gt, b.gt));
    BOOST_TEST(a.max_disp == b.max_disp);
    const v::SynthScene c = v::make_synth_scene(8, 160, 128);
    BOOST_TEST(!same(a.left, c.left));
    BOOST_TEST(!same(a.right, c.right));
    BOOST_TEST(!same(a.gt, c.gt));
}

BOOST_AUTO_TEST_CASE(scene_bytes_are_pinned) {
    // Own PRNG and integer arithmetic only: the same bytes on every platform
    // and library version. If the generator is changed on purpose, update
    // these (and re-check the golden threshold in test_matchers.cpp).
    const v::SynthScene s = v::make_synth_scene(1, 160, 128);
    BOOST_TEST_MESSAGE("left " << fnv1a(s.left) << " right " << fnv1a(s.right) << " gt "
                               << fnv1a(s.gt));
    BOOST_TEST(fnv1a(s.left) == 13019094020261917180ull);
    BOOST_TEST(fnv1a(s.right) == 9930052513164336260ull);
    BOOST_TEST(fnv1a(s.gt) == 1437031782669025424ull);
}

BOOST_AUTO_TEST_CASE(types_sizes_and_disparity_range) {
    for (auto [w, h] :
         {std::pair{2, 2}, {3, 1}, {7, 5}, {64, 2}, {160, 128}, {384, 288}, {1000, 40}}) {
        BOOST_TEST_CONTEXT(w << "x" << h) {
            const v::SynthScene s = v::make_synth_scene(3, w, h);
            BOOST_TEST(s.left.type() == CV_8UC1);
            BOOST_TEST(s.right.type() == CV_8UC1);
            BOOST_TEST(s.gt.type() == CV_8UC1);
            BOOST_TEST(s.left.cols == w);
            BOOST_TEST(s.left.rows == h);
            BOOST_TEST(s.right.size() == s.left.size());
            BOOST_TEST(s.gt.size() == s.left.size());
            double mx = 0;
            cv::minMaxLoc(s.gt, nullptr, &mx);
            BOOST_TEST(static_cast<int>(mx) == s.max_disp);
            BOOST_TEST(s.max_disp <= std::min(w / 4, v::kSynthMaxDisp));
        }
    }
    BOOST_CHECK_THROW(v::make_synth_scene(1, 0, 5), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(objects_at_several_disparities) {
    const v::SynthScene s = v::make_synth_scene(1, 160, 128);
    std::set<int> levels;
    for (int y = 0; y < s.gt.rows; ++y)
        for (int x = 0; x < s.gt.cols; ++x) levels.insert(s.gt.at<uint8_t>(y, x));
    BOOST_TEST(levels.count(0) == 1u);  // background
    BOOST_TEST(levels.size() >= 3u);    // background + at least two object levels
    BOOST_TEST(s.max_disp == 40);       // min(160 / 4, 48), always used by one object
}

BOOST_AUTO_TEST_CASE(ground_truth_matches_the_views) {
    for (uint64_t seed : {1ull, 2ull, 99ull}) {
        BOOST_TEST_CONTEXT("seed " << seed) {
            const v::SynthScene s = v::make_synth_scene(seed, 200, 150);
            vision_test::check_views_match_ground_truth(s.left, s.right, s.gt, s.max_disp,
                                                        v::kSynthNoise);
        }
    }
}
