// SPEC A.7 output frames and fill, A.1 match cost and parameter validation,
// A.4 seed column resolution.
#define BOOST_TEST_MODULE golden_output_params
#include <boost/test/unit_test.hpp>

#include <cctype>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"
#include "test_util.hpp"

namespace g = imap::golden;

namespace {

std::vector<uint8_t> render(const std::vector<g::Event>& ev, g::Frame f, int N) {
    std::vector<uint8_t> out(static_cast<size_t>(N), 7);  // garbage: render must overwrite all
    g::render_line(ev, f, N, out.data());
    return out;
}

std::vector<uint8_t> fill(std::vector<uint8_t> row) {
    g::fill_row(row.data(), static_cast<int>(row.size()));
    return row;
}

constexpr uint8_t X = g::kOccluded;
using Bytes = std::vector<uint8_t>;

}  // namespace

BOOST_AUTO_TEST_SUITE(output_frames)

BOOST_AUTO_TEST_CASE(occluded_value) {
    BOOST_TEST(int(g::kOccluded) == 255);
}

BOOST_AUTO_TEST_CASE(three_frames) {
    // M(0,0) M(1,1) O(2,2) M(2,2) D(3,1) M(4,1) M(5,0), N = 6.
    const std::vector<g::Event> ev = {{0, 0, g::kM}, {1, 1, g::kM}, {2, 2, g::kO}, {2, 2, g::kM},
                                      {3, 1, g::kD}, {4, 1, g::kM}, {5, 0, g::kM}};
    // right: R_map[i] = j.
    BOOST_TEST(render(ev, g::Frame::Right, 6) == (Bytes{0, 1, 2, X, 1, 0}),
               boost::test_tools::per_element());
    // left: L_map[i+j] = j; (4,1) and (5,0) both write x = 5, the later wins.
    BOOST_TEST(render(ev, g::Frame::Left, 6) == (Bytes{0, X, 1, X, 2, 0}),
               boost::test_tools::per_element());
    // cyclopean: c = 2i+j = 0, 3, 6, 9, 10 -> x = 0, 1, 3, 4, 5.
    BOOST_TEST(render(ev, g::Frame::Cyclopean, 6) == (Bytes{0, 1, X, 2, 1, 0}),
               boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(only_m_events_write) {
    const std::vector<g::Event> ev = {{0, 1, g::kO}, {1, 0, g::kD}, {2, 0, g::kO}, {2, 1, g::kD}};
    for (g::Frame f : {g::Frame::Right, g::Frame::Left, g::Frame::Cyclopean})
        BOOST_TEST(render(ev, f, 4) == (Bytes{X, X, X, X}), boost::test_tools::per_element());
    for (g::Frame f : {g::Frame::Right, g::Frame::Left, g::Frame::Cyclopean})
        BOOST_TEST(render({}, f, 3) == (Bytes{X, X, X}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(later_writes_win) {
    // Cyclopean: (1,3) -> c = 5 -> x = 2 and (2,1) -> c = 5 -> x = 2. In bidir
    // order a left event comes first and the right one (here the seed) wins.
    std::vector<g::Event> ev = {{1, 3, g::kM}, {2, 1, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Cyclopean, 6)[2] == 1);
    ev = {{2, 1, g::kM}, {1, 3, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Cyclopean, 6)[2] == 3);
    // (2,0) -> c = 4 and (1,2) -> c = 4 -> x = 2; (1,3) -> c = 5 -> x = 2 too.
    ev = {{2, 0, g::kM}, {1, 2, g::kM}, {1, 3, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Cyclopean, 6)[2] == 3);
    // Right frame: the same site twice.
    ev = {{3, 2, g::kM}, {3, 0, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Right, 6)[3] == 0);
    // Left frame: (1,2) and (2,1) both at x = 3.
    ev = {{1, 2, g::kM}, {2, 1, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Left, 6)[3] == 1);
    ev = {{2, 1, g::kM}, {1, 2, g::kM}};
    BOOST_TEST(render(ev, g::Frame::Left, 6)[3] == 2);
}

BOOST_AUTO_TEST_CASE(cyclopean_half_pixel_rounding) {
    // c >> 1 rounds the half-pixel position down: (0,1) -> 0, (1,1) -> 1,
    // (0,3) -> 1, (1,3) -> 2, (0,4) -> 2.
    BOOST_TEST(render({{0, 1, g::kM}}, g::Frame::Cyclopean, 6)[0] == 1);
    BOOST_TEST(render({{1, 1, g::kM}}, g::Frame::Cyclopean, 6)[1] == 1);
    BOOST_TEST(render({{0, 3, g::kM}}, g::Frame::Cyclopean, 6)[1] == 3);
    BOOST_TEST(render({{1, 3, g::kM}}, g::Frame::Cyclopean, 6)[2] == 3);
    BOOST_TEST(render({{0, 4, g::kM}}, g::Frame::Cyclopean, 6)[2] == 4);
    // Only 0 <= c>>1 < N is written: (2,2) with N = 3 has c>>1 = 3.
    BOOST_TEST(render({{2, 2, g::kM}}, g::Frame::Cyclopean, 3) == (Bytes{X, X, X}),
               boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(random_event_lists_match_reference) {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 300; ++trial) {
        const int N = gt::uni(rng, 1, 20);
        const int D = gt::uni(rng, 1, std::min(N, 255));
        std::vector<g::Event> ev;
        std::vector<specref::Ev> rev;
        const int n = gt::uni(rng, 0, 3 * N);
        for (int k = 0; k < n; ++k) {
            const int i = gt::uni(rng, 0, N - 1);
            const int j = gt::uni(rng, 0, std::min(D - 1, N - 1 - i));
            const int st = gt::uni(rng, 0, 2);
            ev.push_back({i, j, static_cast<g::Step>(st)});
            rev.push_back({i, j, st});
        }
        for (g::Frame f : {g::Frame::Right, g::Frame::Left, g::Frame::Cyclopean})
            BOOST_TEST(render(ev, f, N) == specref::render(rev, f, N),
                       boost::test_tools::per_element());
    }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(fill_post_step)

BOOST_AUTO_TEST_CASE(both_sides_one_side_neither) {
    BOOST_TEST(fill({X, X, 3, X, 5, X, X, 1, X}) == (Bytes{3, 3, 3, 3, 5, 1, 1, 1, 1}),
               boost::test_tools::per_element());
    BOOST_TEST(fill({9, X, X, 2}) == (Bytes{9, 2, 2, 2}), boost::test_tools::per_element());
    BOOST_TEST(fill({2, X, X, 9}) == (Bytes{2, 2, 2, 9}), boost::test_tools::per_element());
    BOOST_TEST(fill({X, X, X, 4}) == (Bytes{4, 4, 4, 4}), boost::test_tools::per_element());
    BOOST_TEST(fill({4, X, X}) == (Bytes{4, 4, 4}), boost::test_tools::per_element());
    BOOST_TEST(fill({X, X, X}) == (Bytes{0, 0, 0}), boost::test_tools::per_element());
    BOOST_TEST(fill({X}) == (Bytes{0}), boost::test_tools::per_element());
    BOOST_TEST(fill({7}) == (Bytes{7}), boost::test_tools::per_element());
    BOOST_TEST(fill({0, 254, 1, 0}) == (Bytes{0, 254, 1, 0}), boost::test_tools::per_element());
    BOOST_TEST(fill({254, X, 253}) == (Bytes{254, 253, 253}), boost::test_tools::per_element());
    BOOST_TEST(fill({0, X, 200, X, X, 0}) == (Bytes{0, 0, 200, 0, 0, 0}),
               boost::test_tools::per_element());
    Bytes empty;
    g::fill_row(empty.data(), 0);  // n = 0 is a no-op
}

BOOST_AUTO_TEST_CASE(random_rows_match_reference) {
    std::mt19937 rng(6);
    for (int trial = 0; trial < 500; ++trial) {
        Bytes row(static_cast<size_t>(gt::uni(rng, 1, 30)));
        const int p_occ = gt::uni(rng, 0, 10);
        for (auto& v : row) v = gt::uni(rng, 0, 9) < p_occ ? X : uint8_t(gt::uni(rng, 0, 254));
        BOOST_TEST(fill(row) == specref::fill(row), boost::test_tools::per_element());
    }
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------

namespace {

// `tok` occurs in `msg` not glued to letters/digits on either side.
bool has_token(const std::string& msg, const std::string& tok) {
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (size_t pos = msg.find(tok); pos != std::string::npos; pos = msg.find(tok, pos + 1)) {
        const size_t end = pos + tok.size();
        const bool left_ok = pos == 0 || !word(msg[pos - 1]) || !word(tok.front());
        const bool right_ok = end >= msg.size() || !word(msg[end]) || !word(tok.back());
        // A number must not continue with more digits or start after a digit or '-'.
        const bool num = std::isdigit(static_cast<unsigned char>(tok.back())) != 0;
        const bool num_ok =
            !num || ((pos == 0 || (!std::isdigit(static_cast<unsigned char>(msg[pos - 1])) &&
                                   (tok.front() == '-' || msg[pos - 1] != '-'))) &&
                     (end >= msg.size() || !std::isdigit(static_cast<unsigned char>(msg[end]))));
        if (left_ok && right_ok && num_ok) return true;
    }
    return false;
}

bool has_ci(const std::string& msg, const std::string& sub) {
    std::string a = msg, b = sub;
    for (auto& c : a) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (auto& c : b) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return a.find(b) != std::string::npos;
}

// Runs f, expects a ParamError whose message passes `ok`; returns the message.
std::string param_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const g::ParamError& e) {
        return e.what();
    } catch (const std::exception& e) {
        BOOST_ERROR("wrong exception type: " << e.what());
        return "";
    }
    BOOST_ERROR("no ParamError thrown");
    return "";
}

void expect_error_for_width(const g::Params& p, int N, const std::vector<std::string>& tokens,
                            const std::vector<std::string>& substrings = {}) {
    const std::string msg = param_error([&] { g::validate_for_width(p, N); });
    BOOST_TEST_MESSAGE("N=" << N << ": " << msg);
    for (const auto& t : tokens) BOOST_TEST(has_token(msg, t), "'" << t << "' not in: " << msg);
    for (const auto& s : substrings) BOOST_TEST(has_ci(msg, s), "'" << s << "' not in: " << msg);
    // The full check and compute() reject the same value.
    const std::string msg2 = param_error([&] { g::validate(p, g::Roi{0, 0, N, 1}, N, 1); });
    for (const auto& t : tokens) BOOST_TEST(has_token(msg2, t), "'" << t << "' not in: " << msg2);
}

g::Params single_params() {
    g::Params p;
    p.mode = g::Mode::Single;
    p.D = 4;
    return p;
}

g::Params bidir_params(int col, int disp) {
    g::Params p;
    p.mode = g::Mode::Bidir;
    p.D = 4;
    p.seed_col = {g::SeedColKind::Fixed, col};
    p.seed_disp.free = disp < 0;
    p.seed_disp.value = disp < 0 ? 0 : disp;
    return p;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(validation)

BOOST_AUTO_TEST_CASE(token_helper) {
    BOOST_TEST(has_token("parameter D = 0 is", "D"));
    BOOST_TEST(!has_token("parameter Dx = 0 is", "D"));
    BOOST_TEST(has_token("km = -7 (allowed", "-7"));
    BOOST_TEST(!has_token("km = -17 (allowed", "-7"));
    BOOST_TEST(!has_token("km = -7 (allowed", "7"));
    BOOST_TEST(!has_token("gb = 2560", "256"));
    BOOST_TEST(has_token("seed-col = 0", "0"));
}

BOOST_AUTO_TEST_CASE(levels_d) {
    g::Params p = single_params();
    p.D = 0;
    expect_error_for_width(p, 10, {"D", "0"});
    p.D = -3;
    expect_error_for_width(p, 10, {"D", "-3"});
    p.D = 13;  // > N = 12
    expect_error_for_width(p, 12, {"D", "13", "12"});
    p.D = 256;  // > 255 even for a wide ROI
    expect_error_for_width(p, 400, {"D", "256", "255"});
    BOOST_CHECK_THROW(g::validate_params(p), g::ParamError);
    p.D = 12;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 12));
    p.D = 255;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 255));
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 400));
    expect_error_for_width(p, 254, {"D", "255"});
    p.D = 1;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 1));
}

