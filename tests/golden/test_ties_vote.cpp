// SPEC A.3/A.4 tie rules on hand-constructed scanlines, and SPEC A.5/A.6 vote
// (with the fallback to the line's own pointer) on hand-built pointer tables.
#define BOOST_TEST_MODULE golden_ties_vote
#include <boost/test/unit_test.hpp>

#include <random>
#include <vector>

#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"
#include "test_util.hpp"

namespace g = imap::golden;

namespace {

// km = 1, kb = 0: Wm(i,j) = |R[i] - L[i+j]|.
g::Params abs_diff_params(g::Mode mode, int D, int Wo, int Wd) {
    g::Params p;
    p.mode = mode;
    p.D = D;
    p.km = 1;
    p.kb = 0;
    p.gb = 0;
    p.Wo = Wo;
    p.Wd = Wd;
    p.vote = false;
    return p;
}

// Single mode, N = 3, D = 3, Wo = 3, Wd = 1. With R0 = 100, L0 = 100 + x,
// L1 = 100 + y:
//   E(0,0) = min(M: x, D: E(-1,1) + Wd = 4)
//   E(0,1) = min(M: E(-1,1) + y = 3 + y, D: E(-1,2) + Wd = 7, O: E(0,0) + 3)
g::LineTables right_tie_case(int x, int y, specref::LineRef* ref = nullptr) {
    const g::Params p = abs_diff_params(g::Mode::Single, 3, 3, 1);
    const std::vector<uint8_t> L = {static_cast<uint8_t>(100 + x), static_cast<uint8_t>(100 + y),
                                    7};
    const std::vector<uint8_t> R = {100, 50, 60};
    g::LineTables t;
    g::forward_line(p, L.data(), R.data(), 3, t);
    if (ref) *ref = specref::forward(p, L.data(), R.data(), 3);
    return t;
}

// Bidir, N = 4, D = 3, seed column 2, free seed disparity, Wo = Wd = 2: G at
// site 1 is 0. With R1 = 100, L1 = 100 + a, L2 = 100 + b, L3 = 100 + c:
//   G(0,2) = min(M: c, D: G(1,1) + 2 = 2)
//   G(0,1) = min(M: b, D: G(1,0) + 2 = 2, O: G(0,2) + 2)
//   G(0,0) = min(M: a, O: G(0,1) + 2)
g::LineTables left_tie_case(int a, int b, int c, specref::LineRef* ref = nullptr) {
    g::Params p = abs_diff_params(g::Mode::Bidir, 3, 2, 2);
    p.seed_col = {g::SeedColKind::Fixed, 2};
    p.seed_disp.free = true;
    const std::vector<uint8_t> L = {0, static_cast<uint8_t>(100 + a), static_cast<uint8_t>(100 + b),
                                    static_cast<uint8_t>(100 + c)};
    const std::vector<uint8_t> R = {30, 100, 40, 50};
    g::validate_for_width(p, 4);
    g::LineTables t;
    g::forward_line(p, L.data(), R.data(), 4, t);
    if (ref) *ref = specref::forward(p, L.data(), R.data(), 4);
    return t;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(ties)

BOOST_AUTO_TEST_CASE(right_m_equals_d_takes_m) {
    BOOST_TEST(right_tie_case(4, 9).bp(0, 0) == g::kM);  // M = 4, D = 4
    BOOST_TEST(right_tie_case(3, 9).bp(0, 0) == g::kM);  // M = 3 < D = 4
    BOOST_TEST(right_tie_case(5, 9).bp(0, 0) == g::kD);  // D = 4 < M = 5
}

BOOST_AUTO_TEST_CASE(right_d_equals_o_takes_d) {
    // x = 4: E(0,0) = 4; y = 5: M = 8, D = 7, O = 7.
    specref::LineRef ref;
    const g::LineTables t = right_tie_case(4, 5, &ref);
    BOOST_TEST(ref.E[1][0] == 4);
    BOOST_TEST(t.bp(0, 1) == g::kD);
    BOOST_TEST(ref.bpv(0, 1) == g::kD);
    // x = 9 (D wins at (0,0), E(0,0) = 4 still): same.
    BOOST_TEST(right_tie_case(9, 5).bp(0, 1) == g::kD);
}

BOOST_AUTO_TEST_CASE(right_all_equal_takes_m) {
    // x = 4, y = 4: M = 7, D = 7, O = 7.
    BOOST_TEST(right_tie_case(4, 4).bp(0, 1) == g::kM);
    BOOST_TEST(right_tie_case(4, 3).bp(0, 1) == g::kM);  // M = 6 smallest
}

BOOST_AUTO_TEST_CASE(right_m_equals_o_takes_m) {
    // x = 0: E(0,0) = 0; y = 0: M = 3, D = 7, O = 3.
    BOOST_TEST(right_tie_case(0, 0).bp(0, 1) == g::kM);
    // y = 1: M = 4 > O = 3: O replaces (strictly smaller).
    BOOST_TEST(right_tie_case(0, 1).bp(0, 1) == g::kO);
}

BOOST_AUTO_TEST_CASE(right_single_costs_by_hand) {
    // x = 0, y = 1 on the full line: E(0,0)=0 M, E(0,1)=3 O, E(0,2)=min(6+|100-7|, 6) = 6 O,
    // E(1,0)=min(E00+|50-101|, E01+1) = 4 D, E(1,1)=min(E01+|50-7|, E02+1, E10+3) = 7 D/O -> D,
    // E(2,0)=min(E10+|60-7|, E11+1) = 8 D.
    const g::LineTables t = right_tie_case(0, 1);
    BOOST_TEST(t.bp(0, 0) == g::kM);
    BOOST_TEST(t.bp(0, 1) == g::kO);
    BOOST_TEST(t.bp(0, 2) == g::kO);
    BOOST_TEST(t.bp(1, 0) == g::kD);
    BOOST_TEST(t.bp(1, 1) == g::kD);
    BOOST_TEST(t.bp(2, 0) == g::kD);
    BOOST_TEST(t.bp(1, 2) == g::kNone);  // invalid: 1 + 2 > N - 1
    BOOST_TEST(t.right_cost == 8);
}

BOOST_AUTO_TEST_CASE(left_m_equals_d_takes_m) {
    BOOST_TEST(left_tie_case(0, 0, 2).fp(0, 2) == g::kM);  // M = 2, D = 2
    BOOST_TEST(left_tie_case(0, 0, 1).fp(0, 2) == g::kM);  // M = 1 < D
    BOOST_TEST(left_tie_case(0, 0, 3).fp(0, 2) == g::kD);  // D = 2 < M = 3
}

BOOST_AUTO_TEST_CASE(left_d_equals_o_takes_d) {
    // c = 0: G(0,2) = 0; b = 3: M = 3, D = 2, O = 2.
    specref::LineRef ref;
    const g::LineTables t = left_tie_case(0, 3, 0, &ref);
    BOOST_TEST(ref.G[1][2] == 0);
    BOOST_TEST(t.fp(0, 1) == g::kD);
    BOOST_TEST(ref.fpv(0, 1) == g::kD);
}

BOOST_AUTO_TEST_CASE(left_all_equal_takes_m) {
    // c = 0, b = 2: M = D = O = 2.
    BOOST_TEST(left_tie_case(0, 2, 0).fp(0, 1) == g::kM);
}

BOOST_AUTO_TEST_CASE(left_m_equals_o_takes_m) {
    // c = 0, b = 3: G(0,1) = 2; a = 4: M = 4, O = 4.
    BOOST_TEST(left_tie_case(4, 3, 0).fp(0, 0) == g::kM);
    BOOST_TEST(left_tie_case(3, 3, 0).fp(0, 0) == g::kM);
    BOOST_TEST(left_tie_case(5, 3, 0).fp(0, 0) == g::kO);  // O = 4 < M = 5
}

BOOST_AUTO_TEST_CASE(left_costs_by_hand) {
    // a = 5, b = 3, c = 0. Site 0: G(0,2) = 0 M, G(0,1) = 2 D, G(0,0) = 4 O.
    // Site -1 (R0 = 30, L0 = 0, L1 = 105, L2 = 103):
    //   G(-1,2) = min(M: G(0,2) + |30-103| = 73, D: G(0,1) + 2 = 4) = 4 D
    //   G(-1,1) = min(M: G(0,1) + |30-105| = 77, D: G(0,0) + 2 = 6, O: G(-1,2) + 2 = 6) = 6 D
    //   G(-1,0) = min(M: G(0,0) + |30-0| = 34, O: G(-1,1) + 2 = 8) = 8 O
    const g::LineTables t = left_tie_case(5, 3, 0);
    BOOST_TEST(t.fp(0, 2) == g::kM);
    BOOST_TEST(t.fp(0, 1) == g::kD);
    BOOST_TEST(t.fp(0, 0) == g::kO);
    BOOST_TEST(t.fp(-1, 2) == g::kD);
    BOOST_TEST(t.fp(-1, 1) == g::kD);
    BOOST_TEST(t.fp(-1, 0) == g::kO);
    BOOST_TEST(t.left_cost == 8);
    // Backtrack of the left wavefront: (-1,0) -O-> (-1,1) -D-> (0,0) -O-> (0,1) -D-> (1,0):
    // arrival at site s-1 = 1 stops it (free seed disparity). The right
    // wavefront: site 2 free (E = 0), E(3,0) = min(M: E(2,0) + |50-100|, D: E(2,1) + 2) = 2 D
    // -> seed at (2, 1).
    BOOST_TEST(t.right_cost == 2);
    const std::vector<g::Event> ev = g::backtrack(nullptr, t, nullptr, false);
    const std::vector<g::Event> want = {{-1, 1, g::kO}, {0, 0, g::kD}, {0, 1, g::kO},
                                        {1, 0, g::kD},  {3, 0, g::kD}, {2, 1, g::kM}};
    BOOST_TEST((ev == want), gt::events_string(ev));
}

BOOST_AUTO_TEST_CASE(random_tie_heavy_lines_match_reference) {
    // Pixels from a 3-value range and weights in 0..3 make most states ties;
    // every pointer must follow the M, D, O strict-replacement order.
    std::mt19937 rng(31337);
    for (int trial = 0; trial < 600; ++trial) {
        g::Params p;
        const int N = gt::uni(rng, 1, 12);
        p.mode = N >= 2 && trial % 2 ? g::Mode::Bidir : g::Mode::Single;
        p.D = gt::uni(rng, 1, N);
        p.km = gt::uni(rng, 0, 2);
        p.kb = gt::uni(rng, 0, 1);
        if (p.km == 0 && p.kb == 0) p.km = 1;
        p.gb = gt::uni(rng, 0, 3);
        p.Wd = gt::uni(rng, 0, 2);
        p.Wo = p.Wd + gt::uni(rng, 0, 2);
        if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, N);
        std::vector<uint8_t> L(N), R(N);
        for (int x = 0; x < N; ++x) {
            L[x] = static_cast<uint8_t>(gt::uni(rng, 0, 2));
            R[x] = static_cast<uint8_t>(gt::uni(rng, 0, 2));
        }
        g::LineTables t;
        g::forward_line(p, L.data(), R.data(), N, t);
        const specref::LineRef ref = specref::forward(p, L.data(), R.data(), N);
        BOOST_TEST_CONTEXT("trial " << trial << " " << gt::describe(p)
                                    << " L=" << gt::row_string(L.data(), N)
                                    << " R=" << gt::row_string(R.data(), N)) {
            BOOST_TEST(t.right_cost == ref.right_cost);
            const int first = p.mode == g::Mode::Bidir ? ref.s + 1 : 0;
            for (int i = first; i < N; ++i)
                for (int j = 0; j < p.D; ++j)
                    BOOST_TEST(int(t.bp(i, j)) == ref.bpv(i, j), "bp(" << i << "," << j << ")");
            if (p.mode == g::Mode::Bidir) {
                BOOST_TEST(t.left_cost == ref.left_cost);
                for (int i = -1; i <= ref.s - 2; ++i)
                    for (int j = 0; j < p.D; ++j)
                        BOOST_TEST(int(t.fp(i, j)) == ref.fpv(i, j), "fp(" << i << "," << j << ")");
            }
        }
    }
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------

namespace {

// Hand-built pointer tables (not produced by forward_line).
g::LineTables single_tables(int N, int D, uint8_t fill) {
    g::LineTables t;
    t.N = N;
    t.D = D;
    t.bidir = false;
    t.s = 0;
    t.ds = -1;
    t.right_first = 0;
    t.right.assign(static_cast<size_t>(N) * D, g::kNone);
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < D && i + j <= N - 1; ++j)
            t.right[static_cast<size_t>(i) * D + j] = fill;
    return t;
}

void set_bp(g::LineTables& t, int i, int j, uint8_t v) {
    t.right[static_cast<size_t>(i - t.right_first) * t.D + j] = v;
}

void set_fp(g::LineTables& t, int i, int j, uint8_t v) {
    t.left[static_cast<size_t>(i + 1) * t.D + j] = v;
}

// Bidir tables with every entry kNone; the caller fills them.
g::LineTables bidir_tables(int N, int D, int s, int ds) {
    g::LineTables t;
    t.N = N;
    t.D = D;
    t.bidir = true;
    t.s = s;
    t.ds = ds;
    t.right_first = s;
    t.right.assign(static_cast<size_t>(N - s) * D, g::kNone);
    t.left.assign(static_cast<size_t>(s + 1) * D, g::kNone);
    return t;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(vote)

BOOST_AUTO_TEST_CASE(voted_bp_rules) {
    // single, N = 3, D = 2: valid states (0,0) (0,1) (1,0) (1,1) (2,0).
    const g::LineTables self = single_tables(3, 2, g::kM);
    g::LineTables a = single_tables(3, 2, g::kM), b = single_tables(3, 2, g::kM);

    set_bp(a, 1, 0, g::kD);
    set_bp(b, 1, 0, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 1, 0) == g::kD);       // agree -> neighbours' pointer
    BOOST_TEST(g::voted_bp(&a, self, nullptr, 1, 0) == g::kM);  // missing neighbour -> own
    BOOST_TEST(g::voted_bp(nullptr, self, &b, 1, 0) == g::kM);
    BOOST_TEST(g::voted_bp(nullptr, self, nullptr, 1, 0) == g::kM);
    set_bp(b, 1, 0, g::kO);
    BOOST_TEST(g::voted_bp(&a, self, &b, 1, 0) == g::kM);  // disagree -> own
    BOOST_TEST(g::voted_bp(&b, self, &a, 1, 0) == g::kM);

    // Agreeing neighbours whose step leaves the valid states -> own.
    set_bp(a, 1, 0, g::kO);  // O at level 0: source (1,-1)
    BOOST_TEST(g::voted_bp(&a, self, &b, 1, 0) == g::kM);
    set_bp(a, 1, 1, g::kD);  // D at the top level: source (0,2), j = D
    set_bp(b, 1, 1, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 1, 1) == g::kM);
    set_bp(a, 0, 1, g::kD);  // source (-1,2): j = D also in column -1
    set_bp(b, 0, 1, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 0, 1) == g::kM);
    set_bp(a, 2, 0, g::kNone);  // agreeing on "no step"
    set_bp(b, 2, 0, g::kNone);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 0) == g::kM);

    // Valid sources, including column -1 (single mode).
    set_bp(a, 0, 0, g::kD);  // source (-1,1)
    set_bp(b, 0, 0, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 0, 0) == g::kD);
    g::LineTables self2 = single_tables(3, 2, g::kM);
    set_bp(self2, 1, 1, g::kO);
    set_bp(a, 1, 1, g::kM);
    set_bp(b, 1, 1, g::kM);
    BOOST_TEST(g::voted_bp(&a, self2, &b, 1, 1) == g::kM);
    set_bp(a, 0, 1, g::kO);  // source (0,0)
    set_bp(b, 0, 1, g::kO);
    BOOST_TEST(g::voted_bp(&a, self2, &b, 0, 1) == g::kO);
}

