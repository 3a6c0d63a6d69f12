// Lockstep co-simulation of the TLM model and the RTL design on the DP
// firmware: passes at every retired instruction with identical cycle
// counts; RTL_TEST_COSTS = 1 runs it with every cost-table entry away from
// its default (the cost table is a set of straps of the design).
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
    if (RTL_TEST_COSTS) {
        for (const auto& [n, v] :
             std::vector<std::pair<const char*, int>>{{"alu", 2},
                                                      {"mem", 3},
                                                      {"indirect_extra", 0},
                                                      {"ring_hop", 2},
                                                      {"mask", 2},
                                                      {"status", 3},
                                                      {"cp", 2},
                                                      {"branch_taken", 0},
                                                      {"video_line", 4},
                                                      {"xfer_setup", 0},
                                                      {"ext_bytes_per_cycle", 3},
                                                      {"shift_bits", 2},
                                                      {"minmax_extra", 1}})
            cfg.costs.set(n, v);
        cfg.validate();
    }
    const g::DisparityMap want = g::compute(c.p, c.frame.left(), c.frame.right(), c.roi);
    const fw::FrameResult core =
        fw::run_frame_core(c.plan, c.prog, c.frame.left(), c.frame.right(), cfg);
    rtl::OutputImages out;
    const rtl::LockstepResult r =
        rtl::run_lockstep(cfg, c.prog, fw::param_block(c.plan), fw::to_video_image(c.frame.left()),
                          fw::to_video_image(c.frame.right()), c.roi.w, c.roi.h, &out);
    BOOST_TEST_INFO(r.divergence.message());
    BOOST_REQUIRE(!r.diverged);
    BOOST_CHECK(out.image[0].pixels == want.data);
    BOOST_CHECK_EQUAL(r.tlm.cycles, r.rtl.cycles);
    BOOST_CHECK_EQUAL(r.rtl.cycles, core.cycles);
    BOOST_CHECK_EQUAL(r.compared, r.instructions);
    BOOST_CHECK_EQUAL(r.instructions, core.stats.instructions);
    BOOST_CHECK(r.tlm.phase_cycles == r.rtl.phase_cycles);
    BOOST_TEST_MESSAGE("P=" << P << " costs " << RTL_TEST_COSTS << ": " << r.instructions
                            << " instructions, " << r.rtl.cycles << " cycles, " << r.wall_s
                            << " s");
}