BOOST_AUTO_TEST_CASE(match_weights) {
    g::Params p = single_params();
    p.km = 0;
    p.kb = 0;
    expect_error_for_width(p, 8, {"km", "kb", "0"});
    p.km = -7;
    p.kb = 1;
    expect_error_for_width(p, 8, {"km", "-7"});
    p.km = 1;
    p.kb = -2;
    expect_error_for_width(p, 8, {"kb", "-2"});
    p.km = 0;
    p.kb = 1;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.km = 1;
    p.kb = 0;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.km = static_cast<int>(g::kMaxWeight);
    p.kb = static_cast<int>(g::kMaxWeight);
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.km = static_cast<int>(g::kMaxWeight) + 1;
    expect_error_for_width(p, 8, {"km", std::to_string(g::kMaxWeight + 1)});
    p.km = 1;
    p.kb = static_cast<int>(g::kMaxWeight) + 1;
    expect_error_for_width(p, 8, {"kb", std::to_string(g::kMaxWeight + 1)});
}

BOOST_AUTO_TEST_CASE(intensity_bound_gb) {
    g::Params p = single_params();
    p.gb = 256;
    expect_error_for_width(p, 8, {"gb", "256", "255"});
    p.gb = -1;
    expect_error_for_width(p, 8, {"gb", "-1"});
    p.gb = 0;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.gb = 255;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
}

