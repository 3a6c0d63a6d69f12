#include "imap/testbench/stream.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "imap/firmware/run.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/score.hpp"

namespace imap::testbench {

namespace g = imap::golden;

namespace {
std::string num(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}
double ms(const sc_core::sc_time& t) {
    return t.to_seconds() * 1e3;
}
}  // namespace

void StreamTiming::resolve(int height) {
    if (!(fps > 0 && fps <= 100000))
        throw std::invalid_argument("invalid value " + num(fps) +
                                    " for the frame rate (--fps): allowed > 0 and <= 100000");
    if (height < 1) throw std::invalid_argument("frame height must be >= 1");
    const double frame_us = 1e6 / fps;
    if (line_us == 0) line_us = std::min(kDefaultLineUs, frame_us / height);
    if (!(line_us > 0 && std::isfinite(line_us)))
        throw std::invalid_argument("invalid value " + num(line_us) +
                                    " for the camera line period (--line-us): allowed > 0");
    if (line_us * height > frame_us * (1 + 1e-9))
        throw std::invalid_argument("a frame of " + std::to_string(height) + " lines at " +
                                    num(line_us) + " us per line takes " +
                                    num(line_us * height / 1000) +
                                    " ms, longer than the frame period " + num(frame_us / 1000) +
                                    " ms (--fps " + num(fps) + "): lower --line-us or --fps");
    if (deadline_ms == 0) deadline_ms = frame_ms();
    if (!(deadline_ms > 0 && std::isfinite(deadline_ms)))
        throw std::invalid_argument("invalid value " + num(deadline_ms) +
                                    " for the deadline (--deadline-ms): allowed > 0");
}

// A frame in the board's input frame buffer.
struct StreamTestbench::Slot {
    SourceFrame frame;
    sc_core::sc_time capture;   // first line started
    int arrived = 0;            // lines complete
    isa::ImageVideoPort video;  // input pixels (read once arrived) and the output map
};

StreamTestbench::StreamTestbench(sc_core::sc_module_name name, tlm::TlmSystem& model,
                                 FrameSource& source, const StreamSetup& setup)
    : sc_module(name), model_(model), source_(source), setup_(setup) {
    if (!model.cp.tlm_config().hosted)
        throw std::logic_error(
            "StreamTestbench: the model's CP must be hosted (TlmConfig::hosted)");
    line_period_ = sc_core::sc_time(setup.timing.line_us, sc_core::SC_US);
    frame_period_ = sc_core::sc_time(setup.timing.frame_ms(), sc_core::SC_MS);
    model_.video.attach_stream(this);
    SC_THREAD(camera);
    SC_THREAD(control);
    // Golden and file output run on these stacks: be generous.
    set_stack_size(8u << 20);
}

void StreamTestbench::camera() {
    try {
        for (int k = 0;; ++k) {
            if (setup_.stop_requested && setup_.stop_requested()) {
                interrupted_ = true;
                break;
            }
            arriving_ = std::make_shared<Slot>();
            Slot* const slot = arriving_.get();
            if (!source_.next(slot->frame)) break;
            const sc_core::sc_time tk = frame_period_ * static_cast<double>(k);
            if (sc_core::sc_time_stamp() < tk) sc_core::wait(tk - sc_core::sc_time_stamp());
            slot->capture = sc_core::sc_time_stamp();
            const bool good = slot->frame.error.empty();
            if (good) {
                slot->video.input[0] = firmware::to_video_image(vision::view_of(slot->frame.left));
                slot->video.input[1] = firmware::to_video_image(vision::view_of(slot->frame.right));
            }
            queue_.push_back(arriving_);
            queued_ev_.notify(sc_core::SC_ZERO_TIME);
            if (!good) continue;
            // Both cameras deliver line y at capture + (y + 1) line periods.
            const int H = slot->frame.left.rows;
            for (int y = 0; y < H; ++y) {
                sc_core::wait(line_period_);
                slot->arrived = y + 1;
                line_ev_.notify(sc_core::SC_ZERO_TIME);
            }
        }
    } catch (...) {
        error_ = std::current_exception();
    }
    arriving_ = nullptr;
    camera_done_ = true;
    queued_ev_.notify(sc_core::SC_ZERO_TIME);
}

void StreamTestbench::control() {
    try {
        for (;;) {
            while (queue_.empty() && !camera_done_) sc_core::wait(queued_ev_);
            if (queue_.empty() || error_) break;
            if (setup_.stop_requested && setup_.stop_requested()) {
                interrupted_ = true;
                break;
            }
            std::shared_ptr<Slot> s = queue_.front();
            queue_.erase(queue_.begin());
            const auto t0 = std::chrono::steady_clock::now();
            FrameRecord rec;
            rec.index = s->frame.index;
            rec.name = s->frame.name;
            rec.capture_ms = ms(s->capture);
            cv::Mat disparity;
            if (!s->frame.error.empty()) {
                rec.status = "bad-frame";
                rec.error = s->frame.error;
            } else {
                s->video.make_output(0, setup_.roi.w, setup_.roi.h);
                current_ = s;
                rec.start_ms = ms(sc_core::sc_time_stamp());
                const auto m0 = std::chrono::steady_clock::now();
                model_.cp.start();
                while (model_.cp.busy()) sc_core::wait(model_.cp.done_event());
                rec.model_wall_s =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - m0).count();
                current_ = nullptr;
                const isa::Machine& m = model_.machine();
                rec.done_ms = ms(sc_core::sc_time_stamp());
                rec.latency_ms = rec.done_ms - rec.capture_ms;
                rec.deadline_met = rec.latency_ms <= setup_.timing.deadline_ms * (1 + 1e-12);
                rec.cycles = m.cycles();
                rec.compute_ms = setup_.machine.milliseconds(rec.cycles);
                rec.stall_ms = ms(model_.cp.video_stall());
                rec.phases = firmware::phase_table(m);
                if (model_.cp.fault()) {
                    rec.status = "fault";
                    try {
                        std::rethrow_exception(model_.cp.fault());
                    } catch (const std::exception& e) {
                        rec.error = e.what();
                    }
                } else {
                    g::DisparityMap got;
                    got.width = setup_.roi.w;
                    got.height = setup_.roi.h;
                    got.data = s->video.output[0].pixels;
                    const g::ImageView lv = vision::view_of(s->frame.left);
                    const g::ImageView rv = vision::view_of(s->frame.right);
                    const auto g0 = std::chrono::steady_clock::now();
                    const g::DisparityMap want = g::compute(setup_.params, lv, rv, setup_.roi);
                    rec.golden_wall_s =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - g0)
                            .count();
                    for (size_t i = 0; i < got.data.size(); ++i)
                        rec.differing += got.data[i] != want.data[i];
                    rec.status = rec.differing == 0 ? "ok" : "mismatch";
                    if (!s->frame.gt.empty()) {
                        g::Params pl = setup_.params;
                        pl.frame = g::Frame::Left;
                        rec.bad1 = vision::bad_percent_roi(g::compute(pl, lv, rv, setup_.roi, true),
                                                           s->frame.gt, setup_.roi);
                    }
                    disparity = cv::Mat(got.height, got.width, CV_8UC1, got.data.data()).clone();
                }
            }
            rec.wall_s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            records_.push_back(rec);
            if (setup_.on_frame)
                setup_.on_frame(FrameOutput{records_.back(), s->frame.left, disparity});
        }
    } catch (...) {
        if (!error_) error_ = std::current_exception();
    }
    // The end of the stream, not an event to report.
    sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                            sc_core::SC_DO_NOTHING);
    sc_core::sc_stop();
}

