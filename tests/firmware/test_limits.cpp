// The planner's refusals name the true limit (issue 30, item 4): batches
// too short for the lines they share (the halo of the vote, --agg-ry and
// --kc) say what a batch holds on the machine (P / span lines, never more
// than 255: the re-layout's one-byte row index) and what it needs, and that
// advice is checked to plan; the census's last video segment; the local
// memory rows as lower bounds ("at least"). Exact messages, from
// fw::plan_frame on the parameters, ROI and machine of each case.
#define BOOST_TEST_MODULE firmware_limits
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"

using namespace fwtest;

namespace {

// The planner's message for p on roi and a machine of `pes` PEs and `mem`
// bytes of local memory per PE, or "" when it plans.
std::string refusal(const g::Params& p, const g::Roi& roi, int pes, int mem = 1024) {
    isa::MachineConfig cfg;
    cfg.pes = static_cast<uint32_t>(pes);
    cfg.mem_bytes = static_cast<uint32_t>(mem);
    try {
        fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        return e.what();
    }
    return "";
}

g::Params quality(int D) {
    g::Params p = g::preset("quality");
    p.D = D;
    return p;
}

g::Params census(g::Mode mode, int D) {
    g::Params p;
    p.kc = 4;
    p.mode = mode;
    p.D = D;
    return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_full_middlebury_roi_takes_batches_and_segments) {
    // tsukuba's 384x288 at the quality preset: more lines than a batch holds
    // (at most 255, the re-layout's one-byte row index) take batches sharing
    // their halo, a line wider than P video segments (it said "needs 576
    // PEs, have 1024", then "use a ROI of at most 128 lines", then "needs
    // --pes >= 384")
    const g::Roi tsukuba{0, 0, 384, 288};
    for (const int P : {1024, 512, 384, 256})
        BOOST_TEST(refusal(quality(16), tsukuba, P, 4096) == "", "P=" << P);
}

BOOST_AUTO_TEST_CASE(too_few_pes_for_the_halo_names_the_pes_needed) {
    // quality: the vote's line, the window's 2, the census's 2 either side
    BOOST_TEST(
        refusal(quality(6), g::Roi{0, 0, 16, 20}, 16) ==
        "firmware: too few PEs for the lines the batches share: 16 PEs hold 8 line(s) per batch, "
        "and a batch holds 5 line(s) either side of the ones it outputs (the vote 1, "
        "--agg-ry 2, the census radius 2), so a batch needs 11 lines (use >= 22 PEs, or a "
        "ROI of at most 8 lines)");
    BOOST_TEST(refusal(quality(6), g::Roi{0, 0, 16, 20}, 22) == "");
    BOOST_TEST(refusal(quality(6), g::Roi{0, 0, 16, 8}, 16) == "");
    // wider than P: video segments
    BOOST_TEST(refusal(quality(6), g::Roi{0, 0, 30, 20}, 22) == "");
    // the one-line-per-batch mode (bidir, 4 PEs, the vote) does not take it
    g::Params t;
    t.agg_ry = 1;
    t.D = 4;
    BOOST_TEST(refusal(t, g::Roi{0, 0, 16, 5}, 4) ==
               "firmware: too few PEs for the lines the batches share: 4 PEs hold 2 line(s) per "
               "batch, and "
               "a batch holds 2 line(s) either side of the ones it outputs (the vote 1, --agg-ry "
               "1), so a batch needs 5 lines (use >= 10 PEs, or a ROI of at most 2 lines)");
    BOOST_TEST(refusal(t, g::Roi{0, 0, 16, 5}, 10) == "");
    BOOST_TEST(refusal(t, g::Roi{0, 0, 16, 7}, 10) == "");  // two batches of 5
    BOOST_TEST(refusal(t, g::Roi{0, 0, 16, 2}, 4) == "");
}

BOOST_AUTO_TEST_CASE(the_census_names_what_a_batch_and_its_last_segment_need) {
    // single mode on 1,024 PEs: one PE per line, 255 lines per batch at most:
    // batches
    BOOST_TEST(refusal(census(g::Mode::Single, 8), g::Roi{0, 0, 64, 300}, 1024, 2048) == "");
    // the one-line-per-batch mode in single mode: P / 1 lines, not 2 per line
    BOOST_TEST(refusal(census(g::Mode::Single, 2), g::Roi{0, 0, 2, 8}, 2) ==
               "firmware: too few PEs for the lines the batches share: 2 PEs hold 2 line(s) per "
               "batch, and "
               "a batch holds 3 line(s) either side of the ones it outputs (the vote 1, the "
               "census radius 2), so a batch needs 7 lines (use >= 7 PEs, or a ROI of at most 2 "
               "lines)");
    BOOST_TEST(refusal(census(g::Mode::Single, 2), g::Roi{0, 0, 2, 8}, 7) == "");
    BOOST_TEST(refusal(census(g::Mode::Single, 2), g::Roi{0, 0, 2, 2}, 2) == "");
    // video segments: the last one at least r pixels wide, and the advice plans
    BOOST_TEST(refusal(census(g::Mode::Bidir, 8), g::Roi{0, 0, 40, 4}, 32) == "");
    BOOST_TEST(refusal(census(g::Mode::Bidir, 8), g::Roi{0, 0, 65, 4}, 32) ==
               "firmware: --kc 4 (census) over 3 video segments of 32 pixels needs the last one "
               "at least 2 pixels wide (the census radius): the ROI is 65 wide, the last segment "
               "1; use a ROI width of 64 or at least 66 (--roi), or other --pes");
    BOOST_TEST(refusal(census(g::Mode::Bidir, 8), g::Roi{0, 0, 64, 4}, 32) == "");
    BOOST_TEST(refusal(census(g::Mode::Bidir, 8), g::Roi{0, 0, 66, 4}, 32) == "");
    BOOST_TEST(refusal(census(g::Mode::Bidir, 8), g::Roi{0, 0, 65, 4}, 33) == "");
}

BOOST_AUTO_TEST_CASE(the_rows_name_a_lower_bound_of_the_local_memory) {
    // --agg-rx 1, 128 lines on 256 PEs: the video rows beside the line
    // buffers need 210 bytes, and then the output rows 315; the frame plans
    // only from 338 bytes, so each figure is "at least"
    g::Params p;
    p.agg_rx = 1;
    p.D = 8;
    const g::Roi roi{0, 0, 64, 128};
    BOOST_TEST(refusal(p, roi, 256, 200) ==
               "does not fit: --agg-rx 1 needs at least 210 bytes of local memory per PE for the "
               "video rows beside the line buffers (have 200, mem_bytes)");
    BOOST_TEST(refusal(p, roi, 256, 210) ==
               "does not fit: needs at least 315 bytes of local memory per PE for the output rows "
               "(have 210, mem_bytes)");
    BOOST_TEST(refusal(p, roi, 256, 337) != "");
    BOOST_TEST(refusal(p, roi, 256, 338) == "");
}