BOOST_AUTO_TEST_CASE(occlusion_and_discontinuity) {
    g::Params p = single_params();
    p.Wo = 17;
    p.Wd = 23;
    expect_error_for_width(p, 8, {"Wo", "17"});
    p.Wo = 5;
    p.Wd = -3;
    expect_error_for_width(p, 8, {"Wd", "-3"});
    p.Wo = -1;
    p.Wd = -3;
    {
        const std::string msg = param_error([&] { g::validate_for_width(p, 8); });
        BOOST_TEST((has_token(msg, "Wd") || has_token(msg, "Wo")), msg);
    }
    p.Wo = 9;
    p.Wd = 9;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.Wo = 0;
    p.Wd = 0;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 8));
    p.Wo = static_cast<int>(g::kMaxWeight) + 1;
    expect_error_for_width(p, 8, {"Wo", std::to_string(g::kMaxWeight + 1)});
}

BOOST_AUTO_TEST_CASE(seed_column) {
    expect_error_for_width(bidir_params(0, -1), 13, {"0"}, {"seed", "col"});
    expect_error_for_width(bidir_params(13, -1), 13, {"13"}, {"seed", "col"});
    expect_error_for_width(bidir_params(-4, -1), 13, {"-4"}, {"seed", "col"});
    expect_error_for_width(bidir_params(40, -1), 13, {"40"}, {"seed", "col"});
    BOOST_CHECK_NO_THROW(g::validate_for_width(bidir_params(1, -1), 13));
    BOOST_CHECK_NO_THROW(g::validate_for_width(bidir_params(12, -1), 13));
    // single mode: the seed settings are bidir-only and not checked.
    g::Params p = bidir_params(0, 300);
    p.mode = g::Mode::Single;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 13));
}