BOOST_AUTO_TEST_CASE(voted_bp_unreachable_source_falls_back) {
    // bidir right table, N = 4, D = 2, s = 1, ds = 1: (1,0) unreachable,
    // (1,1) the seed; (2,0) D, (2,1) M, (3,0) M; (3,1) invalid.
    g::LineTables self = bidir_tables(4, 2, 1, 1);
    set_bp(self, 1, 1, g::kM);
    set_bp(self, 2, 0, g::kD);
    set_bp(self, 2, 1, g::kM);
    set_bp(self, 3, 0, g::kM);
    g::LineTables a = self, b = self;
    set_bp(a, 2, 0, g::kM);  // M from (1,0): unreachable
    set_bp(b, 2, 0, g::kM);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 0) == g::kD);
    set_bp(a, 2, 1, g::kO);  // O from (2,0): reachable
    set_bp(b, 2, 1, g::kO);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 1) == g::kO);
    set_bp(a, 3, 0, g::kD);  // D from (2,1): reachable
    set_bp(b, 3, 0, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 3, 0) == g::kD);
    set_bp(a, 2, 1, g::kD);  // D from (1,2): invalid level
    set_bp(b, 2, 1, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 1) == g::kM);
}

BOOST_AUTO_TEST_CASE(voted_o_to_unreachable_level_falls_back) {
    // Right: N = 6, D = 4, s = 1, ds = 3: (1,0..2) unreachable, so at site 2
    // only levels >= 2 are reachable. At (2,2) an O step would come from (2,1).
    g::LineTables self = bidir_tables(6, 4, 1, 3);
    set_bp(self, 1, 3, g::kM);
    set_bp(self, 2, 2, g::kD);
    set_bp(self, 2, 3, g::kM);
    for (int i = 3; i < 6; ++i)
        for (int j = 0; j < 4 && i + j <= 5; ++j) set_bp(self, i, j, g::kM);
    set_bp(self, 3, 0, g::kD);
    set_bp(self, 3, 1, g::kD);
    g::LineTables a = self, b = self;
    set_bp(a, 2, 2, g::kO);
    set_bp(b, 2, 2, g::kO);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 2) == g::kD);
    set_bp(a, 2, 3, g::kO);  // from (2,2): reachable
    set_bp(b, 2, 3, g::kO);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 3) == g::kO);
    set_bp(a, 3, 1, g::kM);  // from (2,1): unreachable
    set_bp(b, 3, 1, g::kM);
    BOOST_TEST(g::voted_bp(&a, self, &b, 3, 1) == g::kD);

    // Left: N = 6, D = 4, s = 3, ds = 0: site 2 only (2,0) reachable; site 1
    // levels 0, 1 reachable, 2, 3 not. At (1,1) an O step would go to (1,2).
    g::LineTables left = bidir_tables(6, 4, 3, 0);
    set_fp(left, 2, 0, g::kM);
    set_fp(left, 1, 0, g::kM);
    set_fp(left, 1, 1, g::kD);
    for (int i = -1; i <= 0; ++i)
        for (int j = 0; j < 4; ++j) set_fp(left, i, j, g::kM);
    set_fp(left, 0, 3, g::kNone);  // (0,3): M to (1,3), D to (1,2) both unreachable
    set_fp(left, 0, 2, g::kD);
    g::LineTables la = left, lb = left;
    set_fp(la, 1, 1, g::kO);
    set_fp(lb, 1, 1, g::kO);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 1, 1) == g::kD);
    set_fp(la, 1, 0, g::kO);  // to (1,1): reachable
    set_fp(lb, 1, 0, g::kO);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 1, 0) == g::kO);
    set_fp(la, 0, 2, g::kO);  // to (0,3): unreachable
    set_fp(lb, 0, 2, g::kO);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 0, 2) == g::kD);
    set_fp(la, 0, 1, g::kM);  // M to (1,1): reachable (own is M anyway)
    set_fp(la, 0, 2, g::kM);  // M to (1,2): unreachable
    set_fp(lb, 0, 2, g::kM);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 0, 2) == g::kD);
    set_fp(la, 2, 0, g::kO);  // site s-1: O to (2,1), j > ds: unreachable
    set_fp(lb, 2, 0, g::kO);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 2, 0) == g::kM);
    set_fp(la, -1, 2, g::kO);  // column -1: O to (-1,3) reachable
    set_fp(lb, -1, 2, g::kO);
    BOOST_TEST(g::voted_fp(&la, left, &lb, -1, 2) == g::kO);
    set_fp(la, -1, 2, g::kD);  // column -1: D to (0,1)
    set_fp(lb, -1, 2, g::kD);
    BOOST_TEST(g::voted_fp(&la, left, &lb, -1, 2) == g::kD);
    set_fp(la, -1, 3, g::kD);  // column -1: D to (0,2): reachable
    set_fp(lb, -1, 3, g::kD);
    BOOST_TEST(g::voted_fp(&la, left, &lb, -1, 3) == g::kD);
    set_fp(la, -1, 3, g::kM);  // column -1: M to (0,3): unreachable
    set_fp(lb, -1, 3, g::kM);
    set_fp(left, -1, 3, g::kD);
    BOOST_TEST(g::voted_fp(&la, left, &lb, -1, 3) == g::kD);

    // kNone marks an unreachable state (stereo.hpp): a voted D into one falls
    // back too. Mark (1,0) unreachable in a copy; D from (0,1) would go there.
    g::LineTables cut = left;
    set_fp(cut, 1, 0, g::kNone);
    set_fp(la, 0, 1, g::kD);
    set_fp(lb, 0, 1, g::kD);
    BOOST_TEST(g::voted_fp(&la, left, &lb, 0, 1) == g::kD);
    BOOST_TEST(g::voted_fp(&la, cut, &lb, 0, 1) == g::kM);
    // Same for a voted D in the right wavefront (source (0,1) marked kNone).
    g::LineTables single = single_tables(4, 3, g::kM), sa = single, sb = single;
    set_bp(sa, 1, 0, g::kD);
    set_bp(sb, 1, 0, g::kD);
    BOOST_TEST(g::voted_bp(&sa, single, &sb, 1, 0) == g::kD);
    set_bp(single, 0, 1, g::kNone);
    BOOST_TEST(g::voted_bp(&sa, single, &sb, 1, 0) == g::kM);
    set_bp(sa, 1, 1, g::kM);  // M from (0,1), marked kNone
    set_bp(sb, 1, 1, g::kM);
    set_bp(single, 1, 1, g::kO);
    BOOST_TEST(g::voted_bp(&sa, single, &sb, 1, 1) == g::kO);
}

