#include "imap/engine/stream.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "imap/engine/error.hpp"
#include "imap/vision/calib.hpp"
#include "imap/vision/colour.hpp"
#include "imap/vision/image_io.hpp"

namespace imap::engine::stream {

namespace fs = std::filesystem;
namespace g = imap::golden;
namespace tb = imap::testbench;
namespace v = imap::vision;
using nlohmann::json;

namespace {

// Holds back the frames read while looking for the first good one (its size
// fixes the plan), then hands them out again in order.
class PeekedSource : public tb::FrameSource {
  public:
    explicit PeekedSource(std::unique_ptr<tb::FrameSource> src) : src_(std::move(src)) {}
    // The first good frame's size, or an empty size if the stream has none
    // (then first_error() tells why the first frame is bad).
    cv::Size first_good_size() {
        tb::SourceFrame f;
        while (src_->next(f)) {
            if (f.error.empty()) {
                held_.push_back(f);
                return f.left.size();
            }
            if (first_error_.empty()) first_error_ = f.name + ": " + f.error;
            f.left.release();  // a bad frame is only reported: keep no pixels
            f.right.release();
            f.gt.release();
            held_.push_back(f);
        }
        return {};
    }
    const std::string& first_error() const { return first_error_; }
    bool next(tb::SourceFrame& f) override {
        if (!held_.empty()) {
            f = held_.front();
            held_.pop_front();
            return true;
        }
        return src_->next(f);
    }
    int count() const override { return src_->count(); }
    std::string describe() const override { return src_->describe(); }

  private:
    std::unique_ptr<tb::FrameSource> src_;
    std::deque<tb::SourceFrame> held_;
    std::string first_error_;
};

class Limited : public tb::FrameSource {
  public:
    Limited(std::unique_ptr<tb::FrameSource> src, int n) : src_(std::move(src)), n_(n) {}
    bool next(tb::SourceFrame& f) override { return k_ < n_ && src_->next(f) && ++k_ > 0; }
    int count() const override {
        const int c = src_->count();
        return c < 0 ? n_ : std::min(c, n_);
    }
    std::string describe() const override { return src_->describe(); }

  private:
    std::unique_ptr<tb::FrameSource> src_;
    int n_, k_ = 0;
};

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
}

}  // namespace

OpenedSource open_source(const SourceSpec& s) {
    OpenedSource o;
    std::unique_ptr<tb::FrameSource> source;
    if (!s.frames_dir.empty())
        source = tb::open_folder(s.frames_dir);
    else if (!s.left_video.empty())
        source = tb::open_videos(s.left_video, s.right_video);
    else
        source = tb::open_synthetic(s.seed, s.width, s.height, s.synthetic);
    o.calib_note = "none (frames taken as rectified)";
    if (!s.calib.empty()) {
        const v::StereoCalib c = v::load_stereo_calib(s.calib);
        o.size = c.size;
        source = tb::rectified(std::move(source), c);
        o.calib_note = s.calib;
    }
    if (s.max_frames > 0) source = std::make_unique<Limited>(std::move(source), s.max_frames);
    // A stream without a single usable frame (unreadable files, or frames
    // that do not match the calibration's image size) is an input error
    // before any simulation, naming the first problem.
    auto peeked = std::make_unique<PeekedSource>(std::move(source));
    const cv::Size first = peeked->first_good_size();
    if (first.empty())
        throw Error("the stream holds no usable frame (" + peeked->describe() +
                    "): every frame is unreadable or bad; the first: " + peeked->first_error());
    if (o.size.empty()) o.size = first;
    o.source = tb::size_checked(std::move(peeked), o.size);
    return o;
}

json record_json(const tb::FrameRecord& r) {
    json j = {{"index", r.index},
              {"name", r.name},
              {"status", r.status},
              {"error", r.error},
              {"cycles", r.cycles},
              {"compute_ms", r.compute_ms},
              {"stall_ms", r.stall_ms},
              {"capture_ms", r.capture_ms},
              {"start_ms", r.start_ms},
              {"done_ms", r.done_ms},
              {"latency_ms", r.latency_ms},
              {"deadline_met", r.deadline_met},
              {"differing_pixels", r.differing},
              {"wall_s", r.wall_s},
              {"model_wall_s", r.model_wall_s},
              {"golden_wall_s", r.golden_wall_s}};
    j["bad1_percent"] = r.bad1 >= 0 ? json(r.bad1) : json(nullptr);
    json ph = json::object();
    for (const auto& [name, c] : r.phases) ph[name] = c;
    j["phases"] = ph;
    return j;
}

