// The stream engine of `imapsim stream` (docs/stream.md): opening the frame
// source (folder, two videos or the synthetic sequence; rectified with a
// calibration; limited to N frames; the first good frame fixes the size),
// running it through the streaming testbench (testbench::run_stream), and
// the outputs: one disparity PNG per frame, the side-by-side video, the
// per-frame logs (JSON and CSV, rewritten while it runs) and the summary.
// The command parses the flags, plans the firmware and prints.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/testbench/frame_source.hpp"
#include "imap/testbench/stream.hpp"

namespace imap::engine::stream {

struct SourceSpec {
    std::string frames_dir;               // folder of numbered pairs
    std::string left_video, right_video;  // two video files
    int synthetic = 0;                    // frames of the synthetic sequence (0: not it)
    uint64_t seed = 1;
    int width = 128, height = 128;  // synthetic frame size
    std::string calib;              // calibration file (empty: frames taken as rectified)
    int max_frames = 0;             // 0: all
};

struct OpenedSource {
    std::unique_ptr<testbench::FrameSource> source;  // size-checked
    cv::Size size;           // the frame size (calibration's, or the first good frame's)
    std::string calib_note;  // the calibration file, or "none (...)"
};

// Opens the source. engine::Error (exit 2) when it holds no usable frame,
// naming the first problem; vision::InputError for unreadable inputs.
OpenedSource open_source(const SourceSpec& s);

struct Summary {
    size_t frames = 0, ok = 0, mismatch = 0, bad = 0, fault = 0, ran = 0, missed = 0;
    double worst_latency = 0, mean_latency = 0, mean_compute = 0;
    double throughput_fps = 0;  // frames finished per modeled second, first to last,
                                // at most the camera's rate (a stream cannot finish
                                // frames faster than they arrive)
    double capacity_fps = 0;    // 1 / mean compute time: the rate if frames were waiting
};
// `camera_fps` > 0 caps the throughput at the camera's rate (the first and
// last frames' latencies differ, so the finish times alone can exceed it).
Summary summarize(const std::vector<testbench::FrameRecord>& rs, double camera_fps = 0);

nlohmann::json record_json(const testbench::FrameRecord& r);
std::string records_csv(const std::vector<testbench::FrameRecord>& rs);
// The log's JSON: `head` (source, parameters, machine, timing: its fps caps
// the throughput as in summarize), the state
// (running, complete, interrupted, stopped-by-error), every frame, the summary.
nlohmann::json log_json(const nlohmann::json& head, const std::vector<testbench::FrameRecord>& rs,
                        const std::string& state);

// The line printed for one frame.
std::string frame_line(const testbench::FrameRecord& r);

// The side-by-side video (left ROI | colour-mapped disparity), Motion-JPEG in
// AVI, written to a temporary file that is renamed into place when the
// stream ends (removed if it does not). engine::Error when it cannot be opened.
class SideBySide {
  public:
    SideBySide(const std::string& path, double fps, const golden::Roi& roi, int D);
    ~SideBySide();
    SideBySide(const SideBySide&) = delete;
    SideBySide& operator=(const SideBySide&) = delete;
    void add(const cv::Mat& left, const cv::Mat& disp);
    int finish();  // closes and renames into place; the frames written

  private:
    std::string path_, tmp_;
    golden::Roi roi_;
    int D_;
    cv::VideoWriter w_;
    cv::Mat legend_;
    int frames_ = 0;
    bool done_ = false;
};

struct Outputs {
    std::string out_dir;    // disp_NNNN.png per frame (empty: none)
    std::string video;      // side-by-side video (empty: none)
    std::string json_path;  // logs (empty: none)
    std::string csv_path;
    bool out_color = false;  // also disp_NNNN_color.png, colour-mapped (in out_dir)
};

struct Hooks {
    std::function<bool()> stop_requested = [] { return false; };
    std::function<void(const std::string&)> frame = [](const std::string&) {};  // one per frame
};

struct Outcome {
    testbench::StreamResult result;
    std::vector<testbench::FrameRecord> records;
    Summary summary;
    std::string state;  // complete, interrupted, stopped-by-error
    int video_frames = 0;
    // 130 interrupted, 1 a mismatch, 5 a bad frame or fault (or, with
    // `fail_on_deadline`, a missed deadline), else 0 (an error of the run
    // itself is result.error, rethrown by the caller).
    int exit_code(bool fail_on_deadline = false) const;
};

// Runs the stream: opens the video (before any frame), writes the logs at
// the start, every second and at the end, a PNG and a video frame per map,
// and calls hooks.frame with each frame's line. `setup` is handed to
// testbench::run_stream as it is (its on_frame and stop_requested are set here).
Outcome run(testbench::FrameSource& source, testbench::StreamSetup setup, const Outputs& out,
            const nlohmann::json& head, Hooks& hooks);

}  // namespace imap::engine::stream
