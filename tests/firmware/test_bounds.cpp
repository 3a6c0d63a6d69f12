// The machine's bound of each phase (docs/firmware.md, section 11):
//  - the node probe measures the forward node on the run's cost table (the
//    node's instruction mix as docs/firmware.md section 2 lists it);
//  - the forward, video and spill bounds count the work of the frame
//    (valid states counted here by brute force, pointer bytes, lines);
//  - no phase of any run (fixed cases and random parameter sets, batches,
//    segments, spills, census and window options) is faster than its bound;
//  - the re-layout's cut bound finds the pixels a video row already puts in
//    an arc of the ring for any lane offset (arc_pixels, by brute force).
#define BOOST_TEST_MODULE firmware_bounds
#include <boost/test/unit_test.hpp>
#include <random>

#include "fw_test_util.hpp"
#include "imap/firmware/bounds.hpp"
#include "plan_internal.hpp"

using namespace fwtest;

namespace {

// Valid states of one line, by brute force over (site, disparity): site i
// matches i + d inside the line.
int64_t brute_states(int N, int D) {
    int64_t n = 0;
    for (int i = 0; i < N; ++i)
        for (int d = 0; d < D; ++d) n += i + d <= N - 1;
    return n;
}

fw::FramePlan headline_plan(const isa::MachineConfig& cfg, const g::Params& p = g::Params{}) {
    return fw::plan_frame(p, g::Roi{0, 0, 128, 128}, cfg);
}

// Every bounded phase of a run takes at least its bound.
void check_bounds_hold(const g::Params& p, const Measured& m, const isa::MachineConfig& cfg) {
    const fw::FrameBounds b = fw::frame_bounds(p, m.plan, cfg);
    BOOST_TEST(!b.phases.empty());
    for (const fw::PhaseBound& pb : b.phases) {
        BOOST_TEST_CONTEXT("phase " << pb.phase << ": bound " << pb.cycles << ", measured "
                                    << phase(m.r, pb.phase)) {
            BOOST_TEST(pb.cycles > 0);
            BOOST_TEST(uint64_t(pb.cycles) <= phase(m.r, pb.phase));
        }
    }
    BOOST_TEST(uint64_t(b.total()) <= m.r.cycles);
}

}  // namespace

BOOST_AUTO_TEST_CASE(node_probe_measures_the_node) {
    // The node at the defaults: 29 one-cycle instructions, of which 3 loads
    // (b and the two bytes of Q) and 2 stores (docs/firmware.md section 2).
    isa::MachineConfig cfg;
    const g::Params p;
    const fw::FramePlan plan = headline_plan(cfg);
    BOOST_TEST(fw::node_cycles(p, plan, cfg) == 29);
    isa::MachineConfig slow_mem = cfg;
    slow_mem.costs.mem = 3;
    BOOST_TEST(fw::node_cycles(p, plan, slow_mem) == 29 + 5 * 2);
    isa::MachineConfig slow_alu = cfg;
    slow_alu.costs.alu = 2;
    BOOST_TEST(fw::node_cycles(p, plan, slow_alu) == 29 + 24);
}

BOOST_AUTO_TEST_CASE(bounds_count_the_work_of_the_frame) {
    isa::MachineConfig cfg;  // 256 PEs
    const g::Params p;       // D = 64, bidir, vote on
    const int64_t states = 128 * brute_states(128, 64);
    BOOST_TEST(states == 128 * 6176);
    {
        const fw::FrameBounds b = fw::frame_bounds(p, headline_plan(cfg), cfg);
        BOOST_TEST(b.states == states);
        BOOST_TEST(b.of("forward") == (states + 255) / 256 * 29);
        BOOST_TEST(b.of("video_in") == 128 * 2);  // both images, one vin per line each
        BOOST_TEST(b.of("video_out") == 128);
        BOOST_TEST(b.of("spill") == -1);  // the pointers fit in the local memories
        BOOST_TEST(b.of("relayout_in") == headline_plan(cfg).rl.bound_in);
    }
    {
        isa::MachineConfig c = cfg;
        c.pes = 64;  // two video segments per line
        c.costs.video_line = 3;
        const fw::FrameBounds b = fw::frame_bounds(p, headline_plan(c), c);
        BOOST_TEST(b.of("video_in") == 128 * 2 * 2 * 3);
        BOOST_TEST(b.of("video_out") == 128 * 2 * 3);
        BOOST_TEST(b.of("forward") == (states + 63) / 64 * 29);
    }
    {
        // D = 128 on 128-wide lines: 2 bits per state do not fit beside one
        // column's 16-bit costs (2 x 128 bytes) in 256 x 1 KiB.
        g::Params q;
        q.D = 128;
        const int64_t s = 128 * brute_states(128, 128);
        const int64_t excess = (s + 3) / 4 - 256 * (1024 - 2 * 128);
        BOOST_REQUIRE(excess > 0);
        const fw::FrameBounds b = fw::frame_bounds(q, headline_plan(cfg, q), cfg);
        BOOST_TEST(b.of("spill") == 2 * (8 + (excess + 7) / 8));
    }
}

