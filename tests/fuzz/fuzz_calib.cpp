// The calibration-loader target (imap::vision::load_stereo_calib).
#include <cctype>
#include <cmath>
#include <new>
#include <opencv2/core.hpp>
#include <typeinfo>

#include "fuzz_vision.hpp"
#include "imap/vision/calib.hpp"

namespace imap::fuzz {

namespace {

using Text = std::string;

bool finite_f64(const cv::Mat& m) {
    if (m.empty() || m.type() != CV_64FC1) return false;
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c)
            if (!std::isfinite(m.at<double>(r, c))) return false;
    return true;
}

// The rules of calib.hpp, checked independently of the loader. Returns ""
// or what is wrong.
std::string calib_problem(const vision::StereoCalib& c) {
    for (const auto& [name, k] :
         {std::pair<const char*, const cv::Mat*>{"K1", &c.K1}, {"K2", &c.K2}}) {
        if (k->rows != 3 || k->cols != 3 || !finite_f64(*k))
            return std::string(name) + " is not a finite 3x3 CV_64F matrix";
        if (!(k->at<double>(0, 0) > 0) || !(k->at<double>(1, 1) > 0))
            return std::string(name) + " has a non-positive focal length";
    }
    for (const auto& [name, d] :
         {std::pair<const char*, const cv::Mat*>{"D1", &c.D1}, {"D2", &c.D2}}) {
        const int n = static_cast<int>(d->total());
        if ((d->rows != 1 && d->cols != 1) || !(n == 4 || n == 5 || n == 8 || n == 12 || n == 14) ||
            !finite_f64(*d))
            return std::string(name) + " is not a finite 4/5/8/12/14-element vector";
    }
    if (c.R.rows != 3 || c.R.cols != 3 || !finite_f64(c.R)) return "R is not a finite 3x3 matrix";
    const cv::Mat e = c.R.t() * c.R - cv::Mat::eye(3, 3, CV_64F);
    double worst = 0;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(e.at<double>(r, k)));
    if (worst > 1e-3 + 1e-9)
        return "R is not a rotation (|R^T R - I| = " + std::to_string(worst) + ")";
    if (cv::determinant(c.R) < 0) return "R has a negative determinant";
    if (c.T.total() != 3 || (c.T.rows != 1 && c.T.cols != 1) || !finite_f64(c.T))
        return "T is not a finite 3-vector";
    if (!(cv::norm(c.T) > 0)) return "T is a zero baseline";
    if (c.size.width <= 0 || c.size.height <= 0) return "image size is not positive";
    return "";
}

bool looks_xml(const Bytes& b) {
    for (uint8_t c : b) {
        if (std::isspace(c)) continue;
        return c == '<';
    }
    return false;
}

const std::vector<Text>& numbers() {
    static const std::vector<Text> n = {
        "0",      "-0.",      "1",          "-1",         "1e308",       "-1e308",
        "1e-308", "4.9e-324", ".nan",       ".inf",       "-.inf",       "nan",
        "inf",    "1e400",    "2147483647", "2147483648", "-2147483649", "99999999999999999999",
        "0x10",   "1.5",      "65536",      "46341",      "3",           "100000",
        "1e-3",   "0.9995",   "-1e-12"};
    return n;
}

const std::vector<Text>& keys() {
    static const std::vector<Text> k = {"K1",
                                        "M1",
                                        "camera_matrix_left",
                                        "D1",
                                        "dist_left",
                                        "K2",
                                        "M2",
                                        "D2",
                                        "R",
                                        "T",
                                        "image_size",
                                        "image_width",
                                        "image_height",
                                        "rows",
                                        "cols",
                                        "dt",
                                        "data",
                                        "opencv-matrix",
                                        "x",
                                        ""};
    return k;
}

bool num_char(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
           c == 'e' || c == 'E';
}

std::vector<std::pair<size_t, size_t>> number_tokens(const Text& t) {
    std::vector<std::pair<size_t, size_t>> out;
    for (size_t i = 0; i < t.size();) {
        const bool start = (std::isdigit(static_cast<unsigned char>(t[i])) ||
                            ((t[i] == '-' || t[i] == '.') && i + 1 < t.size() &&
                             std::isdigit(static_cast<unsigned char>(t[i + 1])))) &&
                           (i == 0 || !std::isalnum(static_cast<unsigned char>(t[i - 1])));
        if (!start) {
            ++i;
            continue;
        }
        size_t e = i + 1;
        while (e < t.size() && num_char(t[e])) ++e;
        out.emplace_back(i, e);
        i = e;
    }
    return out;
}

std::vector<std::pair<size_t, size_t>> word_tokens(const Text& t) {
    std::vector<std::pair<size_t, size_t>> out;
    for (size_t i = 0; i < t.size();) {
        if (!std::isalpha(static_cast<unsigned char>(t[i]))) {
            ++i;
            continue;
        }
        size_t e = i;
        while (e < t.size() &&
               (std::isalnum(static_cast<unsigned char>(t[e])) || t[e] == '_' || t[e] == '-'))
            ++e;
        out.emplace_back(i, e);
        i = e;
    }
    return out;
}

