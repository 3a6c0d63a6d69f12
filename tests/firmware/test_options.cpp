// The SPEC A.9 options on the firmware (docs/firmware.md, section 10): the
// ones it runs are bit-exact with the golden over random scenes, sizes, D,
// modes and PE counts; the ones it does not run are refused up front with a
// message that names them (never a wrong map).
#define BOOST_TEST_MODULE firmware_options
#include <boost/test/unit_test.hpp>
#include <tuple>

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
    if (N >= 2 && uni(0, 2) == 0) {  // SPEC A.9 joint: bidir's seed rules
        p.mode = g::Mode::Joint;
        if (!p.seed_disp.free) {
            const int s = g::resolve_seed_col(p, N);
            p.seed_disp.value = uni(0, std::min(p.D - 1, N - 1 - s));
        }
    }
    return p;
}

g::Mode mode_of(int i) {
    return i == 0 ? g::Mode::Single : i == 1 ? g::Mode::Bidir : g::Mode::Joint;
}

// A grid point of mode `mode_of(mode)` at the quality preset's pixel weights
// (km 1, kb 0, gb 0) with Wo = Wd = 80.
g::Params quality_weights(int mode, int D, int ad_max) {
    g::Params p;
    p.D = D;
    p.mode = mode_of(mode);
    p.km = 1;
    p.kb = 0;
    p.gb = 0;
    p.Wo = p.Wd = 80;
    p.ad_max = ad_max;
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

// A random ROI of at least 2 x 1 pixels inside a W x H image.
g::Roi random_roi(std::mt19937& rng, int W, int H) {
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    g::Roi roi;
    roi.w = uni(2, W);
    roi.h = uni(1, H);
    roi.x0 = uni(0, W - roi.w);
    roi.y0 = uni(0, H - roi.h);
    return roi;
}

// The lines a batch holds either side of the ones it outputs when the ROI
// takes several batches: the vote's neighbour, the vertical window's lines
// and the census's lines beyond them (docs/firmware.md, section 3).
int halo_of(const g::Params& p) {
    return (p.vote ? 1 : 0) + p.agg_ry + (p.kc > 0 ? p.census : 0);
}

// Random window weights brought inside the 16-bit cost range (the kc cap,
// then km, kc and agg-ry lowered while the window's largest cost exceeds
// 30,000), with at least one match weight.
void fit_window_weights(g::Params& p) {
    if (p.kc * 8 > 1000) p.kc = 50;
    auto wm = [&] {
        return (2 * p.agg_rx + 1) * (2 * p.agg_ry + 1) *
               (p.km * std::min(255, p.ad_max) + p.kb * p.gb + 8 * p.kc);
    };
    while (wm() > 30000 && p.km > 1) p.km /= 2;
    while (wm() > 30000 && p.kc > 1) p.kc /= 2;
    if (wm() > 30000) p.agg_ry = 1;
    if (p.km == 0 && p.kb == 0 && p.kc == 0) p.km = 1;
}

// The census's video segments: a ROI wider than P needs its last segment at
// least r pixels wide; P grows to the ROI's width where it is not.
int census_segments_ok(const g::Params& p, const g::Roi& roi, int P) {
    const int last = roi.w - (roi.w - 1) / P * P;
    return roi.w > P && last < p.census ? std::max(P, roi.w) : P;
}

// A random PE count the firmware accepts: with the census or the vertical
// window a batch holds at least 2 * halo + 1 lines (no one-line-per-batch
// mode); joint needs 3 lines per batch with the vote when the ROI is taller;
// the census takes video segments with a last one of at least r pixels.
int random_pes(std::mt19937& rng, const g::Params& p, const g::Roi& roi, bool census) {
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    const int span = p.mode == g::Mode::Single ? 1 : 2;
    const int lines = std::min(roi.h, 2 * halo_of(p) + 1);
    return census ? census_segments_ok(p, roi, uni(std::max({2, span * lines}), 48))
                  : uni(p.mode == g::Mode::Joint ? 6 : 2, 40);
}

// The test context of a random frame: every A.9 option and the PE count.
std::string options_context(const g::Params& p, const g::Roi& roi, int P) {
    std::ostringstream os;
    os << describe(p, roi.w, roi.h) << " dissim=" << g::to_string(p.dissim)
       << " agg-rx=" << p.agg_rx << " agg-ry=" << p.agg_ry << " kc=" << p.kc
       << " census=" << p.census << " km=" << p.km << " ad-max=" << p.ad_max << " vote=" << p.vote
       << " frame=" << g::to_string(p.frame) << " P=" << P;
    return os.str();
}

}  // namespace