BOOST_AUTO_TEST_CASE(voted_bp_bidir_seed_column) {
    // bidir right table, N = 5, D = 2, s = 2, free: M/D from site s+1 reach
    // site s (ok); nothing of the right wavefront lies left of site s.
    g::LineTables self = bidir_tables(5, 2, 2, -1);
    for (int i = 2; i < 5; ++i)
        for (int j = 0; j < 2 && i + j <= 4; ++j) set_bp(self, i, j, g::kM);
    g::LineTables a = self, b = self;
    set_bp(a, 3, 0, g::kD);  // source (2,1): the free seed column
    set_bp(b, 3, 0, g::kD);
    BOOST_TEST(g::voted_bp(&a, self, &b, 3, 0) == g::kD);
    set_bp(self, 3, 1, g::kO);
    set_bp(a, 3, 1, g::kM);  // source (2,1)
    set_bp(b, 3, 1, g::kM);
    BOOST_TEST(g::voted_bp(&a, self, &b, 3, 1) == g::kM);
    set_bp(self, 2, 1, g::kO);  // artificial own pointer at site s
    set_bp(a, 2, 1, g::kM);     // source (1,1): outside the right wavefront -> own
    set_bp(b, 2, 1, g::kM);
    BOOST_TEST(g::voted_bp(&a, self, &b, 2, 1) == g::kO);
}