std::string records_csv(const std::vector<tb::FrameRecord>& rs) {
    std::ostringstream o;
    o << "index,name,status,cycles,compute_ms,stall_ms,capture_ms,start_ms,done_ms,latency_ms,"
         "deadline_met,differing_pixels,bad1_percent,wall_s,error\n";
    char b[512];
    for (const auto& r : rs) {
        std::snprintf(b, sizeof b, "%d,%s,%s,%llu,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%d,%zu,", r.index,
                      csv_field(r.name).c_str(), r.status.c_str(),
                      static_cast<unsigned long long>(r.cycles), r.compute_ms, r.stall_ms,
                      r.capture_ms, r.start_ms, r.done_ms, r.latency_ms, r.deadline_met ? 1 : 0,
                      r.differing);
        o << b;
        if (r.bad1 >= 0) {
            std::snprintf(b, sizeof b, "%.4f", r.bad1);
            o << b;
        }
        std::snprintf(b, sizeof b, ",%.6f,", r.wall_s);
        o << b << csv_field(r.error) << "\n";
    }
    return o.str();
}

Summary summarize(const std::vector<tb::FrameRecord>& rs, double camera_fps) {
    Summary s;
    s.frames = rs.size();
    double first_done = -1, last_done = 0;
    for (const auto& r : rs) {
        if (r.status == "ok") ++s.ok;
        if (r.status == "mismatch") ++s.mismatch;
        if (r.status == "bad-frame") ++s.bad;
        if (r.status == "fault") ++s.fault;
        if (r.status == "bad-frame") continue;
        ++s.ran;
        s.missed += !r.deadline_met;
        s.worst_latency = std::max(s.worst_latency, r.latency_ms);
        s.mean_latency += r.latency_ms;
        s.mean_compute += r.compute_ms;
        if (first_done < 0) first_done = r.done_ms;
        last_done = r.done_ms;
    }
    if (s.ran) {
        s.mean_latency /= static_cast<double>(s.ran);
        s.mean_compute /= static_cast<double>(s.ran);
        if (s.ran > 1 && last_done > first_done)
            s.throughput_fps = 1000.0 * static_cast<double>(s.ran - 1) / (last_done - first_done);
        if (camera_fps > 0) s.throughput_fps = std::min(s.throughput_fps, camera_fps);
        if (s.mean_compute > 0) s.capacity_fps = 1000.0 / s.mean_compute;
    }
    return s;
}

json log_json(const json& head, const std::vector<tb::FrameRecord>& rs, const std::string& state) {
    const double fps = head.contains("timing") && head["timing"].contains("fps")
                           ? head["timing"]["fps"].get<double>()
                           : 0.0;
    const Summary s = summarize(rs, fps);
    json j = head;
    j["state"] = state;  // running, complete, interrupted, stopped-by-error
    j["frames"] = json::array();
    for (const auto& r : rs) j["frames"].push_back(record_json(r));
    j["summary"] = {{"frames", s.frames},
                    {"ok", s.ok},
                    {"mismatch", s.mismatch},
                    {"bad_frames", s.bad},
                    {"faults", s.fault},
                    {"missed_deadlines", s.missed},
                    {"worst_latency_ms", s.worst_latency},
                    {"mean_latency_ms", s.mean_latency},
                    {"mean_compute_ms", s.mean_compute},
                    {"modeled_fps", s.throughput_fps},
                    {"capacity_fps", s.capacity_fps}};
    return j;
}

std::string frame_line(const tb::FrameRecord& r) {
    char line[512];
    if (r.status == "bad-frame") {
        std::snprintf(line, sizeof line, "frame %d %s: BAD FRAME: %s", r.index, r.name.c_str(),
                      r.error.c_str());
    } else if (r.status == "fault") {
        std::snprintf(line, sizeof line, "frame %d %s: MACHINE FAULT: %s", r.index, r.name.c_str(),
                      r.error.c_str());
    } else {
        char acc[48] = "";
        if (r.bad1 >= 0) std::snprintf(acc, sizeof acc, ", bad-1 %.2f%%", r.bad1);
        std::snprintf(line, sizeof line,
                      "frame %d %s: %s, %llu cycles = %.3f ms, stall %.3f ms, "
                      "latency %.3f ms %s%s",
                      r.index, r.name.c_str(),
                      r.status == "ok" ? "bit-exact" : "MISMATCH vs golden",
                      static_cast<unsigned long long>(r.cycles), r.compute_ms, r.stall_ms,
                      r.latency_ms, r.deadline_met ? "(deadline met)" : "(DEADLINE MISSED)", acc);
    }
    return line;
}

