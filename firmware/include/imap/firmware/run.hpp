// Running the DP firmware on a frame: the result every model reports.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/model_run.hpp"

namespace imap::firmware {

struct FrameResult {
    golden::DisparityMap map;  // ROI-sized, from the video output
    uint64_t cycles = 0;
    double modeled_ms = 0;
    std::vector<std::pair<std::string, uint64_t>> phases;  // name, cycles (non-zero only)
    isa::Stats stats;
    double wall_s = 0;
    // Re-layout: measured cycles of the phases relayout_in / relayout_out and
    // the lower bound of the plan (FramePlan::rl, docs/firmware.md section 5):
    // bound = ring + memory instructions.
    uint64_t relayout_in = 0, relayout_out = 0;
    int64_t relayout_bound_in = 0, relayout_bound_out = 0;
    int64_t relayout_ring_in = 0, relayout_ring_out = 0, relayout_mem_in = 0, relayout_mem_out = 0;
};

// Fills the re-layout fields of a result from its phases and the plan.
void set_relayout_figures(const FramePlan& plan, FrameResult& r);

// Phase table of a finished machine (names from the program, zero phases
// left out).
std::vector<std::pair<std::string, uint64_t>> phase_table(const isa::Machine& m);
std::vector<std::pair<std::string, uint64_t>> phase_table(const isa::Program& prog,
                                                          const std::vector<uint64_t>& cycles);

// A frame's result from any model's run result: the phases named by the
// program, the disparity map from the model's video output (the plan's ROI
// size), the re-layout figures against the plan's bound.
FrameResult frame_result(const FramePlan& plan, const isa::Program& prog, const isa::ModelRun& run,
                         std::vector<uint8_t> pixels);

// Runs one frame on the bare machine core (the executor every model wraps).
// `observer` (optional, e.g. the waves tracer) is attached for the run.
FrameResult run_frame_core(const FramePlan& plan, const isa::Program& prog,
                           const golden::ImageView& left, const golden::ImageView& right,
                           const isa::MachineConfig& cfg, isa::Observer* observer = nullptr);

// Copies an image view into a video-port image.
isa::ImageVideoPort::Image to_video_image(const golden::ImageView& v);

}  // namespace imap::firmware