BOOST_AUTO_TEST_CASE(voted_fp_rules) {
    // bidir left table, N = 4, D = 2, s = 3, ds = 0: site s-1 = 2: (2,0) seed,
    // (2,1) unreachable. (1,1) D, (1,0) M, (0,*) M, (-1,*) M.
    g::LineTables self = bidir_tables(4, 2, 3, 0);
    set_fp(self, 2, 0, g::kM);
    set_fp(self, 1, 1, g::kD);
    set_fp(self, 1, 0, g::kM);
    for (int i = -1; i <= 0; ++i)
        for (int j = 0; j < 2; ++j) set_fp(self, i, j, g::kM);
    set_bp(self, 3, 0, g::kM);
    g::LineTables a = self, b = self;

    set_fp(a, 1, 1, g::kM);  // M to (2,1): unreachable -> own
    set_fp(b, 1, 1, g::kM);
    BOOST_TEST(g::voted_fp(&a, self, &b, 1, 1) == g::kD);
    set_fp(a, 1, 0, g::kO);  // O to (1,1): reachable
    set_fp(b, 1, 0, g::kO);
    BOOST_TEST(g::voted_fp(&a, self, &b, 1, 0) == g::kO);
    BOOST_TEST(g::voted_fp(&a, self, nullptr, 1, 0) == g::kM);  // missing neighbour
    BOOST_TEST(g::voted_fp(nullptr, self, &b, 1, 0) == g::kM);
    set_fp(b, 1, 0, g::kD);
    BOOST_TEST(g::voted_fp(&a, self, &b, 1, 0) == g::kM);  // disagree
    set_fp(a, 0, 1, g::kO);                                // O to (0,2): level D -> own
    set_fp(b, 0, 1, g::kO);
    BOOST_TEST(g::voted_fp(&a, self, &b, 0, 1) == g::kM);
    set_fp(a, 0, 0, g::kD);  // D to (1,-1) -> own
    set_fp(b, 0, 0, g::kD);
    BOOST_TEST(g::voted_fp(&a, self, &b, 0, 0) == g::kM);
    set_fp(a, 0, 1, g::kD);  // D to (1,0): reachable
    set_fp(b, 0, 1, g::kD);
    BOOST_TEST(g::voted_fp(&a, self, &b, 0, 1) == g::kD);
    set_fp(a, -1, 0, g::kO);  // O in column -1 to (-1,1)
    set_fp(b, -1, 0, g::kO);
    BOOST_TEST(g::voted_fp(&a, self, &b, -1, 0) == g::kO);
    set_fp(a, -1, 1, g::kNone);  // agreeing on "no step"
    set_fp(b, -1, 1, g::kNone);
    BOOST_TEST(g::voted_fp(&a, self, &b, -1, 1) == g::kM);
    // A step out of the left wavefront (site s-1 -> site s) -> own.
    g::LineTables self2 = self;
    set_fp(self2, 2, 0, g::kD);
    set_fp(a, 2, 0, g::kM);
    set_fp(b, 2, 0, g::kM);
    BOOST_TEST(g::voted_fp(&a, self2, &b, 2, 0) == g::kD);
}