BOOST_AUTO_TEST_CASE(ad_max_random_frames) {
    std::mt19937 rng(917);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 48), Hi = uni(1, 14);
        const g::Roi roi = random_roi(rng, W, Hi);
        const g::Params p = random_option_params(rng, roi.w);
        const int P = random_pes(rng, p, roi, false);
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P)) {
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
        {"agg-rx", [](g::Params& p) { p.agg_rx = 3; }, "--agg-rx 3"},
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
    {
        // the forward-pass test layout (host-filled line buffers) has no bounds
        g::Params b;
        b.dissim = g::Dissim::Bt;
        BOOST_TEST(refusal(b, roi).empty());
        isa::MachineConfig cfg;
        try {
            fw::plan_forward(b, roi.w, cfg);
            BOOST_ERROR("plan_forward accepted --dissim bt");
        } catch (const fw::FirmwareError& e) {
            BOOST_TEST(std::string(e.what()).find("--dissim bt (the forward-pass test layout") !=
                       std::string::npos);
        }
    }
    {
        // the forward-pass test layout has no border flags for the vertical window
        g::Params v;
        v.agg_ry = 1;
        BOOST_TEST(refusal(v, roi).empty());
        isa::MachineConfig cfg;
        try {
            fw::plan_forward(v, roi.w, cfg);
            BOOST_ERROR("plan_forward accepted --agg-ry 1");
        } catch (const fw::FirmwareError& e) {
            BOOST_TEST(std::string(e.what()).find("--agg-ry 1 (the forward-pass test layout") !=
                       std::string::npos);
        }
    }
    // the forward-pass test layout (host-filled line buffers) has no codes
    g::Params c;
    c.kc = 4;
    BOOST_TEST(refusal(c, roi).empty());
    isa::MachineConfig cfg;
    try {
        fw::plan_forward(c, roi.w, cfg);
        BOOST_ERROR("plan_forward accepted --kc 4");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()).find("--kc 4 (the forward-pass test layout") !=
                   std::string::npos);
    }
}

namespace {
// A random census set: the option params plus kc and the radius.
g::Params random_census_params(std::mt19937& rng, int N) {
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    g::Params p = random_option_params(rng, N);
    const int pick = uni(0, 3);
    p.kc = pick == 0 ? 1 : pick == 1 ? 4 : pick == 2 ? uni(2, 40) : uni(41, 1000);
    p.census = uni(1, 2);
    if (uni(0, 5) == 0) p.km = p.kb = 0;  // a census-only cost
    return p;
}
}  // namespace

BOOST_AUTO_TEST_CASE(census_random_frames) {
    // The census term on every mode, with ad-max and the quality weights:
    // ROI inside a larger random image (the codes clamp into the ROI, not
    // the image), one batch and one segment, random PE counts.
    std::mt19937 rng(4242);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 44), Hi = uni(1, 12);
        const g::Roi roi = random_roi(rng, W, Hi);
        g::Params p = random_census_params(rng, roi.w);
        if (p.mode != g::Mode::Single && p.kc * 8 > 20000) p.kc = 100;
        const int P = random_pes(rng, p, roi, true);
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P)) {
            check_frame(p, fr, roi, P);
        }
    }
}

BOOST_AUTO_TEST_CASE(census_grid_radius_kc_modes_ad_max) {
    std::mt19937 rng(808);
    const Frame fr = random_frame(rng, 72, 24, 24);
    const g::Roi roi{5, 3, 60, 18};
    for (int mode = 0; mode < 3; ++mode)
        for (int r : {1, 2})
            for (int kc : {1, 4, 9})
                for (int ad : {16, 255}) {
                    g::Params p = quality_weights(mode, 20, ad);
                    p.kc = kc;
                    p.census = r;
                    BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                                       << " kc=" << kc << " census=" << r << " ad-max=" << ad) {
                        check_frame(p, fr, roi, 64);
                    }
                }
}

