#include "imap/firmware/run.hpp"

#include <chrono>

namespace imap::firmware {

std::vector<std::pair<std::string, uint64_t>> phase_table(const isa::Program& prog,
                                                          const std::vector<uint64_t>& cycles) {
    std::vector<std::pair<std::string, uint64_t>> t;
    for (size_t i = 0; i < cycles.size(); ++i)
        if (cycles[i] > 0) t.emplace_back(prog.phase_name(static_cast<uint32_t>(i)), cycles[i]);
    return t;
}

std::vector<std::pair<std::string, uint64_t>> phase_table(const isa::Machine& m) {
    return phase_table(m.program(), m.phase_cycles());
}

isa::ImageVideoPort::Image to_video_image(const golden::ImageView& v) {
    isa::ImageVideoPort::Image im;
    im.width = v.width;
    im.height = v.height;
    im.pixels.resize(static_cast<size_t>(v.width) * v.height);
    for (int y = 0; y < v.height; ++y)
        std::copy(v.row(y), v.row(y) + v.width,
                  im.pixels.begin() + static_cast<ptrdiff_t>(y) * v.width);
    return im;
}

void set_relayout_figures(const FramePlan& plan, FrameResult& r) {
    r.relayout_in = r.relayout_out = 0;
    for (const auto& [name, cyc] : r.phases) {
        if (name == "relayout_in") r.relayout_in = cyc;
        if (name == "relayout_out") r.relayout_out = cyc;
    }
    r.relayout_bound_in = plan.rl.bound_in;
    r.relayout_bound_out = plan.rl.bound_out;
    r.relayout_ring_in = plan.rl.ring_bound_in;
    r.relayout_ring_out = plan.rl.ring_bound_out;
    r.relayout_mem_in = plan.rl.mem_bound_in;
    r.relayout_mem_out = plan.rl.mem_bound_out;
}

FrameResult run_frame_core(const FramePlan& plan, const isa::Program& prog,
                           const golden::ImageView& left, const golden::ImageView& right,
                           const isa::MachineConfig& cfg, isa::Observer* observer) {
    isa::Machine m(cfg);
    m.load(prog);
    for (const auto& [i, v] : param_block(plan)) m.set_param(i, v);
    isa::ImageVideoPort video;
    video.input[0] = to_video_image(left);
    video.input[1] = to_video_image(right);
    video.make_output(0, plan.roi.w, plan.roi.h);
    m.set_video(&video);
    m.set_observer(observer);
    const auto t0 = std::chrono::steady_clock::now();
    m.run();
    isa::ModelRun run = isa::model_run_of(m);
    run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return frame_result(plan, prog, run, std::move(video.output[0].pixels));
}

FrameResult frame_result(const FramePlan& plan, const isa::Program& prog, const isa::ModelRun& run,
                         std::vector<uint8_t> pixels) {
    FrameResult r;
    r.cycles = run.cycles;
    r.modeled_ms = run.modeled_ms;
    r.wall_s = run.wall_s;
    r.phases = phase_table(prog, run.phase_cycles);
    r.stats = run.stats;
    r.map.width = plan.roi.w;
    r.map.height = plan.roi.h;
    r.map.data = std::move(pixels);
    set_relayout_figures(plan, r);
    return r;
}

}  // namespace imap::firmware