BOOST_AUTO_TEST_CASE(backtrack_single_with_vote_and_fallback) {
    // self: (2,0) M, (1,0) M, (1,1) O, (0,0) M, (0,1) M.
    g::LineTables self = single_tables(3, 2, g::kM);
    set_bp(self, 1, 1, g::kO);
    // neighbours: (2,0) D, (1,1) D (source (0,2) invalid -> own O), (0,0) D.
    g::LineTables nb = single_tables(3, 2, g::kM);
    set_bp(nb, 2, 0, g::kD);
    set_bp(nb, 1, 1, g::kD);
    set_bp(nb, 0, 0, g::kD);
    const std::vector<g::Event> off = {{2, 0, g::kM}, {1, 0, g::kM}, {0, 0, g::kM}};
    const std::vector<g::Event> on = {{2, 0, g::kD}, {1, 1, g::kO}, {1, 0, g::kM}, {0, 0, g::kD}};
    std::vector<g::Event> ev = g::backtrack(&nb, self, &nb, false);
    BOOST_TEST((ev == off), gt::events_string(ev));
    ev = g::backtrack(&nb, self, &nb, true);
    BOOST_TEST((ev == on), gt::events_string(ev));
    ev = g::backtrack(&nb, self, nullptr, true);
    BOOST_TEST((ev == off), gt::events_string(ev));
    ev = g::backtrack(nullptr, self, &nb, true);
    BOOST_TEST((ev == off), gt::events_string(ev));
    // Disagreeing neighbours.
    const g::LineTables plain = single_tables(3, 2, g::kM);
    ev = g::backtrack(&nb, self, &plain, true);
    BOOST_TEST((ev == off), gt::events_string(ev));
}