BOOST_AUTO_TEST_CASE(census_headline_and_range) {
    std::mt19937 rng(99);
    const Frame fr = random_frame(rng, 160, 140, 40);
    g::Params q = g::preset("quality");  // joint, km 1, ad-max 16, kc 4, census 2
    q.agg_rx = q.agg_ry = 0;
    q.D = 64;
    q.Wo = q.Wd = 80;
    uint64_t cycles = 0;
    check_frame(q, fr, g::Roi{16, 6, 128, 128}, 256, &cycles);
    BOOST_TEST_MESSAGE("census joint headline cycles: " << cycles);
    // 8*kc enters the 16-bit range check
    g::Params p;
    p.km = 0;
    p.kb = 0;
    p.kc = 4096;  // 32,768 > 32,766
    const g::Roi roi{0, 0, 64, 4};
    BOOST_TEST(refusal(p, roi).find("kb*gb + 8*kc), Wo + Wd) = 32768") != std::string::npos);
    p.kc = 4095;  // 32,760
    BOOST_TEST(refusal(p, roi).empty());
}

BOOST_AUTO_TEST_CASE(census_over_batches_and_segments) {
    isa::MachineConfig cfg;
    g::Params p;
    p.kc = 4;
    p.D = 8;
    std::mt19937 rng(6502);
    const Frame fr = random_frame(rng, 20, 30, p.D);
    // bidir, vote, census radius 2: 3 lines either side of a batch's output.
    // 16 PEs: 8 lines per batch, 2 output (the second batch starts at ROI
    // line 0, less than the halo before its output); 24 PEs: 12 and 6;
    // 14 PEs, the fewest: 7 and 1.
    for (const int P : {16, 24, 14}) {
        cfg.pes = uint32_t(P);
        const fw::FramePlan fp = fw::plan_frame(p, g::Roi{2, 3, 14, 25}, cfg);
        BOOST_TEST(fp.batches.size() > 2u);
        BOOST_TEST_CONTEXT("census over batches, P=" << P) {
            check_frame(p, fr, g::Roi{2, 3, 14, 25}, P);
        }
    }
    cfg.pes = 12;  // 6 lines per batch: too few for the halo
    try {
        fw::plan_frame(p, g::Roi{0, 0, 12, 12}, cfg);
        BOOST_ERROR("census in batches shorter than their halo was accepted");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()) ==
                   "firmware: too few PEs for the lines the batches share: 12 PEs hold 6 line(s) "
                   "per batch, "
                   "and a batch holds 3 line(s) either side of the ones it outputs (the vote 1, "
                   "the census radius 2), so a batch needs 7 lines (use >= 14 PEs, or a ROI of "
                   "at most 6 lines)");
    }
    // video segments: the codes at a segment's edges read the pixels x -+ r
    // of the segments either side (two and three segments, single and bidir)
    const Frame wide = random_frame(rng, 100, 14, p.D);
    for (const auto& [P, w, mode] :
         {std::tuple{32, 40, g::Mode::Bidir}, std::tuple{16, 42, g::Mode::Bidir},
          std::tuple{16, 34, g::Mode::Single}, std::tuple{32, 90, g::Mode::Joint}}) {
        cfg.pes = uint32_t(P);
        g::Params q = p;
        q.mode = mode;
        const g::Roi roi{3, 1, w, 12};
        const fw::FramePlan fp = fw::plan_frame(q, roi, cfg);
        BOOST_TEST(fp.nseg == (w + P - 1) / P);
        BOOST_TEST_CONTEXT("census over segments, P=" << P << " W=" << w) {
            check_frame(q, wide, roi, P);
        }
    }
    cfg.mem_bytes = 1024;
    cfg.pes = 32;  // a last segment narrower than r
    try {
        fw::plan_frame(p, g::Roi{0, 0, 33, 4}, cfg);
        BOOST_ERROR("census with a last segment of 1 pixel was accepted");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()) ==
                   "firmware: --kc 4 (census) over 2 video segments of 32 pixels needs the last "
                   "one at least 2 pixels wide (the census radius): the ROI is 33 wide, the last "
                   "segment 1; use a ROI width of 32 or at least 34 (--roi), or other --pes");
    }
    cfg.pes = 2;  // the one-line-per-batch mode
    p.mode = g::Mode::Single;
    p.D = 2;
    try {
        fw::plan_frame(p, g::Roi{0, 0, 2, 8}, cfg);
        BOOST_ERROR("census in the one-line-per-batch mode was accepted");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()) ==
                   "firmware: too few PEs for the lines the batches share: 2 PEs hold 2 line(s) "
                   "per batch, "
                   "and a batch holds 3 line(s) either side of the ones it outputs (the vote 1, "
                   "the census radius 2), so a batch needs 7 lines (use >= 7 PEs, or a ROI of "
                   "at most 2 lines)");
    }
}