BOOST_AUTO_TEST_CASE(seed_disparity) {
    // ds >= D (D = 4, s = 2, N = 20: s + ds < N holds).
    expect_error_for_width(bidir_params(2, 4), 20, {"4"}, {"seed", "disp"});
    expect_error_for_width(bidir_params(2, 9), 20, {"9"}, {"seed", "disp"});
    g::Params p = bidir_params(2, 3);
    p.seed_disp.value = -5;  // not free, negative
    expect_error_for_width(p, 20, {"-5"}, {"seed", "disp"});
    BOOST_CHECK_NO_THROW(g::validate_for_width(bidir_params(2, 3), 20));
    BOOST_CHECK_NO_THROW(g::validate_for_width(bidir_params(2, 0), 20));
    // s + ds >= N (N = 10, s = 7, D = 5): ds = 3 fails, ds = 2 is the largest.
    p = bidir_params(7, 3);
    p.D = 5;
    expect_error_for_width(p, 10, {"3"}, {"seed", "disp"});
    p.seed_disp.value = 2;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 10));
    // Seed column N-1 admits only ds = 0.
    p = bidir_params(9, 1);
    expect_error_for_width(p, 10, {"1"}, {"seed", "disp"});
    p.seed_disp.value = 0;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 10));
    // center (s = N/2 = 2 for N = 4, D = 4): ds = 2 gives s + ds = 4 = N.
    p = bidir_params(1, 2);
    p.seed_col.kind = g::SeedColKind::Center;
    expect_error_for_width(p, 4, {"2"}, {"seed", "disp"});
    p.seed_disp.value = 1;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 4));
    // balanced (N = 4, D = 4: nodes 4,3,2,1, s = 1): ds = 3 fails (s + ds = 4 = N).
    p = bidir_params(1, 3);
    p.seed_col.kind = g::SeedColKind::Balanced;
    expect_error_for_width(p, 4, {"3"}, {"seed", "disp"});
    p.seed_disp.value = 2;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 4));
}