BOOST_AUTO_TEST_CASE(backtrack_bidir_with_vote_and_fallback) {
    // N = 4, D = 2, s = 2, ds = 1.
    g::LineTables self = bidir_tables(4, 2, 2, 1);
    set_bp(self, 2, 1, g::kM);  // the seed; (2,0) unreachable (kNone)
    set_bp(self, 3, 0, g::kD);
    set_fp(self, 1, 1, g::kM);  // site s-1: (1,1) seed's left neighbour, (1,0) O
    set_fp(self, 1, 0, g::kO);
    for (int i = -1; i <= 0; ++i)
        for (int j = 0; j < 2; ++j) set_fp(self, i, j, g::kM);
    g::LineTables nb = self;
    set_bp(nb, 3, 0, g::kM);   // source (2,0) unreachable -> own D
    set_fp(nb, -1, 0, g::kO);  // -> (-1,1)
    set_fp(nb, 0, 1, g::kO);   // -> (0,2) invalid -> own M

    const std::vector<g::Event> off = {
        {0, 0, g::kM}, {1, 0, g::kM}, {1, 1, g::kO}, {3, 0, g::kD}, {2, 1, g::kM}};
    const std::vector<g::Event> on = {
        {-1, 1, g::kO}, {0, 1, g::kM}, {1, 1, g::kM}, {3, 0, g::kD}, {2, 1, g::kM}};
    std::vector<g::Event> ev = g::backtrack(&nb, self, &nb, false);
    BOOST_TEST((ev == off), gt::events_string(ev));
    ev = g::backtrack(&nb, self, &nb, true);
    BOOST_TEST((ev == on), gt::events_string(ev));
    ev = g::backtrack(nullptr, self, &nb, true);
    BOOST_TEST((ev == off), gt::events_string(ev));
}

