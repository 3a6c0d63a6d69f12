// The sweep's grid: an axis from a flag's text (make_axis: the parameter's
// kind, its value list parsed and every value checked), an axis value as a
// number (numeric_value), the input's description, and the points of the
// swept axes (product: the cartesian product, the last axis fastest, refused
// beyond kMaxPoints).
#include <cmath>
#include <string>
#include <vector>

#include "imap/engine/error.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/isa/config.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

namespace isa = imap::isa;
using namespace detail;

namespace detail {

bool parse_wxh(const std::string& v, int* w, int* h) {
    const size_t x = v.find('x');
    if (x == std::string::npos) return false;
    long long a = 0, b = 0;
    if (!parse_uint_text(v.substr(0, x), &a) || !parse_uint_text(v.substr(x + 1), &b)) return false;
    if (a > 1000000 || b > 1000000) return false;
    *w = static_cast<int>(a);
    *h = static_cast<int>(b);
    return true;
}

}  // namespace detail

namespace {

const isa::ParamInfo* machine_param(const std::vector<isa::ParamInfo>& list, const std::string& n) {
    for (const isa::ParamInfo& pi : list)
        if (pi.name == n) return &pi;
    return nullptr;
}

ValueType machine_type(const isa::ParamInfo& pi) {
    if (pi.range.find('|') != std::string::npos) return ValueType::Text;
    if (pi.name == "clock_mhz" || pi.group == "energy" || pi.group == "board" ||
        pi.range.find('.') != pi.range.rfind("..") ||
        pi.range.find("exclusive") != std::string::npos)
        return ValueType::Real;
    return ValueType::Int;
}

}  // namespace

Axis make_axis(const std::string& name, const std::string& flag, const std::string& text) {
    Axis a;
    a.name = name;
    a.flag = flag;
    if (name == "roi_size") {
        a.kind = AxisKind::RoiSize;
        a.values = parse_value_list(flag, text, ValueType::Text);
        for (const std::string& v : a.values) {
            int w = 0, h = 0;
            if (!parse_wxh(v, &w, &h) || w < 2 || h < 1 || w > 4096 || h > 4096)
                throw Error("invalid value '" + v + "' in " + flag +
                            ": expected WxH with W in 2..4096, H in 1..4096 (a comma list, "
                            "e.g. 64x64,128x128)");
        }
        return a;
    }
    if (name == "mode") {
        a.kind = AxisKind::Algo;
        a.values = parse_value_list(flag, text, ValueType::Text);
        for (const std::string& v : a.values)
            if (v != "single" && v != "bidir" && v != "joint")
                throw Error("invalid value '" + v + "' in " + flag +
                            ": expected single, bidir or joint (a comma list, e.g. single,bidir)");
        return a;
    }
    for (const AlgoInt& r : kAlgoInts)
        if (name == r.name) {
            a.kind = AxisKind::Algo;
            a.values = parse_value_list(flag, text, ValueType::Int);
            for (const std::string& v : a.values) {
                long long x = 0;
                parse_uint_text(v, &x);
                if (x < r.lo || x > r.hi)
                    throw Error("value " + v + " for " + flag + " is out of range (allowed: " +
                                std::to_string(r.lo) + ".." + std::to_string(r.hi) + ")");
            }
            return a;
        }
    // A machine or cost parameter.
    a.kind = AxisKind::Machine;
    const isa::MachineConfig probe;
    const std::vector<isa::ParamInfo> list = probe.list();
    const isa::ParamInfo* pi = machine_param(list, name);
    if (!pi) {
        std::string names;
        for (const isa::ParamInfo& p : list) names += (names.empty() ? "" : ", ") + p.name;
        throw Error("unknown machine parameter '" + name + "' in " + flag + " (known: " + names +
                    ")");
    }
    a.values = parse_value_list(flag, text, machine_type(*pi));
    for (const std::string& v : a.values) {
        isa::MachineConfig c;
        try {
            c.set(name, v);
        } catch (const std::exception& e) {
            throw Error(flag + ": " + e.what());
        }
    }
    return a;
}

double numeric_value(const Axis& a, const std::string& v) {
    if (a.kind == AxisKind::RoiSize || a.name == "mode") return NAN;
    double d = 0;
    return parse_real_text(v, &d) ? d : NAN;
}

std::string Input::describe() const {
    if (left.empty())
        return "synthetic scene seed " + std::to_string(seed) + " (generated at the ROI size)";
    std::string d =
        left + " + " + right + " (" + std::to_string(width) + "x" + std::to_string(height) + ")";
    if (has_fixed_roi)
        d += ", ROI " + std::to_string(roi.x0) + "," + std::to_string(roi.y0) + "," +
             std::to_string(roi.w) + "," + std::to_string(roi.h);
    return d;
}

std::vector<std::vector<size_t>> product(const std::vector<Axis>& swept) {
    size_t n = 1;
    std::string sizes;
    bool too_many = false;
    for (const Axis& a : swept) {
        sizes += (sizes.empty() ? "" : " x ") + a.name + " " + std::to_string(a.values.size());
        if (a.values.size() > 0 && n > kMaxPoints * 10 / a.values.size()) too_many = true;
        n *= a.values.size();
        if (n > kMaxPoints) too_many = true;
    }
    if (too_many)
        throw Error("the sweep has " +
                    (n > kMaxPoints * 10
                         ? std::string("more than ") + std::to_string(kMaxPoints * 10)
                         : std::to_string(n)) +
                    " points (" + sizes + "); at most " + std::to_string(kMaxPoints) +
                    " are allowed: use fewer values or coarser steps");
    std::vector<std::vector<size_t>> pts;
    std::vector<size_t> idx(swept.size(), 0);
    for (size_t k = 0; k < n; ++k) {
        pts.push_back(idx);
        for (size_t i = swept.size(); i-- > 0;) {  // the last axis varies fastest
            if (++idx[i] < swept[i].values.size()) break;
            idx[i] = 0;
        }
    }
    return pts;
}

}  // namespace imap::engine::sweep
