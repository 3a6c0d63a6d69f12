#include "imap/engine/values.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include "imap/engine/error.hpp"

namespace imap::engine {

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

bool parse_uint_text(const std::string& s, long long* out) {
    if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
        return false;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (errno != 0 || *end != '\0') return false;
    *out = v;
    return true;
}

bool parse_real_text(const std::string& s, double* out) {
    if (s.empty() || s.find_first_not_of("0123456789.eE+-") != std::string::npos) return false;
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (errno != 0 || *end != '\0' || !std::isfinite(v)) return false;
    *out = v;
    return true;
}

// ---- value lists and ranges ---------------------------------------------------

namespace {

constexpr size_t kMaxValues = kMaxPoints;  // per range, before the product check

[[noreturn]] void bad_list(const std::string& flag, const std::string& text, ValueType type,
                           const std::string& why) {
    std::string expect =
        type == ValueType::Text
            ? "expected a comma list of values, e.g. a,b,c"
            : "expected a comma list of values and ranges A..B (step 1), A..B:S (step S) or "
              "A..B*F (factor F), e.g. 8,16,64 or 8..1024*2";
    throw Error("invalid value '" + text + "' for " + flag + ": " + why + "; " + expect);
}

std::string real_text(double v) {
    return fmt("%.10g", v);
}

// "A..B", "A..B:S" or "A..B*F" split into its texts (op 0, ':' or '*').
struct RangeText {
    std::string a, b, step;
    char op = 0;
};

RangeText split_range(const std::string& item) {
    RangeText r;
    const size_t dots = item.find("..");
    r.a = item.substr(0, dots);
    r.b = item.substr(dots + 2);
    const size_t k = r.b.find_first_of(":*");
    if (k != std::string::npos) {
        r.op = r.b[k];
        r.step = r.b.substr(k + 1);
        r.b.resize(k);
    }
    return r;
}

void expand_int_range(const std::string& flag, const std::string& text, const std::string& item,
                      std::vector<std::string>& out) {
    const RangeText r = split_range(item);
    long long a = 0, b = 0, s = 1;
    const char op = r.op;
    if (!parse_uint_text(r.a, &a) || !parse_uint_text(r.b, &b) ||
        (op && !parse_uint_text(r.step, &s)))
        bad_list(flag, text, ValueType::Int, "'" + item + "' is not a range of integers");
    if (a > b) bad_list(flag, text, ValueType::Int, "range '" + item + "' has A > B");
    if (op == '*') {
        if (s < 2) bad_list(flag, text, ValueType::Int, "factor in '" + item + "' must be >= 2");
        if (a < 1)
            bad_list(flag, text, ValueType::Int, "geometric range '" + item + "' needs A >= 1");
        for (long long v = a;; v *= s) {
            out.push_back(std::to_string(v));
            if (v > b / s) break;
        }
    } else {
        if (s < 1) bad_list(flag, text, ValueType::Int, "step in '" + item + "' must be >= 1");
        if ((b - a) / s + 1 > static_cast<long long>(kMaxValues))
            bad_list(
                flag, text, ValueType::Int,
                "range '" + item + "' has more than " + std::to_string(kMaxValues) + " values");
        for (long long v = a; v <= b; v += s) {
            out.push_back(std::to_string(v));
            if (v > b - s) break;
        }
    }
}

void expand_real_range(const std::string& flag, const std::string& text, const std::string& item,
                       std::vector<std::string>& out) {
    const RangeText r = split_range(item);
    double a = 0, b = 0, s = 1;
    const char op = r.op;
    if (!parse_real_text(r.a, &a) || !parse_real_text(r.b, &b) ||
        (op && !parse_real_text(r.step, &s)))
        bad_list(flag, text, ValueType::Real, "'" + item + "' is not a range of numbers");
    if (a > b) bad_list(flag, text, ValueType::Real, "range '" + item + "' has A > B");
    const double tol = 1e-9 * std::max(1.0, std::fabs(b));
    if (op == '*') {
        if (!(s > 1)) bad_list(flag, text, ValueType::Real, "factor in '" + item + "' must be > 1");
        if (!(a > 0))
            bad_list(flag, text, ValueType::Real, "geometric range '" + item + "' needs A > 0");
        for (int i = 0;; ++i) {
            const double v = a * std::pow(s, i);
            if (v > b + tol) break;
            out.push_back(real_text(v));
        }
    } else {
        if (!(s > 0)) bad_list(flag, text, ValueType::Real, "step in '" + item + "' must be > 0");
        if ((b - a) / s + 1 > static_cast<double>(kMaxValues))
            bad_list(
                flag, text, ValueType::Real,
                "range '" + item + "' has more than " + std::to_string(kMaxValues) + " values");
        for (long long i = 0;; ++i) {
            const double v = a + static_cast<double>(i) * s;
            if (v > b + tol) break;
            out.push_back(real_text(v));
        }
    }
}

}  // namespace

std::vector<std::string> parse_value_list(const std::string& flag, const std::string& text,
                                          ValueType type) {
    if (text.empty()) bad_list(flag, text, type, "empty list");
    std::vector<std::string> out;
    std::string item;
    std::stringstream ss(text);
    std::vector<std::string> items;
    while (std::getline(ss, item, ',')) items.push_back(item);
    if (text.back() == ',') items.push_back("");
    for (const std::string& it : items) {
        if (it.empty()) bad_list(flag, text, type, "empty item");
        if (it.find("..") != std::string::npos) {
            if (type == ValueType::Text)
                bad_list(flag, text, type, "ranges (A..B) need a numeric parameter");
            if (type == ValueType::Int)
                expand_int_range(flag, text, it, out);
            else
                expand_real_range(flag, text, it, out);
        } else if (type == ValueType::Int) {
            long long v = 0;
            if (!parse_uint_text(it, &v))
                bad_list(flag, text, type, "'" + it + "' is not an integer");
            out.push_back(std::to_string(v));
        } else if (type == ValueType::Real) {
            double v = 0;
            if (!parse_real_text(it, &v))
                bad_list(flag, text, type, "'" + it + "' is not a number");
            out.push_back(real_text(v));
        } else {
            out.push_back(it);
        }
        if (out.size() > kMaxValues)
            bad_list(flag, text, type, "more than " + std::to_string(kMaxValues) + " values");
    }
    std::set<std::string> seen;
    for (const std::string& v : out)
        if (!seen.insert(v).second)
            throw Error("invalid value '" + text + "' for " + flag + ": value " + v +
                        " appears twice");
    return out;
}

}  // namespace imap::engine