BOOST_AUTO_TEST_CASE(halo_batches_random_frames) {
    // The census and the vertical window over batches: random options,
    // modes and ROIs, each on a PE count that takes at least two batches of
    // at least 2 * halo + 1 lines (the halo either side of a batch's output).
    std::mt19937 rng(1234);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    int clamped = 0;
    for (int it = 0; it < 24; ++it) {
        const int W = uni(4, 24), Hi = uni(10, 40);
        g::Roi roi = random_roi(rng, W, Hi);
        roi.h = std::max(roi.h, std::min(Hi - roi.y0, 10));
        const bool census = uni(0, 1) == 0;
        g::Params p = census ? random_census_params(rng, roi.w) : random_option_params(rng, roi.w);
        p.agg_ry = census && uni(0, 1) == 0 ? 0 : uni(1, 2);
        p.agg_rx = uni(0, 2);
        p.vote = uni(0, 3) != 0;
        fit_window_weights(p);
        const int span = p.mode == g::Mode::Single ? 1 : 2, halo = halo_of(p);
        const int lo = 2 * halo + 1, hi = std::min(roi.h - 1, 3 * halo + 3);
        if (lo > hi) continue;
        const int lines = uni(lo, hi);  // lines per batch < ROI lines: batches
        const int P = census_segments_ok(p, roi, std::max(span * lines, 2));
        if (P / span >= roi.h) continue;
        isa::MachineConfig cfg;
        cfg.pes = static_cast<uint32_t>(P);
        cfg.mem_bytes = 2048;
        const fw::FramePlan fp = fw::plan_frame(p, roi, cfg);
        BOOST_TEST(fp.batches.size() > 1u);
        if (P / span - 2 * halo < halo) ++clamped;  // a batch starts at ROI line 0 late
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P) << " halo=" << halo) {
            check_frame(p, fr, roi, P, nullptr, 2048);
        }
    }
    BOOST_TEST(clamped > 0);
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
            BOOST_TEST((f.dissim == p.dissim));
            BOOST_TEST((f.mode == p.mode));
            BOOST_TEST((f.kc == p.kc && f.census == p.census));
            BOOST_TEST((f.agg_rx == p.agg_rx && f.agg_ry == p.agg_ry));
            // never refused for an option; a variant may not fit the memory
            // (quality-single: the window copies need 1,072 bytes per PE)
            const std::string why = refusal(f, roi);
            BOOST_TEST((why.empty() || why.find("does not fit") != std::string::npos), why);
        }
    }
    // the quality preset is its own firmware part
    g::Params q = g::preset("quality");
    q.D = 64;
    BOOST_TEST(refusal(q, roi).empty());
    BOOST_TEST(fw::firmware_part(q).agg_rx == q.agg_rx);
}

BOOST_AUTO_TEST_CASE(joint_votes_seeds_frames_batches) {
    // SPEC A.9 joint on the firmware: vote on/off, free and fixed seeds, a
    // fixed seed column, every frame, one batch (64 PEs) and batches of 4
    // lines (8 PEs, the ROI is taller than the array).
    std::mt19937 rng(202);
    const Frame fr = random_frame(rng, 72, 40, 24);
    const g::Roi roi{4, 3, 64, 34};
    const g::Frame frames[] = {g::Frame::Cyclopean, g::Frame::Left, g::Frame::Right};
    for (int P : {8, 64})
        for (int vote = 0; vote < 2; ++vote)
            for (int seed = 0; seed < 3; ++seed)
                for (g::Frame f : frames) {
                    g::Params p;
                    p.D = 24;
                    p.mode = g::Mode::Joint;
                    p.vote = vote != 0;
                    p.frame = f;
                    if (seed == 1) {
                        p.seed_disp.free = false;
                        p.seed_disp.value = 5;
                    } else if (seed == 2) {
                        p.seed_col.kind = g::SeedColKind::Fixed;
                        p.seed_col.value = 9;
                        p.ad_max = 16;
                    }
                    BOOST_TEST_CONTEXT("P=" << P << " " << describe(p, roi.w, roi.h)
                                            << " vote=" << p.vote << " frame=" << g::to_string(f)) {
                        check_frame(p, fr, roi, P);
                    }
                }
}

