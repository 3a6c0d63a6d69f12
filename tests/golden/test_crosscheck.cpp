// compute() and every intermediate (pointer tables, costs, voted pointers,
// events, frames, fill) against spec_ref.hpp, an independent literal
// transcription of SPEC Part A, on a few hundred random small images; plus
// determinism, ROI/stride handling, exact 64-bit costs and the vote end to end.
#define BOOST_TEST_MODULE golden_crosscheck
#include <boost/test/unit_test.hpp>

#include <climits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"
#include "test_util.hpp"

namespace g = imap::golden;
using gt::uni;

namespace {

// A random image pair of size W x H with stride `stride` (>= W).
struct Pair {
    int W = 0, H = 0, stride = 0;
    std::vector<uint8_t> L, R;  // stride * H bytes
    g::ImageView left() const { return {L.data(), W, H, stride}; }
    g::ImageView right() const { return {R.data(), W, H, stride}; }
    // Contiguous copies (row stride W) for spec_ref.
    std::vector<uint8_t> packed(const std::vector<uint8_t>& img) const {
        std::vector<uint8_t> out;
        for (int y = 0; y < H; ++y)
            out.insert(out.end(), img.begin() + y * stride, img.begin() + y * stride + W);
        return out;
    }
};

Pair random_pair(std::mt19937& rng, int W, int H) {
    Pair p;
    p.W = W;
    p.H = H;
    p.stride = W + uni(rng, 0, 3);
    p.L.assign(static_cast<size_t>(p.stride) * H, 0xAB);
    p.R.assign(static_cast<size_t>(p.stride) * H, 0xCD);
    std::vector<uint8_t> l, r;
    const bool similar_rows = uni(rng, 0, 2) == 0;  // rows alike: the vote matters
    gt::random_rows(rng, W, l, r);
    for (int y = 0; y < H; ++y) {
        if (!similar_rows || uni(rng, 0, 3) == 0) gt::random_rows(rng, W, l, r);
        for (int x = 0; x < W; ++x) {
            p.L[static_cast<size_t>(y) * p.stride + x] = l[x];
            p.R[static_cast<size_t>(y) * p.stride + x] = r[x];
        }
    }
    return p;
}

std::string ctx_string(const g::Params& p, const Pair& img, const g::Roi& roi, bool fill) {
    std::ostringstream os;
    os << gt::describe(p) << " fill=" << fill << " image " << img.W << "x" << img.H << " ROI "
       << roi.x0 << "," << roi.y0 << "," << roi.w << "," << roi.h << "\n";
    for (int y = 0; y < img.H; ++y)
        os << "  L" << y << "=" << gt::row_string(img.L.data() + y * img.stride, img.W) << " R" << y
           << "=" << gt::row_string(img.R.data() + y * img.stride, img.W) << "\n";
    return os.str();
}

// The pointer tables and costs of one line: every entry the SPEC or stereo.hpp
// defines. Returns the number of mismatches (each one reported).
int compare_tables(const g::LineTables& t, const specref::LineRef& r) {
    int bad = 0;
    auto check = [&](bool ok, const std::string& what) {
        if (!ok) {
            ++bad;
            BOOST_ERROR(what);
        }
    };
    const int N = r.N, D = r.D;
    check(t.N == N && t.D == D, "N/D");
    check(t.bidir == r.bidir, "bidir flag");
    check(t.right_cost == r.right_cost,
          "right_cost " + std::to_string(t.right_cost) + " != " + std::to_string(r.right_cost));
    if (bad) return bad;
    if (!r.bidir) {
        check(t.right_first == 0, "right_first");
        check(t.right.size() == static_cast<size_t>(N) * D, "right size");
        if (bad) return bad;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < D; ++j)
                check(t.bp(i, j) == r.bpv(i, j),
                      "bp(" + std::to_string(i) + "," + std::to_string(j) + ") = " +
                          std::to_string(t.bp(i, j)) + ", want " + std::to_string(r.bpv(i, j)));
        return bad;
    }
    check(t.s == r.s, "s " + std::to_string(t.s) + " != " + std::to_string(r.s));
    check(t.ds == r.ds, "ds " + std::to_string(t.ds) + " != " + std::to_string(r.ds));
    check(t.left_cost == r.left_cost,
          "left_cost " + std::to_string(t.left_cost) + " != " + std::to_string(r.left_cost));
    check(t.right_first == r.s, "right_first");
    check(t.right.size() == static_cast<size_t>(N - r.s) * D, "right size");
    check(t.left.size() == static_cast<size_t>(r.s + 1) * D, "left size");
    if (bad) return bad;
    // Site s as stereo.hpp describes it, sites > s by A.3 (spec_ref does both).
    for (int i = r.s; i < N; ++i)
        for (int j = 0; j < D; ++j)
            check(t.bp(i, j) == r.bpv(i, j), "bp(" + std::to_string(i) + "," + std::to_string(j) +
                                                 ") = " + std::to_string(t.bp(i, j)) + ", want " +
                                                 std::to_string(r.bpv(i, j)));
    for (int i = -1; i <= r.s - 1; ++i) {
        for (int j = 0; j < D; ++j) {
            const std::string where = "fp(" + std::to_string(i) + "," + std::to_string(j) +
                                      ") = " + std::to_string(t.fp(i, j)) + ", want " +
                                      std::to_string(r.fpv(i, j));
            if (i == r.s - 1 && r.Gr[i + 1][j] && r.fpv(i, j) != g::kO) {
                // The seed's left neighbour / a free site s-1: the pointer value
                // is not specified, only that the state is reachable.
                check(t.fp(i, j) != g::kNone, where + " (reachable)");
            } else {
                check(t.fp(i, j) == r.fpv(i, j), where);
            }
        }
    }
    return bad;
}

