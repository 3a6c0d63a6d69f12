// The whole firmware (dp.s: video in, re-layout, DP, vote, backtrack, merge,
// re-layout, video out) on the bare machine core: the disparity map leaving
// the video output must equal the golden's, bit for bit.
#define BOOST_TEST_MODULE firmware_frame
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"

using namespace fwtest;

namespace {

struct Frame {
    int W = 0, H = 0;
    std::vector<uint8_t> L, R;
};

Frame random_frame(std::mt19937& rng, int W, int H, int D) {
    Frame f;
    f.W = W;
    f.H = H;
    const std::vector<Line> lines = random_lines(rng, W, H, std::max(1, std::min(D, W)));
    for (const Line& ln : lines) {
        f.L.insert(f.L.end(), ln.L.begin(), ln.L.end());
        f.R.insert(f.R.end(), ln.R.begin(), ln.R.end());
    }
    return f;
}

void check_frame(const g::Params& p, const Frame& fr, const g::Roi& roi, int P,
                 uint64_t* cycles = nullptr) {
    isa::MachineConfig cfg;
    cfg.pes = uint32_t(P);
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg);
    const isa::Program prog = fw::assemble_frame(p, plan);
    isa::Machine m(cfg);
    m.load(prog);
    for (const auto& [i, v] : fw::param_block(plan)) m.set_param(i, v);
    isa::ImageVideoPort video;
    video.input[0] = {fr.W, fr.H, fr.L};
    video.input[1] = {fr.W, fr.H, fr.R};
    video.make_output(0, roi.w, roi.h);
    m.set_video(&video);
    m.run();
    BOOST_REQUIRE(m.halted());
    if (cycles) *cycles = m.cycles();

    const g::DisparityMap want = g::compute(p, g::ImageView{fr.L.data(), fr.W, fr.H, fr.W},
                                            g::ImageView{fr.R.data(), fr.W, fr.H, fr.W}, roi);
    int bad = 0;
    for (int y = 0; y < roi.h; ++y)
        for (int x = 0; x < roi.w; ++x) {
            const int got = video.output[0].pixels[size_t(y) * roi.w + x];
            const int exp = want.at(x, y);
            if (got != exp && ++bad <= 5)
                BOOST_ERROR("(" << x << "," << y << "): firmware " << got << " golden " << exp);
        }
    BOOST_TEST(bad == 0);
}

}  // namespace

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
        int P = uni(2, 24);
        if (p.vote && P < 6) P = 6;  // the vote across batches needs 3 lines per batch
        const Frame fr = random_frame(rng, W, Hi, p.D);
        BOOST_TEST_CONTEXT(describe(p, roi.w, roi.h)
                           << " vote=" << p.vote << " frame=" << g::to_string(p.frame)
                           << " P=" << P << " roi=" << roi.x0 << "," << roi.y0 << " image " << W
                           << "x" << Hi) {
            check_frame(p, fr, roi, P);
        }
    }
}
