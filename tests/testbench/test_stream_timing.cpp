// Streaming at a camera rate the model keeps up with: every frame is
// bit-exact, costs the cycles of a stand-alone run, and its timestamps obey
// the camera timing (frame k at k / fps, line y at +(y + 1) line periods).
#define BOOST_TEST_MODULE testbench.stream_timing
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "tb_test_util.hpp"

using namespace tbtest;

BOOST_AUTO_TEST_CASE(frames_at_camera_timing) {
    const int W = 64, H = 32, N = 6;
    const double fps = 50, line_us = 100;  // a frame arrives in 3.2 ms of its 20 ms
    tb::StreamSetup setup = make_setup(W, H, 16, 32, fps, line_us);
    const auto frames = sequence(7, W, H, N);
    std::vector<cv::Mat> maps;
    setup.on_frame = [&](const tb::FrameOutput& f) { maps.push_back(f.disparity.clone()); };
    ListSource src(frames);
    const tb::StreamResult r = tb::run_stream(src, setup);
    BOOST_REQUIRE(!r.error);
    BOOST_TEST(!r.interrupted);
    BOOST_REQUIRE_EQUAL(r.frames.size(), static_cast<size_t>(N));
    BOOST_REQUIRE_EQUAL(maps.size(), static_cast<size_t>(N));
    const double frame_ms = 1000.0 / fps, tol = 1e-6;
    for (int k = 0; k < N; ++k) {
        const tb::FrameRecord& f = r.frames[static_cast<size_t>(k)];
        BOOST_TEST_CONTEXT("frame " << k) {
            BOOST_TEST(f.status == "ok");
            BOOST_TEST(f.differing == 0u);
            // The same frame on the bare core: same map, same cycles.
            const fw::FrameResult ref = core_run(setup, frames[static_cast<size_t>(k)]);
            BOOST_TEST(f.cycles == ref.cycles);
            BOOST_REQUIRE_EQUAL(maps[static_cast<size_t>(k)].total(), ref.map.data.size());
            BOOST_TEST(std::equal(ref.map.data.begin(), ref.map.data.end(),
                                  maps[static_cast<size_t>(k)].data));
            BOOST_TEST(f.compute_ms == ref.cycles / 40e3, boost::test_tools::tolerance(1e-9));
            // Camera timing and time accounting.
            BOOST_TEST(std::abs(f.capture_ms - k * frame_ms) < tol);
            BOOST_TEST(std::abs(f.start_ms - f.capture_ms) < tol);  // the CP was idle
            BOOST_TEST(std::abs((f.done_ms - f.start_ms) - (f.compute_ms + f.stall_ms)) < tol);
            BOOST_TEST(std::abs(f.latency_ms - (f.done_ms - f.capture_ms)) < tol);
            // The map is complete only after the last line has arrived.
            BOOST_TEST(f.done_ms >= f.capture_ms + H * line_us / 1000.0 - tol);
            // Lines come slower than the firmware reads them: the CP stalls.
            BOOST_TEST(f.stall_ms > 0.0);
            BOOST_TEST(f.stall_ms < H * line_us / 1000.0 + tol);
            BOOST_TEST(f.deadline_met);
            BOOST_TEST(f.bad1 >= 0.0);
            BOOST_TEST(f.bad1 < 25.0);
        }
    }
    BOOST_TEST(std::abs(r.modeled_end_ms - r.frames.back().done_ms) < tol);
}
