// The firmware over the parameter grid of the machine issue: both modes,
// vote on/off, fixed and free seeds, every output frame, several ROIs
// (one taller than the array), D from 1 to the largest that fits, and PE
// counts 8, 64, 256 and 320 -- every run bit-exact with the golden.
#define BOOST_TEST_MODULE firmware_grid
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"

using namespace fwtest;

namespace {

const g::Frame kFrames[] = {g::Frame::Cyclopean, g::Frame::Left, g::Frame::Right};

// Largest D that the default 1 KiB machine accepts for ROI width N.
int max_fitting_d(const g::Params& base, const g::Roi& roi, int P) {
    isa::MachineConfig cfg;
    cfg.pes = P;
    int best = 0;
    for (int D = 1; D <= std::min(roi.w, 255); ++D) {
        g::Params p = base;
        p.D = D;
        try {
            fw::plan_frame(p, roi, cfg);
            best = D;
        } catch (const fw::FirmwareError&) {
        }
    }
    return best;
}

}  // namespace

BOOST_AUTO_TEST_CASE(modes_votes_seeds_frames) {
    std::mt19937 rng(101);
    const Frame fr = random_frame(rng, 72, 40, 24);
    const g::Roi roi{4, 3, 64, 34};  // taller than 8 PEs' line capacity
    for (int P : {8, 64}) {
        for (int mode = 0; mode < 2; ++mode)
            for (int vote = 0; vote < 2; ++vote)
                for (int seed = 0; seed < 3; ++seed)
                    for (g::Frame f : kFrames) {
                        g::Params p;
                        p.D = 24;
                        p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
                        p.vote = vote != 0;
                        p.frame = f;
                        if (seed == 1) {
                            p.seed_disp.free = false;
                            p.seed_disp.value = 5;
                        } else if (seed == 2) {
                            p.seed_col.kind = g::SeedColKind::Center;
                            p.seed_disp.free = false;
                            p.seed_disp.value = 0;
                        }
                        BOOST_TEST_CONTEXT("P=" << P << " " << describe(p, roi.w, roi.h) << " vote="
                                                << p.vote << " frame=" << g::to_string(f)) {
                            check_frame(p, fr, roi, P);
                        }
                    }
    }
}

BOOST_AUTO_TEST_CASE(d_from_one_to_the_largest_that_fits) {
    std::mt19937 rng(102);
    const Frame fr = random_frame(rng, 140, 24, 30);
    const g::Roi roi{6, 2, 128, 20};
    g::Params base;
    const int dmax = max_fitting_d(base, roi, 256);
    BOOST_TEST_MESSAGE("largest D that fits 1 KiB for a 128-wide ROI: " << dmax);
    BOOST_TEST(dmax >= 128);  // the paper's grid runs up to D = 128 at width 128
    for (int D : {1, 2, 3, 17, 64, 100, dmax}) {
        g::Params p = base;
        p.D = D;
        BOOST_TEST_CONTEXT("D=" << D) {
            check_frame(p, fr, roi, 256);
        }
    }
}

BOOST_AUTO_TEST_CASE(pe_counts_8_64_256_320) {
    std::mt19937 rng(103);
    const Frame fr = random_frame(rng, 100, 50, 20);
    const g::Roi roi{0, 0, 96, 50};
    for (int P : {8, 64, 256, 320}) {
        g::Params p;
        p.D = 20;
        BOOST_TEST_CONTEXT("P=" << P) {
            check_frame(p, fr, roi, P);
        }
    }
}

BOOST_AUTO_TEST_CASE(edge_cases) {
    std::mt19937 rng(104);
    const Frame fr = random_frame(rng, 40, 30, 8);
    struct Case {
        g::Roi roi;
        int D;
        int P;
        g::Mode mode;
    };
    const Case cases[] = {
        {{0, 0, 2, 10}, 1, 8, g::Mode::Bidir},      // ROI width 2
        {{0, 0, 2, 10}, 2, 8, g::Mode::Single},     // D = width
        {{3, 5, 30, 1}, 8, 8, g::Mode::Bidir},      // one-line ROI
        {{0, 0, 40, 30}, 40, 16, g::Mode::Single},  // D = width, taller than the array
        {{1, 1, 33, 29}, 7, 6, g::Mode::Bidir},     // smallest array that votes across batches
    };
    for (const Case& c : cases) {
        g::Params p;
        p.D = c.D;
        p.mode = c.mode;
        BOOST_TEST_CONTEXT("roi " << c.roi.w << "x" << c.roi.h << " D=" << c.D << " P=" << c.P) {
            check_frame(p, fr, c.roi, c.P);
        }
    }
}

// SPEC Part B: any PE count >= 2 runs. With the vote on, 2 to 5 PEs hold
// fewer than 3 lines per batch: the firmware runs one line per batch and
// keeps the pointer tables of the neighbouring lines in the external memory
// (this used to be refused).
BOOST_AUTO_TEST_CASE(two_to_five_pes_with_the_vote) {
    std::mt19937 rng(105);
    const Frame fr = random_frame(rng, 30, 12, 10);
    const g::Roi roi{2, 1, 26, 9};
    for (int P : {2, 3, 4, 5})
        for (int mode = 0; mode < 2; ++mode)
            for (int seed = 0; seed < 2; ++seed) {
                g::Params p;
                p.D = 10;
                p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
                p.frame = kFrames[(P + seed) % 3];
                if (seed == 1 && mode == 1) {
                    p.seed_disp.free = false;
                    p.seed_disp.value = 3;
                }
                BOOST_TEST_CONTEXT("P=" << P << " " << describe(p, roi.w, roi.h)
                                        << " frame=" << g::to_string(p.frame)) {
                    check_frame(p, fr, roi, P);
                }
            }
}
