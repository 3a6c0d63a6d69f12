// Image perturbations (perturb.hpp): integer arithmetic end to end.
#include "imap/vision/perturb.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

#include "imap/vision/splitmix64.hpp"

namespace imap::vision {

namespace {

[[noreturn]] void bad(const std::string& key, const std::string& value, const std::string& want) {
    throw PerturbSpecError(key + "=" + value, want);
}

double parse_number(const std::string& key, const std::string& value, double lo, double hi,
                    bool lo_open, const std::string& want) {
    if (value.empty()) bad(key, value, want);
    const char* s = value.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !std::isfinite(v)) bad(key, value, want);
    if ((lo_open ? !(v > lo) : !(v >= lo)) || !(v <= hi)) bad(key, value, want);
    return v;
}

PerturbImages parse_images(const std::string& key, const std::string& value) {
    if (value == "left") return PerturbImages::Left;
    if (value == "right") return PerturbImages::Right;
    if (value == "both") return PerturbImages::Both;
    bad(key, value, "expected left, right or both");
}

const char* images_name(PerturbImages i) {
    return i == PerturbImages::Left ? "left" : i == PerturbImages::Right ? "right" : "both";
}

bool applies(PerturbImages i, bool is_right) {
    return i == PerturbImages::Both || (i == PerturbImages::Right) == is_right;
}

// A value of perturb.hpp's ranges as a multiple of 2^-16 (exact for the
// parsed double times a power of two, then rounded to the nearest).
int64_t q16(double v) {
    return static_cast<int64_t>(std::llround(v * 65536.0));
}

}  // namespace

Perturbation parse_perturbation(const std::string& spec) {
    Perturbation p;
    if (spec.empty()) throw PerturbSpecError(spec, "expected key=value[,key=value...]");
    std::set<std::string> seen;
    std::stringstream ss(spec);
    for (std::string item; std::getline(ss, item, ',');) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos)
            throw PerturbSpecError(item,
                                   "expected key=value with the keys gain, offset, noise, "
                                   "seed, image, noise-image");
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        if (!seen.insert(key).second) throw PerturbSpecError(item, "'" + key + "' given twice");
        if (key == "gain") {
            p.gain = parse_number(key, value, 0, 16, true, "expected a number > 0 and <= 16");
        } else if (key == "offset") {
            p.offset = parse_number(key, value, -255, 255, false, "expected a number in -255..255");
        } else if (key == "noise") {
            p.noise = parse_number(key, value, 0, 64, false,
                                   "expected a standard deviation in 0..64 grey levels");
        } else if (key == "seed") {
            const std::string want = "expected an integer in 0..18446744073709551615";
            if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos)
                bad(key, value, want);
            errno = 0;
            const unsigned long long s = std::strtoull(value.c_str(), nullptr, 10);
            if (errno == ERANGE) bad(key, value, want);
            p.seed = static_cast<uint64_t>(s);
        } else if (key == "image") {
            p.image = parse_images(key, value);
        } else if (key == "noise-image") {
            p.noise_image = parse_images(key, value);
        } else {
            throw PerturbSpecError(item, "unknown key '" + key +
                                             "': expected gain, offset, noise, seed, image "
                                             "or noise-image");
        }
    }
    if (!spec.empty() && spec.back() == ',') throw PerturbSpecError(spec, "trailing ','");
    return p;
}

namespace {
// The shortest decimal text that reads back as `v`.
std::string shortest(double v) {
    for (int prec = 6; prec < 17; ++prec) {
        std::ostringstream os;
        os.precision(prec);
        os << v;
        if (std::strtod(os.str().c_str(), nullptr) == v) return os.str();
    }
    std::ostringstream os;
    os.precision(17);
    os << v;
    return os.str();
}
}  // namespace

std::string to_string(const Perturbation& p) {
    return "gain=" + shortest(p.gain) + ",offset=" + shortest(p.offset) +
           ",image=" + images_name(p.image) + ",noise=" + shortest(p.noise) +
           ",noise-image=" + images_name(p.noise_image) + ",seed=" + std::to_string(p.seed);
}

void perturb_image(cv::Mat& img, const Perturbation& p, bool is_right) {
    if (img.type() != CV_8UC1) throw std::invalid_argument("perturb_image: not a CV_8UC1 image");
    const bool lin = applies(p.image, is_right) && (p.gain != 1.0 || p.offset != 0.0);
    const bool noisy = applies(p.noise_image, is_right) && p.noise > 0;
    if (!lin && !noisy) return;
    // Fixed point: value = g * x * 2^16 + o * 2^16 + s * (S - mean), in units of 2^-32.
    const int64_t g = lin ? q16(p.gain) : 65536;
    const int64_t o = lin ? q16(p.offset) : 0;
    const int64_t s = noisy ? q16(p.noise) : 0;
    constexpr int64_t kMean = 12 * 65535 / 2;  // 393210: mean of 12 draws of 0..65535
    // Independent streams for the two images of one seed.
    SplitMix64 rng(p.seed ^ (is_right ? 0x5249474854000000ull : 0x4C45465400000000ull));
    for (int y = 0; y < img.rows; ++y) {
        uint8_t* row = img.ptr<uint8_t>(y);
        for (int x = 0; x < img.cols; ++x) {
            int64_t v = g * row[x] * 65536 + o * 65536;
            if (noisy) {
                int64_t sum = 0;
                for (int k = 0; k < 3; ++k) {  // 3 x 64 bits = 12 draws of 16 bits
                    const uint64_t r = rng.next();
                    sum += static_cast<int64_t>(r & 0xFFFF) +
                           static_cast<int64_t>((r >> 16) & 0xFFFF) +
                           static_cast<int64_t>((r >> 32) & 0xFFFF) + static_cast<int64_t>(r >> 48);
                }
                v += s * (sum - kMean);
            }
            // Round half up: floor(v / 2^32 + 1/2). v >= -(255 + 64 * 6) * 2^32 > -1024 * 2^32,
            // so the shift sees a non-negative value (no implementation-defined >>).
            const int64_t r =
                static_cast<int64_t>(
                    static_cast<uint64_t>(v + (int64_t{1024} << 32) + (int64_t{1} << 31)) >> 32) -
                1024;
            row[x] = static_cast<uint8_t>(r < 0 ? 0 : r > 255 ? 255 : r);
        }
    }
}

void perturb_pair(cv::Mat& left, cv::Mat& right, const Perturbation& p) {
    perturb_image(left, p, false);
    perturb_image(right, p, true);
}

}  // namespace imap::vision
