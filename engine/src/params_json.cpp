#include "imap/engine/params_json.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace imap::engine {

nlohmann::json param_value_json(const isa::ParamInfo& p) {
    const std::string& v = p.value;
    if (v == "on" || v == "true") return true;
    if (v == "off" || v == "false") return false;
    if (!v.empty()) {
        errno = 0;
        char* end = nullptr;
        const long long i = std::strtoll(v.c_str(), &end, 10);
        if (errno == 0 && end != v.c_str() && *end == '\0') return i;
        errno = 0;
        const unsigned long long u = std::strtoull(v.c_str(), &end, 10);
        if (errno == 0 && end != v.c_str() && *end == '\0' && v[0] != '-') return u;
        errno = 0;
        const double d = std::strtod(v.c_str(), &end);
        if (errno == 0 && end != v.c_str() && *end == '\0' && std::isfinite(d)) return d;
    }
    return v;  // not a number: kept as text
}

nlohmann::json machine_params_json(const isa::MachineConfig& cfg) {
    nlohmann::json j = nlohmann::json::object();
    for (const isa::ParamInfo& p : cfg.list()) j[p.name] = param_value_json(p);
    return j;
}

nlohmann::json machine_param_info_json(const isa::MachineConfig& cfg) {
    nlohmann::json j = nlohmann::json::object();
    for (const isa::ParamInfo& p : cfg.list())
        j[p.name] = {{"assumption", p.assumption},
                     {"faster", p.faster},
                     {"unit", p.unit},
                     {"group", p.group}};
    return j;
}

std::string faster_assumptions_text(const isa::MachineConfig& cfg) {
    std::string s;
    for (const isa::ParamInfo& p : cfg.list()) {
        if (!p.faster) continue;
        if (!s.empty()) s += ", ";
        s += p.name + " " + p.value + (p.unit.empty() ? "" : " " + p.unit);
    }
    return s;
}

nlohmann::json algo_params_json(const golden::Params& p) {
    nlohmann::json j = {{"D", p.D},
                        {"km", p.km},
                        {"kb", p.kb},
                        {"gb", p.gb},
                        {"Wo", p.Wo},
                        {"Wd", p.Wd},
                        {"mode", golden::to_string(p.mode)},
                        {"seed_col", golden::seed_col_string(p.seed_col)},
                        {"seed_disp", golden::seed_disp_string(p.seed_disp)},
                        {"vote", p.vote},
                        {"frame", golden::to_string(p.frame)}};
    if (golden::uses_options(p)) {  // SPEC A.9 (absent for the paper's algorithm)
        j["dissim"] = golden::to_string(p.dissim);
        j["ad_max"] = p.ad_max;
        j["kc"] = p.kc;
        j["census"] = p.census;
        j["agg_rx"] = p.agg_rx;
        j["agg_ry"] = p.agg_ry;
    }
    return j;
}

}  // namespace imap::engine