bool unspecified_left_entry(const specref::LineRef& r, int i, int j) {
    return i == r.s - 1 && r.Gr[i + 1][j] && r.fpv(i, j) != g::kO;
}

int compare_votes(const g::LineTables* ta, const g::LineTables& t, const g::LineTables* tb,
                  const specref::LineRef* ra, const specref::LineRef& r,
                  const specref::LineRef* rb) {
    int bad = 0;
    const int first = r.bidir ? r.s : 0;
    for (int i = first; i < r.N; ++i)
        for (int j = 0; j < r.D; ++j) {
            const int got = g::voted_bp(ta, t, tb, i, j), want = specref::voted_bp(ra, r, rb, i, j);
            if (got != want) {
                ++bad;
                BOOST_ERROR("voted_bp(" << i << "," << j << ") = " << got << ", want " << want);
            }
        }
    if (!r.bidir) return bad;
    for (int i = -1; i <= r.s - 1; ++i)
        for (int j = 0; j < r.D; ++j) {
            if (unspecified_left_entry(r, i, j)) continue;
            const int got = g::voted_fp(ta, t, tb, i, j), want = specref::voted_fp(ra, r, rb, i, j);
            if (got != want) {
                ++bad;
                BOOST_ERROR("voted_fp(" << i << "," << j << ") = " << got << ", want " << want);
            }
        }
    return bad;
}

std::vector<g::Event> to_events(const std::vector<specref::Ev>& ev) {
    std::vector<g::Event> out;
    for (const auto& e : ev) out.push_back({e.i, e.j, static_cast<g::Step>(e.step)});
    return out;
}

