// The SPEC A.9 options on the firmware (docs/firmware.md, section 10): the
// ones it runs are bit-exact with the golden over random scenes, sizes, D,
// modes and PE counts; the ones it does not run are refused up front with a
// message that names them (never a wrong map).
#define BOOST_TEST_MODULE firmware_options
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"
#include "imap/golden/estimate.hpp"

using namespace fwtest;

namespace {

// A random parameter set with the A.9 options the firmware implements.
g::Params random_option_params(std::mt19937& rng, int N) {
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    g::Params p = random_params(rng, N);
    const int pick = uni(0, 3);
    p.ad_max = pick == 0 ? uni(0, 3) : pick == 1 ? uni(4, 40) : pick == 2 ? 16 : uni(41, 255);
    if (uni(0, 2) == 0) {  // the quality preset's pixel weights
        p.km = 1;
        p.kb = 0;
        p.gb = 0;
        p.Wo = p.Wd = uni(0, 400);
    }
    if (p.km == 0 && p.kb == 0) p.km = 1;
    return p;
}

std::string refusal(const g::Params& p, const g::Roi& roi) {
    isa::MachineConfig cfg;
    try {
        fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

BOOST_AUTO_TEST_CASE(ad_max_random_frames) {
    std::mt19937 rng(917);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 48), Hi = uni(1, 14);
        g::Roi roi;
        roi.w = uni(2, W);
        roi.h = uni(1, Hi);
        roi.x0 = uni(0, W - roi.w);
        roi.y0 = uni(0, Hi - roi.h);
        const g::Params p = random_option_params(rng, roi.w);
        const int P = uni(2, 40);
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                           << " ad-max=" << p.ad_max << " vote=" << p.vote
                           << " frame=" << g::to_string(p.frame) << " P=" << P) {
            check_frame(p, fr, roi, P);
        }
    }
}

BOOST_AUTO_TEST_CASE(ad_max_grid_modes_and_d) {
    std::mt19937 rng(31);
    const Frame fr = random_frame(rng, 72, 24, 32);
    const g::Roi roi{4, 2, 64, 20};
    for (int mode = 0; mode < 2; ++mode)
        for (int ad : {0, 1, 7, 16, 254})
            for (int D : {1, 16, 32}) {
                g::Params p;
                p.D = D;
                p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
                p.km = 1;
                p.kb = 0;
                p.gb = 0;
                p.Wo = p.Wd = 40;
                p.ad_max = ad;
                BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h) << " ad-max=" << ad) {
                    check_frame(p, fr, roi, 64);
                }
            }
}

BOOST_AUTO_TEST_CASE(ad_max_headline_paper_weights) {
    std::mt19937 rng(5);
    g::Params p;
    p.D = 64;
    p.ad_max = 24;
    const Frame fr = random_frame(rng, 160, 140, 40);
    check_frame(p, fr, g::Roi{16, 6, 128, 128}, 256);
}

BOOST_AUTO_TEST_CASE(ad_max_enters_the_16_bit_range_check) {
    g::Params p;
    p.km = 200;  // 200 * 255 = 51,000 > 32,766: refused without truncation
    p.kb = 0;
    const g::Roi roi{0, 0, 96, 4};
    BOOST_TEST(refusal(p, roi).find("exceeds the 16-bit costs' range") != std::string::npos);
    p.ad_max = 100;  // 200 * 100 = 20,000: accepted
    BOOST_TEST(refusal(p, roi).empty());
}

BOOST_AUTO_TEST_CASE(options_not_in_the_firmware_are_refused) {
    const g::Roi roi{0, 0, 96, 8};
    struct Case {
        const char* name;
        void (*set)(g::Params&);
        const char* expect;
    };
    const Case cases[] = {
        {"joint", [](g::Params& p) { p.mode = g::Mode::Joint; }, "--mode joint"},
        {"bt", [](g::Params& p) { p.dissim = g::Dissim::Bt; }, "--dissim bt"},
        {"kc", [](g::Params& p) { p.kc = 4; }, "--kc 4"},
        {"agg-rx", [](g::Params& p) { p.agg_rx = 2; }, "--agg-rx 2"},
        {"agg-ry", [](g::Params& p) { p.agg_ry = 1; }, "--agg-ry 1"},
    };
    for (const Case& c : cases) {
        g::Params p;
        c.set(p);
        const std::string msg = refusal(p, roi);
        BOOST_TEST_CONTEXT(c.name << ": " << msg) {
            BOOST_TEST(msg.find("does not implement") != std::string::npos);
            BOOST_TEST(msg.find(c.expect) != std::string::npos);
        }
        isa::MachineConfig cfg;  // the forward-pass planner refuses them too
        BOOST_CHECK_THROW(fw::plan_forward(p, roi.w, cfg), fw::FirmwareError);
    }
    const std::string q = refusal(g::preset("quality"), g::Roi{0, 0, 128, 128});
    BOOST_TEST(q.find("--mode joint, --kc 4, --agg-rx 2, --agg-ry 2") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(firmware_part_of_every_tradeoff_variant_runs) {
    // eval --tradeoff measures firmware_part(p) at the headline case: it must
    // keep what the firmware implements (ad-max) and be accepted.
    const g::Roi roi{0, 0, 128, 128};
    for (const auto& v : g::tradeoff_variants()) {
        g::Params p = v.p;
        p.D = 64;
        const g::Params f = fw::firmware_part(p);
        BOOST_TEST_CONTEXT(v.name) {
            BOOST_TEST(f.ad_max == p.ad_max);
            BOOST_TEST(refusal(f, roi).empty());
        }
    }
    g::Params q = g::preset("quality");
    q.D = 64;
    BOOST_TEST(!refusal(q, roi).empty());
}