BOOST_AUTO_TEST_CASE(bidir_needs_two_pixels) {
    g::Params p = bidir_params(1, -1);
    p.D = 1;
    p.seed_col.kind = g::SeedColKind::Center;
    const std::string msg = param_error([&] { g::validate_for_width(p, 1); });
    BOOST_TEST(has_token(msg, "1"), msg);
    BOOST_TEST((has_token(msg, "N") || has_ci(msg, "width") || has_ci(msg, "seed")), msg);
    BOOST_CHECK_THROW(g::validate(p, g::Roi{0, 0, 1, 1}, 1, 1), g::ParamError);
    p.mode = g::Mode::Single;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 1));
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{0, 0, 1, 1}, 1, 1));
    p.mode = g::Mode::Bidir;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 2));
    p.seed_col.kind = g::SeedColKind::Balanced;
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 2));
}

BOOST_AUTO_TEST_CASE(region_of_interest) {
    g::Params p = single_params();
    p.D = 2;
    auto roi_error = [&](g::Roi roi, int w, int h, const std::vector<std::string>& tokens) {
        const std::string msg = param_error([&] { g::validate(p, roi, w, h); });
        BOOST_TEST_MESSAGE(msg);
        BOOST_TEST(has_ci(msg, "ROI"), msg);
        for (const auto& t : tokens) BOOST_TEST(has_token(msg, t), "'" << t << "' not in: " << msg);
    };
    roi_error({5, 0, 10, 3}, 12, 4, {"5", "10"});  // x0 + w > width
    roi_error({0, 3, 12, 2}, 12, 4, {"3", "2"});   // y0 + h > height
    roi_error({-2, 0, 4, 2}, 12, 4, {"-2"});       // x0 < 0
    roi_error({0, -1, 4, 2}, 12, 4, {"-1"});       // y0 < 0
    roi_error({0, 0, 0, 2}, 12, 4, {"0"});         // w = 0
    roi_error({0, 0, 4, 0}, 12, 4, {"0"});         // h = 0
    roi_error({13, 0, 1, 1}, 12, 4, {"13"});       // x0 beyond the image
    roi_error({3, 0, 10, 1}, 12, 4, {"3", "10"});  // one pixel too wide
    roi_error({0, 1, 12, 4}, 12, 4, {"1", "4"});   // one line too high
    roi_error({0, 0, 13, 4}, 12, 4, {"13"});       // wider than the image
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{0, 0, 12, 4}, 12, 4));
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{10, 3, 2, 1}, 12, 4));
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{2, 0, 10, 4}, 12, 4));
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{10, 0, 2, 4}, 12, 4));
    // D is checked against the ROI width, not the image width.
    p.D = 5;
    BOOST_CHECK_THROW(g::validate(p, g::Roi{0, 0, 4, 4}, 12, 4), g::ParamError);
    BOOST_CHECK_NO_THROW(g::validate(p, g::Roi{0, 0, 5, 4}, 12, 4));
}

BOOST_AUTO_TEST_CASE(compute_validates) {
    std::vector<uint8_t> img(12 * 4, 100);
    const g::ImageView v{img.data(), 12, 4, 12};
    g::Params p = single_params();
    p.D = 5;
    BOOST_CHECK_THROW(g::compute(p, v, v, g::Roi{0, 0, 4, 4}), g::ParamError);
    p.D = 2;
    BOOST_CHECK_THROW(g::compute(p, v, v, g::Roi{5, 0, 10, 3}), g::ParamError);
    BOOST_CHECK_THROW(g::compute(p, v, v, g::Roi{0, 0, 0, 3}), g::ParamError);
    p.gb = 300;
    BOOST_CHECK_THROW(g::compute(p, v, v, g::Roi{0, 0, 4, 4}), g::ParamError);
    p.gb = 10;
    // Images of different sizes are rejected.
    const g::ImageView small{img.data(), 11, 4, 12};
    BOOST_CHECK_THROW(g::compute(p, v, small, g::Roi{0, 0, 4, 4}), std::exception);
    BOOST_CHECK_NO_THROW(g::compute(p, v, v, g::Roi{0, 0, 4, 4}));
}

