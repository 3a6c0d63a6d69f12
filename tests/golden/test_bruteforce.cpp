// SPEC A.2-A.4 and A.6 against exhaustive path enumeration: the DP costs are
// the minimum over ALL monotone paths, every path consumes every pixel exactly
// once, and the backtracked path is a valid path of exactly that cost.
#define BOOST_TEST_MODULE golden_bruteforce
#include <boost/test/unit_test.hpp>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brute_force.hpp"
#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"
#include "test_util.hpp"

namespace g = imap::golden;
using gt::uni;

namespace {

std::string context(const g::Params& p, const std::vector<uint8_t>& L,
                    const std::vector<uint8_t>& R) {
    const int N = static_cast<int>(L.size());
    return gt::describe(p) + " N=" + std::to_string(N) + " L=" + gt::row_string(L.data(), N) +
           " R=" + gt::row_string(R.data(), N);
}

void source_of(const g::Event& e, int& si, int& sj) {
    specref::source_of(e.step, e.i, e.j, si, sj);
}

// Checks the single-mode backtrack (vote off) against A.6: starts at (N-1,0),
// each event is the table's pointer, consecutive events are linked by their
// steps, the last step leaves column -1. Returns "" or the problem. `cost` is
// set to the path's total (including the column -1 O chain E(-1,j0) = j0*Wo).
std::string check_single_path(const g::LineTables& t, const std::vector<g::Event>& ev,
                              const bf::Line& l, int64_t& cost) {
    const int N = l.N, D = l.p.D;
    if (ev.empty()) return "no events";
    if (ev.front().i != N - 1 || ev.front().j != 0) return "first event is not (N-1,0)";
    cost = 0;
    bf::Path path;
    for (size_t k = 0; k < ev.size(); ++k) {
        const g::Event& e = ev[k];
        if (e.i < 0 || !bf::valid(N, D, e.i, e.j)) return "event at an invalid state";
        if (e.step != g::kM && e.step != g::kD && e.step != g::kO) return "event with no step";
        if (t.bp(e.i, e.j) != e.step) return "event step differs from bp";
        int si = 0, sj = 0;
        source_of(e, si, sj);
        if (k + 1 < ev.size()) {
            if (si != ev[k + 1].i || sj != ev[k + 1].j) return "events not linked";
        } else {
            if (si != -1 || !bf::valid(N, D, si, sj)) return "path does not end in column -1";
            cost += static_cast<int64_t>(sj) * l.p.Wo;
            for (int j = 1; j <= sj; ++j) path.push_back({-1, j, g::kO});
        }
        cost += bf::step_cost(l, e.i, e.j, e.step);
    }
    for (size_t k = ev.size(); k-- > 0;) path.push_back({ev[k].i, ev[k].j, ev[k].step});
    if (!bf::consumes_exactly(path, N, 0, N, 0, N)) return "path does not consume each pixel once";
    return "";
}

// Checks the bidir backtrack (vote off) against A.6. Sets the costs of the
// left part (from (-1,0) to the seed's left neighbour) and of the right part
// (seed to (N-1,0), the seed's M event itself costs nothing).
std::string check_bidir_path(const g::LineTables& t, const std::vector<g::Event>& ev,
                             const bf::Line& l, int s, int ds, int64_t& left_cost,
                             int64_t& right_cost) {
    const int N = l.N, D = l.p.D;
    size_t k0 = 0;
    while (k0 < ev.size() && ev[k0].i < s) ++k0;
    for (size_t k = k0; k < ev.size(); ++k)
        if (ev[k].i < s) return "left event after a right event";
    // Left part, in path order from (-1, 0).
    left_cost = 0;
    int pi = -1, pj = 0;
    bf::Path lpath;
    for (size_t k = 0; k < k0; ++k) {
        const g::Event& e = ev[k];
        if (!bf::valid(N, D, e.i, e.j) || e.i > s - 1) return "left event at an invalid state";
        if (pi == s - 1 && (ds < 0 || pj == ds)) return "left path continues after the seed";
        int si = 0, sj = 0;
        source_of(e, si, sj);
        if (si != pi || sj != pj) return "left events not linked";
        if (t.fp(pi, pj) != e.step) return "left event step differs from fp";
        left_cost += bf::step_cost(l, e.i, e.j, e.step);
        lpath.push_back({e.i, e.j, e.step});
        pi = e.i;
        pj = e.j;
    }
    if (pi != s - 1 || (ds >= 0 && pj != ds)) return "left path does not end at the seed";
    if (!bf::consumes_exactly(lpath, N, 0, s, 0, s + pj))
        return "left path does not consume right 0..s-1 and left 0..s-1+j once";
    // Right part: (N-1,0) ... seed.
    if (ev.size() == k0) return "no right events";
    const g::Event& seed = ev.back();
    if (seed.i != s || seed.step != g::kM) return "last event is not the seed M at site s";
    if (ds >= 0 && seed.j != ds) return "seed event not at ds";
    if (ev[k0].i != N - 1 || ev[k0].j != 0) return "right part does not start at (N-1,0)";
    right_cost = 0;
    bf::Path rpath;
    for (size_t k = k0; k + 1 < ev.size(); ++k) {
        const g::Event& e = ev[k];
        if (!bf::valid(N, D, e.i, e.j)) return "right event at an invalid state";
        if (e.i == s && e.step != g::kO) return "non-O event at site s before the seed";
        if (t.bp(e.i, e.j) != e.step) return "right event step differs from bp";
        int si = 0, sj = 0;
        source_of(e, si, sj);
        if (si != ev[k + 1].i || sj != ev[k + 1].j) return "right events not linked";
        right_cost += bf::step_cost(l, e.i, e.j, e.step);
        rpath.insert(rpath.begin(), bf::Step{e.i, e.j, e.step});
    }
    if (!bf::consumes_exactly(rpath, N, s + 1, N, s + seed.j + 1, N))
        return "right path does not consume right s+1.. and left s+j+1.. once";
    return "";
}

}  // namespace

