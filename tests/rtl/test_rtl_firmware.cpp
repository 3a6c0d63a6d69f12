// The DP firmware (dp.s) on the RTL model, P = RTL_TEST_PES: the disparity
// map leaving the video output equals the golden's, bit for bit, and the
// cycle count equals the bare machine core's (same cost table).
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
    rtl::RtlConfig rc;
    rc.trace_pe_first = 1;
    rc.trace_pe_count = 4;
    rc.trace_regs = {0, 1, 2};
    rtl::OutputImages out;
    const rtl::RtlRunResult r =
        rtl::run_rtl(cfg, c.prog, fw::param_block(c.plan), fw::to_video_image(c.frame.left()),
                     fw::to_video_image(c.frame.right()), c.roi.w, c.roi.h, &out, rc);
    BOOST_CHECK(r.halted);
    BOOST_CHECK(out.image[0].pixels == want.data);
    BOOST_CHECK(core.map.data == want.data);
    BOOST_CHECK_EQUAL(r.cycles, core.cycles);
    BOOST_CHECK_EQUAL(r.traced_pes, 4);
    BOOST_TEST_MESSAGE("P=" << P << " cycles " << r.cycles << " wall " << r.wall_s << " s");
}
