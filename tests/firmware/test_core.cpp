// The DP core of the firmware (set-up, start column, forward pass, vote,
// backtrack, merge) on the bare machine core with host-filled line buffers:
// every output line must equal the golden's, bit for bit.
#define BOOST_TEST_MODULE firmware_core
#include <boost/test/unit_test.hpp>

#include "fw_test_util.hpp"

using namespace fwtest;

namespace {

void check_core(const g::Params& p, int N, int H, std::mt19937& rng) {
    isa::MachineConfig cfg;
    const bool bidir = p.mode == g::Mode::Bidir;
    cfg.pes = bidir ? 2 * H : std::max(H, 2);
    cfg.mem_bytes = 4096;
    const fw::ForwardPlan f = fw::plan_forward(p, N, cfg);
    const isa::Program prog = fw::assemble_test(p, f, "dp_core_test.s", H, int(cfg.pes));
    isa::Machine m(cfg);
    m.load(prog);
    const std::vector<Line> lines = random_lines(rng, N, H, p.D);
    load_lines(m, f, lines);
    m.run();
    BOOST_REQUIRE(m.halted());

    std::vector<uint8_t> L(size_t(N) * H), R(size_t(N) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < N; ++x) {
            L[size_t(y) * N + x] = lines[size_t(y)].L[size_t(x)];
            R[size_t(y) * N + x] = lines[size_t(y)].R[size_t(x)];
        }
    const g::DisparityMap want = g::compute(p, g::ImageView{L.data(), N, H, N},
                                            g::ImageView{R.data(), N, H, N}, g::Roi{0, 0, N, H});
    int bad = 0;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < N; ++x) {
            const int pe = bidir ? 2 * y + (x & 1) : y;
            const int got = m.mem_read(pe, uint32_t(f.map + x));
            const int exp = want.at(x, y);
            if (got != exp && ++bad <= 5)
                BOOST_ERROR("line " << y << " x " << x << ": firmware " << got << " golden "
                                    << exp);
        }
    }
    BOOST_TEST(bad == 0);
}

}  // namespace

BOOST_AUTO_TEST_CASE(headline_sized_lines) {
    std::mt19937 rng(3);
    g::Params p;
    p.D = 64;
    BOOST_TEST_CONTEXT(describe(p, 128, 6)) {
        check_core(p, 128, 6, rng);
    }
}

BOOST_AUTO_TEST_CASE(random_parameter_sets) {
    std::mt19937 rng(11);
    for (int it = 0; it < 120; ++it) {
        const int N = std::uniform_int_distribution<int>(2, 40)(rng);
        const g::Params p = random_params(rng, N);
        const int H = std::uniform_int_distribution<int>(1, 5)(rng);
        BOOST_TEST_CONTEXT(describe(p, N, H)
                           << " vote=" << p.vote << " frame=" << g::to_string(p.frame)) {
            check_core(p, N, H, rng);
        }
    }
}