SideBySide::SideBySide(const std::string& path, double fps, const g::Roi& roi, int D)
    : path_(path), roi_(roi), D_(D) {
    const fs::path p(path);
    tmp_ = (p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                               p.extension().string()))
               .string();
    legend_ = v::disparity_legend(roi.w, D);
    const bool ok = w_.open(tmp_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps,
                            cv::Size(2 * roi.w, roi.h + legend_.rows), true);
    if (!ok) {
        std::remove(tmp_.c_str());
        throw Error("--video '" + path +
                    "': cannot write a video there (folder missing or not writable, or no "
                    "encoder: use an .avi name)");
    }
}

SideBySide::~SideBySide() {
    if (!done_) {
        w_.release();
        std::remove(tmp_.c_str());
    }
}

void SideBySide::add(const cv::Mat& left, const cv::Mat& disp) {
    cv::Mat frame(roi_.h + legend_.rows, 2 * roi_.w, CV_8UC3, cv::Scalar(0, 0, 0));
    cv::cvtColor(left(cv::Rect(roi_.x0, roi_.y0, roi_.w, roi_.h)),
                 frame(cv::Rect(0, 0, roi_.w, roi_.h)), cv::COLOR_GRAY2BGR);
    // The colours of the disparity PNGs' colour maps (occluded: white), with
    // the legend under the map (docs/stream.md).
    v::colorize_disparity(disp, D_).copyTo(frame(cv::Rect(roi_.w, 0, roi_.w, roi_.h)));
    legend_.copyTo(frame(cv::Rect(roi_.w, roi_.h, roi_.w, legend_.rows)));
    w_.write(frame);
    ++frames_;
}

int SideBySide::finish() {
    w_.release();
    std::error_code ec;
    fs::rename(tmp_, path_, ec);
    if (ec) {
        std::remove(tmp_.c_str());
        throw Error("--video '" + path_ + "': cannot rename into place (" + ec.message() + ")");
    }
    done_ = true;
    return frames_;
}

int Outcome::exit_code(bool fail_on_deadline) const {
    if (result.interrupted) return kExitInterrupted;
    if (summary.mismatch) return kExitMismatch;
    if (summary.bad || summary.fault) return kExitItemErrors;
    if (fail_on_deadline && summary.missed) return kExitItemErrors;
    return kExitOk;
}

Outcome run(tb::FrameSource& source, tb::StreamSetup setup, const Outputs& out, const json& head,
            Hooks& hooks) {
    Outcome o;
    std::unique_ptr<SideBySide> video;
    if (!out.video.empty())
        video =
            std::make_unique<SideBySide>(out.video, setup.timing.fps, setup.roi, setup.params.D);
    auto write_logs = [&](const char* state) {
        if (out.json_path.empty() && out.csv_path.empty()) return;
        if (!out.json_path.empty())
            v::write_text_atomic(out.json_path, log_json(head, o.records, state).dump(2) + "\n");
        if (!out.csv_path.empty()) v::write_text_atomic(out.csv_path, records_csv(o.records));
    };
    write_logs("running");  // fails early on an unwritable log path

    auto last_log = std::chrono::steady_clock::now();
    setup.stop_requested = hooks.stop_requested;
    setup.on_frame = [&](const tb::FrameOutput& f) {
        const tb::FrameRecord& r = f.record;
        o.records.push_back(r);
        if (!f.disparity.empty()) {
            if (!out.out_dir.empty()) {
                char name[32];
                std::snprintf(name, sizeof name, "disp_%04d.png", r.index);
                v::write_image_atomic((fs::path(out.out_dir) / name).string(), f.disparity);
                if (out.out_color) {
                    std::snprintf(name, sizeof name, "disp_%04d_color.png", r.index);
                    v::write_image_atomic((fs::path(out.out_dir) / name).string(),
                                          v::colorize_disparity(f.disparity, setup.params.D));
                }
            }
            if (video) video->add(f.left, f.disparity);
        }
        hooks.frame(frame_line(r));
        const auto now = std::chrono::steady_clock::now();
        if (now - last_log > std::chrono::seconds(1)) {
            write_logs("running");
            last_log = now;
        }
    };
    o.result = tb::run_stream(source, setup);
    o.state = o.result.error         ? "stopped-by-error"
              : o.result.interrupted ? "interrupted"
                                     : "complete";
    write_logs(o.state.c_str());
    if (video) o.video_frames = video->finish();
    o.summary = summarize(o.records, setup.timing.fps);
    return o;
}

}  // namespace imap::engine::stream
