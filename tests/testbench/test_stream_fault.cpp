// A machine fault (here the watchdog) ends that frame's run only: the hosted
// CP records it, the simulation goes on, and the next frame runs on a reset
// machine (same fault at the same cycle every time).
#define BOOST_TEST_MODULE testbench.stream_fault
#include <boost/test/unit_test.hpp>

#include "tb_test_util.hpp"

using namespace tbtest;

BOOST_AUTO_TEST_CASE(every_frame_faults_and_the_stream_goes_on) {
    const int W = 48, H = 16, N = 3;
    tb::StreamSetup setup = make_setup(W, H, 12, 16, 100, 50);
    setup.machine.watchdog_cycles = 5000;  // far fewer than the frame needs
    ListSource src(sequence(9, W, H, N));
    const tb::StreamResult r = tb::run_stream(src, setup);
    BOOST_REQUIRE(!r.error);
    BOOST_REQUIRE_EQUAL(r.frames.size(), static_cast<size_t>(N));
    for (const tb::FrameRecord& f : r.frames) {
        BOOST_TEST(f.status == "fault");
        BOOST_TEST(f.error.find("watchdog") != std::string::npos, f.error);
        BOOST_TEST(f.cycles == r.frames[0].cycles);
        BOOST_TEST(f.cycles >= 5000u);
        BOOST_TEST(f.cycles < 6000u);
    }
}
