// The forward pass of the DP firmware on the bare machine core: every PE's
// pointer table must equal the golden's bp (right wavefront / single) or fp
// (left wavefront, mirrored) on every valid, reachable state.
#define BOOST_TEST_MODULE firmware_forward
#include <boost/test/unit_test.hpp>
#include <random>
#include <sstream>

#include "imap/firmware/plan.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;

namespace {

struct Line {
    std::vector<uint8_t> L, R;
};

std::string describe(const g::Params& p, int N, int H) {
    std::ostringstream os;
    os << "N=" << N << " H=" << H << " D=" << p.D << " mode=" << g::to_string(p.mode)
       << " seed=" << g::seed_col_string(p.seed_col) << "/" << g::seed_disp_string(p.seed_disp)
       << " km=" << p.km << " kb=" << p.kb << " gb=" << p.gb << " Wo=" << p.Wo
       << " Wd=" << p.Wd;
    return os.str();
}

// Fills the PE's R' / L' buffers as docs/firmware.md section 1 lays them out.
void fill_buffers(isa::Machine& m, int pe, const fw::ForwardPlan& f, const Line& ln, bool left) {
    auto put = [&](int base, int idx, int v) { m.mem_write(pe, uint32_t(base + idx), uint8_t(v)); };
    const int N = f.N;
    for (int k = 0; k <= f.kmax; ++k) {
        int x = -1;
        if (!f.bidir)
            x = k - 1;
        else
            x = left ? f.s - k : f.s + k;
        put(f.imgr, k, x >= 0 && x < N ? ln.R[x] : 0);
    }
    for (int mi = 0; mi < f.kmax + f.D + 1; ++mi) {
        int x = -1;
        if (!f.bidir)
            x = mi - 1;
        else
            x = left ? f.s + f.D - 1 - mi : f.s + mi;
        put(f.imgl, mi, x >= 0 && x < N ? ln.L[x] : 0);
    }
}

uint8_t fw_pointer(const isa::Machine& m, int pe, const fw::ForwardPlan& f, int k, int j) {
    const uint8_t byte = m.ext_read(pe, uint32_t((k - 1) * f.dq + j / 4));
    return uint8_t((byte >> (2 * (3 - j % 4))) & 3);
}

void check_case(const g::Params& p, int N, int H, std::mt19937& rng) {
    isa::MachineConfig cfg;
    const bool bidir = p.mode == g::Mode::Bidir;
    cfg.pes = bidir ? 2 * H : std::max(H, 2);
    cfg.mem_bytes = 4096;
    const fw::ForwardPlan f = fw::plan_forward(p, N, cfg);
    const isa::Program prog = fw::assemble_forward(p, f);
    isa::Machine m(cfg);
    m.load(prog);

    std::vector<Line> lines(static_cast<size_t>(H));
    std::uniform_int_distribution<int> pix(0, 255);
    for (auto& ln : lines) {
        ln.L.resize(size_t(N));
        ln.R.resize(size_t(N));
        for (int x = 0; x < N; ++x) ln.R[size_t(x)] = uint8_t(pix(rng));
        const int shift = std::uniform_int_distribution<int>(0, p.D - 1)(rng);
        for (int x = 0; x < N; ++x)
            ln.L[size_t(x)] = x - shift >= 0 ? uint8_t(std::min(255, ln.R[size_t(x - shift)] + pix(rng) % 9))
                                             : uint8_t(pix(rng));
    }
    for (int y = 0; y < H; ++y) {
        if (bidir) {
            fill_buffers(m, 2 * y, f, lines[size_t(y)], true);
            fill_buffers(m, 2 * y + 1, f, lines[size_t(y)], false);
        } else {
            fill_buffers(m, y, f, lines[size_t(y)], false);
        }
    }
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
                    const uint8_t got = fw_pointer(m, y, f, site + 1, j);
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
                const uint8_t got = fw_pointer(m, 2 * y + 1, f, site - f.s, j);
                ++checked;
                if (got != want && ++bad <= 5)
                    BOOST_ERROR("right line " << y << " bp(" << site << "," << j << ") firmware "
                                              << int(got) << " golden " << int(want));
            }
        for (int site = -1; site <= f.s - 2; ++site)
            for (int j = 0; j < (site < 0 ? p.D : g::levels_at(site, N, p.D)); ++j) {
                const uint8_t want = t.fp(site, j);
                if (want == g::kNone) continue;
                const uint8_t got = fw_pointer(m, 2 * y, f, f.s - 1 - site, p.D - 1 - j);
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
    BOOST_TEST_CONTEXT(describe(p, 128, 4)) { check_case(p, 128, 4, rng); }
}

BOOST_AUTO_TEST_CASE(random_parameter_sets) {
    std::mt19937 rng(7);
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int it = 0; it < 60; ++it) {
        g::Params p;
        const int N = uni(2, 40);
        p.D = uni(1, std::min(N, 40));
        p.km = uni(0, 20);
        p.kb = uni(0, 4);
        if (p.km == 0 && p.kb == 0) p.km = 1;
        p.gb = uni(0, 255);
        p.Wd = uni(0, 200);
        p.Wo = p.Wd + uni(0, 200);
        p.mode = uni(0, 1) ? g::Mode::Bidir : g::Mode::Single;
        const int sc = uni(0, 2);
        p.seed_col.kind = sc == 0   ? g::SeedColKind::Balanced
                          : sc == 1 ? g::SeedColKind::Center
                                    : g::SeedColKind::Fixed;
        if (p.mode == g::Mode::Bidir && N < 2) p.mode = g::Mode::Single;
        p.seed_col.value = uni(1, std::max(1, N - 1));
        p.seed_disp.free = uni(0, 1) == 0;
        if (p.mode == g::Mode::Bidir && !p.seed_disp.free) {
            const int s = g::resolve_seed_col(p, N);
            p.seed_disp.value = uni(0, std::min(p.D - 1, N - 1 - s));
        }
        const int H = uni(1, 4);
        BOOST_TEST_CONTEXT(describe(p, N, H)) { check_case(p, N, H, rng); }
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
