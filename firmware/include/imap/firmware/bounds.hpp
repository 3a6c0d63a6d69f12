// The machine's bound of each phase of a frame: the least cycles this
// machine (its PE count, memories and cost table) needs for the phase's
// work, whatever the firmware (docs/firmware.md, section 11). Beside the
// cycles a model measured, achieved / bound says which part of a what-if's
// difference is the machine and which the firmware.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"

namespace imap::firmware {

struct PhaseBound {
    std::string phase;  // the program's phase name
    int64_t cycles = 0;
    std::string basis;  // what the bound counts, in words
};

struct FrameBounds {
    std::vector<PhaseBound> phases;  // only the phases with a bound
    int64_t node_cycles = 0;         // cycles of one forward node on this cost table
    int64_t states = 0;              // valid states of the frame (ROI lines x states per line)
    // The frame's bound: the sum of the phase bounds (phases without one
    // count zero, so it stays a lower bound).
    int64_t total() const;
    // The bound of `phase`, or -1 when it has none.
    int64_t of(const std::string& phase) const;
};

// Cycles of one node of the forward pass (dp_forward.inc NODE, with the
// match cost of `p`) on cfg's cost table, measured by running it alone
// (node_probe.s) on the instruction-set executor.
int64_t node_cycles(const golden::Params& p, const FramePlan& plan, const isa::MachineConfig& cfg);

// The bounds of every phase that has one (video_in, relayout_in, forward,
// spill, backtrack, relayout_out, video_out) for a frame plan on cfg.
FrameBounds frame_bounds(const golden::Params& p, const FramePlan& plan,
                         const isa::MachineConfig& cfg);

}  // namespace imap::firmware
