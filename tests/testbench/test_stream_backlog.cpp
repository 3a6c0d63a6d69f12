// A camera faster than the model: frames wait in the input frame buffer, the
// CP starts each as soon as it is free, latency grows and deadlines are
// missed; a tight --line-us makes the CP never stall once frames queue.
#define BOOST_TEST_MODULE testbench.stream_backlog
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "tb_test_util.hpp"

using namespace tbtest;

BOOST_AUTO_TEST_CASE(frames_queue_when_the_model_is_slower) {
    const int W = 64, H = 32, N = 5;
    // 8 PEs: several batches per frame, a few ms of compute per frame; the
    // camera sends a frame every 0.5 ms.
    const double fps = 2000, line_us = 10;
    tb::StreamSetup setup = make_setup(W, H, 16, 8, fps, line_us);
    setup.timing.deadline_ms = 0;
    setup.timing.resolve(H);
    ListSource src(sequence(3, W, H, N));
    const tb::StreamResult r = tb::run_stream(src, setup);
    BOOST_REQUIRE(!r.error);
    BOOST_REQUIRE_EQUAL(r.frames.size(), static_cast<size_t>(N));
    const double tol = 1e-6;
    BOOST_TEST(r.frames[0].compute_ms > 2 * setup.timing.frame_ms());
    for (size_t k = 0; k < r.frames.size(); ++k) {
        const tb::FrameRecord& f = r.frames[k];
        BOOST_TEST_CONTEXT("frame " << k) {
            BOOST_TEST(f.status == "ok");
            BOOST_TEST(std::abs(f.capture_ms - k * setup.timing.frame_ms()) < tol);
            const double free_at = k == 0 ? 0.0 : r.frames[k - 1].done_ms;
            BOOST_TEST(std::abs(f.start_ms - std::max(f.capture_ms, free_at)) < tol);
            if (k > 0) {
                // Whole frame already buffered: no stall, latency grows.
                BOOST_TEST(f.stall_ms < tol);
                BOOST_TEST(f.latency_ms > r.frames[k - 1].latency_ms);
                BOOST_TEST(!f.deadline_met);
            }
        }
    }
}
