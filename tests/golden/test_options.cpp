// SPEC A.9 options (docs/golden.md, "Options"): the pixel terms (census,
// Birchfield-Tomasi), the aggregated match cost, joint mode and the whole
// pipeline with options against spec_ref.hpp (an independent literal
// transcription), joint mode against exhaustive path enumeration, the
// validation of the new parameters, the presets and the cost estimate.
#define BOOST_TEST_MODULE golden_options
#include <boost/test/unit_test.hpp>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brute_force.hpp"
#include "imap/golden/cost.hpp"
#include "imap/golden/estimate.hpp"
#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"
#include "test_util.hpp"

namespace g = imap::golden;
using gt::uni;

namespace {

// A random image pair, row stride W.
struct Img {
    int W = 0, H = 0;
    std::vector<uint8_t> L, R;
    g::ImageView left() const { return {L.data(), W, H, W}; }
    g::ImageView right() const { return {R.data(), W, H, W}; }
};

Img random_img(std::mt19937& rng, int W, int H) {
    Img m;
    m.W = W;
    m.H = H;
    std::vector<uint8_t> l, r;
    gt::random_rows(rng, W, l, r);
    const bool similar = uni(rng, 0, 1) == 0;
    for (int y = 0; y < H; ++y) {
        if (!similar || uni(rng, 0, 3) == 0) gt::random_rows(rng, W, l, r);
        m.L.insert(m.L.end(), l.begin(), l.end());
        m.R.insert(m.R.end(), r.begin(), r.end());
    }
    return m;
}

g::Roi random_roi(std::mt19937& rng, const Img& m, int wmax, int hmax) {
    g::Roi roi;
    roi.w = uni(rng, 1, std::min(m.W, wmax));
    roi.h = uni(rng, 1, std::min(m.H, hmax));
    roi.x0 = uni(rng, 0, m.W - roi.w);
    roi.y0 = uni(rng, 0, m.H - roi.h);
    return roi;
}

// Random A.9 options on top of random paper parameters for width N.
g::Params random_options(std::mt19937& rng, int N) {
    g::Params p;
    const int mode = N >= 2 ? uni(rng, 0, 2) : 0;
    p.mode = mode == 0 ? g::Mode::Single : mode == 1 ? g::Mode::Bidir : g::Mode::Joint;
    p.D = uni(rng, 0, 3) == 0 ? std::min(N, 255) : uni(rng, 1, std::min(N, 255));
    gt::random_weights(rng, p, uni(rng, 0, 15) == 0);
    if (p.mode != g::Mode::Single) gt::random_seed(rng, p, N);
    p.vote = uni(rng, 0, 3) != 0;
    const int f = uni(rng, 0, 2);
    p.frame = f == 0 ? g::Frame::Cyclopean : f == 1 ? g::Frame::Left : g::Frame::Right;
    p.dissim = uni(rng, 0, 2) == 0 ? g::Dissim::Bt : g::Dissim::Ad;
    p.ad_max = uni(rng, 0, 2) == 0 ? 255 : uni(rng, 0, 255);
    p.kc = uni(rng, 0, 2) == 0 ? 0 : uni(rng, 0, 3) == 0 ? uni(rng, 0, 200000) : uni(rng, 1, 12);
    p.census = uni(rng, 1, 2);
    p.agg_rx = uni(rng, 0, 2);
    p.agg_ry = uni(rng, 0, 2);
    if (uni(rng, 0, 3) == 0) p.km = p.kb = 0, p.kc = std::max(p.kc, 1);  // census only
    return p;
}

std::string describe(const g::Params& p) {
    std::ostringstream os;
    os << gt::describe(p) << " dissim=" << g::to_string(p.dissim) << " ad_max=" << p.ad_max
       << " kc=" << p.kc << " census=" << p.census << " agg=" << p.agg_rx << "," << p.agg_ry;
    return os.str();
}

std::string img_string(const Img& m) {
    std::ostringstream os;
    for (int y = 0; y < m.H; ++y)
        os << "  L" << y << "=" << gt::row_string(m.L.data() + y * m.W, m.W) << " R" << y << "="
           << gt::row_string(m.R.data() + y * m.W, m.W) << "\n";
    return os.str();
}

// The A.9 cost table of ROI line y by spec_ref (int64, [i * D + j], valid states).
std::vector<int64_t> ref_costs(const g::Params& p, const Img& m, const g::Roi& roi, int y) {
    std::vector<int64_t> c(static_cast<size_t>(roi.w) * p.D, 0);
    for (int i = 0; i < roi.w; ++i)
        for (int j = 0; j < p.D && i + j < roi.w; ++j)
            c[static_cast<size_t>(i) * p.D + j] = specref::a9_cost(p, m.L, m.R, m.W, roi, y, i, j);
    return c;
}

std::vector<g::Event> to_events(const std::vector<specref::Ev>& ev) {
    std::vector<g::Event> out;
    for (const auto& e : ev) out.push_back({e.i, e.j, static_cast<g::Step>(e.step)});
    return out;
}

// Joint-mode tables against spec_ref: costs, meeting level, every pointer.
int compare_joint(const g::LineTables& t, const specref::LineRef& r) {
    int bad = 0;
    auto check = [&](bool ok, const std::string& what) {
        if (!ok) {
            ++bad;
            BOOST_ERROR(what);
        }
    };
    check(t.joint && r.joint, "joint flag");
    check(t.s == r.s, "s " + std::to_string(t.s) + " != " + std::to_string(r.s));
    check(t.js == r.js, "js " + std::to_string(t.js) + " != " + std::to_string(r.js));
    check(t.right_cost == r.right_cost,
          "cost " + std::to_string(t.right_cost) + " != " + std::to_string(r.right_cost));
    if (bad) return bad;
    for (int i = 0; i <= r.s; ++i)
        for (int j = 0; j < r.D; ++j)
            check(t.bp(i, j) == r.bpv(i, j), "bp(" + std::to_string(i) + "," + std::to_string(j) +
                                                 ") = " + std::to_string(t.bp(i, j)) + ", want " +
                                                 std::to_string(r.bpv(i, j)));
    for (int i = r.s; i < r.N; ++i)
        for (int j = 0; j < r.D; ++j)
            check(t.fp(i, j) == r.fpv(i, j), "fp(" + std::to_string(i) + "," + std::to_string(j) +
                                                 ") = " + std::to_string(t.fp(i, j)) + ", want " +
                                                 std::to_string(r.fpv(i, j)));
    return bad;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pixel_terms)

BOOST_AUTO_TEST_CASE(census_codes_match_the_definition) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 60; ++trial) {
        const Img m = random_img(rng, uni(rng, 1, 14), uni(rng, 1, 7));
        const g::Roi roi = random_roi(rng, m, 12, 6);
        for (int r = 1; r <= 2; ++r) {
            const std::vector<uint8_t> got = g::census_codes(m.left(), roi, r);
            for (int y = 0; y < roi.h; ++y)
                for (int x = 0; x < roi.w; ++x)
                    BOOST_TEST(int(got[static_cast<size_t>(y) * roi.w + x]) ==
                                   specref::census(m.L, m.W, roi, x, y, r),
                               "trial " << trial << " r " << r << " x " << x << " y " << y);
        }
    }
}

