// The streaming testbench (docs/stream.md): a SystemC module that plays a
// camera pair into the TLM model and checks every disparity map.
//
//   tb.camera   SC_THREAD: frame k starts at k / fps; its lines arrive one
//               every line_us (both cameras genlocked) into the board's
//               input frame buffer [A: unbounded, no frame is dropped]
//   tb.control  SC_THREAD: for each buffered frame, when the CP is idle:
//               Cp::start() (machine reset, program from PC 0), wait for
//               Cp::done_event(), read the map from the video output, check
//               it against the golden, record the frame
//
// The testbench is the model's video path (top.video.attach_stream): a vin of
// a line that has not arrived yet blocks the CP until it has (video stall).
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <systemc>
#include <utility>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/testbench/frame_source.hpp"
#include "imap/tlm/system.hpp"

namespace imap::testbench {

// Camera and deadline timing (named model parameters, docs/stream.md).
struct StreamTiming {
    double fps = 25.0;         // camera frame rate: frame k starts at k / fps
    double line_us = 0.0;      // camera line period; 0 = 64 us (PAL) or less if the frame
                               // would not fit in the frame period [A]
    double deadline_ms = 0.0;  // latency budget per frame; 0 = the frame period
    // Resolved values (after resolve()).
    double frame_ms() const { return 1000.0 / fps; }
    // Fills line_us and deadline_ms defaults for `height` lines; throws
    // std::invalid_argument naming the parameter when out of range.
    void resolve(int height);
};

inline constexpr double kDefaultLineUs = 64.0;  // PAL line period [A]

// What happened to one frame.
struct FrameRecord {
    int index = 0;
    std::string name;
    // "ok" (bit-exact), "mismatch" (differs from the golden), "bad-frame"
    // (could not be read / rectified / wrong size), "fault" (the machine
    // faulted: error holds its message)
    std::string status;
    std::string error;
    uint64_t cycles = 0;    // machine cycles of the program run (no stalls)
    double compute_ms = 0;  // cycles at the clock
    double stall_ms = 0;    // CP waiting for video lines
    double capture_ms = 0;  // modeled time the frame's first line started
    double start_ms = 0;    // modeled time the CP started on it
    double done_ms = 0;     // modeled time the last output line was written (halt)
    double latency_ms = 0;  // done - capture
    bool deadline_met = false;
    size_t differing = 0;  // pixels that differ from the golden
    double bad1 = -1;      // % of ROI pixels > 1 off the ground truth (if known), else -1
    double wall_s = 0;     // host time spent on this frame (model + golden + checks)
    // Of wall_s: the model (Cp::start to done: reset, the program under the
    // SystemC kernel, the camera lines that arrive meanwhile) and the one
    // golden::compute of the bit-exactness check (not the ground-truth score).
    double model_wall_s = 0;
    double golden_wall_s = 0;
    std::vector<std::pair<std::string, uint64_t>> phases;
};

// Everything the per-frame callback may want to write out.
struct FrameOutput {
    const FrameRecord& record;
    const cv::Mat& left;       // rectified left frame (empty for a bad frame)
    const cv::Mat& disparity;  // the model's map, ROI-sized CV_8UC1 (empty if none)
};

struct StreamSetup {
    golden::Params params;
    golden::Roi roi;
    cv::Size size;  // frame size (the plan is made for it)
    firmware::FramePlan plan;
    isa::Program program;
    isa::MachineConfig machine;
    tlm::TlmConfig tlm;
    StreamTiming timing;  // resolved
    // Stop taking new frames when this returns true (Ctrl-C); may be empty.
    std::function<bool()> stop_requested;
    // Called after every frame, in order (untimed host work: files, progress).
    std::function<void(const FrameOutput&)> on_frame;
};

class StreamTestbench : public sc_core::sc_module, private isa::VideoPort {
  public:
    SC_HAS_PROCESS(StreamTestbench);
    // Attaches itself as the video path of `model` (hosted CP).
    StreamTestbench(sc_core::sc_module_name name, tlm::TlmSystem& model, FrameSource& source,
                    const StreamSetup& setup);
    const char* kind() const override { return "imap::testbench::StreamTestbench"; }

    const std::vector<FrameRecord>& records() const { return records_; }
    bool interrupted() const { return interrupted_; }
    // An exception that stopped the testbench (e.g. an output file could not
    // be written); rethrown by run_stream.
    std::exception_ptr error() const { return error_; }

  private:
    struct Slot;
    void camera();
    void control();
    void read_line(int port, int y, int x0, uint8_t* dst, int n) override;
    void write_line(int port, int y, int x0, const uint8_t* src, int n) override;

    tlm::TlmSystem& model_;
    FrameSource& source_;
    const StreamSetup& setup_;
    sc_core::sc_time line_period_, frame_period_;
    std::vector<std::shared_ptr<Slot>> queue_;  // frames buffered, oldest first
    bool camera_done_ = false;
    sc_core::sc_event queued_ev_, line_ev_;
    std::shared_ptr<Slot> current_;  // frame being processed
    // The frame the camera is delivering. A member, not a local of camera():
    // when the stream stops early (Ctrl-C, an error) the camera thread stays
    // suspended and its stack is never unwound, so nothing it owns may live
    // there.
    std::shared_ptr<Slot> arriving_;
    std::vector<FrameRecord> records_;
    bool interrupted_ = false;
    std::exception_ptr error_;
};

struct StreamResult {
    std::vector<FrameRecord> frames;
    bool interrupted = false;
    double wall_s = 0;          // wall time of sc_start
    double modeled_end_ms = 0;  // modeled time at the end
    std::exception_ptr error;   // what stopped the stream early (frames so far are kept)
};

// Elaborates top (TlmSystem, hosted) + tb (StreamTestbench), runs to the end
// of the source (or a stop request) and returns the records; an exception
// of the source or the callback ends the stream and comes back in `error`.
// Once per process (SystemC elaborates once).
StreamResult run_stream(FrameSource& source, const StreamSetup& setup);

}  // namespace imap::testbench