BOOST_AUTO_TEST_CASE(joint_edges_d_and_headline) {
    std::mt19937 rng(77);
    const Frame fr = random_frame(rng, 160, 140, 40);
    for (int D : {1, 2, 17, 32}) {  // D = 32 = the ROI width: every level of site s
        g::Params p;
        p.mode = g::Mode::Joint;
        p.D = D;
        BOOST_TEST_CONTEXT("D=" << D) {
            check_frame(p, fr, g::Roi{3, 2, 32, 12}, 64);
        }
    }
    for (int c : {1, 30}) {  // the seed column at both ends of a 32-wide ROI
        g::Params p;
        p.mode = g::Mode::Joint;
        p.D = 12;
        p.seed_col.kind = g::SeedColKind::Fixed;
        p.seed_col.value = c;
        BOOST_TEST_CONTEXT("seed col " << c) {
            check_frame(p, fr, g::Roi{0, 0, 32, 9}, 32);
        }
    }
    g::Params p;  // ROI width 2, one line
    p.mode = g::Mode::Joint;
    p.D = 2;
    check_frame(p, fr, g::Roi{7, 7, 2, 1}, 4);
    g::Params q;  // the headline with the quality preset's pixel weights
    q.mode = g::Mode::Joint;
    q.D = 64;
    q.km = 1;
    q.kb = 0;
    q.gb = 0;
    q.ad_max = 16;
    q.Wo = q.Wd = 400;
    uint64_t cycles = 0;
    check_frame(q, fr, g::Roi{16, 6, 128, 128}, 256, &cycles);
    BOOST_TEST_MESSAGE("joint headline cycles: " << cycles);
}

BOOST_AUTO_TEST_CASE(joint_one_line_per_batch_is_refused) {
    g::Params p;
    p.mode = g::Mode::Joint;
    p.D = 8;
    isa::MachineConfig cfg;
    cfg.pes = 4;  // 2 lines per batch: the one-line-per-batch mode with the vote
    try {
        fw::plan_frame(p, g::Roi{0, 0, 32, 8}, cfg);
        BOOST_ERROR("joint with 4 PEs and the vote was accepted");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()).find("needs at least 3 lines per batch") !=
                   std::string::npos);
    }
    p.vote = false;  // without the vote, 2 lines per batch are fine
    std::mt19937 rng(3);
    check_frame(p, random_frame(rng, 32, 8, 8), g::Roi{0, 0, 32, 8}, 4);
}

BOOST_AUTO_TEST_CASE(window_random_frames) {
    // SPEC A.9 horizontal aggregation (agg-rx 1..2, agg-ry 0) with and
    // without the census, every mode; without the census also over batches,
    // video segments and the one-line-per-batch mode.
    std::mt19937 rng(5150);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 44), Hi = uni(1, 12);
        const g::Roi roi = random_roi(rng, W, Hi);
        const bool census = uni(0, 1) == 0;
        g::Params p = census ? random_census_params(rng, roi.w) : random_option_params(rng, roi.w);
        p.agg_rx = uni(1, 2);
        if (p.kc * 8 > 2000) p.kc = 100;
        while (g::Params(p).km * std::min(255, p.ad_max) + p.kb * p.gb + 8 * p.kc > 6500) p.km /= 2;
        if (p.km == 0 && p.kb == 0 && p.kc == 0) p.km = 1;
        const int P = random_pes(rng, p, roi, census);
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P)) {
            check_frame(p, fr, roi, P);
        }
    }
}