BOOST_AUTO_TEST_CASE(backtrack_bidir_fixed_seed_o_chain) {
    // N = 5, D = 3, s = 1, ds = 0. Right: site 1: (1,0) seed M, (1,1) O, (1,2) O.
    // Backtrack (4,0) -D-> (3,1) -D-> (2,2) -M-> (1,2): site s reached at level
    // 2, then the O pointers lead down to the seed (1,0).
    g::LineTables self = bidir_tables(5, 3, 1, 0);
    set_bp(self, 1, 0, g::kM);
    set_bp(self, 1, 1, g::kO);
    set_bp(self, 1, 2, g::kO);
    for (int i = 2; i < 5; ++i)
        for (int j = 0; j < 3 && i + j <= 4; ++j) set_bp(self, i, j, g::kM);
    set_bp(self, 4, 0, g::kD);
    set_bp(self, 3, 1, g::kD);
    set_fp(self, 0, 0, g::kM);
    for (int j = 1; j < 3; ++j) set_fp(self, 0, j, g::kNone);  // j > ds: unreachable
    for (int j = 0; j < 3; ++j) set_fp(self, -1, j, g::kM);
    const std::vector<g::Event> want = {{0, 0, g::kM}, {4, 0, g::kD}, {3, 1, g::kD}, {2, 2, g::kM},
                                        {1, 2, g::kO}, {1, 1, g::kO}, {1, 0, g::kM}};
    const std::vector<g::Event> ev = g::backtrack(nullptr, self, nullptr, false);
    BOOST_TEST((ev == want), gt::events_string(ev));
}

BOOST_AUTO_TEST_SUITE_END()