BOOST_AUTO_TEST_CASE(enumerator_sanity) {
    // The enumerator itself: D = 1 admits only the all-M path; N = 2, D = 2
    // admits exactly MM, MOD, ODM, ODOD, OMD (5 paths).
    g::Params p;
    p.mode = g::Mode::Single;
    p.km = 1;
    p.kb = 0;
    p.Wo = 5;
    p.Wd = 2;
    std::vector<uint8_t> L = {10, 20, 30}, R = {11, 25, 27};
    p.D = 1;
    bf::Result r = bf::single(bf::Line{p, L.data(), R.data(), 3});
    BOOST_TEST(r.paths == 1);
    BOOST_TEST(r.best == 1 + 5 + 3);
    BOOST_TEST(r.consumption_ok);
    p.D = 2;
    r = bf::single(bf::Line{p, L.data(), R.data(), 2});
    BOOST_TEST(r.paths == 5);
    BOOST_TEST(r.consumption_ok);
    // MM = 1 + 5 = 6; MOD = 1 + 5 + 2 = 8; ODM = 5 + 2 + 5 = 12; ODOD = 14; OMD = 5 + 9 + 2.
    BOOST_TEST(r.best == 6);
}

BOOST_AUTO_TEST_CASE(single_mode_vs_bruteforce) {
    std::mt19937 rng(20240601);
    long total_paths = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        g::Params p;
        p.mode = g::Mode::Single;
        const int N = uni(rng, 1, 7);
        p.D = uni(rng, 1, N);
        gt::random_weights(rng, p, trial % 17 == 0);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        BOOST_TEST_CONTEXT("trial " << trial << ": " << context(p, L, R)) {
            g::validate_for_width(p, N);
            const bf::Line line{p, L.data(), R.data(), N};
            const bf::Result r = bf::single(line);
            total_paths += r.paths;
            BOOST_REQUIRE(r.any);
            BOOST_TEST(r.consumption_ok, "path " << r.first_bad);

            g::LineTables t;
            g::forward_line(p, L.data(), R.data(), N, t);
            BOOST_TEST(t.right_cost == r.best);
            // The independent SPEC transcription agrees with the brute force too.
            BOOST_TEST(specref::forward(p, L.data(), R.data(), N).right_cost == r.best);

            const std::vector<g::Event> ev = g::backtrack(nullptr, t, nullptr, false);
            int64_t cost = -1;
            const std::string err = check_single_path(t, ev, line, cost);
            BOOST_TEST(err.empty(), err << " events " << gt::events_string(ev));
            if (err.empty()) BOOST_TEST(cost == r.best);
            // Vote on without neighbours is vote off.
            BOOST_TEST((g::backtrack(nullptr, t, nullptr, true) == ev));
        }
    }
    BOOST_TEST_MESSAGE("single: " << total_paths << " paths enumerated");
}

