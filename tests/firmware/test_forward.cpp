// The forward pass of the DP firmware on the bare machine core: every PE's
// pointer table must equal the golden's bp (right wavefront / single) or fp
// (left wavefront, mirrored) on every valid, reachable state.
#define BOOST_TEST_MODULE firmware_forward
#include <boost/test/unit_test.hpp>
#include <random>
#include <sstream>

#include "fw_test_util.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;

namespace {

using namespace fwtest;

uint8_t fw_pointer(const isa::Machine& m, int pe, const fw::ForwardPlan& f, int kind, int k,
                   int j) {
    return f.pointer(
        kind, k, j, [&](uint32_t a) { return m.mem_read(pe, a); },
        [&](uint32_t a) { return m.ext_read(pe, a); });
}

void check_case(const g::Params& p, int N, int H, std::mt19937& rng) {
    isa::MachineConfig cfg;
    const bool bidir = p.mode == g::Mode::Bidir;
    cfg.pes = bidir ? 2 * H : std::max(H, 2);
    cfg.mem_bytes = 4096;
    const fw::ForwardPlan f = fw::plan_forward(p, N, cfg);
    const isa::Program prog = fw::assemble_test(p, f, "dp_forward_test.s", H, int(cfg.pes));
    isa::Machine m(cfg);
    m.load(prog);

    const std::vector<Line> lines = random_lines(rng, N, H, p.D);
    load_lines(m, f, lines);
    m.run();
    BOOST_REQUIRE(m.halted());

    int checked = 0, bad = 0;
    for (int y = 0; y < H && bad < 5; ++y) {
        g::LineTables t;
        g::forward_line(p, lines[size_t(y)].L.data(), lines[size_t(y)].R.data(), N, t);
        if (!bidir) {
            for (int site = 0; site < N; ++site)
                for (int j = 0; j < g::levels_at(site, N, p.D); ++j) {
                    const uint8_t want = t.bp(site, j);
                    if (want == g::kNone) continue;
                    const uint8_t got = fw_pointer(m, y, f, 0, site + 1, j);
                    ++checked;
                    if (got != want && ++bad <= 5)
                        BOOST_ERROR("single line " << y << " bp(" << site << "," << j
                                                   << ") firmware " << int(got) << " golden "
                                                   << int(want));
                }
            continue;
        }
        for (int site = f.s + 1; site < N; ++site)
            for (int j = 0; j < g::levels_at(site, N, p.D); ++j) {
                const uint8_t want = t.bp(site, j);
                if (want == g::kNone) continue;
                const uint8_t got = fw_pointer(m, 2 * y + 1, f, 1, site - f.s, j);
                ++checked;
                if (got != want && ++bad <= 5)
                    BOOST_ERROR("right line " << y << " bp(" << site << "," << j << ") firmware "
                                              << int(got) << " golden " << int(want));
            }
        for (int site = -1; site <= f.s - 2; ++site)
            for (int j = 0; j < (site < 0 ? p.D : g::levels_at(site, N, p.D)); ++j) {
                const uint8_t want = t.fp(site, j);
                if (want == g::kNone) continue;
                const uint8_t got = fw_pointer(m, 2 * y, f, 0, f.s - 1 - site, p.D - 1 - j);
                ++checked;
                if (got != want && ++bad <= 5)
                    BOOST_ERROR("left line " << y << " fp(" << site << "," << j << ") firmware "
                                             << int(got) << " golden " << int(want));
            }
    }
    BOOST_TEST(checked > 0);
}

}  // namespace

BOOST_AUTO_TEST_CASE(headline_sized_line_default_weights) {
    std::mt19937 rng(1);
    g::Params p;  // defaults: bidir, balanced seed, free
    p.D = 64;
    BOOST_TEST_CONTEXT(describe(p, 128, 4)) {
        check_case(p, 128, 4, rng);
    }
}

BOOST_AUTO_TEST_CASE(random_parameter_sets) {
    std::mt19937 rng(7);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 60; ++it) {
        const int N = uni(2, 40);
        const g::Params p = random_params(rng, N);
        const int H = uni(1, 4);
        BOOST_TEST_CONTEXT(describe(p, N, H)) {
            check_case(p, N, H, rng);
        }
    }
}

BOOST_AUTO_TEST_CASE(out_of_range_weights_are_refused) {
    isa::MachineConfig cfg;
    g::Params p;
    p.km = 1000;
    BOOST_CHECK_THROW(fw::plan_forward(p, 128, cfg), fw::FirmwareError);
    g::Params q;
    q.Wo = q.Wd = 100000;
    BOOST_CHECK_THROW(fw::plan_forward(q, 128, cfg), fw::FirmwareError);
}
