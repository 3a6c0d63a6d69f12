// The machine's bound of each phase (docs/firmware.md, section 11): the work
// a phase must do, counted from the plan and the parameters, times the least
// cycles this machine's cost table charges for a unit of it. Every bound
// assumes the work spread evenly over all P PEs, so the PEs a firmware
// leaves idle show as the firmware's share of the difference.
#include "imap/firmware/bounds.hpp"

#include <algorithm>

#include "imap/isa/machine.hpp"

namespace imap::firmware {

namespace {

int64_t ceil_div(int64_t a, int64_t b) {
    return (a + b - 1) / b;
}

}  // namespace

int64_t FrameBounds::total() const {
    int64_t t = 0;
    for (const PhaseBound& b : phases) t += b.cycles;
    return t;
}

int64_t FrameBounds::of(const std::string& phase) const {
    for (const PhaseBound& b : phases)
        if (b.phase == phase) return b.cycles;
    return -1;
}

int64_t node_cycles(const golden::Params& p, const FramePlan& plan, const isa::MachineConfig& cfg) {
    isa::MachineConfig c = cfg;
    c.pes = 2;  // one node is the same on every PE; two keep the probe cheap
    const isa::Program prog = assemble_test(p, plan.f, "node_probe.s", 1, c.pes);
    isa::Machine m(c);
    m.load(prog);
    m.run();
    for (size_t i = 0; i < m.phase_cycles().size(); ++i)
        if (prog.phase_name(static_cast<uint32_t>(i)) == "node")
            return static_cast<int64_t>(m.phase_cycles()[i]);
    throw FirmwareError("firmware: node_probe.s has no phase 'node'");
}

FrameBounds frame_bounds(const golden::Params& p, const FramePlan& plan,
                         const isa::MachineConfig& cfg) {
    FrameBounds b;
    const isa::CostTable& k = cfg.costs;
    const int64_t P = cfg.pes, H = plan.roi.h, W = plan.roi.w;
    const int64_t segs = ceil_div(W, P);  // a vin / vout moves P pixels of a line
    b.node_cycles = node_cycles(p, plan, cfg);
    b.states = H * plan.f.valid_states;

    // With a timed camera the lines also cannot come faster than it
    // delivers them: from the ROI's first segment to its last. This holds
    // for a frame of one batch, whose vins are all in one stretch of the
    // phase that starts before the first segment has arrived (the program's
    // prologue is shorter than P pixel times); a later batch's lines may
    // have arrived while the previous batch computed.
    int64_t video_in = H * 2 * segs * k.video_line;
    const char* video_why = "every ROI line of both images through the video port";
    if (cfg.board.camera_timed() && plan.batches.size() == 1) {
        // the narrowest image that holds the ROI: its lines come soonest
        const int width = plan.roi.x0 + plan.roi.w, np = static_cast<int>(P);
        const int64_t first =
            static_cast<int64_t>(cfg.camera_ready_cycle(width, plan.roi.y0, plan.roi.x0, np));
        const int64_t last = static_cast<int64_t>(
            cfg.camera_ready_cycle(width, plan.roi.y0 + plan.roi.h - 1,
                                   plan.roi.x0 + static_cast<int>((segs - 1) * P), np));
        if (last - first + k.video_line > video_in) {
            video_in = last - first + k.video_line;
            video_why = "the camera's lines from the ROI's first segment to its last";
        }
    }
    b.phases.push_back({"video_in", video_in, video_why});
    if (plan.rl.bound_in > 0)
        b.phases.push_back({"relayout_in", plan.rl.bound_in,
                            "ring: byte-hops over P links and bytes into every arc"});

    // Forward: the frame's valid states spread over every PE, or the
    // dependency chain of one line (a state needs its column's predecessor),
    // whichever is longer; one node each.
    const int64_t per_pe = std::max(ceil_div(b.states, P), int64_t{plan.f.kmax} + 1);
    b.phases.push_back({"forward", per_pe * b.node_cycles,
                        "valid states / P (or one line's column chain) x one node"});

    // Spill: the pointers (2 bits per state) of a batch's lines that do not
    // fit beside one column's 16-bit costs in the local memories go out and
    // come back; each batch's backtrack frees the memory for the next, so
    // the excess is counted batch by batch (of the plan's batches, as the
    // re-layout's bound is of the plan's placement).
    const int64_t room = P * std::max<int64_t>(0, int64_t{cfg.mem_bytes} - 2 * p.D);
    int64_t spill = 0;
    for (const Batch& bt : plan.batches) {
        const int64_t excess =
            std::max<int64_t>(0, ceil_div(int64_t{bt.lines} * plan.f.valid_states, 4) - room);
        if (excess > 0)
            spill += 2 * (int64_t{k.xfer_setup} +
                          ceil_div(excess, k.ext_bytes_per_cycle) * int64_t{k.ext_beat});
    }
    if (spill > 0)
        b.phases.push_back(
            {"spill", spill,
             "each batch's pointer bytes beyond local memory, out and back over the external "
             "path"});

    // Backtrack: every line's path (one per kind) crosses its columns one
    // step each, a step reading a pointer at a per-PE address; with the vote
    // it also needs the neighbouring lines' fields (two ring moves of the
    // lines' spacing).
    const int64_t kinds = plan.f.kinds, span = plan.span();
    const int64_t waves = ceil_div(H * kinds, P);
    const int64_t read = int64_t{k.mem} + (cfg.indirect ? k.indirect_extra : 0);
    const int64_t step = read + (p.vote ? 2 * span * int64_t{k.ring_hop} : 0);
    b.phases.push_back({"backtrack", waves * plan.f.kmax * step,
                        p.vote ? "path columns x (pointer read + neighbours' fields)"
                               : "path columns x pointer read"});

    if (plan.rl.bound_out > 0)
        b.phases.push_back({"relayout_out", plan.rl.bound_out,
                            "ring: byte-hops over P links and bytes into every arc"});
    b.phases.push_back(
        {"video_out", H * segs * k.video_line, "every ROI line of the map through the video port"});
    return b;
}

}  // namespace imap::firmware
