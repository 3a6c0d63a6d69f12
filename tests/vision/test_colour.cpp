// Colour-mapped disparity maps (issue 13 item 5): occlusion in one colour
// that the colour map never uses, the ends of the range at the ends of JET,
// the legend's bar and occlusion box.
#define BOOST_TEST_MODULE vision_colour
#include <boost/test/unit_test.hpp>
#include <opencv2/imgproc.hpp>

#include "imap/vision/colour.hpp"

namespace v = imap::vision;

namespace {
cv::Vec3b jet(int level) {
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(level)), c;
    cv::applyColorMap(one, c, cv::COLORMAP_JET);
    return c.at<cv::Vec3b>(0, 0);
}
}  // namespace

BOOST_AUTO_TEST_CASE(occlusion_is_white_and_never_a_disparity_colour) {
    BOOST_TEST((v::disparity_colour(255, 16) == cv::Vec3b(255, 255, 255)));
    for (const int D : {1, 2, 16, 64, 255})
        for (int d = 0; d < D; ++d) BOOST_TEST((v::disparity_colour(d, D) != v::kOccludedColour));
}

BOOST_AUTO_TEST_CASE(range_spans_the_colour_map) {
    BOOST_TEST((v::disparity_colour(0, 16) == jet(0)));
    BOOST_TEST((v::disparity_colour(15, 16) == jet(255)));
    BOOST_TEST((v::disparity_colour(8, 16) == jet(136)));  // round(255 * 8 / 15)
    BOOST_TEST((v::disparity_colour(0, 1) == jet(0)));
    BOOST_CHECK_THROW(v::disparity_colour(16, 16), std::invalid_argument);
    BOOST_CHECK_THROW(v::disparity_colour(-1, 16), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(map_pixels_follow_the_table) {
    cv::Mat m(3, 4, CV_8UC1);
    const uint8_t vals[12] = {0, 1, 2, 3, 255, 4, 5, 6, 7, 255, 0, 7};
    for (int i = 0; i < 12; ++i) m.at<uint8_t>(i / 4, i % 4) = vals[i];
    const cv::Mat c = v::colorize_disparity(m, 8);
    BOOST_TEST(c.type() == CV_8UC3);
    BOOST_TEST(c.size() == m.size());
    for (int i = 0; i < 12; ++i)
        BOOST_TEST((c.at<cv::Vec3b>(i / 4, i % 4) == v::disparity_colour(vals[i], 8)));
    BOOST_CHECK_THROW(v::colorize_disparity(cv::Mat(2, 2, CV_8UC3), 8), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(legend_has_bar_and_occlusion_box) {
    const cv::Mat l = v::disparity_legend(128, 16);
    BOOST_TEST(l.type() == CV_8UC3);
    BOOST_TEST(l.cols == 128);
    BOOST_TEST(l.rows == v::legend_height());
    BOOST_TEST((l.at<cv::Vec3b>(0, 0) == v::disparity_colour(0, 16)));  // bar starts at 0
    BOOST_TEST((l.at<cv::Vec3b>(0, 127) == v::kOccludedColour));        // box at the right
    // The bar ends at D-1 just before the box.
    int last_bar = 127;
    while (last_bar > 0 && l.at<cv::Vec3b>(0, last_bar) == v::kOccludedColour) --last_bar;
    --last_bar;  // the gap
    while (last_bar > 0 && l.at<cv::Vec3b>(0, last_bar) == cv::Vec3b(0, 0, 0)) --last_bar;
    BOOST_TEST((l.at<cv::Vec3b>(0, last_bar) == v::disparity_colour(15, 16)));
    // Narrow widths still work.
    BOOST_TEST(v::disparity_legend(16, 64).cols == 16);
}
