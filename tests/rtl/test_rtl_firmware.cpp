// The DP firmware (dp.s) on the RTL design, P = RTL_TEST_PES: the disparity
// map leaving the video output port equals the golden's, bit for bit, and
// the design's own cycle counter, per-phase counters and PE utilisation
// equal the instruction-set model's (same cost table).
#define BOOST_TEST_MODULE rtl_firmware
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(dp_firmware_bit_exact) {
    const int P = RTL_TEST_PES;
    const FirmwareCase c = firmware_case(P, 7, 8, true, g::Mode::Bidir);
    isa::MachineConfig cfg;
    cfg.pes = P;
    const g::DisparityMap want = g::compute(c.p, c.frame.left(), c.frame.right(), c.roi);
    const fw::FrameResult core =
        fw::run_frame_core(c.plan, c.prog, c.frame.left(), c.frame.right(), cfg);
    rtl::OutputImages out;
    const rtl::RtlRunResult r =
        rtl::run_rtl(cfg, c.prog, fw::param_block(c.plan), fw::to_video_image(c.frame.left()),
                     fw::to_video_image(c.frame.right()), c.roi.w, c.roi.h, &out);
    BOOST_CHECK(r.halted);
    BOOST_CHECK(out.image[0].pixels == want.data);
    BOOST_CHECK(core.map.data == want.data);
    BOOST_CHECK_EQUAL(r.cycles, core.cycles);
    BOOST_CHECK(fw::phase_table(c.prog, r.phase_cycles) == core.phases);
    BOOST_CHECK_EQUAL(r.stats.instructions, core.stats.instructions);
    BOOST_CHECK_EQUAL(r.stats.pe_cycles, core.stats.pe_cycles);
    BOOST_CHECK_EQUAL(r.stats.active_lane_cycles, core.stats.active_lane_cycles);
    for (size_t k = 0; k < r.stats.class_cycles.size(); ++k)
        BOOST_CHECK_EQUAL(r.stats.class_cycles[k], core.stats.class_cycles[k]);
    BOOST_CHECK(r.stats.op_counts == core.stats.op_counts);
    // every clock is a machine cycle but for the zero-cost phase markers
    BOOST_CHECK_GE(r.clocks, r.cycles);
    BOOST_CHECK_LE(r.clocks, r.cycles + r.stats.op_counts[0x02] + 8);
    BOOST_REQUIRE(r.state);
    BOOST_CHECK_EQUAL(r.state->pes, P);
    BOOST_TEST_MESSAGE("P=" << P << " cycles " << r.cycles << " clocks " << r.clocks << " wall "
                            << r.wall_s << " s, " << r.configuration);
}
