// Set / validate / list of a table of named double-valued parameters (the
// energy table, the board timing): one range check and one message shape.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "imap/isa/config.hpp"

namespace imap::isa::detail {

inline std::string num_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

template <class F>
std::string num_bounds(const F& f) {
    return num_text(f.min) + ".." + num_text(f.max);
}

template <class F>
std::string num_range(const F& f) {
    return num_bounds(f) + (*f.unit ? " " : "") + f.unit;
}

template <class F>
void num_check(const F& f, double v) {
    if (!std::isfinite(v) || v < f.min || v > f.max)
        throw ConfigError("invalid value " + num_text(v) + " for " + f.name + ": allowed " +
                          num_range(f));
}

template <class T>
bool num_has(std::string_view name) {
    for (const auto& f : T::fields())
        if (name == f.name) return true;
    return false;
}

template <class T>
void num_set(T& t, std::string_view name, double v, const char* group) {
    for (const auto& f : T::fields()) {
        if (name != f.name) continue;
        num_check(f, v);
        t.*f.ptr = v;
        return;
    }
    std::string names;
    for (const auto& f : T::fields()) names += std::string(names.empty() ? "" : ", ") + f.name;
    throw ConfigError("unknown " + std::string(group) + " parameter '" + std::string(name) +
                      "' (known: " + names + ")");
}

template <class T>
void num_validate(const T& t) {
    for (const auto& f : T::fields()) num_check(f, t.*f.ptr);
}

template <class T>
std::vector<ParamInfo> num_list(const T& t, const char* group) {
    std::vector<ParamInfo> out;
    for (const auto& f : T::fields())
        out.push_back(
            {f.name, num_text(t.*f.ptr), num_bounds(f), f.unit, group, f.doc, true, false});
    return out;
}

}  // namespace imap::isa::detail