BOOST_AUTO_TEST_CASE(census_code_by_hand) {
    // 3x3 image, centre 50: darker neighbours are bits 0 (-1,-1), 4 (1,0), 7 (1,1).
    const std::vector<uint8_t> img = {10, 60, 70, 50, 50, 20, 80, 90, 49};
    const g::Roi roi{0, 0, 3, 3};
    const std::vector<uint8_t> c = g::census_codes({img.data(), 3, 3, 3}, roi, 1);
    BOOST_TEST(int(c[4]) == (1 | 16 | 128));
    // Corner (0,0) = 10 with replicated borders: nothing is darker.
    BOOST_TEST(int(c[0]) == 0);
}

BOOST_AUTO_TEST_CASE(bt_matches_the_interval_definition) {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = uni(rng, 1, 5);
        std::vector<uint8_t> lrow(static_cast<size_t>(n)), rrow(static_cast<size_t>(n));
        const int base = uni(rng, 0, 255);
        for (int x = 0; x < n; ++x) {
            lrow[x] = static_cast<uint8_t>(uni(rng, 0, 1) ? uni(rng, 0, 255)
                                                          : std::min(255, base + uni(rng, 0, 9)));
            rrow[x] = static_cast<uint8_t>(uni(rng, 0, 1) ? uni(rng, 0, 255)
                                                          : std::min(255, base + uni(rng, 0, 9)));
        }
        std::vector<uint8_t> llo(n), lhi(n), rlo(n), rhi(n);
        g::bt_bounds(lrow.data(), n, llo.data(), lhi.data());
        g::bt_bounds(rrow.data(), n, rlo.data(), rhi.data());
        const g::Roi roi{0, 0, n, 1};
        const int xr = uni(rng, 0, n - 1), xl = uni(rng, 0, n - 1);
        const int a = rrow[xr], b = lrow[xl];
        const int want = std::min(specref::bt_half(a, lrow, n, roi, xl, 0),
                                  specref::bt_half(b, rrow, n, roi, xr, 0));
        const int got = g::bt_dissim(a, rlo[xr], rhi[xr], b, llo[xl], lhi[xl]);
        BOOST_TEST(got == want, "trial " << trial << " L " << gt::row_string(lrow.data(), n)
                                         << " R " << gt::row_string(rrow.data(), n) << " xr " << xr
                                         << " xl " << xl);
        BOOST_TEST(got <= std::abs(a - b));  // never more than |a - b|
    }
}

