// Lockstep co-simulation of the TLM and RTL models on the DP firmware:
// passes with identical cycle counts, every instruction compared.
#define BOOST_TEST_MODULE rtl_lockstep
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(lockstep_passes_on_dp_firmware) {
    const int P = RTL_TEST_PES;
    const FirmwareCase c = firmware_case(P, RTL_TEST_SEED, RTL_TEST_D, RTL_TEST_VOTE,
                                         RTL_TEST_VOTE ? g::Mode::Bidir : g::Mode::Single);
    isa::MachineConfig cfg;
    cfg.pes = P;
    const g::DisparityMap want = g::compute(c.p, c.frame.left(), c.frame.right(), c.roi);
    rtl::OutputImages out;
    const rtl::LockstepResult r =
        rtl::run_lockstep(cfg, c.prog, fw::param_block(c.plan), fw::to_video_image(c.frame.left()),
                          fw::to_video_image(c.frame.right()), c.roi.w, c.roi.h, &out);
    BOOST_CHECK_MESSAGE(!r.diverged, r.divergence.message());
    BOOST_CHECK_EQUAL(r.tlm.cycles, r.rtl.cycles);
    BOOST_CHECK_EQUAL(r.compared, r.instructions);
    BOOST_CHECK_GT(r.instructions, 1000u);
    BOOST_CHECK(out.image[0].pixels == want.data);
    BOOST_TEST_MESSAGE("P=" << P << " instructions " << r.instructions << " cycles " << r.rtl.cycles
                            << " wall " << r.wall_s << " s");
}
