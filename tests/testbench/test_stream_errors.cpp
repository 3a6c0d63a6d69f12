// Bad frames in the middle of a stream (unreadable, wrong size) are recorded
// with their reason and the stream goes on.
#define BOOST_TEST_MODULE testbench.stream_errors
#include <boost/test/unit_test.hpp>

#include <opencv2/imgproc.hpp>

#include "tb_test_util.hpp"

using namespace tbtest;

BOOST_AUTO_TEST_CASE(bad_frames_and_a_faulting_frame) {
    const int W = 48, H = 16;
    tb::StreamSetup setup = make_setup(W, H, 12, 16, 100, 50);
    auto frames = sequence(5, W, H, 5);
    frames[1].left.release();
    frames[1].right.release();
    frames[1].error = "left frame 'x.png': cannot read";
    cv::resize(frames[3].left, frames[3].left, cv::Size(W + 2, H));
    cv::resize(frames[3].right, frames[3].right, cv::Size(W + 2, H));
    auto src_inner = std::make_unique<ListSource>(frames);
    auto checked = tb::size_checked(std::move(src_inner), cv::Size(W, H));
    int callbacks = 0;
    setup.on_frame = [&](const tb::FrameOutput& f) {
        ++callbacks;
        BOOST_TEST(f.disparity.empty() == (f.record.status != "ok"));
    };
    const tb::StreamResult r = tb::run_stream(*checked, setup);
    BOOST_REQUIRE(!r.error);
    BOOST_REQUIRE_EQUAL(r.frames.size(), 5u);
    BOOST_TEST(callbacks == 5);
    BOOST_TEST(r.frames[0].status == "ok");
    BOOST_TEST(r.frames[1].status == "bad-frame");
    BOOST_TEST(r.frames[1].error.find("cannot read") != std::string::npos);
    BOOST_TEST(r.frames[3].status == "bad-frame");
    BOOST_TEST(r.frames[3].error.find("50x16") != std::string::npos);
    BOOST_TEST(r.frames[3].error.find("48x16") != std::string::npos);
    for (int k : {2, 4}) BOOST_TEST(r.frames[static_cast<size_t>(k)].status == "ok");
    // A bad frame still took its camera slot: frame 2 starts at 2 / fps.
    BOOST_TEST(r.frames[2].capture_ms == 20.0, boost::test_tools::tolerance(1e-9));
}