BOOST_AUTO_TEST_CASE(bt_by_hand) {
    // Left row 10 20 30: pixel 1 spans [15, 25]. Right pixel 24 is inside: 0.
    const std::vector<uint8_t> l = {10, 20, 30}, r = {24, 24, 24};
    uint8_t llo[3], lhi[3], rlo[3], rhi[3];
    g::bt_bounds(l.data(), 3, llo, lhi);
    g::bt_bounds(r.data(), 3, rlo, rhi);
    BOOST_TEST(int(llo[1]) == 15);
    BOOST_TEST(int(lhi[1]) == 25);
    BOOST_TEST(g::bt_dissim(24, rlo[0], rhi[0], 20, llo[1], lhi[1]) == 0);
    // Right 40 (flat) against left pixel 2 ([25, 30]): 10 both ways.
    BOOST_TEST(g::bt_dissim(40, 40, 40, 30, llo[2], lhi[2]) == 10);
    // Right 24 against [25, 30]: 1; left 30 against the flat right [24, 24]:
    // 6; the smaller wins.
    BOOST_TEST(g::bt_dissim(24, rlo[0], rhi[0], 30, llo[2], lhi[2]) == 1);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(aggregated_cost)

BOOST_AUTO_TEST_CASE(cost_volume_matches_the_window_sum) {
    std::mt19937 rng(21);
    int failures = 0;
    for (int trial = 0; trial < 150 && failures < 3; ++trial) {
        const Img m = random_img(rng, uni(rng, 1, 14), uni(rng, 1, 7));
        const g::Roi roi = random_roi(rng, m, 12, 6);
        g::Params p = random_options(rng, roi.w);
        if (!g::uses_cost_volume(p)) p.agg_rx = 1;
        BOOST_TEST_CONTEXT("trial " << trial << " " << describe(p) << "\n" << img_string(m)) {
            g::CostVolume<int64_t> vol(p, m.left(), m.right(), roi);
            g::CostVolume<int32_t> vol32(p, m.left(), m.right(), roi);
            const bool fits32 = g::window_terms(p) * g::pixel_cost_max(p) < (int64_t{1} << 30);
            for (int y = 0; y < roi.h; ++y) {
                const int64_t* got = vol.line(y);
                const int32_t* got32 = vol32.line(y);
                const std::vector<int64_t> want = ref_costs(p, m, roi, y);
                int bad = 0;
                for (int i = 0; i < roi.w; ++i)
                    for (int j = 0; j < p.D && i + j < roi.w; ++j) {
                        const size_t k = static_cast<size_t>(i) * p.D + j;
                        if (got[k] != want[k] || (fits32 && got32[k] != want[k])) ++bad;
                    }
                BOOST_TEST(bad == 0, "line " << y);
                failures += bad != 0;
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(aggregation_by_hand) {
    // One line of 4 pixels, D = 1, |a - b| summed over 3 sites (borders replicated).
    const std::vector<uint8_t> L = {10, 20, 30, 40}, R = {11, 25, 30, 50};
    g::Params p;
    p.D = 1;
    p.km = 1;
    p.kb = 0;
    p.agg_rx = 1;
    g::CostVolume<int64_t> vol(p, {L.data(), 4, 1, 4}, {R.data(), 4, 1, 4}, {0, 0, 4, 1});
    const int64_t* c = vol.line(0);
    // pixel terms 1 5 0 10; site 0 sums sites -1 (= 0), 0, 1: 1 + 1 + 5.
    BOOST_TEST(c[0] == 7);
    BOOST_TEST(c[1] == 6);
    BOOST_TEST(c[2] == 15);
    BOOST_TEST(c[3] == 20);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(joint_mode)

BOOST_AUTO_TEST_CASE(joint_finds_the_line_optimum) {
    // Exhaustive enumeration: the joint cost is the optimum over every
    // complete path (-1,0) -> (N-1,0), and its events (vote off) are such a
    // path of exactly that cost.
    std::mt19937 rng(31);
    for (int trial = 0; trial < 250; ++trial) {
        const int N = uni(rng, 2, 7);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        g::Params p;
        p.mode = g::Mode::Joint;
        p.D = uni(rng, 1, N);
        gt::random_weights(rng, p);
        gt::random_seed(rng, p, N);
        p.seed_disp.free = true;
        p.vote = false;
        g::LineTables t;
        g::forward_line(p, L.data(), R.data(), N, t);
        const bf::Line line{p, L.data(), R.data(), N};
        const bf::Result best = bf::single(line);
        BOOST_TEST_CONTEXT("trial " << trial << " " << gt::describe(p) << " L "
                                    << gt::row_string(L.data(), N) << " R "
                                    << gt::row_string(R.data(), N)) {
            BOOST_REQUIRE(best.any);
            BOOST_TEST(t.right_cost == best.best);
            const std::vector<g::Event> ev = g::backtrack(nullptr, t, nullptr, false);
            // Events are in backtrack order: reversed, they are the path.
            bf::Path path;
            int64_t cost = 0;
            for (auto it = ev.rbegin(); it != ev.rend(); ++it) {
                path.push_back({it->i, it->j, it->step});
                cost += bf::step_cost(line, it->i, it->j, it->step);
            }
            // plus the O steps in column -1 before the first event
            const int j0 = path.empty() ? 0 : path.front().j + (path.front().step == g::kD ? 1 : 0);
            cost += static_cast<int64_t>(j0) * p.Wo;
            BOOST_TEST(cost == best.best, "path " << bf::path_string(path));
            BOOST_TEST(!path.empty());
            BOOST_TEST((path.back().i == N - 1 && path.back().j == 0));
            // every pixel exactly once, counting column -1's O steps
            std::vector<int> right(static_cast<size_t>(N), 0), left(static_cast<size_t>(N), 0);
            bf::consume(path, right, left);
            for (int x = 0; x < j0; ++x) ++left[x];
            for (int x = 0; x < N; ++x) BOOST_TEST((right[x] == 1 && left[x] == 1), "pixel " << x);
        }
    }
}

BOOST_AUTO_TEST_CASE(joint_with_options_finds_the_optimum) {
    // The same with an A.9 cost table (any costs: the DP only reads them).
    std::mt19937 rng(32);
    for (int trial = 0; trial < 150; ++trial) {
        const int N = uni(rng, 2, 7);
        g::Params p;
        p.mode = g::Mode::Joint;
        p.D = uni(rng, 1, N);
        p.km = 1;
        p.kb = 0;
        p.kc = 4;
        p.agg_rx = 1;  // bound: 3 * (255 + 32)
        p.Wd = uni(rng, 0, 300);
        p.Wo = p.Wd + uni(rng, 0, 300);
        p.vote = false;
        std::vector<int64_t> cost(static_cast<size_t>(N) * p.D);
        for (auto& c : cost) c = uni(rng, 0, 3 * 287);
        g::LineTables t;
        g::forward_line_cost(p, cost.data(), N, t);
        bf::Line line{p, nullptr, nullptr, N};
        line.wm = [&](int i, int j) { return cost[static_cast<size_t>(i) * p.D + j]; };
        const bf::Result best = bf::single(line);
        BOOST_TEST(t.right_cost == best.best, "trial " << trial);
        // and the single mode on the same table agrees
        g::Params ps = p;
        ps.mode = g::Mode::Single;
        g::LineTables ts;
        g::forward_line_cost(ps, cost.data(), N, ts);
        BOOST_TEST(ts.right_cost == best.best, "trial " << trial);
    }
}

BOOST_AUTO_TEST_CASE(joint_fixed_seed_disparity_passes_through_it) {
    std::mt19937 rng(33);
    for (int trial = 0; trial < 100; ++trial) {
        const int N = uni(rng, 2, 7);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        g::Params p;
        p.mode = g::Mode::Joint;
        p.D = uni(rng, 1, N);
        gt::random_weights(rng, p);
        p.seed_col = {g::SeedColKind::Fixed, uni(rng, 1, N - 1)};
        p.seed_disp.free = false;
        p.seed_disp.value = uni(rng, 0, std::min(p.D - 1, N - 1 - p.seed_col.value));
        g::LineTables t;
        g::forward_line(p, L.data(), R.data(), N, t);
        BOOST_TEST(t.js == p.seed_disp.value);
        // the optimum over the paths through (s, ds)
        const bf::Line line{p, L.data(), R.data(), N};
        int64_t best = -1;
        const int s = p.seed_col.value, ds = p.seed_disp.value;
        bf::Path path;
        bf::enumerate(
            line, N - 1, -1, 0, path, 0, [&](int i, int j) { return i == N - 1 && j == 0; },
            [&](const bf::Path& pa, int64_t c) {
                bool through = false;
                for (const auto& st : pa) through |= st.i == s && st.j == ds;
                if (through && (best < 0 || c < best)) best = c;
            });
        BOOST_TEST(t.right_cost == best, "trial " << trial << " " << gt::describe(p));
    }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(pipeline)

BOOST_AUTO_TEST_CASE(random_options_match_spec_ref) {
    // compute(), the joint tables and the events against spec_ref.hpp.
    std::mt19937 rng(41);
    int failures = 0, joint = 0, census = 0, agg = 0, bt = 0;
    for (int trial = 0; trial < 300 && failures < 3; ++trial) {
        const Img m = random_img(rng, uni(rng, 1, 14), uni(rng, 1, 7));
        const g::Roi roi = random_roi(rng, m, 12, 6);
        const g::Params p = random_options(rng, roi.w);
        const bool fill = uni(rng, 0, 1) == 1;
        joint += p.mode == g::Mode::Joint;
        census += p.kc > 0;
        agg += p.agg_rx + p.agg_ry > 0;
        bt += p.dissim == g::Dissim::Bt;
        BOOST_TEST_CONTEXT("trial " << trial << " " << describe(p) << " fill=" << fill << " ROI "
                                    << roi.x0 << "," << roi.y0 << "," << roi.w << "," << roi.h
                                    << "\n"
                                    << img_string(m)) {
            int bad = 0;
            if (p.mode == g::Mode::Joint) {
                std::vector<g::LineTables> tabs(static_cast<size_t>(roi.h));
                std::vector<specref::LineRef> refs;
                for (int y = 0; y < roi.h; ++y) {
                    const std::vector<int64_t> c = ref_costs(p, m, roi, y);
                    g::forward_line_cost(p, c.data(), roi.w, tabs[y]);
                    refs.push_back(specref::forward(p, roi.w, [&](int i, int j) {
                        return c[static_cast<size_t>(i) * p.D + j];
                    }));
                    bad += compare_joint(tabs[y], refs[y]);
                }
                for (int y = 0; y < roi.h && bad == 0; ++y) {
                    const g::LineTables* a = y > 0 ? &tabs[y - 1] : nullptr;
                    const g::LineTables* b = y + 1 < roi.h ? &tabs[y + 1] : nullptr;
                    const specref::LineRef* ra = y > 0 ? &refs[y - 1] : nullptr;
                    const specref::LineRef* rb = y + 1 < roi.h ? &refs[y + 1] : nullptr;
                    const auto got = g::backtrack(a, tabs[y], b, p.vote);
                    const auto want = to_events(specref::backtrack(ra, refs[y], rb, p.vote));
                    if (!(got == want)) {
                        ++bad;
                        BOOST_ERROR("line " << y << " events " << gt::events_string(got)
                                            << "\n  want " << gt::events_string(want));
                    }
                }
            }
            const g::DisparityMap map = g::compute(p, m.left(), m.right(), roi, fill);
            const std::vector<uint8_t> want = specref::compute(p, m.L, m.R, m.W, roi, fill);
            if (map.data != want) {
                ++bad;
                BOOST_ERROR("compute() output differs");
            }
            BOOST_TEST(bad == 0);
            failures += bad != 0;
        }
    }
    BOOST_TEST(joint > 60);
    BOOST_TEST(census > 100);
    BOOST_TEST(agg > 150);
    BOOST_TEST(bt > 50);
}

BOOST_AUTO_TEST_CASE(options_off_is_the_paper_algorithm) {
    // Options at their "off" values take the paper's code path and give
    // exactly its output; census radius alone (kc = 0) changes nothing.
    std::mt19937 rng(43);
    for (int trial = 0; trial < 40; ++trial) {
        const Img m = random_img(rng, uni(rng, 2, 14), uni(rng, 1, 6));
        const g::Roi roi{0, 0, m.W, m.H};
        g::Params p;
        p.D = uni(rng, 1, m.W);
        gt::random_weights(rng, p);
        p.mode = uni(rng, 0, 1) ? g::Mode::Bidir : g::Mode::Single;
        BOOST_TEST(!g::uses_options(p));
        BOOST_TEST(!g::uses_cost_volume(p));
        g::Params q = p;
        q.census = 1;
        BOOST_TEST(!g::uses_options(q));
        BOOST_TEST(g::compute(p, m.left(), m.right(), roi).data ==
                   specref::compute(p, m.L, m.R, m.W, roi, false));
        BOOST_TEST(g::compute(q, m.left(), m.right(), roi).data ==
                   g::compute(p, m.left(), m.right(), roi).data);
        // A window of 1 x 1 with the paper's Wm through the cost volume: same result.
        q = p;
        q.ad_max = 254;  // forces the cost volume; only |a - b| = 255 differs
        bool has255 = false;
        for (size_t k = 0; k < m.L.size(); ++k) has255 |= std::abs(m.L[k] - m.R[k]) == 255;
        if (!has255 && p.km > 0) {
            BOOST_TEST(g::uses_cost_volume(q));
        }
    }
}

BOOST_AUTO_TEST_CASE(cost_table_path_equals_the_paper_path) {
    // The paper's Wm given as a cost table gives the paper's tables exactly
    // (the kTable code path is the same recurrence).
    std::mt19937 rng(44);
    for (int trial = 0; trial < 200; ++trial) {
        const int N = uni(rng, 2, 20);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        g::Params p;
        p.D = uni(rng, 1, std::min(N, 255));
        gt::random_weights(rng, p, trial % 13 == 0);
        const int mode = uni(rng, 0, 2);
        p.mode = mode == 0 ? g::Mode::Single : mode == 1 ? g::Mode::Bidir : g::Mode::Joint;
        gt::random_seed(rng, p, N);
        std::vector<int64_t> c(static_cast<size_t>(N) * p.D, 0);
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < p.D && i + j < N; ++j)
                c[static_cast<size_t>(i) * p.D + j] = g::match_cost(p, R[i], L[i + j]);
        g::LineTables a, b;
        g::forward_line(p, L.data(), R.data(), N, a);
        g::forward_line_cost(p, c.data(), N, b);
        BOOST_TEST((a.right == b.right && a.left == b.left && a.right_cost == b.right_cost &&
                    a.left_cost == b.left_cost && a.js == b.js),
                   "trial " << trial << " " << gt::describe(p));
    }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(params_and_presets)

BOOST_AUTO_TEST_CASE(new_parameters_are_validated) {
    auto expect = [](g::Params p, const std::string& needle) {
        try {
            g::validate_params(p);
            BOOST_ERROR("accepted: " << needle);
        } catch (const g::ParamError& e) {
            BOOST_TEST(std::string(e.what()).find(needle) != std::string::npos,
                       e.what() << " (want " << needle << ")");
        }
    };
    g::Params p;
    p.kc = -1;
    expect(p, "parameter kc = -1 is out of range (allowed: 0..1000000)");
    p = {};
    p.ad_max = 256;
    expect(p, "parameter ad-max = 256 is out of range (allowed: 0..255)");
    p = {};
    p.census = 3;
    expect(p, "parameter census = 3 is out of range (allowed: 1..2");
    p = {};
    p.census = 0;
    expect(p, "parameter census = 0");
    p = {};
    p.agg_rx = 8;
    expect(p, "parameter agg-rx = 8 is out of range (allowed: 0..7)");
    p = {};
    p.agg_ry = -1;
    expect(p, "parameter agg-ry = -1 is out of range (allowed: 0..7)");
    p = {};
    p.km = p.kb = 0;
    expect(p, "km = 0, kb = 0 and kc = 0");
    p.kc = 1;  // census alone is a valid match cost
    BOOST_CHECK_NO_THROW(g::validate_params(p));
    p = {};
    p.mode = g::Mode::Joint;
    p.D = 1;
    try {
        g::validate_for_width(p, 1);
        BOOST_ERROR("joint mode accepted N = 1");
    } catch (const g::ParamError& e) {
        BOOST_TEST(std::string(e.what()).find("joint mode") != std::string::npos, e.what());
    }
    p.seed_col = {g::SeedColKind::Fixed, 5};
    try {
        g::validate_for_width(p, 5);
        BOOST_ERROR("joint mode accepted seed column 5 of 5");
    } catch (const g::ParamError& e) {
        BOOST_TEST(std::string(e.what()).find("seed-col = 5") != std::string::npos, e.what());
    }
}

BOOST_AUTO_TEST_CASE(presets) {
    const g::Params paper = g::preset("paper");
    const g::Params d;
    BOOST_TEST(!g::uses_options(paper));
    BOOST_TEST(g::options_string(paper).empty());
    BOOST_TEST((paper.km == d.km && paper.kb == d.kb && paper.gb == d.gb && paper.Wo == d.Wo &&
                paper.Wd == d.Wd && paper.mode == d.mode && paper.vote == d.vote &&
                paper.D == d.D));
    const g::Params q = g::preset("quality");
    BOOST_TEST(g::uses_options(q));
    BOOST_CHECK_NO_THROW(g::validate_for_width(q, 128));
    BOOST_TEST(g::options_string(q) == "--mode joint --ad-max 16 --kc 4 --agg-rx 2 --agg-ry 2");
    BOOST_TEST((q.agg_ry == 2 && q.Wo == 400 && q.Wd == 400 && q.census == 2));
    BOOST_CHECK_THROW(g::preset("fast"), g::ParamError);
    // joint alone is an option; a census radius without kc is not
    g::Params p;
    p.mode = g::Mode::Joint;
    BOOST_TEST(g::options_string(p) == "--mode joint");
}

BOOST_AUTO_TEST_CASE(cost_estimate_arithmetic) {
    // docs/golden.md, "Firmware cost estimates": the quality preset (its 5x5
    // window) at the headline case (N = 128, D = 64,
    // balanced s = 48: the busier joint PE computes max(s + 1, N - 1 - s) =
    // 79 columns).
    g::Params q = g::preset("quality");
    q.agg_ry = 2;
    q.D = 64;
    BOOST_TEST(g::resolve_seed_col(q, 128) == 48);
    const g::OptionCost c = g::estimate_options(q, 128);
    BOOST_TEST(c.nodes == 79 * 64);
    // pixel cost <= 16 + 4 * 8 = 48 (1 byte), row sum <= 240 (1 byte), window
    // <= 1200 (2 bytes): ad-max 1 + census (ld 1 + xor 1 + nibbles 2 + 2 ldx 4
    // + add 1 + kc = one shift 1 + add into the pixel cost 1) 11 + agg-rx (st 1
    // + 4 ld + 4 add) 9 + agg-ry 2 x (ring 2 x 2 hops + 2 selects + 2 two-byte
    // adds = 4 + 2 + 4) 20.
    BOOST_TEST(c.per_node == 1.0 + 11 + 9 + 20);
    BOOST_TEST(c.pixels == (79 + 1) + (79 + 64 + 1) + 8);
    BOOST_TEST(c.per_pixel == 2.0 * 2 * 2 + 4 + 25);
    BOOST_TEST(c.per_batch == 14 * 64 + 20);
    BOOST_TEST(c.local_bytes == 232 + 16 + 4 * 64);
    BOOST_TEST(c.cycles == 79 * 64 * 41 + 232 * 37 + 916);
    BOOST_TEST(g::estimate_options(g::preset("paper"), 128).cycles == 0);
    // every option runs in the firmware (ad-max, joint, the census, the
    // whole window): measured, not estimated
    const g::OptionCost m = g::estimate_options(q, 128, /*in_firmware=*/true);
    BOOST_TEST(m.per_node == 0);
    BOOST_TEST(m.per_pixel == 0);
    BOOST_TEST(m.per_batch == 0);
    BOOST_TEST(m.cycles == 0);
    g::Params h = g::preset("quality");
    h.D = 64;
    BOOST_TEST(g::estimate_options(h, 128, /*in_firmware=*/true).cycles == 0);
    BOOST_TEST(g::estimate_options(h, 128).cycles > 0);
    // bt runs in the firmware too (BT_BOUNDS, WM_ADD): estimated only outside it
    g::Params b = h;
    b.dissim = g::Dissim::Bt;
    BOOST_TEST(g::estimate_options(b, 128, /*in_firmware=*/true).cycles == 0);
    BOOST_TEST(g::estimate_options(b, 128).cycles > g::estimate_options(h, 128).cycles);
    const g::Params pp = g::paper_part(q);
    BOOST_TEST(!g::uses_options(pp));
    BOOST_TEST((pp.mode == g::Mode::Bidir && pp.km == q.km && pp.Wo == q.Wo));
}

BOOST_AUTO_TEST_CASE(tradeoff_variants_are_valid) {
    bool have_paper = false, have_quality = false;
    for (const auto& v : g::tradeoff_variants()) {
        BOOST_CHECK_NO_THROW(g::validate_for_width(v.p, 128));
        have_paper |= v.name == "paper";
        have_quality |= v.name == "quality";
    }
    BOOST_TEST(have_paper);
    BOOST_TEST(have_quality);
}

BOOST_AUTO_TEST_SUITE_END()