// Everything for one image / parameter set. Returns false on a mismatch.
bool crosscheck(const g::Params& p, const Pair& img, const g::Roi& roi, bool fill) {
    int bad = 0;
    BOOST_TEST_CONTEXT(ctx_string(p, img, roi, fill)) {
        const int N = roi.w;
        std::vector<g::LineTables> tabs(static_cast<size_t>(roi.h));
        std::vector<specref::LineRef> refs;
        for (int y = 0; y < roi.h; ++y) {
            const size_t off = static_cast<size_t>(roi.y0 + y) * img.stride + roi.x0;
            g::forward_line(p, img.L.data() + off, img.R.data() + off, N, tabs[y]);
            refs.push_back(specref::forward(p, img.L.data() + off, img.R.data() + off, N));
            BOOST_TEST_CONTEXT("line " << y) {
                bad += compare_tables(tabs[y], refs[y]);
            }
        }
        if (bad) return false;
        for (int y = 0; y < roi.h; ++y) {
            BOOST_TEST_CONTEXT("line " << y) {
                const bool has_nb = p.vote && y > 0 && y + 1 < roi.h;
                const g::LineTables* ta = has_nb ? &tabs[y - 1] : nullptr;
                const g::LineTables* tb = has_nb ? &tabs[y + 1] : nullptr;
                const specref::LineRef* ra = has_nb ? &refs[y - 1] : nullptr;
                const specref::LineRef* rb = has_nb ? &refs[y + 1] : nullptr;
                bad += compare_votes(ta, tabs[y], tb, ra, refs[y], rb);
                const g::LineTables* na = y > 0 ? &tabs[y - 1] : nullptr;
                const g::LineTables* nb = y + 1 < roi.h ? &tabs[y + 1] : nullptr;
                const specref::LineRef* rna = y > 0 ? &refs[y - 1] : nullptr;
                const specref::LineRef* rnb = y + 1 < roi.h ? &refs[y + 1] : nullptr;
                const auto got = g::backtrack(na, tabs[y], nb, p.vote);
                const auto want = to_events(specref::backtrack(rna, refs[y], rnb, p.vote));
                if (!(got == want)) {
                    ++bad;
                    BOOST_ERROR("events " << gt::events_string(got) << "\n  want "
                                          << gt::events_string(want));
                }
            }
        }
        const g::DisparityMap map = g::compute(p, img.left(), img.right(), roi, fill);
        const std::vector<uint8_t> want =
            specref::compute(p, img.packed(img.L), img.packed(img.R), img.W, roi, fill);
        if (map.width != roi.w || map.height != roi.h || map.data != want) {
            ++bad;
            BOOST_ERROR("compute() output differs");
            for (int y = 0; y < roi.h && map.data.size() == want.size(); ++y)
                BOOST_TEST_MESSAGE(
                    "row " << y << " got " << gt::row_string(map.data.data() + y * roi.w, roi.w)
                           << " want " << gt::row_string(want.data() + y * roi.w, roi.w));
        }
    }
    return bad == 0;
}

g::Params random_params(std::mt19937& rng, int N, bool big) {
    g::Params p;
    p.mode = N >= 2 && uni(rng, 0, 1) ? g::Mode::Bidir : g::Mode::Single;
    p.D = uni(rng, 0, 3) == 0 ? std::min(N, 255) : uni(rng, 1, std::min(N, 255));
    gt::random_weights(rng, p, big);
    if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, N);
    p.vote = uni(rng, 0, 3) != 0;
    const int f = uni(rng, 0, 2);
    p.frame = f == 0 ? g::Frame::Cyclopean : f == 1 ? g::Frame::Left : g::Frame::Right;
    return p;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(crosscheck_reference)

BOOST_AUTO_TEST_CASE(random_small_images) {
    std::mt19937 rng(123456);
    int failures = 0, bidir = 0, voted = 0;
    for (int trial = 0; trial < 400 && failures < 3; ++trial) {
        const int W = uni(rng, 1, 18), H = uni(rng, 1, 8);
        const Pair img = random_pair(rng, W, H);
        g::Roi roi;
        roi.w = uni(rng, 1, std::min(W, 16));
        roi.h = uni(rng, 1, std::min(H, 6));
        roi.x0 = uni(rng, 0, W - roi.w);
        roi.y0 = uni(rng, 0, H - roi.h);
        const g::Params p = random_params(rng, roi.w, trial % 11 == 0);
        bidir += p.mode == g::Mode::Bidir;
        voted += p.vote && roi.h >= 3;
        BOOST_TEST_CONTEXT("trial " << trial) {
            const bool ok = crosscheck(p, img, roi, uni(rng, 0, 1) == 1);
            BOOST_TEST(ok);
            failures += !ok;  // stop after a few failing cases: one explains them all
        }
    }
    BOOST_TEST(bidir > 100);
    BOOST_TEST(voted > 100);
}