BOOST_AUTO_TEST_CASE(window_grid_and_headline) {
    std::mt19937 rng(616);
    const Frame fr = random_frame(rng, 72, 24, 24);
    const g::Roi roi{5, 3, 60, 18};
    for (int mode = 0; mode < 3; ++mode)
        for (int rx : {1, 2})
            for (int kc : {0, 4}) {
                g::Params p = quality_weights(mode, 20, 16);
                p.kc = kc;
                p.agg_rx = rx;
                BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h) << " agg-rx=" << rx << " kc=" << kc) {
                    // most slots update the previous column's window sum
                    // (AGG_BODY's agginc); the first column and the level a
                    // kind gains at the bottom are summed whole
                    isa::MachineConfig cfg;
                    cfg.pes = 64;
                    const fw::FramePlan fp = fw::plan_frame(p, roi, cfg);
                    int64_t inc = 0;
                    for (const fw::ForwardPass& ps : fp.f.passes) {
                        BOOST_TEST(ps.rfull + ps.rinc <= ps.n);
                        BOOST_TEST((ps.k > 1 || ps.rinc == 0));
                        inc += ps.rinc;
                    }
                    BOOST_TEST(2 * inc > fp.f.slots);
                    check_frame(p, fr, roi, 64);
                }
            }
    // the headline with census + a 5x1 window (quality weights, Wo = Wd = 80)
    const Frame big = random_frame(rng, 160, 140, 40);
    g::Params q = g::preset("quality");
    q.agg_ry = 0;
    q.D = 64;
    q.Wo = q.Wd = 80;
    uint64_t cycles = 0;
    check_frame(q, big, g::Roi{16, 6, 128, 128}, 256, &cycles);
    BOOST_TEST_MESSAGE("census + 5x1 joint headline cycles: " << cycles);
    // the window multiplies Wm_max in the 16-bit range check
    g::Params r;
    r.km = 30;
    r.kb = 0;
    r.agg_rx = 2;  // 5 * 30 * 255 = 38,250 > 32,766
    BOOST_TEST(refusal(r, g::Roi{0, 0, 64, 4}).find("= 38250 exceeds") != std::string::npos);
    r.agg_rx = 1;  // 22,950
    BOOST_TEST(refusal(r, g::Roi{0, 0, 64, 4}).empty());
}

BOOST_AUTO_TEST_CASE(census_on_skewed_rows) {
    // Where the lines do not fill the ring, census frames take the skewed
    // video rows (docs/firmware.md, section 5): pixel x of line y on lane
    // x + span * y, so the codes read the rows y -+ r span * r hops away and
    // the first and last r lines (clamped neighbours) are emitted one by
    // one. Every mode, both radii, ROIs of 1 to 12 lines (no middle loop up
    // to 2r + 1 lines), with and without the windows.
    std::mt19937 rng(4242);
    const Frame fr = random_frame(rng, 30, 16, 8);
    int runs = 0;
    for (int mode = 0; mode < 3; ++mode)
        for (int r : {1, 2})
            for (int H : {1, 2, 3, 4, 5, 6, 12}) {
                g::Params p;
                p.D = 8;
                p.mode = mode_of(mode);
                p.kc = 3;
                p.census = r;
                p.agg_rx = H % 3 == 0 ? 1 : 0;
                p.agg_ry = H % 4 == 0 ? 1 : 0;
                const g::Roi roi{3, 1, 20, H};
                isa::MachineConfig cfg;
                cfg.pes = 64;
                BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                                   << " census=" << r << " agg-rx=" << p.agg_rx
                                   << " agg-ry=" << p.agg_ry) {
                    // (the planner weighs them against the direct routes,
                    // cheaper for a few lines: take them here)
                    const fw::FramePlan fp = fw::plan_frame(p, roi, cfg, fw::SpillLayout::Cheaper,
                                                            fw::RowLayout::Skewed);
                    BOOST_TEST(fp.rl.skew);
                    check_frame(p, fr, roi, 64, nullptr, 0, fw::RowLayout::Skewed);
                    ++runs;
                }
            }
    BOOST_TEST(runs == 42);
}

BOOST_AUTO_TEST_CASE(vertical_window_random_frames) {
    // SPEC A.9 vertical aggregation (agg-ry 1..3) over random frames: with and
    // without the horizontal window, the census and bt, every mode, the
    // ROI's lines in one batch or in batches of the halo, video segments
    // without the census; both the one-byte and the two-byte row sums.
    std::mt19937 rng(8086);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    int h8 = 0, h16 = 0;
    for (int it = 0; it < 40; ++it) {
        const int W = uni(4, 40), Hi = uni(1, 12);
        const g::Roi roi = random_roi(rng, W, Hi);
        const bool census = uni(0, 2) == 0;
        g::Params p = census ? random_census_params(rng, roi.w) : random_option_params(rng, roi.w);
        p.agg_ry = uni(1, 3);
        p.agg_rx = uni(0, 2);
        if (uni(0, 3) == 0) p.dissim = g::Dissim::Bt;
        fit_window_weights(p);
        const int span = p.mode == g::Mode::Single ? 1 : 2;
        const int lines = std::min(roi.h, 2 * halo_of(p) + 1);  // batches of the halo
        int P = uni(std::max({p.mode == g::Mode::Joint ? 6 : 2, span * lines}), 48);
        if (census) P = census_segments_ok(p, roi, P);
        isa::MachineConfig cfg;
        cfg.pes = static_cast<uint32_t>(P);
        cfg.mem_bytes = 2048;  // the bt bounds of the window copies need more than 1 KB
        const fw::FramePlan fp = fw::plan_frame(p, roi, cfg);
        (fp.f.h8 ? h8 : h16) += 1;
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P) << " h8=" << fp.f.h8) {
            check_frame(p, fr, roi, P, nullptr, 2048);
        }
    }
    BOOST_TEST(h8 > 0);
    BOOST_TEST(h16 > 0);
}