void StreamTestbench::read_line(int port, int y, int x0, uint8_t* dst, int n) {
    // A raw pointer (current_ owns the frame until the CP is done with it):
    // this runs on the CP's stack, which may stay suspended here for good.
    Slot* const s = current_.get();
    if (!s) throw std::runtime_error("video input read with no frame in progress");
    if (port >= 0 && port <= 1 && y >= 0 && y < s->video.input[port].height)
        while (s->arrived <= y) sc_core::wait(line_ev_);
    s->video.read_line(port, y, x0, dst, n);
}

void StreamTestbench::write_line(int port, int y, int x0, const uint8_t* src, int n) {
    if (!current_) throw std::runtime_error("video output write with no frame in progress");
    current_->video.write_line(port, y, x0, src, n);
}

StreamResult run_stream(FrameSource& source, const StreamSetup& setup) {
    tlm::TlmConfig tc = setup.tlm;
    tc.hosted = true;
    auto top = std::make_unique<tlm::TlmSystem>("top", setup.machine, setup.program, tc);
    for (const auto& [i, v] : firmware::param_block(setup.plan)) top->set_param(i, v);
    auto tb = std::make_unique<StreamTestbench>("tb", *top, source, setup);
    const auto t0 = std::chrono::steady_clock::now();
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();
    StreamResult r;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.frames = tb->records();
    r.interrupted = tb->interrupted();
    r.error = tb->error();
    r.modeled_end_ms = ms(sc_core::sc_time_stamp());
    return r;
}

}  // namespace imap::testbench