BOOST_AUTO_TEST_CASE(every_option_combination) {
    // One image; every mode / seed column / seed disparity / vote / frame / fill.
    std::mt19937 rng(2);
    const Pair img = random_pair(rng, 12, 5);
    const g::Roi roi{0, 0, 12, 5};
    int failures = 0;
    for (int D : {1, 3, 7, 12}) {
        for (int mode = 0; mode < 2; ++mode) {
            for (int col = -2; col <= 11 && failures < 3; ++col) {
                if (mode == 0 && col != -2) continue;
                if (col == 0) continue;
                g::Params p;
                p.D = D;
                p.km = 4;
                p.kb = 1;
                p.gb = 40;
                p.Wo = 25;
                p.Wd = 10;
                p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
                p.seed_col = col == -2   ? g::SeedCol{g::SeedColKind::Balanced, 0}
                             : col == -1 ? g::SeedCol{g::SeedColKind::Center, 0}
                                         : g::SeedCol{g::SeedColKind::Fixed, col};
                const int s = mode ? specref::seed_col(p, 12) : 0;
                const int dmax = mode ? std::min(D - 1, 11 - s) : -1;
                for (int ds = -1; ds <= dmax; ++ds) {
                    p.seed_disp.free = ds < 0;
                    p.seed_disp.value = ds < 0 ? 0 : ds;
                    for (int vote = 0; vote < 2; ++vote)
                        for (g::Frame f : {g::Frame::Cyclopean, g::Frame::Left, g::Frame::Right}) {
                            p.vote = vote != 0;
                            p.frame = f;
                            const bool ok = crosscheck(p, img, roi, (ds + vote) % 2 == 0);
                            BOOST_TEST(ok);
                            failures += !ok;
                        }
                }
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(wide_lines_and_255_levels) {
    // N up to 300 with D = 255 (the maximum), both modes, vote on.
    std::mt19937 rng(77);
    const int widths[] = {255, 256, 300};
    for (int k = 0; k < 6; ++k) {
        const int W = widths[k % 3];
        const Pair img = random_pair(rng, W, 3);
        g::Params p;
        p.D = 255;
        p.mode = k < 3 ? g::Mode::Single : g::Mode::Bidir;
        gt::random_weights(rng, p, k == 5);
        if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, W);
        p.vote = true;
        BOOST_TEST(crosscheck(p, img, g::Roi{0, 0, W, 3}, k % 2 == 0));
    }
}

BOOST_AUTO_TEST_CASE(costs_beyond_32_bits_are_exact) {
    // Black right row, white left row: every match costs km*255 + kb*(gb - 0),
    // every occlusion/discontinuity 10^6: with N = 40 and D = 1 (matches only)
    // or N = 1200 (occlusions) the line cost exceeds 2^31.
    g::Params p;
    p.km = static_cast<int>(g::kMaxWeight);
    p.kb = static_cast<int>(g::kMaxWeight);
    p.gb = 255;
    p.Wo = static_cast<int>(g::kMaxWeight);
    p.Wd = static_cast<int>(g::kMaxWeight);
    for (int mode = 0; mode < 2; ++mode) {
        p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
        for (int D : {1, 5, 40}) {
            p.D = D;
            const int N = D == 1 ? 40 : 1200;
            const std::vector<uint8_t> L(N, 255), R(N, 0);
            g::LineTables t;
            g::forward_line(p, L.data(), R.data(), N, t);
            const specref::LineRef r = specref::forward(p, L.data(), R.data(), N);
            BOOST_TEST(compare_tables(t, r) == 0);
            BOOST_TEST(t.right_cost == r.right_cost);
            BOOST_TEST(t.left_cost == r.left_cost);
            BOOST_TEST(t.right_cost + t.left_cost > INT64_C(1) << 31);
            if (mode == 0) {
                // D = 1: only matches, N * (255 + 255) * kMaxWeight.
                if (D == 1) BOOST_TEST(t.right_cost == int64_t{N} * 510 * g::kMaxWeight);
            }
        }
    }
    // Random images with the largest weights.
    std::mt19937 rng(31);
    for (int k = 0; k < 30; ++k) {
        const int W = uni(rng, 2, 40);
        const Pair img = random_pair(rng, W, 3);
        g::Params q = random_params(rng, W, true);
        BOOST_TEST(crosscheck(q, img, g::Roi{0, 0, W, 3}, false));
    }
}

BOOST_AUTO_TEST_CASE(weights_around_the_32_bit_limit) {
    // Costs are exact whatever word width an implementation picks: lines whose
    // worst-case path cost, about (2N + D + 4) * w for the largest weight w,
    // lies around 2^29 .. 2^33 (w near kMaxWeight, N up to ~4300). With
    // black/white rows every match costs about w, so the optimal costs
    // themselves cross 2^30 and 2^31.
    std::mt19937 rng(21);
    for (int64_t target = INT64_C(1) << 29; target <= INT64_C(1) << 33; target *= 2) {
        for (int k = 0; k < 4; ++k) {
            g::Params p;
            p.D = uni(rng, 1, 6);
            p.mode = k % 2 ? g::Mode::Bidir : g::Mode::Single;
            const int w = static_cast<int>(g::kMaxWeight) - uni(rng, 0, 1000);
            const int N = std::max<int>(
                p.D + 1, static_cast<int>((target / w - p.D - 4) / 2) + uni(rng, -1, 1));
            p.Wo = p.Wd = w;
            p.km = w / 255;
            p.kb = uni(rng, 0, 1);
            p.gb = uni(rng, 0, 1) ? 0 : 255;
            if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, N);
            Pair img;
            img.W = img.stride = N;
            img.H = 1;
            if (k < 2) {
                img.L.assign(static_cast<size_t>(N), 255);
                img.R.assign(static_cast<size_t>(N), 0);
            } else {
                gt::random_rows(rng, N, img.L, img.R);
            }
            BOOST_TEST_CONTEXT("N=" << N << " " << gt::describe(p)) {
                g::LineTables t;
                g::forward_line(p, img.L.data(), img.R.data(), N, t);
                const specref::LineRef r = specref::forward(p, img.L.data(), img.R.data(), N);
                BOOST_TEST(compare_tables(t, r) == 0);
                const g::DisparityMap m = g::compute(p, img.left(), img.right(), {0, 0, N, 1});
                BOOST_TEST(m.data == specref::compute(p, img.L, img.R, N, {0, 0, N, 1}, false),
                           boost::test_tools::per_element());
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(long_line) {
    // One long scanline per mode, D = 255, smallest and largest weights.
    std::mt19937 rng(22);
    const int N = 2000;
    std::vector<uint8_t> L, R;
    gt::random_rows(rng, N, L, R);
    for (int k = 0; k < 4; ++k) {
        g::Params p;
        p.D = 255;
        p.mode = k % 2 ? g::Mode::Bidir : g::Mode::Single;
        gt::random_weights(rng, p, k >= 2);
        if (p.mode == g::Mode::Bidir) gt::random_seed(rng, p, N);
        g::LineTables t;
        g::forward_line(p, L.data(), R.data(), N, t);
        const specref::LineRef r = specref::forward(p, L.data(), R.data(), N);
        BOOST_TEST_CONTEXT(gt::describe(p)) {
            BOOST_TEST(compare_tables(t, r) == 0);
            const auto got = g::backtrack(nullptr, t, nullptr, false);
            BOOST_TEST((got == to_events(specref::backtrack(nullptr, r, nullptr, false))));
        }
    }
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------

BOOST_AUTO_TEST_SUITE(determinism_and_views)

BOOST_AUTO_TEST_CASE(same_input_same_output) {
    std::mt19937 rng(9);
    for (int k = 0; k < 40; ++k) {
        const int W = uni(rng, 2, 24), H = uni(rng, 1, 6);
        const Pair img = random_pair(rng, W, H);
        const g::Params p = random_params(rng, W, false);
        const g::Roi roi{0, 0, W, H};
        const g::DisparityMap a = g::compute(p, img.left(), img.right(), roi, k % 2 == 0);
        // Something else in between (other sizes, other mode) must not matter.
        const Pair other = random_pair(rng, 30, 4);
        g::Params q = random_params(rng, 30, false);
        g::compute(q, other.left(), other.right(), g::Roi{0, 0, 30, 4}, true);
        const g::DisparityMap b = g::compute(p, img.left(), img.right(), roi, k % 2 == 0);
        BOOST_TEST(a.width == b.width);
        BOOST_TEST(a.height == b.height);
        BOOST_TEST(a.data == b.data, boost::test_tools::per_element());
    }
}

BOOST_AUTO_TEST_CASE(reused_line_tables) {
    // forward_line into a LineTables that held another line (bigger, other
    // mode) gives exactly the tables of a fresh object.
    std::mt19937 rng(10);
    g::LineTables reused;
    for (int k = 0; k < 60; ++k) {
        const int N = uni(rng, 1, 20);
        std::vector<uint8_t> L, R;
        gt::random_rows(rng, N, L, R);
        const g::Params p = random_params(rng, N, k % 9 == 0);
        g::LineTables fresh;
        g::forward_line(p, L.data(), R.data(), N, fresh);
        g::forward_line(p, L.data(), R.data(), N, reused);
        BOOST_TEST(reused.right == fresh.right, boost::test_tools::per_element());
        BOOST_TEST(reused.left == fresh.left, boost::test_tools::per_element());
        BOOST_TEST(reused.right_cost == fresh.right_cost);
        BOOST_TEST(reused.left_cost == fresh.left_cost);
        BOOST_TEST(reused.s == fresh.s);
        BOOST_TEST(reused.ds == fresh.ds);
        BOOST_TEST(reused.right_first == fresh.right_first);
        BOOST_TEST(reused.bidir == fresh.bidir);
        BOOST_TEST(compare_tables(reused, specref::forward(p, L.data(), R.data(), N)) == 0);
    }
}

BOOST_AUTO_TEST_CASE(roi_and_stride) {
    // compute() on a ROI of a padded image equals compute() on the cropped,
    // contiguous ROI, and never reads outside the ROI's pixels.
    std::mt19937 rng(11);
    for (int k = 0; k < 40; ++k) {
        const Pair big = random_pair(rng, uni(rng, 2, 20), uni(rng, 1, 8));
        g::Roi roi;
        roi.w = uni(rng, 1, big.W);
        roi.h = uni(rng, 1, big.H);
        roi.x0 = uni(rng, 0, big.W - roi.w);
        roi.y0 = uni(rng, 0, big.H - roi.h);
        const g::Params p = random_params(rng, roi.w, false);
        Pair crop;
        crop.W = crop.stride = roi.w;
        crop.H = roi.h;
        for (int y = 0; y < roi.h; ++y)
            for (int x = 0; x < roi.w; ++x) {
                const size_t o = static_cast<size_t>(roi.y0 + y) * big.stride + roi.x0 + x;
                crop.L.push_back(big.L[o]);
                crop.R.push_back(big.R[o]);
            }
        const g::DisparityMap a = g::compute(p, big.left(), big.right(), roi, false);
        const g::DisparityMap b =
            g::compute(p, crop.left(), crop.right(), g::Roi{0, 0, roi.w, roi.h}, false);
        BOOST_TEST(a.data == b.data, boost::test_tools::per_element());
        BOOST_TEST(a.width == roi.w);
        BOOST_TEST(a.height == roi.h);
        BOOST_TEST(a.data.size() == static_cast<size_t>(roi.w) * roi.h);
        if (roi.w > 0 && roi.h > 0) BOOST_TEST(a.at(roi.w - 1, roi.h - 1) == a.data.back());
    }
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------

namespace {

// Three lines: 0 and 2 identical (pattern A), line 1 pattern B.
Pair three_lines(const std::vector<uint8_t>& la, const std::vector<uint8_t>& ra,
                 const std::vector<uint8_t>& lb, const std::vector<uint8_t>& rb) {
    Pair p;
    p.W = p.stride = static_cast<int>(la.size());
    p.H = 3;
    for (const auto* row : {&la, &lb, &la}) p.L.insert(p.L.end(), row->begin(), row->end());
    for (const auto* row : {&ra, &rb, &ra}) p.R.insert(p.R.end(), row->begin(), row->end());
    return p;
}

std::vector<uint8_t> row_of(const g::DisparityMap& m, int y) {
    return std::vector<uint8_t>(m.data.begin() + y * m.width, m.data.begin() + (y + 1) * m.width);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(vote_end_to_end)

BOOST_AUTO_TEST_CASE(hand_built_three_lines) {
    // Pattern A: the right row is the left row shifted by 3 (disparity 3);
    // pattern B: the right row equals the left row (disparity 0). Identical
    // neighbours agree at every state and the states reachable are the same in
    // every line, so with the vote line 1 follows line 0's pointers exactly:
    // its row becomes line 0's row; lines 0 and 2 (one neighbour) are unchanged.
    const std::vector<uint8_t> la = {10, 200, 40, 90, 250, 15, 130, 60, 220, 5, 170, 80, 30, 240};
    std::vector<uint8_t> ra(la.size());
    for (size_t x = 0; x < la.size(); ++x) ra[x] = x + 3 < la.size() ? la[x + 3] : 128;
    const std::vector<uint8_t> lb = {100, 30, 220, 70, 160, 10, 250, 90, 45, 190, 120, 0, 210, 60};
    const std::vector<uint8_t> rb = lb;
    const Pair img = three_lines(la, ra, lb, rb);
    const g::Roi roi{0, 0, img.W, 3};
    for (int mode = 0; mode < 2; ++mode)
        for (g::Frame f : {g::Frame::Cyclopean, g::Frame::Left, g::Frame::Right})
            for (int fill = 0; fill < 2; ++fill) {
                g::Params p;
                p.D = 6;
                p.km = 6;
                p.kb = 1;
                p.gb = 48;
                p.Wo = 60;
                p.Wd = 30;
                p.mode = mode ? g::Mode::Bidir : g::Mode::Single;
                p.frame = f;
                BOOST_TEST_CONTEXT(gt::describe(p) << " fill=" << fill) {
                    p.vote = false;
                    const g::DisparityMap off = g::compute(p, img.left(), img.right(), roi, fill);
                    p.vote = true;
                    const g::DisparityMap on = g::compute(p, img.left(), img.right(), roi, fill);
                    BOOST_TEST(row_of(off, 0) == row_of(off, 2), boost::test_tools::per_element());
                    BOOST_REQUIRE(row_of(off, 1) != row_of(off, 0));  // the test means something
                    BOOST_TEST(row_of(on, 0) == row_of(off, 0), boost::test_tools::per_element());
                    BOOST_TEST(row_of(on, 2) == row_of(off, 2), boost::test_tools::per_element());
                    BOOST_TEST(row_of(on, 1) == row_of(off, 0), boost::test_tools::per_element());
                }
            }
    // Single mode, right frame, by hand: right pixels 0..10 are exact copies of
    // left pixels 3..13: the path (-1,3) [3*Wo = 180], M at (0..10, 3) [kb*(48-min)
    // for the dark pixels 15, 5, 30: 33 + 43 + 18 = 94], D at (11,2) (12,1) (13,0)
    // [3*Wd = 90] costs 364. With the vote, line 1 gets the same row.
    g::Params p;
    p.D = 6;
    p.km = 6;
    p.kb = 1;
    p.gb = 48;
    p.Wo = 60;
    p.Wd = 30;
    p.mode = g::Mode::Single;
    p.frame = g::Frame::Right;
    p.vote = true;
    const g::DisparityMap on = g::compute(p, img.left(), img.right(), roi, false);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x <= 10; ++x) BOOST_TEST(int(on.at(x, y)) == 3, "x=" << x << " y=" << y);
        for (int x = 11; x < 14; ++x) BOOST_TEST(int(on.at(x, y)) == 255, "x=" << x << " y=" << y);
    }
    g::LineTables t;
    g::forward_line(p, la.data(), ra.data(), 14, t);
    BOOST_TEST(t.right_cost == 364);
}

BOOST_AUTO_TEST_CASE(random_identical_neighbours) {
    std::mt19937 rng(12);
    int meaningful = 0;
    for (int k = 0; k < 150; ++k) {
        const int W = uni(rng, 2, 16);
        std::vector<uint8_t> la, ra, lb, rb;
        gt::random_rows(rng, W, la, ra);
        gt::random_rows(rng, W, lb, rb);
        const Pair img = three_lines(la, ra, lb, rb);
        g::Params p = random_params(rng, W, false);
        const g::Roi roi{0, 0, W, 3};
        BOOST_TEST_CONTEXT(ctx_string(p, img, roi, false)) {
            p.vote = false;
            const g::DisparityMap off = g::compute(p, img.left(), img.right(), roi, false);
            p.vote = true;
            const g::DisparityMap on = g::compute(p, img.left(), img.right(), roi, false);
            meaningful += row_of(off, 1) != row_of(off, 0);
            BOOST_TEST(row_of(on, 0) == row_of(off, 0), boost::test_tools::per_element());
            BOOST_TEST(row_of(on, 2) == row_of(off, 2), boost::test_tools::per_element());
            BOOST_TEST(row_of(on, 1) == row_of(off, 0), boost::test_tools::per_element());
        }
    }
    BOOST_TEST(meaningful > 50);
}

BOOST_AUTO_TEST_CASE(fewer_than_three_lines_no_vote_effect) {
    std::mt19937 rng(13);
    for (int k = 0; k < 60; ++k) {
        const int W = uni(rng, 2, 16), H = uni(rng, 1, 2);
        const Pair img = random_pair(rng, W, H);
        g::Params p = random_params(rng, W, false);
        const g::Roi roi{0, 0, W, H};
        p.vote = false;
        const g::DisparityMap off = g::compute(p, img.left(), img.right(), roi, false);
        p.vote = true;
        const g::DisparityMap on = g::compute(p, img.left(), img.right(), roi, false);
        BOOST_TEST(on.data == off.data, boost::test_tools::per_element());
    }
}

BOOST_AUTO_TEST_CASE(neighbours_are_inside_the_roi) {
    // A ROI of 3 lines inside a 5-line image: lines outside the ROI never vote.
    // Image lines 0..4 = B, A, B, A, B; the ROI holds image lines 1..3 = A, B, A.
    // ROI line 1 follows its neighbours (A); ROI lines 0 and 2 have one
    // neighbour inside the ROI and keep their own A result (the B lines just
    // outside the ROI would otherwise outvote them).
    std::mt19937 rng(14);
    for (int k = 0; k < 40; ++k) {
        const int W = uni(rng, 2, 14);
        std::vector<uint8_t> la, ra, lb, rb;
        gt::random_rows(rng, W, la, ra);
        gt::random_rows(rng, W, lb, rb);
        Pair img;
        img.W = img.stride = W;
        img.H = 5;
        for (int y = 0; y < 5; ++y) {
            const bool a = y % 2 == 1;
            img.L.insert(img.L.end(), (a ? la : lb).begin(), (a ? la : lb).end());
            img.R.insert(img.R.end(), (a ? ra : rb).begin(), (a ? ra : rb).end());
        }
        g::Params p = random_params(rng, W, false);
        p.vote = true;
        const g::DisparityMap m = g::compute(p, img.left(), img.right(), g::Roi{0, 1, W, 3}, false);
        p.vote = false;
        const g::DisparityMap a = g::compute(p, img.left(), img.right(), g::Roi{0, 1, W, 1}, false);
        BOOST_TEST(row_of(m, 0) == row_of(a, 0), boost::test_tools::per_element());
        BOOST_TEST(row_of(m, 1) == row_of(a, 0), boost::test_tools::per_element());
        BOOST_TEST(row_of(m, 2) == row_of(a, 0), boost::test_tools::per_element());
    }
}

BOOST_AUTO_TEST_SUITE_END()