BOOST_AUTO_TEST_CASE(bidir_mode_vs_bruteforce) {
    std::mt19937 rng(777);
    long total_paths = 0;
    int free_count = 0, fixed_count = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        g::Params p;
        p.mode = g::Mode::Bidir;
        const int N = uni(rng, 2, 8);
        p.D = uni(rng, 1, N);
        gt::random_weights(rng, p, trial % 17 == 0);
        gt::random_seed(rng, p, N);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        BOOST_TEST_CONTEXT("trial " << trial << ": " << context(p, L, R)) {
            g::validate_for_width(p, N);
            const int s = specref::seed_col(p, N);
            const int ds = p.seed_disp.free ? -1 : p.seed_disp.value;
            (ds < 0 ? free_count : fixed_count)++;
            const bf::Line line{p, L.data(), R.data(), N};
            const bf::Result rr = bf::bidir_right(line, s, ds);
            const bf::Result rl = bf::bidir_left(line, s, ds);
            total_paths += rr.paths + rl.paths;
            BOOST_REQUIRE(rr.any);
            BOOST_REQUIRE(rl.any);
            BOOST_TEST(rr.consumption_ok, "right path " << rr.first_bad);
            BOOST_TEST(rl.consumption_ok, "left path " << rl.first_bad);

            g::LineTables t;
            g::forward_line(p, L.data(), R.data(), N, t);
            BOOST_TEST(t.bidir);
            BOOST_TEST(t.s == s);
            BOOST_TEST(t.ds == ds);
            BOOST_TEST(t.right_cost == rr.best);
            BOOST_TEST(t.left_cost == rl.best);
            const specref::LineRef ref = specref::forward(p, L.data(), R.data(), N);
            BOOST_TEST(ref.right_cost == rr.best);
            BOOST_TEST(ref.left_cost == rl.best);

            const std::vector<g::Event> ev = g::backtrack(nullptr, t, nullptr, false);
            int64_t lc = -1, rc = -1;
            const std::string err = check_bidir_path(t, ev, line, s, ds, lc, rc);
            BOOST_TEST(err.empty(), err << " events " << gt::events_string(ev));
            if (err.empty()) {
                BOOST_TEST(lc == rl.best);
                BOOST_TEST(rc == rr.best);
            }
            BOOST_TEST((g::backtrack(nullptr, t, nullptr, true) == ev));
        }
    }
    BOOST_TEST(free_count > 400);
    BOOST_TEST(fixed_count > 400);
    BOOST_TEST_MESSAGE("bidir: " << total_paths << " paths enumerated");
}

BOOST_AUTO_TEST_CASE(bidir_every_seed_column_and_disparity) {
    // Exhaustive over the seed settings of a few fixed lines: every numeric
    // s in 1..N-1, every ds in 0..min(D-1, N-1-s) and free, plus balanced and
    // center.
    std::mt19937 rng(99);
    for (int trial = 0; trial < 12; ++trial) {
        const int N = uni(rng, 2, 6);
        g::Params base;
        base.mode = g::Mode::Bidir;
        base.D = uni(rng, 1, N);
        gt::random_weights(rng, base);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        std::vector<g::SeedCol> cols = {{g::SeedColKind::Balanced, 0}, {g::SeedColKind::Center, 0}};
        for (int s = 1; s <= N - 1; ++s) cols.push_back({g::SeedColKind::Fixed, s});
        for (const g::SeedCol& sc : cols) {
            g::Params p = base;
            p.seed_col = sc;
            const int s = specref::seed_col(p, N);
            for (int ds = -1; ds <= std::min(p.D - 1, N - 1 - s); ++ds) {
                p.seed_disp.free = ds < 0;
                p.seed_disp.value = ds < 0 ? 0 : ds;
                BOOST_TEST_CONTEXT("trial " << trial << ": " << context(p, L, R)) {
                    BOOST_REQUIRE_NO_THROW(g::validate_for_width(p, N));
                    const bf::Line line{p, L.data(), R.data(), N};
                    g::LineTables t;
                    g::forward_line(p, L.data(), R.data(), N, t);
                    BOOST_TEST(t.s == s);
                    BOOST_TEST(t.right_cost == bf::bidir_right(line, s, ds).best);
                    BOOST_TEST(t.left_cost == bf::bidir_left(line, s, ds).best);
                    const std::vector<g::Event> ev = g::backtrack(nullptr, t, nullptr, false);
                    int64_t lc = -1, rc = -1;
                    const std::string err = check_bidir_path(t, ev, line, s, ds, lc, rc);
                    BOOST_TEST(err.empty(), err << " events " << gt::events_string(ev));
                    if (err.empty()) {
                        BOOST_TEST(lc == t.left_cost);
                        BOOST_TEST(rc == t.right_cost);
                    }
                }
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(largest_bruteforce_sizes) {
    // N = 7 with D = 7 and D = 4 in both modes, several weight regimes.
    std::mt19937 rng(4242);
    for (int trial = 0; trial < 24; ++trial) {
        const int N = 7;
        g::Params p;
        p.D = trial % 2 ? 7 : 4;
        p.mode = trial % 4 < 2 ? g::Mode::Single : g::Mode::Bidir;
        gt::random_weights(rng, p, trial % 6 == 5);
        if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, N);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        BOOST_TEST_CONTEXT("trial " << trial << ": " << context(p, L, R)) {
            const bf::Line line{p, L.data(), R.data(), N};
            g::LineTables t;
            g::forward_line(p, L.data(), R.data(), N, t);
            if (p.mode == g::Mode::Single) {
                BOOST_TEST(t.right_cost == bf::single(line).best);
            } else {
                const int s = specref::seed_col(p, N);
                const int ds = p.seed_disp.free ? -1 : p.seed_disp.value;
                BOOST_TEST(t.right_cost == bf::bidir_right(line, s, ds).best);
                BOOST_TEST(t.left_cost == bf::bidir_left(line, s, ds).best);
            }
        }
    }
}
