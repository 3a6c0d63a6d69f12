// Lockstep co-simulation of the TLM model and the RTL design on the DP
// firmware: passes at every retired instruction with identical cycle
// counts; RTL_TEST_COSTS = 1 runs it with every cost-table entry away from
// its default (the cost table is a set of straps of the design);
// RTL_TEST_SPILL = 1 runs a frame whose pointers spill to the external
// memory under the mask of the PEs holding a line; with RTL_TEST_BOARD = 1
// at a clock where the path beats and with a timed camera.
#define BOOST_TEST_MODULE rtl_lockstep
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

namespace {

// Runs the frame on the core and in lockstep (TLM against RTL) and checks
// that they agree at every instruction, bit-exact against the golden's
// map, with the same cycles per phase on all three; returns both results.
std::pair<fw::FrameResult, rtl::LockstepResult> lockstep_frame(
    const isa::MachineConfig& cfg, const fw::FramePlan& plan, const isa::Program& prog,
    const Frame& frame, const g::Roi& roi, const g::DisparityMap& want) {
    fw::FrameResult core = fw::run_frame_core(plan, prog, frame.left(), frame.right(), cfg);
    rtl::OutputImages out;
    rtl::LockstepResult r =
        rtl::run_lockstep(cfg, prog, fw::param_block(plan), fw::to_video_image(frame.left()),
                          fw::to_video_image(frame.right()), roi.w, roi.h, &out);
    BOOST_TEST_INFO(r.divergence.message());
    BOOST_REQUIRE(!r.diverged);
    BOOST_CHECK(out.image[0].pixels == want.data);
    BOOST_CHECK_EQUAL(r.tlm.cycles, r.rtl.cycles);
    BOOST_CHECK_EQUAL(r.rtl.cycles, core.cycles);
    BOOST_CHECK_EQUAL(r.compared, r.instructions);
    BOOST_CHECK_EQUAL(r.instructions, core.stats.instructions);
    BOOST_CHECK(r.tlm.phase_cycles == r.rtl.phase_cycles);
    return {std::move(core), std::move(r)};
}

// The spilling frame: single mode, 6 lines of a 96-wide ROI at D = 90.
struct SpillFrame {
    g::Params p;
    Frame frame;
    g::Roi roi{2, 1, 96, 6};
    SpillFrame() : frame(random_frame(RTL_TEST_SEED, 100, 8, 90)) {
        p.mode = g::Mode::Single;
        p.D = 90;
    }
};

}  // namespace

#if RTL_TEST_SPILL && !RTL_TEST_BOARD
BOOST_AUTO_TEST_CASE(lockstep_passes_on_masked_spills) {
    // Single mode, 6 lines of a 96-wide ROI at D = 90 on 16 PEs: 376 B of
    // pointers per PE do not fit and go out by xst and back by xld under
    // the mask of the 6 PEs holding a line (docs/isa.md, xld / xst: a
    // masked PE's memory keeps its bytes, a transfer costs what the active
    // PEs move). Both models agree at every instruction, bit-exact, and the
    // spill phase costs less than its transfers would with every PE's bytes.
    const int P = 16;
    const SpillFrame s;
    const g::Params& p = s.p;
    const Frame& frame = s.frame;
    const g::Roi& roi = s.roi;
    isa::MachineConfig cfg;
    cfg.pes = P;
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg);
    BOOST_REQUIRE(plan.ext_needed > 0);
    BOOST_REQUIRE(!plan.spare);
    BOOST_REQUIRE(plan.batches.size() == 1u);
    BOOST_REQUIRE(plan.batches[0].lines < P);
    const isa::Program prog = fw::assemble_frame(p, plan);
    const g::DisparityMap want = g::compute(p, frame.left(), frame.right(), roi);
    const auto [core, r] = lockstep_frame(cfg, plan, prog, frame, roi, want);
    uint64_t spill = 0, every_pe = 0;
    for (const auto& [n, c] : core.phases)
        if (n == "spill") spill = c;
    for (const auto* ts : {&plan.f.spills, &plan.f.reloads})
        for (const fw::Transfer& t : *ts) every_pe += cfg.costs.xfer_cycles(uint64_t(t.len), P);
    BOOST_TEST_MESSAGE("masked spills: "
                       << plan.ext_needed << " B per PE, " << plan.batches[0].lines << " of " << P
                       << " PEs hold a line; spill " << spill
                       << " cycles (the transfers with every PE: " << every_pe << "), "
                       << r.instructions << " instructions, " << r.rtl.cycles << " cycles");
    BOOST_CHECK_GT(spill, 0u);
    BOOST_CHECK_LT(spill, every_pe);
}
#endif
#if RTL_TEST_SPILL && RTL_TEST_BOARD
BOOST_AUTO_TEST_CASE(lockstep_passes_with_board_timing) {
    // The same spilling frame at 300 MHz, where the external path moves 8
    // bytes every 3 cycles (800 MB/s, docs/isa.md 2.4), and a camera at a
    // 5 MHz pixel clock whose lines arrive while the program runs: the RTL's
    // transfer engine beats and its vin waits as the instruction-set model
    // charges them, at every instruction.
    const SpillFrame s;
    const g::Params& p = s.p;
    const Frame& frame = s.frame;
    const g::Roi& roi = s.roi;
    isa::MachineConfig cfg;
    cfg.set("pes", "16");
    cfg.set("clock_mhz", "300");
    cfg.set("camera_pixel_mhz", "5");
    BOOST_REQUIRE_EQUAL(cfg.costs.ext_beat, 3u);
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg);
    BOOST_REQUIRE(plan.ext_needed > 0);
    const isa::Program prog = fw::assemble_frame(p, plan);
    const g::DisparityMap want = g::compute(p, frame.left(), frame.right(), roi);
    const auto [core, r] = lockstep_frame(cfg, plan, prog, frame, roi, want);
    uint64_t video = 0;
    for (const auto& [n, c] : core.phases)
        if (n == "video_in") video = c;
    // line 6 of the 100-wide frame (+140 blanking) has arrived after
    // 7 x 240 pixel times less the pixels beyond the ROI's last segment
    BOOST_CHECK_GT(video, uint64_t(6 * 240 / 5 * 300));
}
#endif
#if !RTL_TEST_SPILL
BOOST_AUTO_TEST_CASE(lockstep_passes_on_dp_firmware) {
    const int P = RTL_TEST_PES;
    const FirmwareCase c = firmware_case(P, RTL_TEST_SEED, RTL_TEST_D, RTL_TEST_VOTE,
                                         RTL_TEST_VOTE ? g::Mode::Bidir : g::Mode::Single);
    isa::MachineConfig cfg;
    cfg.pes = P;
    if (RTL_TEST_COSTS) {
        for (const auto& [n, v] :
             std::vector<std::pair<const char*, int> >{{"alu", 2},
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
    const auto [core, r] = lockstep_frame(cfg, c.plan, c.prog, c.frame, c.roi, want);
    BOOST_TEST_MESSAGE("P=" << P << " costs " << RTL_TEST_COSTS << ": " << r.instructions
                            << " instructions, " << r.rtl.cycles << " cycles, " << r.wall_s
                            << " s");
}
#endif
