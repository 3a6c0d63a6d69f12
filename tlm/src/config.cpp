#include "imap/tlm/config.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace imap::tlm {

namespace {
std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
}  // namespace

void TlmConfig::validate() const {
    if (!(quantum_ns > 0.0 && quantum_ns <= 1e9))
        throw isa::ConfigError("invalid value " + num(quantum_ns) +
                               " for quantum_ns: allowed > 0 and <= 1000000000 (1 s)");
}

std::vector<isa::ParamInfo> TlmConfig::list() const {
    isa::ParamInfo q;
    q.name = "quantum_ns";
    q.value = num(quantum_ns);
    q.range = "0..1000000000 (exclusive of 0)";
    q.unit = "ns";
    q.group = "tlm";
    q.doc =
        "global quantum of the loosely-timed model: the CP synchronises with the SystemC kernel "
        "at quantum ends and at every video line";
    q.assumption = false;
    return {q};
}

sc_core::sc_time clock_period(const isa::MachineConfig& cfg) {
    const double res_s = sc_core::sc_get_time_resolution().to_seconds();
    const double units = std::round(1.0 / (cfg.clock_mhz * 1e6) / res_s);
    if (!(units >= 1.0))
        throw isa::ConfigError("invalid value " + num(cfg.clock_mhz) +
                               " for clock_mhz: the clock period rounds to 0 at the SystemC time "
                               "resolution (" +
                               sc_core::sc_get_time_resolution().to_string() + ")");
    return sc_core::sc_time::from_value(static_cast<sc_dt::uint64>(units));
}

sc_core::sc_time cycles_to_time(uint64_t cycles, const sc_core::sc_time& period) {
    return sc_core::sc_time::from_value(static_cast<sc_dt::uint64>(cycles) * period.value());
}

}  // namespace imap::tlm