BOOST_AUTO_TEST_CASE(vertical_window_grid_headline_and_refusals) {
    std::mt19937 rng(1999);
    const Frame fr = random_frame(rng, 72, 24, 24);
    const g::Roi roi{5, 3, 60, 18};
    for (int mode = 0; mode < 3; ++mode)
        for (int ry : {1, 2})
            for (int rx : {0, 2})
                for (int kc : {0, 4}) {
                    g::Params p = quality_weights(mode, 20, 16);
                    p.kc = kc;
                    p.agg_rx = rx;
                    p.agg_ry = ry;
                    BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                                       << " agg-rx=" << rx << " agg-ry=" << ry << " kc=" << kc) {
                        check_frame(p, fr, roi, 64);
                    }
                }
    // the paper's weights: two-byte row sums
    g::Params w;
    w.D = 16;
    w.agg_ry = 2;
    w.agg_rx = 1;
    {
        isa::MachineConfig cfg;
        cfg.pes = 64;
        BOOST_TEST(!fw::plan_frame(w, roi, cfg).f.h8);
    }
    check_frame(w, fr, roi, 64);
    // the headline with the 5x5 window (quality, agg-ry 2)
    const Frame big = random_frame(rng, 160, 140, 40);
    g::Params q = g::preset("quality");
    q.agg_ry = 2;
    q.D = 64;
    uint64_t cycles = 0;
    check_frame(q, big, g::Roi{16, 6, 128, 128}, 256, &cycles);
    BOOST_TEST_MESSAGE("quality 5x5 joint headline cycles: " << cycles);
    BOOST_TEST(cycles <= 40u * 40000u);  // within the 40 ms budget at 40 MHz
    // the vertical part multiplies Wm_max in the 16-bit range check
    g::Params r;
    r.km = 30;
    r.kb = 0;
    r.agg_ry = 2;  // 5 * 30 * 255 = 38,250 > 32,766
    BOOST_TEST(refusal(r, g::Roi{0, 0, 64, 4}).find("= 38250 exceeds") != std::string::npos);
    BOOST_TEST(refusal(r, g::Roi{0, 0, 64, 4}).find("--agg-ry") != std::string::npos);
    r.agg_ry = 1;  // 22,950
    BOOST_TEST(refusal(r, g::Roi{0, 0, 64, 4}).empty());
    // the lines of the window over batches: the halo is the vote's line, the
    // window's 2 and the census's 2 (joint, 2 PEs per line)
    g::Params b = g::preset("quality");
    b.agg_ry = 2;
    b.D = 8;
    isa::MachineConfig small;
    small.pes = 20;
    try {
        fw::plan_frame(b, g::Roi{0, 0, 16, 12}, small);
        BOOST_ERROR("a vertical window in batches shorter than their halo was accepted");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(
            std::string(e.what()) ==
                "firmware: too few PEs for the lines the batches share: 20 PEs hold 10 line(s) per "
                "batch, and a batch holds 5 line(s) either side of the ones it outputs "
                "(the vote 1, --agg-ry 2, the census radius 2), so a batch needs 11 lines "
                "(use >= 22 PEs, or a ROI of at most 10 lines)",
            e.what());
    }
    small.pes = 22;
    const Frame tall = random_frame(rng, 24, 20, b.D);
    check_frame(b, tall, g::Roi{2, 1, 16, 18}, 22);
    g::Params t;  // the one-line-per-batch mode (bidir, 4 PEs, the vote)
    t.agg_ry = 1;
    t.D = 4;
    small.pes = 4;
    BOOST_CHECK_THROW(fw::plan_frame(t, g::Roi{0, 0, 16, 5}, small), fw::FirmwareError);
}

