// The forward pass of the DP firmware on the bare machine core: every PE's
// pointer table must equal the golden's bp (right wavefront / single) or fp
// (left wavefront, mirrored) on every valid, reachable state.
#define BOOST_TEST_MODULE firmware_forward
#include <boost/test/unit_test.hpp>
#include <climits>
#include <map>
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

// The split schedule of docs/firmware.md, section 7 (fw::pair_schedule),
// checked by running its layout symbolically: every step is a pass over
// the hull of both PEs' addresses, a node at every address in increasing
// order (the parts' nodes, and junk where a PE has none); each PE's memory
// holds which value sits at each address. A node reads its M source at its
// own address (the previous node's Q), its D source one above, its O source
// one below (just written), as the firmware's in-place node does, except a
// part's first node, which takes them from the setup: M from memory at the
// column's first level, else from the value sent over from the partner
// (the top of the kind's lower part one column earlier), O from the lower
// part's top just sent (or none at the column's first level). Every read
// must find the right (kind, column, level) or the pad above level D - 1,
// and the L' byte it reads (at step + address, the node's c2 + slot) must
// be the one its level needs, the same for every node that reads it.
namespace {

struct Val {
    int kind = -1, k = 0, j = 0;  // kind -1: junk; j == D: the pad
    bool operator==(const Val& o) const { return kind == o.kind && k == o.k && j == o.j; }
};

struct Split {
    int m[2];
    // per PE q: its lower part's and the partner kind's upper part's offsets
    int off_lower[2], off_upper[2];
    int fall = 1;            // levels the boundary falls a column
    bool indexed_l = false;  // L' read through a per-part offset: not checked
};

struct PartNode {
    int kind, k, j;
    bool first;
};

bool simulate_split(const fw::ForwardPlan& f, const Split& sp, int64_t& slots, std::string& why) {
    const int D = f.D, T = f.kmax + 1;
    auto boundary = [&](int p, int k) { return sp.m[p] - sp.fall * (k - 1); };
    auto valid = [&](int p, int k, int j) {
        return k >= 0 && k <= f.K[p] && j >= f.lo[p][k] && j <= f.hi[p][k];
    };
    auto cut = [&](int p, int k) { return std::clamp(boundary(p, k), f.lo[p][k], f.hi[p][k] + 1); };
    std::map<int, Val> mem[2];
    std::map<int, std::pair<int, int>> lbuf[2];  // per PE: L' byte k + x -> (kind, index)
    // per kind: the top of its lower part sent after the previous step
    // (column k - 1 at step k) and the one before (column k - 2)
    Val sent[2][2];
    // column 0 (the start column, init): the levels below m_p(0) at home
    // before the first step, the rest on the partner after it (the first
    // step's lower part reads the address its lowest level takes), pads
    // above level D - 1
    auto start_column = [&](bool home) {
        for (int p = 0; p < 2; ++p) {
            const int c = cut(p, 0);
            for (int j = f.lo[p][0]; j <= f.hi[p][0]; ++j) {
                if (home && j < c) mem[p][j + sp.off_lower[p]] = Val{p, 0, j};
                if (!home && j >= c) mem[1 - p][j + sp.off_upper[1 - p]] = Val{p, 0, j};
            }
            if (f.hi[p][0] == D - 1) {
                if (home && c > D - 1) mem[p][D + sp.off_lower[p]] = Val{p, 0, D};
                if (!home && c <= D - 1) mem[1 - p][D + sp.off_upper[1 - p]] = Val{p, 0, D};
            }
            if (home) sent[p][0] = c > f.lo[p][0] ? Val{p, 0, c - 1} : Val{};
        }
    };
    start_column(true);
    slots = 0;
    for (int k = 1; k <= T; ++k) {
        std::map<int, PartNode> nodes[2];
        int lo = INT_MAX, hi = INT_MIN;
        for (int q = 0; q < 2; ++q) {
            const int o = 1 - q;
            auto add = [&](int p, int col, int a, int b, int off) {
                for (int j = a; j <= b; ++j) {
                    const int x = j + off;
                    if (!nodes[q].emplace(x, PartNode{p, col, j, j == a}).second) return false;
                    lo = std::min(lo, x);
                    hi = std::max(hi, x);
                }
                return true;
            };
            bool ok = true;
            if (k <= f.K[q]) ok = add(q, k, f.lo[q][k], cut(q, k) - 1, sp.off_lower[q]);
            if (ok && k - 1 >= 1 && k - 1 <= f.K[o])
                ok = add(o, k - 1, cut(o, k - 1), f.hi[o][k - 1], sp.off_upper[q]);
            if (!ok) {
                why = "two nodes at one address, step " + std::to_string(k);
                return false;
            }
        }
        if (lo > hi) {
            if (k == 1) start_column(false);
            continue;
        }
        slots += hi - lo + 1;
        Val now[2];  // per kind: the top of its lower part of column k, sent after the step
        for (int q = 0; q < 2; ++q) {
            auto& M = mem[q];
            auto at = [&](int x) {
                auto it = M.find(x);
                return it == M.end() ? Val{} : it->second;
            };
            for (int x = lo; x <= hi; ++x) {
                auto it = nodes[q].find(x);
                if (it == nodes[q].end()) {
                    M[x] = Val{};
                    continue;
                }
                const PartNode& n = it->second;
                const int p = n.kind, c = n.k, j = n.j;
                // b = L'_p[c + j], read at k + x: one byte for every node that reads it
                const auto pix = std::make_pair(p, c + j);
                const auto [lb, fresh] = lbuf[q].emplace(k + x, pix);
                if (!sp.indexed_l && !fresh && lb->second != pix) {
                    std::ostringstream os;
                    os << "step " << k << " PE " << q << ": kind " << p << " (" << c << ", " << j
                       << ") reads L' byte " << k + x << ", which holds kind " << lb->second.first
                       << "'s L'[" << lb->second.second << "]";
                    why = os.str();
                    return false;
                }
                auto expect = [&](const Val& got, int kk, int jj, const char* what) {
                    const Val want = jj == D ? Val{p, kk, D} : Val{p, kk, jj};
                    if (got == want) return true;
                    std::ostringstream os;
                    os << "step " << k << " PE " << q << ": kind " << p << " (" << c << ", " << j
                       << ") reads its " << what << " (" << kk << ", " << jj << ") and finds kind "
                       << got.kind << " (" << got.k << ", " << got.j << ")";
                    why = os.str();
                    return false;
                };
                // D source: (c - 1, j + 1), or the pad above level D - 1 (a
                // part's first node at level D - 1 right above the partner's
                // lower part derives it from the value sent)
                if (valid(p, c - 1, j + 1) || j + 1 == D) {
                    const bool pad_sent =
                        n.first && j + 1 == D && sent[p][1] == Val{p, c - 1, D - 1};
                    if (!pad_sent && !expect(at(x + 1), c - 1, j + 1, "D source")) return false;
                }
                if (valid(p, c - 1, j)) {
                    const bool from_partner = n.first && j == cut(p, c - 1) - 1;
                    const Val got = from_partner ? sent[p][1] : at(x);
                    if (!expect(got, c - 1, j, "M source")) return false;
                }
                if (valid(p, c, j - 1)) {
                    const Val got = n.first ? sent[p][0] : at(x - 1);
                    if (!expect(got, c, j - 1, "O source")) return false;
                }
                M[x] = Val{p, c, j};
                if (q == p && j == cut(p, c) - 1) now[p] = Val{p, c, j};
            }
            // pads after the pass: each part reaching level D - 1
            for (const auto& [x, n] : nodes[q])
                if (n.j == D - 1) M[x + 1] = Val{n.kind, n.k, D};
        }
        for (int p = 0; p < 2; ++p) {
            sent[p][1] = sent[p][0];
            sent[p][0] = now[p];
        }
        if (k == 1) start_column(false);
    }
    return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(split_schedule_runs_in_place_with_one_value_sent_a_kind_and_step) {
    // The paper's grid (widths 32/64/128, D 16..128): today's passes take
    // 1.03 to 1.36 node times per state of a PE's even share.
    isa::MachineConfig cfg;
    for (int N : {32, 64, 128})
        for (int D : {16, 32, 64, 128}) {
            if (D > N) continue;
            g::Params p;
            p.D = D;
            const fw::ForwardPlan f = fw::plan_forward(p, N, cfg);
            for (bool indexed : {false, true}) {
                const fw::PairSchedule s = fw::pair_schedule(f, indexed);
                BOOST_TEST_CONTEXT("N=" << N << " D=" << D << (indexed ? ", indexed L'" : "")) {
                    Split sp{{s.m[0], s.m[1]}, {s.sigma[0], s.sigma[1]}, {s.tau[0], s.tau[1]}};
                    sp.indexed_l = indexed;
                    std::string why;
                    int64_t slots = 0;
                    BOOST_TEST(simulate_split(f, sp, slots, why), why);
                    BOOST_TEST(slots == s.split);
                    BOOST_TEST(s.split <= s.passes);
                    BOOST_TEST(s.balanced <= s.split);
                    // Planted faults: the upper parts one address lower (onto
                    // the lower parts' tops), boundaries falling two levels a
                    // column (two values to send) or none (the lower part's top
                    // would read the upper part computed at the same step).
                    Split low = sp;
                    low.off_upper[0] -= 1;
                    low.off_upper[1] -= 1;
                    BOOST_TEST(!simulate_split(f, low, slots, why));
                    Split two = sp;
                    two.fall = 2;
                    BOOST_TEST(!simulate_split(f, two, slots, why));
                    Split flat = sp;  // inside every column of both kinds, for good
                    flat.fall = 0;
                    for (int p = 0; p < 2; ++p) flat.m[p] = (f.lo[p][1] + f.hi[p][1] + 1) / 2;
                    BOOST_TEST(!simulate_split(f, flat, slots, why));
                    // Where the indexed read finds a shorter layout, that
                    // layout's L' bytes clash when read by broadcast address.
                    if (indexed && s.split < fw::pair_schedule(f, false).split) {
                        Split clash = sp;
                        clash.indexed_l = false;
                        BOOST_TEST(!simulate_split(f, clash, slots, why));
                    }
                    // Every valid state is reachable in bidir with a free seed
                    // disparity: the forward's nodes are the golden's valid states
                    // of sites -1 .. N - 1 but the two start columns s - 1, s.
                    const int64_t nodes =
                        f.valid_states + D - g::levels_at(f.s - 1, N, D) - g::levels_at(f.s, N, D);
                    BOOST_TEST(s.even == (nodes + 1) / 2);
                    BOOST_TEST_MESSAGE(
                        "N=" << N << " D=" << D << (indexed ? ", indexed L'" : "") << ": passes "
                             << s.passes << ", split " << s.split << ", balanced " << s.balanced
                             << ", even " << s.even << " node times (m " << s.m[0] << ", " << s.m[1]
                             << "; upper first " << s.upper_first[0] << s.upper_first[1] << ")");
                }
            }
        }
}

// The split forward (dp_split.inc) on the bare machine core: every state's
// pointer, read from the pass of the PE that computed it, equals the
// golden's.
namespace {

uint64_t forward_cycles(const isa::Machine& m, const isa::Program& prog) {
    for (size_t i = 0; i < prog.phases.size(); ++i)
        if (prog.phases[i] == "forward") return m.phase_cycles()[i];
    return 0;
}

void check_split(const g::Params& p, int N, int H, std::mt19937& rng, bool indexed = false) {
    isa::MachineConfig cfg;
    cfg.pes = 2 * H;
    cfg.mem_bytes = 4096;
    const fw::ForwardPlan f = fw::plan_forward(p, N, cfg);
    const fw::SplitForward sf = fw::plan_split_forward(p, f, indexed);
    BOOST_TEST_REQUIRE(sf.mem_needed <= int(cfg.mem_bytes),
                       "needs " << sf.mem_needed << ": slots " << sf.slots << ", L' " << sf.lbytes
                                << ", m " << sf.s.m[0] << "," << sf.s.m[1] << " sigma "
                                << sf.s.sigma[0] << "," << sf.s.sigma[1] << " tau " << sf.s.tau[0]
                                << "," << sf.s.tau[1]);
    const isa::Program prog = fw::assemble_split_test(p, f, sf, H, int(cfg.pes));
    isa::Machine m(cfg);
    m.load(prog);
    const std::vector<Line> lines = random_lines(rng, N, H, p.D);
    auto px = [&](const std::vector<uint8_t>& v, int x) {
        return x >= 0 && x < N ? v[size_t(x)] : uint8_t(0);
    };
    // kind 0 (left): R'[k] = R[s - k], L'[m] = L[s + D - 1 - m]; kind 1: R[s + k], L[s + m]
    auto rp = [&](const Line& ln, int kind, int i) {
        return px(ln.R, kind == 0 ? f.s - i : f.s + i);
    };
    auto lp = [&](const Line& ln, int kind, int i) {
        return px(ln.L, kind == 0 ? f.s + p.D - 1 - i : f.s + i);
    };
    for (int y = 0; y < H; ++y)
        for (int q = 0; q < 2; ++q) {
            const int pe = 2 * y + q;
            const Line& ln = lines[size_t(y)];
            for (int i = 0; i <= f.kmax; ++i) {
                m.mem_write(pe, uint32_t(sf.rbr - i), rp(ln, q, i));
                m.mem_write(pe, uint32_t(sf.rbr2 - i), rp(ln, 1 - q, i));
            }
            if (sf.indexed) {
                for (int i = 0; i <= f.kmax + p.D; ++i) {
                    m.mem_write(pe, uint32_t(sf.rl + i), lp(ln, 0, i));
                    m.mem_write(pe, uint32_t(sf.ru + i), lp(ln, 1, i));
                }
            } else {
                for (const fw::SplitStep& st : sf.steps)
                    for (const fw::SplitPart& sp : st.part[q])
                        for (int j = sp.lo; j <= sp.hi; ++j)
                            m.mem_write(pe, uint32_t(sf.rbl + st.k + j + sp.off - sf.v0),
                                        lp(ln, sp.kind, sp.col + j));
            }
        }
    m.run();
    BOOST_REQUIRE(m.halted());
    int checked = 0, bad = 0;
    for (int y = 0; y < H && bad < 5; ++y) {
        g::LineTables t;
        g::forward_line(p, lines[size_t(y)].L.data(), lines[size_t(y)].R.data(), N, t);
        for (const fw::SplitStep& st : sf.steps)
            for (int q = 0; q < 2; ++q)
                for (const fw::SplitPart& sp : st.part[q])
                    for (int j = sp.lo; j <= sp.hi && bad < 5; ++j) {
                        const int node = j + sp.off - st.x0;
                        const uint8_t b = m.mem_read(2 * y + q, uint32_t(st.addr + node / 4));
                        const int bits = (b >> (6 - 2 * (node % 4))) & 3;
                        const uint8_t got = uint8_t((bits & 1) ? 2 : (bits >> 1));
                        // kind 1 column k = site s + k; kind 0 column k = site s - 1 - k, level D -
                        // 1 - j
                        const uint8_t want = sp.kind == 1 ? t.bp(f.s + sp.col, j)
                                                          : t.fp(f.s - 1 - sp.col, p.D - 1 - j);
                        if (want == g::kNone) continue;
                        ++checked;
                        if (got != want && ++bad <= 5)
                            BOOST_ERROR("line " << y << " kind " << sp.kind << " column " << sp.col
                                                << " level " << j << " (step " << st.k << ", PE "
                                                << q << (sp.upper ? ", upper" : ", lower")
                                                << ") firmware " << int(got) << " golden "
                                                << int(want));
                    }
    }
    BOOST_TEST(checked > 0);
    // today's passes on the same lines, for the message
    const isa::Program today = fw::assemble_test(p, f, "dp_forward_test.s", H, int(cfg.pes));
    isa::Machine m2(cfg);
    m2.load(today);
    load_lines(m2, f, lines);
    m2.run();
    BOOST_TEST_MESSAGE("N=" << N << " D=" << p.D << (indexed ? ", indexed L'" : "") << ": "
                            << checked << " pointers, forward " << forward_cycles(m, prog)
                            << " cycles in " << sf.steps.size() << " steps (split " << sf.s.split
                            << " slots), today's passes " << forward_cycles(m2, today)
                            << " cycles (" << sf.s.passes << " slots)");
}

}  // namespace

BOOST_AUTO_TEST_CASE(split_forward_runs_bit_exact) {
    std::mt19937 rng(3);
    for (int N : {32, 64, 128})
        for (int D : {16, 32, 64, 128}) {
            if (D > N) continue;
            g::Params p;
            p.D = D;
            for (bool indexed : {false, true})
                BOOST_TEST_CONTEXT(describe(p, N, 2) << (indexed ? ", indexed L'" : "")) {
                    check_split(p, N, 2, rng, indexed);
                }
        }
    // what the harness does not run is refused
    {
        isa::MachineConfig cfg;
        g::Params single;
        single.mode = g::Mode::Single;
        single.D = 16;
        BOOST_CHECK_THROW(fw::plan_split_forward(single, fw::plan_forward(single, 32, cfg)),
                          fw::FirmwareError);
        g::Params fixed;
        fixed.D = 16;
        fixed.seed_disp.free = false;
        fixed.seed_disp.value = 3;
        BOOST_CHECK_THROW(fw::plan_split_forward(fixed, fw::plan_forward(fixed, 32, cfg)),
                          fw::FirmwareError);
    }
    // random weights, seed columns and sizes (bidir, free seed disparity)
    for (int it = 0; it < 30; ++it) {
        const int N = std::uniform_int_distribution<int>(2, 48)(rng);
        g::Params p = random_params(rng, N);
        p.mode = g::Mode::Bidir;
        p.seed_disp.free = true;
        const bool indexed = it % 2 == 1;
        BOOST_TEST_CONTEXT(describe(p, N, 2) << (indexed ? ", indexed L'" : "")) {
            check_split(p, N, 2, rng, indexed);
        }
    }
}
