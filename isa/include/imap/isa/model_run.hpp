// What every model of the machine reports about a run: the bare executor,
// the TLM model and the RTL model return this one type (the SystemC models
// derive from it to add their own statistics), so that a frame's result is
// made from any of them in one place (firmware::frame_result).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "imap/isa/machine.hpp"

namespace imap::isa {

struct ModelRun {
    bool halted = false;
    uint64_t cycles = 0;
    double modeled_ms = 0;  // MachineConfig::milliseconds(cycles)
    double wall_s = 0;      // wall time of the run (set by the one-call runners)
    std::vector<uint64_t> phase_cycles;
    Stats stats;
    double sim_time_s = 0;  // simulated time at the end (SystemC models: sc_time_stamp())
    // The final architectural state (registers, flags, memories, CP).
    std::shared_ptr<const Machine> machine;
};

// The model-independent part of a finished machine (machine and times unset).
inline ModelRun model_run_of(const Machine& m) {
    ModelRun r;
    r.halted = m.halted();
    r.cycles = m.cycles();
    r.modeled_ms = m.config().milliseconds(m.cycles());
    r.phase_cycles = m.phase_cycles();
    r.stats = m.stats();
    return r;
}

}  // namespace imap::isa