std::vector<Text> split_lines(const Text& t) {
    std::vector<Text> out;
    size_t b = 0;
    while (b <= t.size()) {
        const size_t e = t.find('\n', b);
        out.push_back(t.substr(b, e == Text::npos ? Text::npos : e - b));
        if (e == Text::npos) break;
        b = e + 1;
    }
    return out;
}

Text join_lines(const std::vector<Text>& v) {
    Text s;
    for (size_t i = 0; i < v.size(); ++i) s += (i ? "\n" : "") + v[i];
    return s;
}

}  // namespace

Result check_calib(const Bytes& file) {
    const std::string path =
        put_scratch_file(std::string("calib-input") + (looks_xml(file) ? ".xml" : ".yml"), file);
    vision::StereoCalib c;
    try {
        c = vision::load_stereo_calib(path);
    } catch (const vision::InputError& e) {
        const std::string w = e.what();
        if (w.find('\n') != std::string::npos)
            return {"InputError", "InputError message on several lines: " + w};
        // Parser messages quote the (fuzzed) text: one class for them.
        const size_t q = w.find("(cannot parse: ");
        return {signature("InputError", q == std::string::npos ? w : w.substr(0, q + 14) + ")"),
                ""};
    } catch (const cv::Exception& e) {
        return {"cv::Exception",
                std::string("cv::Exception escaped load_stereo_calib: ") + e.what()};
    } catch (const std::bad_alloc&) {
        return {"bad_alloc", "std::bad_alloc escaped load_stereo_calib"};
    } catch (const std::exception& e) {
        return {"other exception",
                std::string("load_stereo_calib threw ") + typeid(e).name() + ": " + e.what()};
    }
    const std::string bad = calib_problem(c);
    if (!bad.empty())
        return {"loaded, invalid", "load_stereo_calib accepted a calibration where " + bad};
    // A small accepted calibration must also give rectification maps.
    if (static_cast<int64_t>(c.size.width) * c.size.height > 320 * 240)
        return {"loaded (large, not rectified)", ""};
    try {
        const vision::Rectifier r(c);
        (void)r;
    } catch (const vision::InputError& e) {
        return {signature("loaded, Rectifier InputError", e.what()), ""};
    } catch (const std::exception& e) {
        return {"loaded, Rectifier threw",
                std::string("Rectifier threw on an accepted calibration: ") + e.what()};
    }
    return {"loaded, rectified", ""};
}

void mutate_calib(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    Text t(b.begin(), b.end());
    const int steps = 1 + static_cast<int>(rng.below(3));
    for (int s = 0; s < steps; ++s) {
        switch (rng.below(9)) {
            case 0:
            case 1: {  // a number
                const auto nums = number_tokens(t);
                if (nums.empty()) break;
                const auto [x, y] = rng.pick(nums);
                t.replace(x, y - x, rng.pick(numbers()));
                break;
            }
            case 2: {  // a key or word
                const auto words = word_tokens(t);
                if (words.empty()) break;
                const auto [x, y] = rng.pick(words);
                t.replace(x, y - x, rng.pick(keys()));
                break;
            }
            case 3: {  // dt of a matrix
                const size_t at = t.find(rng.chance(50) ? "dt" : "<dt>");
                if (at == Text::npos) break;
                static const char* dts[] = {"d", "f", "u", "i", "s", "c", "w", "2d", "3f", "x", ""};
                size_t v = t.find_first_of("df", at + 2);
                if (v != Text::npos && v < at + 10) t.replace(v, 1, dts[rng.index(11)]);
                break;
            }
            case 4: {  // delete, duplicate or swap a line
                std::vector<Text> L = split_lines(t);
                if (L.empty()) break;
                const size_t i = rng.index(L.size());
                const uint64_t how = rng.below(3);
                if (how == 0)
                    L.erase(L.begin() + static_cast<std::ptrdiff_t>(i));
                else if (how == 1)
                    L.insert(L.begin() + static_cast<std::ptrdiff_t>(rng.index(L.size() + 1)),
                             L[i]);
                else
                    std::swap(L[i], L[rng.index(L.size())]);
                t = join_lines(L);
                break;
            }
            case 5: {  // a structure character
                static const char syn[] = "[]{}<>:,-\"'&*!|%#\n \t/=";
                const size_t at = rng.index(t.size() + 1);
                if (rng.chance(50) && at < t.size())
                    t[at] = syn[rng.index(sizeof syn - 1)];
                else
                    t.insert(t.begin() + static_cast<std::ptrdiff_t>(at),
                             syn[rng.index(sizeof syn - 1)]);
                break;
            }
            case 6: {  // many more matrix elements
                const auto nums = number_tokens(t);
                if (nums.empty()) break;
                const auto [x, y] = rng.pick(nums);
                Text rep = t.substr(x, y - x);
                const size_t n = 1 + rng.index(rng.chance(90) ? 20 : 5000);
                Text more;
                for (size_t i = 0; i < n; ++i) more += (looks_xml(b) ? " " : ", ") + rep;
                t.insert(y, more);
                break;
            }
            default: {  // bytes and splices
                Bytes x(t.begin(), t.end());
                mutate_bytes(rng, x, corpus, 1 << 17, 2);
                t.assign(x.begin(), x.end());
                break;
            }
        }
    }
    if (t.size() > (1u << 17)) t.resize(1u << 17);
    b.assign(t.begin(), t.end());
}

}  // namespace imap::fuzz