BOOST_AUTO_TEST_CASE(bt_random_frames) {
    // SPEC A.9 dissim bt: with and without the census and the horizontal
    // window, every mode, batches, video segments and the one-line-per-batch
    // mode (without the census), ad-max, random weights.
    std::mt19937 rng(4711);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 48; ++it) {
        const int W = uni(4, 44), Hi = uni(1, 12);
        const g::Roi roi = random_roi(rng, W, Hi);
        const bool census = uni(0, 2) == 0;
        g::Params p = census ? random_census_params(rng, roi.w) : random_option_params(rng, roi.w);
        p.dissim = g::Dissim::Bt;
        if (p.km == 0) p.km = 1;
        p.agg_rx = uni(0, 3) == 0 ? 0 : uni(0, 2);
        if (p.kc * 8 > 2000) p.kc = 100;
        while ((2 * p.agg_rx + 1) * (p.km * std::min(255, p.ad_max) + p.kb * p.gb + 8 * p.kc) >
                   30000 &&
               p.km > 1)
            p.km /= 2;
        if ((2 * p.agg_rx + 1) * (p.km * std::min(255, p.ad_max) + p.kb * p.gb + 8 * p.kc) > 30000)
            p.kc = 1;
        const int P = random_pes(rng, p, roi, census);
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(options_context(p, roi, P)) {
            check_frame(p, fr, roi, P);
        }
    }
}

BOOST_AUTO_TEST_CASE(bt_grid_modes_window_census_and_headline) {
    std::mt19937 rng(2718);
    const Frame fr = random_frame(rng, 72, 24, 24);
    const g::Roi roi{5, 3, 60, 18};
    for (int mode = 0; mode < 3; ++mode)
        for (int rx : {0, 1, 2})
            for (int kc : {0, 4})
                for (int ad : {16, 255}) {
                    g::Params p;
                    p.D = 20;
                    p.mode = mode_of(mode);
                    p.dissim = g::Dissim::Bt;
                    p.km = kc > 0 ? 1 : 8;
                    p.kb = kc > 0 ? 0 : 1;
                    p.gb = kc > 0 ? 0 : 64;
                    p.Wo = p.Wd = 80;
                    p.ad_max = ad;
                    p.kc = kc;
                    p.agg_rx = rx;
                    BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                                       << " bt agg-rx=" << rx << " kc=" << kc << " ad-max=" << ad) {
                        check_frame(p, fr, roi, 64);
                    }
                }
    // bt differs from ad on this scene (the test can tell them apart)
    {
        g::Params a;
        a.D = 20;
        g::Params b = a;
        b.dissim = g::Dissim::Bt;
        uint64_t ca = 0, cb = 0;
        check_frame(a, fr, roi, 64, &ca);
        check_frame(b, fr, roi, 64, &cb);
        BOOST_TEST(cb > ca);  // the bounds phase and the longer node
    }
    // the quality preset with bt at the headline
    const Frame big = random_frame(rng, 160, 140, 40);
    g::Params q = g::preset("quality");
    q.dissim = g::Dissim::Bt;
    q.D = 64;
    // the window's copies and their bounds do not fit 1024 bytes: refused
    // with the least memory that does (1,392 for the copies, constants and
    // costs of the 5x1 window, + 2 for the vertical window's border flags),
    // and bit-exact with it
    BOOST_TEST(refusal(q, g::Roi{16, 6, 128, 128}).find("needs at least 1394 bytes") !=
               std::string::npos);
    uint64_t cycles = 0;
    check_frame(q, big, g::Roi{16, 6, 128, 128}, 256, &cycles, 1394);
    BOOST_TEST_MESSAGE("quality + bt headline cycles: " << cycles);
}

BOOST_AUTO_TEST_CASE(bt_memory_refusal_is_precise) {
    // the bounds take 2 bytes per line-buffer byte: a memory that fits ad but
    // not bt is refused with the least memory that would do
    g::Params p;
    p.D = 32;
    const g::Roi roi{0, 0, 96, 4};
    isa::MachineConfig cfg;
    const fw::FramePlan ad = fw::plan_frame(p, roi, cfg);
    p.dissim = g::Dissim::Bt;
    const fw::FramePlan bt = fw::plan_frame(p, roi, cfg);
    BOOST_TEST(bt.f.preg > ad.f.preg);
    cfg.mem_bytes = static_cast<uint32_t>(bt.f.preg - 1);
    try {
        fw::plan_frame(p, roi, cfg);
        BOOST_ERROR("bt accepted with too little memory");
    } catch (const fw::FirmwareError& e) {
        BOOST_TEST(std::string(e.what()).find("does not fit: needs at least") != std::string::npos,
                   e.what());
    }
}
