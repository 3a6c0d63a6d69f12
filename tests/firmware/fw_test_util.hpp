// Helpers shared by the firmware tests: parameter sets, line buffers.
#pragma once

#include <boost/test/unit_test.hpp>
#include <random>
#include <sstream>

#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"

namespace fwtest {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;

struct Line {
    std::vector<uint8_t> L, R;
};

inline std::string describe(const g::Params& p, int N, int H) {
    std::ostringstream os;
    os << "N=" << N << " H=" << H << " D=" << p.D << " mode=" << g::to_string(p.mode)
       << " seed=" << g::seed_col_string(p.seed_col) << "/" << g::seed_disp_string(p.seed_disp)
       << " km=" << p.km << " kb=" << p.kb << " gb=" << p.gb << " Wo=" << p.Wo << " Wd=" << p.Wd;
    return os.str();
}

// Fills the PE's R' / L' buffers as docs/firmware.md section 1 lays them out.
inline void fill_buffers(isa::Machine& m, int pe, const fw::ForwardPlan& f, const Line& ln,
                         bool left) {
    const int N = f.N;
    auto px = [&](const std::vector<uint8_t>& v, int x) {
        return x >= 0 && x < N ? v[size_t(x)] : 0;
    };
    for (int k = 0; k <= f.kr; ++k) {
        const int x = !f.bidir ? k - 1 : left ? f.s - k : f.s + k;
        m.mem_write(pe, uint32_t(f.rp_addr(k)), uint8_t(px(ln.R, x)));
    }
    const int kind = f.bidir && !left ? 1 : 0;
    for (int mi = 0; mi <= f.kl - f.lsh[kind]; ++mi) {
        const int x = !f.bidir ? mi - 1 : left ? f.s + f.D - 1 - mi : f.s + mi;
        m.mem_write(pe, uint32_t(f.lp_addr(mi, kind)), uint8_t(px(ln.L, x)));
    }
}

// Host-fills every PE's line buffers: line y on PEs 2y (left wavefront) and
// 2y+1 (right) in bidir mode, on PE y in single mode.
inline void load_lines(isa::Machine& m, const fw::ForwardPlan& f, const std::vector<Line>& lines) {
    for (size_t y = 0; y < lines.size(); ++y) {
        const int yi = static_cast<int>(y);
        if (f.bidir) {
            fill_buffers(m, 2 * yi, f, lines[y], true);
            fill_buffers(m, 2 * yi + 1, f, lines[y], false);
        } else {
            fill_buffers(m, yi, f, lines[y], false);
        }
    }
}

// Random lines: the left line is the right line shifted by a random
// disparity plus noise, so the DP has real structure.
inline std::vector<Line> random_lines(std::mt19937& rng, int N, int H, int D) {
    std::vector<Line> lines(static_cast<size_t>(H));
    std::uniform_int_distribution<int> pix(0, 255);
    for (auto& ln : lines) {
        ln.L.resize(size_t(N));
        ln.R.resize(size_t(N));
        for (int x = 0; x < N; ++x) ln.R[size_t(x)] = uint8_t(pix(rng));
        const int shift = std::uniform_int_distribution<int>(0, D - 1)(rng);
        for (int x = 0; x < N; ++x)
            ln.L[size_t(x)] = x - shift >= 0
                                  ? uint8_t(std::min(255, ln.R[size_t(x - shift)] + pix(rng) % 9))
                                  : uint8_t(pix(rng));
    }
    return lines;
}

// A random valid parameter set for scanlines of length N.
inline g::Params random_params(std::mt19937& rng, int N) {
    auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    g::Params p;
    p.D = uni(1, std::min(N, 40));
    p.km = uni(0, 20);
    p.kb = uni(0, 4);
    if (p.km == 0 && p.kb == 0) p.km = 1;
    p.gb = uni(0, 255);
    p.Wd = uni(0, 200);
    p.Wo = p.Wd + uni(0, 200);
    p.mode = (uni(0, 1) && N >= 2) ? g::Mode::Bidir : g::Mode::Single;
    const int sc = uni(0, 2);
    p.seed_col.kind = sc == 0   ? g::SeedColKind::Balanced
                      : sc == 1 ? g::SeedColKind::Center
                                : g::SeedColKind::Fixed;
    p.seed_col.value = uni(1, std::max(1, N - 1));
    p.seed_disp.free = uni(0, 1) == 0;
    if (p.mode == g::Mode::Bidir && !p.seed_disp.free) {
        const int s = g::resolve_seed_col(p, N);
        p.seed_disp.value = uni(0, std::min(p.D - 1, N - 1 - s));
    }
    p.vote = uni(0, 3) != 0;
    const int fr = uni(0, 2);
    p.frame = fr == 0 ? g::Frame::Cyclopean : fr == 1 ? g::Frame::Left : g::Frame::Right;
    return p;
}

struct Frame {
    int W = 0, H = 0;
    std::vector<uint8_t> L, R;
};

inline Frame random_frame(std::mt19937& rng, int W, int H, int D) {
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

inline void check_frame(const g::Params& p, const Frame& fr, const g::Roi& roi, int P,
                        uint64_t* cycles = nullptr, uint32_t mem_bytes = 0,
                        fw::RowLayout rows = fw::RowLayout::Fastest) {
    isa::MachineConfig cfg;
    cfg.pes = uint32_t(P);
    if (mem_bytes > 0) cfg.mem_bytes = mem_bytes;
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg, fw::SpillLayout::Cheaper, rows);
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

// One frame of random lines (the same frame at every P) on the bare machine
// core, required bit-exact with the golden; its plan and result.
struct Measured {
    fw::FramePlan plan;
    fw::FrameResult r;
};

inline Measured run_on(const g::Params& p, int W, int H, const isa::MachineConfig& cfg,
                       fw::SpillLayout layout = fw::SpillLayout::Cheaper, uint32_t seed = 0,
                       fw::PassLayout passes = fw::PassLayout::Fastest) {
    std::mt19937 rng(seed ? seed : uint32_t(W * 131 + H * 7));  // the same frame at every P
    const Frame fr = random_frame(rng, W, H, p.D);
    const g::Roi roi{0, 0, W, H};
    Measured m;
    m.plan = fw::plan_frame(p, roi, cfg, layout, fw::RowLayout::Fastest, passes);
    const isa::Program prog = fw::assemble_frame(p, m.plan);
    m.r = fw::run_frame_core(m.plan, prog, g::ImageView{fr.L.data(), W, H, W},
                             g::ImageView{fr.R.data(), W, H, W}, cfg);
    const g::DisparityMap want =
        g::compute(p, g::ImageView{fr.L.data(), W, H, W}, g::ImageView{fr.R.data(), W, H, W}, roi);
    BOOST_REQUIRE(m.r.map.data == want.data);  // every what-if point is bit-exact
    return m;
}

inline Measured run_case(const g::Params& p, int W, int H, int P,  // NOLINT
                         fw::SpillLayout layout = fw::SpillLayout::Cheaper, uint32_t mem = 0,
                         uint32_t seed = 0) {
    isa::MachineConfig cfg;
    cfg.pes = P;
    if (mem) cfg.mem_bytes = mem;
    return run_on(p, W, H, cfg, layout, seed);
}

inline uint64_t phase(const fw::FrameResult& r, const std::string& name) {
    for (const auto& [n, c] : r.phases)
        if (n == name) return c;
    return 0;
}

}  // namespace fwtest