BOOST_AUTO_TEST_CASE(no_phase_runs_below_its_bound) {
    struct C {
        int W, H, D, P;
        g::Mode mode;
        uint32_t mem;
    };
    for (const C& c :
         {C{128, 128, 64, 256, g::Mode::Bidir, 0}, C{128, 128, 64, 512, g::Mode::Bidir, 0},
          C{128, 128, 128, 256, g::Mode::Bidir, 0}, C{32, 32, 16, 8, g::Mode::Bidir, 0},
          C{32, 32, 32, 64, g::Mode::Bidir, 0}, C{64, 32, 32, 32, g::Mode::Single, 0},
          C{64, 24, 32, 64, g::Mode::Single, 256}, C{48, 12, 12, 16, g::Mode::Joint, 0},
          C{20, 9, 8, 5, g::Mode::Bidir, 0},
          // three batches whose pointers spill (the Tsukuba scene's shape)
          C{384, 288, 16, 256, g::Mode::Bidir, 0}}) {
        g::Params p;
        p.D = c.D;
        p.mode = c.mode;
        isa::MachineConfig cfg;
        cfg.pes = c.P;
        if (c.mem) cfg.mem_bytes = c.mem;
        BOOST_TEST_CONTEXT("W=" << c.W << " H=" << c.H << " D=" << c.D << " P=" << c.P << " mode "
                                << g::to_string(c.mode) << " mem " << cfg.mem_bytes) {
            check_bounds_hold(p, run_on(p, c.W, c.H, cfg), cfg);
        }
    }
    // The match-cost options: census, a window, Birchfield-Tomasi.
    {
        g::Params p;
        p.D = 16;
        p.kc = 4;
        p.census = 1;
        p.agg_rx = 1;
        p.dissim = g::Dissim::Bt;
        isa::MachineConfig cfg;
        cfg.pes = 64;
        BOOST_TEST_CONTEXT("census, agg-rx 1, bt") {
            check_bounds_hold(p, run_on(p, 32, 16, cfg), cfg);
        }
    }
    // Random parameter sets and machines.
    std::mt19937 rng(2026);
    for (int t = 0; t < 16; ++t) {
        auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
        const int W = uni(8, 48), H = uni(2, 12);
        const g::Params p = random_params(rng, W);
        isa::MachineConfig cfg;
        cfg.pes = uni(2, 6) * 8;
        cfg.costs.mem = uni(1, 2);
        cfg.costs.ring_hop = uni(1, 2);
        cfg.costs.video_line = uni(1, 3);
        BOOST_TEST_CONTEXT("random " << t << ": " << describe(p, W, H) << " P=" << cfg.pes) {
            try {
                check_bounds_hold(p, run_on(p, W, H, cfg), cfg);
            } catch (const fw::FirmwareError& e) {
                BOOST_TEST_MESSAGE("refused: " << e.what());
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(relayout_bound_counts_the_loads_and_stores) {
    // One line of 8 pixels on 8 PEs in single mode: the line's PE needs all
    // 8 pixels of both images; the video rows put one of each on its own
    // lane, so it stores 7 + 7 bytes, and each other lane loads its 2 bytes
    // (14 loads over 8 lanes: at least 2 per lane). Out: 7 map pixels leave
    // the line's PE (7 loads there), one into each other lane (1 store).
    g::Params p;
    p.D = 4;
    p.mode = g::Mode::Single;
    p.vote = false;
    for (const int mem : {1, 3})
        for (const int hop : {1, 2}) {
            isa::MachineConfig cfg;
            cfg.pes = 8;
            cfg.costs.mem = mem;
            cfg.costs.ring_hop = hop;
            const fw::FramePlan plan = fw::plan_frame(p, g::Roi{0, 0, 8, 1}, cfg);
            BOOST_TEST_CONTEXT("mem " << mem << ", ring_hop " << hop) {
                BOOST_REQUIRE(plan.batches.size() == 1u);
                BOOST_REQUIRE(plan.nseg == 1);
                BOOST_TEST(plan.rl.mem_bound_in == (14 + 2) * mem);
                BOOST_TEST(plan.rl.mem_bound_out == (7 + 1) * mem);
                // the ring part is in ring_hop units; the bound is the sum
                BOOST_TEST(plan.rl.ring_bound_in > 0);
                BOOST_TEST(plan.rl.ring_bound_in % hop == 0);
                BOOST_TEST(plan.rl.bound_in == plan.rl.ring_bound_in + plan.rl.mem_bound_in);
                BOOST_TEST(plan.rl.bound_out == plan.rl.ring_bound_out + plan.rl.mem_bound_out);
                isa::MachineConfig one = cfg;
                one.costs.ring_hop = 1;
                BOOST_TEST(plan.rl.ring_bound_in ==
                           hop * fw::plan_frame(p, g::Roi{0, 0, 8, 1}, one).rl.ring_bound_in);
                // the byte-hops: pixel x of both images from lane x to the
                // line's PE, the shorter way round the ring of 8 (over P)
                int64_t hops = 0;
                const int pe = ((plan.rl.base % 8) + 8) % 8;
                for (int x = 0; x < 8; ++x) {
                    const int d = ((x - pe) % 8 + 8) % 8;
                    hops += 2 * std::min(d, 8 - d);
                }
                BOOST_TEST(plan.rl.hop_bound_in == (hops + 7) / 8 * hop);
            }
        }
}

BOOST_AUTO_TEST_CASE(arc_pixels_finds_every_pixel_in_the_arc) {
    // Pixels x of [lo, hi] whose lane (x + off) mod P lies in the arc [a, a +
    // len): against a count pixel by pixel, with lane offsets far beyond the
    // ring (the windowed rows' copies start up to several rings away on few
    // PEs), and the intervals disjoint.
    std::mt19937 rng(30);
    for (int it = 0; it < 4000; ++it) {
        const int P = 1 << std::uniform_int_distribution<int>(1, 7)(rng);
        const int lo = std::uniform_int_distribution<int>(-3 * P, 3 * P)(rng);
        const int hi = lo + std::uniform_int_distribution<int>(-1, P - 1)(rng);
        const int off = std::uniform_int_distribution<int>(-12 * P, 12 * P)(rng);
        const int a = std::uniform_int_distribution<int>(0, P - 1)(rng);
        const int len = std::uniform_int_distribution<int>(1, P)(rng);
        std::vector<std::pair<int, int>> iv;
        fw::detail::arc_pixels(P, lo, hi, off, a, len, &iv);
        std::vector<int> seen(std::max(0, hi - lo + 1), 0);
        for (const auto& [b0, b1] : iv)
            for (int x = b0; x <= b1; ++x)
                if (x >= lo && x <= hi) ++seen[x - lo];
        int wrong = 0;
        for (int x = lo; x <= hi; ++x) {
            const bool in = (((x + off - a) % P) + P) % P < len;
            wrong += seen[x - lo] != (in ? 1 : 0);
        }
        BOOST_TEST_CONTEXT("P " << P << " [" << lo << ", " << hi << "] off " << off << " arc " << a
                                << "+" << len) {
            BOOST_TEST(wrong == 0);
        }
    }
}
