// Parameters of the TLM model that are not parameters of the machine, and the
// conversion of cycles to SystemC time. The machine itself is configured by
// isa::MachineConfig (pes, clock_mhz, mem_bytes, costs, watchdog, ...).
#pragma once

#include <systemc>
#include <vector>

#include "imap/isa/config.hpp"

namespace imap::isa {
class Observer;
}

namespace imap::tlm {

struct TlmConfig {
    // Length of the global quantum of the loosely-timed model (modeled time).
    // The CP runs the machine for up to one quantum of cycles between two
    // synchronisations with the SystemC kernel; video transfers synchronise
    // as well. Larger = faster simulation, coarser interleaving with other
    // processes. Range: > 0 and at most 1 s.
    double quantum_ns = 10000.0;

    // Hosted CP: the CP does not start the program by itself but waits for
    // Cp::start() from a testbench, runs it to halt, notifies
    // Cp::done_event() and waits again (one program run per frame). A
    // machine fault ends that run only (Cp::fault()), not the simulation.
    bool hosted = false;

    // Attached to the machine before sc_start by run_tlm (waves, profiling);
    // nullptr = none (costs nothing). Not a model parameter (not listed).
    isa::Observer* observer = nullptr;

    // Throws isa::ConfigError naming the parameter, the value and the range.
    void validate() const;
    // For run reports (group "tlm").
    std::vector<isa::ParamInfo> list() const;
};

// One clock period of the array at cfg.clock_mhz, rounded to the SystemC
// time resolution (1 ps by default: exact for 40 MHz = 25 ns). Throws
// isa::ConfigError when the period would round to 0.
sc_core::sc_time clock_period(const isa::MachineConfig& cfg);

// `cycles` clock periods, computed in integer resolution units (exact).
sc_core::sc_time cycles_to_time(uint64_t cycles, const sc_core::sc_time& period);

}  // namespace imap::tlm