BOOST_AUTO_TEST_CASE(defaults_are_valid) {
    const g::Params p;
    BOOST_CHECK_NO_THROW(g::validate_params(p));
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, 128));
    BOOST_CHECK_NO_THROW(g::validate_for_width(p, p.D));
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------

BOOST_AUTO_TEST_SUITE(definitions)

BOOST_AUTO_TEST_CASE(match_cost_formula) {
    g::Params p;
    p.km = 6;
    p.kb = 1;
    p.gb = 48;
    BOOST_TEST(g::match_cost(p, 100, 90) == 6 * 10 + 0);      // gb - min < 0 -> 0
    BOOST_TEST(g::match_cost(p, 20, 30) == 6 * 10 + 1 * 28);  // gb - 20
    BOOST_TEST(g::match_cost(p, 30, 20) == 6 * 10 + 1 * 28);  // symmetric
    BOOST_TEST(g::match_cost(p, 48, 48) == 0);
    BOOST_TEST(g::match_cost(p, 0, 255) == 6 * 255 + 48);
    std::mt19937 rng(8);
    for (int trial = 0; trial < 200; ++trial) {
        gt::random_weights(rng, p, trial % 5 == 0);
        for (int k = 0; k < 50; ++k) {
            const int a = gt::uni(rng, 0, 255), b = gt::uni(rng, 0, 255);
            BOOST_TEST(g::match_cost(p, a, b) == specref::wm(p, a, b));
        }
    }
}

BOOST_AUTO_TEST_CASE(levels_at_counts_valid_levels) {
    for (int N = 1; N <= 40; ++N)
        for (int D = 1; D <= N; ++D)
            for (int i = 0; i < N; ++i)
                BOOST_TEST(g::levels_at(i, N, D) == specref::nodes(N, D, i));
}

BOOST_AUTO_TEST_CASE(seed_column_by_hand) {
    g::Params p;
    p.mode = g::Mode::Bidir;
    p.seed_disp.free = true;
    p.seed_col.kind = g::SeedColKind::Balanced;
    // N = 4, D = 4: nodes 4,3,2,1; s = 1: |4 - 6| = 2, s = 2: 4, s = 3: 8.
    p.D = 4;
    BOOST_TEST(g::resolve_seed_col(p, 4) == 1);
    // N = 3, D = 1: nodes 1,1,1; s = 1 and s = 2 tie at 1 -> the smaller.
    p.D = 1;
    BOOST_TEST(g::resolve_seed_col(p, 3) == 1);
    // N = 6, D = 3: nodes 3,3,3,3,2,1; s = 2: |6 - 9| = 3, s = 3: |9 - 6| = 3 -> 2.
    p.D = 3;
    BOOST_TEST(g::resolve_seed_col(p, 6) == 2);
    // N = 4, D = 1: s = 2 exactly balanced.
    p.D = 1;
    BOOST_TEST(g::resolve_seed_col(p, 4) == 2);
    // N = 2: the only choice.
    BOOST_TEST(g::resolve_seed_col(p, 2) == 1);
    p.seed_col.kind = g::SeedColKind::Center;
    BOOST_TEST(g::resolve_seed_col(p, 7) == 3);
    BOOST_TEST(g::resolve_seed_col(p, 8) == 4);
    BOOST_TEST(g::resolve_seed_col(p, 2) == 1);
    p.seed_col = {g::SeedColKind::Fixed, 5};
    BOOST_TEST(g::resolve_seed_col(p, 8) == 5);
}

BOOST_AUTO_TEST_CASE(balanced_seed_column_matches_definition) {
    g::Params p;
    p.mode = g::Mode::Bidir;
    p.seed_col.kind = g::SeedColKind::Balanced;
    for (int N = 2; N <= 300; N += (N < 40 ? 1 : 7)) {
        for (int D = 1; D <= std::min(N, 255); D += (D < 20 ? 1 : 11)) {
            p.D = D;
            BOOST_TEST(g::resolve_seed_col(p, N) == specref::seed_col(p, N),
                       "N=" << N << " D=" << D);
        }
    }
}

BOOST_AUTO_TEST_SUITE_END()
