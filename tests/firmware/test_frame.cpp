// The whole firmware (dp.s: video in, re-layout, DP, vote, backtrack, merge,
// re-layout, video out) on the bare machine core: the disparity map leaving
// the video output must equal the golden's, bit for bit.
#define BOOST_TEST_MODULE firmware_frame
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"

using namespace fwtest;

BOOST_AUTO_TEST_CASE(headline_case_256_pes) {
    std::mt19937 rng(5);
    g::Params p;
    p.D = 64;
    const Frame fr = random_frame(rng, 160, 140, 40);
    uint64_t cycles = 0;
    check_frame(p, fr, g::Roi{16, 6, 128, 128}, 256, &cycles);
    BOOST_TEST_MESSAGE("headline cycles: " << cycles);
}

BOOST_AUTO_TEST_CASE(random_frames_small_arrays) {
    std::mt19937 rng(21);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 40), Hi = uni(1, 14);
        g::Roi roi;
        roi.w = uni(2, W);
        roi.h = uni(1, Hi);
        roi.x0 = uni(0, W - roi.w);
        roi.y0 = uni(0, Hi - roi.h);
        const g::Params p = random_params(rng, roi.w);
        const int P = uni(2, 24);  // 2..5 with the vote: one line per batch (docs/firmware.md)
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                           << " vote=" << p.vote << " frame=" << g::to_string(p.frame) << " P=" << P
                           << " roi=" << roi.x0 << "," << roi.y0 << " image " << W << "x" << Hi) {
            check_frame(p, fr, roi, P);
        }
    }
}
