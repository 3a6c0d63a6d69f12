// Image perturbations (vision/perturb.hpp): the gain/offset arithmetic and
// the 0..255 clamp against hand-computed values, the identity, seeds and
// streams, the noise statistics, and the SPEC grammar.
#define BOOST_TEST_MODULE vision_perturb
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "imap/vision/perturb.hpp"

namespace v = imap::vision;

namespace {

cv::Mat row_of(const std::vector<int>& px) {
    cv::Mat m(1, static_cast<int>(px.size()), CV_8UC1);
    for (size_t i = 0; i < px.size(); ++i) m.at<uint8_t>(0, static_cast<int>(i)) = px[i];
    return m;
}

std::vector<int> values(const cv::Mat& m) {
    std::vector<int> out;
    for (int x = 0; x < m.cols; ++x) out.push_back(m.at<uint8_t>(0, x));
    return out;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
    return cv::countNonZero(a != b) == 0;
}

cv::Mat flat(int value, int size = 512) {
    return cv::Mat(size, size, CV_8UC1, cv::Scalar(value));
}

// Applies `spec` to a copy of `img` as the right (or left) image.
cv::Mat perturbed(const std::string& spec, const cv::Mat& img, bool is_right = true) {
    cv::Mat out = img.clone();
    v::perturb_image(out, v::parse_perturbation(spec), is_right);
    return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(gain_offset_by_hand) {
    const cv::Mat in = row_of({0, 5, 100, 200, 255});
    // 0.8 x + 10: 10, 14, 90, 170, 214
    BOOST_TEST(
        values(perturbed("gain=0.8,offset=10", in)) == (std::vector<int>{10, 14, 90, 170, 214}),
        boost::test_tools::per_element());
    // the default image is the right one: the left stays as it was
    BOOST_TEST(same(perturbed("gain=0.8,offset=10", in, false), in));
    BOOST_TEST(values(perturbed("gain=0.8,offset=10,image=left", in, false)) ==
                   (std::vector<int>{10, 14, 90, 170, 214}),
               boost::test_tools::per_element());
    BOOST_TEST(same(perturbed("gain=0.8,offset=10,image=left", in, true), in));
    BOOST_TEST(!same(perturbed("gain=0.8,offset=10,image=both", in, false), in));
    // halves round up: 0.5 x of 1, 3, 255 = 0.5, 1.5, 127.5
    BOOST_TEST(values(perturbed("gain=0.5", row_of({1, 3, 255}))) == (std::vector<int>{1, 2, 128}),
               boost::test_tools::per_element());
    BOOST_TEST(values(perturbed("offset=-0.5", row_of({10, 0}))) == (std::vector<int>{10, 0}),
               boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(clamp_by_hand) {
    // 1.2 x - 20 of 0, 10, 100, 228, 229, 230, 250 = -20, -8, 100, 253.6, 254.8, 256, 280
    BOOST_TEST(values(perturbed("gain=1.2,offset=-20", row_of({0, 10, 100, 228, 229, 230, 250}))) ==
                   (std::vector<int>{0, 0, 100, 254, 255, 255, 255}),
               boost::test_tools::per_element());
    BOOST_TEST(
        values(perturbed("offset=255", row_of({0, 1, 200}))) == (std::vector<int>{255, 255, 255}),
        boost::test_tools::per_element());
    BOOST_TEST(
        values(perturbed("offset=-255", row_of({0, 254, 255}))) == (std::vector<int>{0, 0, 0}),
        boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(identity_is_bit_identical) {
    cv::Mat img(64, 80, CV_8UC1);
    cv::randu(img, 0, 256);
    for (const char* spec : {"gain=1", "offset=0", "noise=0", "gain=1,offset=0,noise=0,seed=99",
                             "image=both,noise-image=left"}) {
        BOOST_TEST_CONTEXT(spec) {
            BOOST_TEST(v::parse_perturbation(spec).identity());
            BOOST_TEST(same(perturbed(spec, img, true), img));
            BOOST_TEST(same(perturbed(spec, img, false), img));
        }
    }
}

BOOST_AUTO_TEST_CASE(seeds_and_streams) {
    const cv::Mat img = flat(128, 96);
    const cv::Mat a = perturbed("noise=3,seed=1", img), b = perturbed("noise=3,seed=1", img);
    BOOST_TEST(same(a, b));
    BOOST_TEST(!same(a, img));
    BOOST_TEST(!same(a, perturbed("noise=3,seed=2", img)));
    // the left and right images draw from different streams
    BOOST_TEST(!same(a, perturbed("noise=3,seed=1", img, false)));
    // noise-image=right leaves the left image alone
    BOOST_TEST(same(perturbed("noise=3,noise-image=right", img, false), img));
    BOOST_TEST(!same(perturbed("noise=3,noise-image=left", img, false), img));
    BOOST_TEST(same(perturbed("noise=3,noise-image=left", img, true), img));
    // the default seed is 1
    BOOST_TEST(same(perturbed("noise=3", img), a));
}

BOOST_AUTO_TEST_CASE(noise_statistics) {
    for (const double sigma : {3.0, 6.0}) {
        const cv::Mat img = flat(128);
        const cv::Mat out = perturbed("noise=" + std::to_string(sigma), img);
        double sum = 0, sum2 = 0, maxdev = 0;
        const double n = static_cast<double>(out.total());
        for (int y = 0; y < out.rows; ++y)
            for (int x = 0; x < out.cols; ++x) {
                const double d = out.at<uint8_t>(y, x) - 128.0;
                sum += d;
                sum2 += d * d;
                maxdev = std::max(maxdev, std::abs(d));
            }
        const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
        BOOST_TEST_CONTEXT("sigma " << sigma) {
            BOOST_TEST(std::abs(mean) < 0.05);
            // rounding adds 1/12 to the variance: sqrt(sigma^2 + 1/12)
            BOOST_TEST(std::abs(sd - std::sqrt(sigma * sigma + 1.0 / 12)) < 0.03 * sigma);
            BOOST_TEST(maxdev > 3 * sigma);       // a real spread, not a constant shift
            BOOST_TEST(maxdev <= 6 * sigma + 1);  // the sum of 12 uniforms is bounded at 6 sigma
        }
    }
}

BOOST_AUTO_TEST_CASE(grammar_and_canonical_text) {
    const v::Perturbation p = v::parse_perturbation("gain=0.8,offset=-10,noise=2.5,seed=7");
    BOOST_TEST(p.gain == 0.8);
    BOOST_TEST(p.offset == -10.0);
    BOOST_TEST(p.noise == 2.5);
    BOOST_TEST(p.seed == 7u);
    BOOST_TEST((p.image == v::PerturbImages::Right));
    BOOST_TEST((p.noise_image == v::PerturbImages::Both));
    BOOST_TEST(v::to_string(p) ==
               "gain=0.8,offset=-10,image=right,noise=2.5,noise-image=both,seed=7");
    const v::Perturbation q = v::parse_perturbation(v::to_string(p));
    BOOST_TEST(v::to_string(q) == v::to_string(p));
    BOOST_TEST(v::parse_perturbation("seed=18446744073709551615").seed == 18446744073709551615ull);
}

BOOST_AUTO_TEST_CASE(bad_specs_name_the_key_and_the_range) {
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"", "expected key=value"},
        {"gain=0", "gain=0"},
        {"gain=-1", "> 0"},
        {"gain=nan", "gain=nan"},
        {"gain=inf", "gain=inf"},
        {"gain=17", "<= 16"},
        {"gain=", "gain="},
        {"gain=0.8x", "gain=0.8x"},
        {"noise=-1", "0..64"},
        {"offset=300", "-255..255"},
        {"seed=-1", "seed=-1"},
        {"seed=18446744073709551616", "seed"},
        {"image=top", "left, right or both"},
        {"blur=2", "unknown key 'blur'"},
        {"gain", "key=value"},
        {"gain=1,gain=2", "twice"},
        {"gain=1,", "trailing"},
        {",gain=1", "key=value"},
    };
    for (const auto& [spec, needle] : bad) {
        BOOST_TEST_CONTEXT("spec '" << spec << "'") {
            try {
                v::parse_perturbation(spec);
                BOOST_ERROR("accepted");
            } catch (const std::invalid_argument& e) {
                BOOST_TEST(std::string(e.what()).find(needle) != std::string::npos, e.what());
            }
        }
    }
}
