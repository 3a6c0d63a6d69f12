// imapsim stream: the streaming testbench (docs/stream.md). Frames from a
// folder of numbered pairs, two video files or the built-in synthetic
// sequence, optionally rectified with a calibration file, stream line by line
// into the TLM model at camera timing; every disparity map is checked against
// the golden. Per-frame log (JSON + CSV), disparity PNGs, a side-by-side video.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "cli_common.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/testbench/frame_source.hpp"
#include "imap/testbench/stream.hpp"
#include "imap/vision/calib.hpp"
#include "imap/vision/colour.hpp"
#include "imap/vision/image_io.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"
#include "progress.hpp"

namespace imapsim {

namespace fs = std::filesystem;
namespace g = imap::golden;
namespace v = imap::vision;
namespace fw = imap::firmware;
namespace tb = imap::testbench;
using nlohmann::json;

namespace {

struct StreamOptions {
    std::string frames_dir, left_video, right_video, synthetic, calib;
    std::string fps = "25", deadline_ms, line_us;
    std::string out_dir, video, json_log, csv_log, max_frames;
    std::string seed = "1", size = "128x128";
    std::string quantum_ns;
    AlgoFlags algo;
    MachineFlags machine;
};

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

void parse_size(const std::string& text, int* w, int* h) {
    const auto x = text.find('x');
    if (x == std::string::npos)
        throw UserError("invalid value '" + text + "' for --size: expected WxH (16..4096 each)");
    *w = static_cast<int>(parse_int_flag("--size width", text.substr(0, x), 16, 4096));
    *h = static_cast<int>(parse_int_flag("--size height", text.substr(x + 1), 16, 4096));
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

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
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

struct Summary {
    size_t frames = 0, ok = 0, mismatch = 0, bad = 0, fault = 0, ran = 0, missed = 0;
    double worst_latency = 0, mean_latency = 0, mean_compute = 0;
    double throughput_fps = 0;  // frames finished per modeled second, first to last
    double capacity_fps = 0;    // 1 / mean compute time: the rate if frames were waiting
};

Summary summarize(const std::vector<tb::FrameRecord>& rs) {
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
        if (s.mean_compute > 0) s.capacity_fps = 1000.0 / s.mean_compute;
    }
    return s;
}

// The side-by-side video (left ROI | colour-mapped disparity), written to a
// temporary file that is renamed into place when the stream ends.
class SideBySide {
  public:
    SideBySide(const std::string& path, double fps, const g::Roi& roi, int D)
        : path_(path), roi_(roi), D_(D) {
        const fs::path p(path);
        tmp_ = (p.parent_path() / ("." + p.filename().string() + ".tmp-" +
                                   std::to_string(::getpid()) + p.extension().string()))
                   .string();
        legend_ = v::disparity_legend(roi.w, D);
        const bool ok = w_.open(tmp_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps,
                                cv::Size(2 * roi.w, roi.h + legend_.rows), true);
        if (!ok) {
            std::remove(tmp_.c_str());
            throw UserError("--video '" + path +
                            "': cannot write a video there (folder missing or not writable, or "
                            "no encoder: use an .avi name)");
        }
    }
    ~SideBySide() {
        if (!done_) {
            w_.release();
            std::remove(tmp_.c_str());
        }
    }
    void add(const cv::Mat& left, const cv::Mat& disp) {
        cv::Mat frame(roi_.h + legend_.rows, 2 * roi_.w, CV_8UC3, cv::Scalar(0, 0, 0));
        cv::cvtColor(left(cv::Rect(roi_.x0, roi_.y0, roi_.w, roi_.h)),
                     frame(cv::Rect(0, 0, roi_.w, roi_.h)), cv::COLOR_GRAY2BGR);
        // The colours of the disparity PNGs' colour maps (occluded: white),
        // with the legend under the map (docs/stream.md).
        v::colorize_disparity(disp, D_).copyTo(frame(cv::Rect(roi_.w, 0, roi_.w, roi_.h)));
        legend_.copyTo(frame(cv::Rect(roi_.w, roi_.h, roi_.w, legend_.rows)));
        w_.write(frame);
        ++frames_;
    }
    // Closes the file and renames it into place; returns the frames written.
    int finish() {
        w_.release();
        std::error_code ec;
        fs::rename(tmp_, path_, ec);
        if (ec) {
            std::remove(tmp_.c_str());
            throw UserError("--video '" + path_ + "': cannot rename into place (" + ec.message() +
                            ")");
        }
        done_ = true;
        return frames_;
    }

  private:
    std::string path_, tmp_;
    g::Roi roi_;
    int D_;
    cv::VideoWriter w_;
    cv::Mat legend_;
    int frames_ = 0;
    bool done_ = false;
};

}  // namespace

Subcommand register_stream(CLI::App& app) {
    auto o = std::make_shared<StreamOptions>();
    CLI::App* sub = app.add_subcommand(
        "stream",
        "Stream a sequence of stereo frames through the TLM model at camera timing, checking every "
        "disparity map against the golden (docs/stream.md)");
    const char* src = "Source (one of)";
    sub->add_option("--frames", o->frames_dir,
                    "folder of numbered pairs (left_0001.png + right_0001.png, or left/ and "
                    "right/ subfolders); gt_0001.png beside them is used as ground truth")
        ->group(src);
    sub->add_option("--left-video", o->left_video, "left camera video file")->group(src);
    sub->add_option("--right-video", o->right_video, "right camera video file")->group(src);
    sub->add_option("--synthetic", o->synthetic,
                    "N frames of the built-in synthetic sequence (--seed, --size)")
        ->group(src);
    sub->add_option("--seed", o->seed, "synthetic sequence seed")->capture_default_str();
    sub->add_option("--size", o->size, "synthetic frame size WxH")->capture_default_str();
    sub->add_option("--calib", o->calib,
                    "stereo calibration (OpenCV YAML/XML, docs/calibration.md): rectify every "
                    "frame first; without it frames are taken as rectified");
    sub->add_option("--max-frames", o->max_frames, "stop after N frames");
    const char* tim = "Timing";
    sub->add_option("--fps", o->fps, "camera frame rate; frame k starts at k/fps")
        ->capture_default_str()
        ->group(tim);
    sub->add_option("--deadline-ms", o->deadline_ms,
                    "latency budget per frame, capture start to last output line [default: the "
                    "frame period]")
        ->group(tim);
    sub->add_option("--line-us", o->line_us,
                    "camera line period [default: 64 (PAL), less if a frame would not fit in the "
                    "frame period]")
        ->group(tim);
    sub->add_option("--quantum-ns", o->quantum_ns, "TLM global quantum [default: 10000]")
        ->group(tim);
    const char* out = "Outputs";
    sub->add_option("--out-dir", o->out_dir,
                    "write disp_NNNN.png per frame and the logs stream.json / stream.csv here")
        ->group(out);
    sub->add_option("--video", o->video, "write a side-by-side video (left | disparity), .avi")
        ->group(out);
    sub->add_option("--json", o->json_log, "per-frame log as JSON [default: OUT-DIR/stream.json]")
        ->group(out);
    sub->add_option("--csv", o->csv_log, "per-frame log as CSV [default: OUT-DIR/stream.csv]")
        ->group(out);
    add_algo_flags(sub, o->algo);
    add_machine_flags(sub, o->machine);

    return {
        sub, [o]() {
            // ---- flags -------------------------------------------------
            const int nsrc = !o->frames_dir.empty() + !o->synthetic.empty() +
                             (!o->left_video.empty() || !o->right_video.empty());
            if (nsrc != 1)
                throw UserError(
                    "give exactly one source: --frames DIR, --left-video L --right-video R, "
                    "or --synthetic N");
            if (o->left_video.empty() != o->right_video.empty())
                throw UserError("--left-video and --right-video must be given together");
            g::Roi roi;
            bool has_roi = false;
            const g::Params p = parse_algo_flags(o->algo, &roi, &has_roi);
            const imap::isa::MachineConfig cfg = parse_machine_flags(o->machine);
            tb::StreamTiming timing;
            timing.fps = parse_real_flag("--fps", o->fps, 0, 100000, true);
            if (!o->deadline_ms.empty())
                timing.deadline_ms = parse_real_flag("--deadline-ms", o->deadline_ms, 0, 1e9, true);
            if (!o->line_us.empty())
                timing.line_us = parse_real_flag("--line-us", o->line_us, 0, 1e9, true);
            imap::tlm::TlmConfig tcfg;
            if (!o->quantum_ns.empty())
                tcfg.quantum_ns = parse_real_flag("--quantum-ns", o->quantum_ns, 0, 1e9, true);
            const int max_frames = o->max_frames.empty()
                                       ? 0
                                       : static_cast<int>(parse_int_flag(
                                             "--max-frames", o->max_frames, 1, 1000000000));
            // The side-by-side video is Motion-JPEG in an AVI container; any
            // other name would get a file of the wrong type (OpenCV picks the
            // container from the name, e.g. one JPEG frame for ".png").
            if (!o->video.empty()) {
                if (lower_extension(o->video) != ".avi")
                    throw UserError("--video '" + o->video +
                                    "': the side-by-side video is Motion-JPEG in AVI: use a "
                                    "name ending in .avi");
            }
            // Every output path can be written, before any work (the logs
            // are first written a second into the stream).
            check_output_dir("--out-dir", o->out_dir);
            // A file inside --out-dir: its folder is created with it, and
            // checked above.
            auto check_file = [&](const char* flag, const std::string& path) {
                if (file_in_folder(path, o->out_dir)) return;
                check_output_file(flag, path, false);
            };
            check_file("--json", o->json_log);
            check_file("--csv", o->csv_log);
            check_file("--video", o->video);
            std::string json_path = o->json_log, csv_path = o->csv_log;
            if (!o->out_dir.empty()) {
                if (json_path.empty()) json_path = (fs::path(o->out_dir) / "stream.json").string();
                if (csv_path.empty()) csv_path = (fs::path(o->out_dir) / "stream.csv").string();
            }

            // ---- source ------------------------------------------------
            std::unique_ptr<tb::FrameSource> source;
            if (!o->frames_dir.empty()) {
                source = tb::open_folder(o->frames_dir);
            } else if (!o->left_video.empty()) {
                source = tb::open_videos(o->left_video, o->right_video);
            } else {
                const int n =
                    static_cast<int>(parse_int_flag("--synthetic", o->synthetic, 1, 1000000));
                int w = 0, h = 0;
                parse_size(o->size, &w, &h);
                const long long seed = parse_int_flag("--seed", o->seed, 0, INT64_MAX);
                source = tb::open_synthetic(static_cast<uint64_t>(seed), w, h, n);
            }
            cv::Size size;
            std::string calib_note = "none (frames taken as rectified)";
            if (!o->calib.empty()) {
                const v::StereoCalib c = v::load_stereo_calib(o->calib);
                size = c.size;
                source = tb::rectified(std::move(source), c);
                calib_note = o->calib;
            }
            if (max_frames > 0) source = std::make_unique<Limited>(std::move(source), max_frames);
            // A stream without a single usable frame (unreadable files, or
            // frames that do not match the calibration's image size) is an
            // input error before any simulation, naming the first problem.
            auto peeked = std::make_unique<PeekedSource>(std::move(source));
            const cv::Size first = peeked->first_good_size();
            if (first.empty())
                throw UserError(
                    "the stream holds no usable frame (" + peeked->describe() +
                    "): every frame is unreadable or bad; the first: " + peeked->first_error());
            if (size.empty()) size = first;
            source = tb::size_checked(std::move(peeked), size);
            if (!has_roi) roi = {0, 0, size.width, size.height};
            try {
                g::validate(p, roi, size.width, size.height);
                timing.resolve(size.height);
            } catch (const g::ParamError& e) {
                throw UserError(e.what());
            } catch (const std::invalid_argument& e) {
                throw UserError(e.what());
            }

            // ---- firmware ----------------------------------------------
            tb::StreamSetup setup;
            setup.params = p;
            setup.roi = roi;
            setup.size = size;
            try {
                setup.plan = fw::plan_frame(p, roi, cfg);
            } catch (const fw::FirmwareError& e) {
                throw UserError(e.what());
            }
            setup.program = fw::assemble_frame(p, setup.plan);
            setup.machine = cfg;
            setup.tlm = tcfg;
            setup.timing = timing;

            std::printf("imapsim stream: %s\n", source->describe().c_str());
            std::printf("  calibration: %s\n", calib_note.c_str());
            std::printf("  frames %dx%d, ROI %d,%d,%dx%d, D=%d, %s, vote %s, frame %s\n",
                        size.width, size.height, roi.x0, roi.y0, roi.w, roi.h, p.D,
                        g::to_string(p.mode), p.vote ? "on" : "off", g::to_string(p.frame));
            std::printf(
                "  machine: %d PEs at %g MHz, %u B local + %u B external per PE; "
                "TLM model\n",
                cfg.pes, cfg.clock_mhz, cfg.mem_bytes, cfg.ext_bytes);
            std::printf(
                "  camera: %g fps (frame every %.3f ms), line every %g us; deadline "
                "%.3f ms\n",
                timing.fps, timing.frame_ms(), timing.line_us, timing.deadline_ms);
            std::fflush(stdout);

            // ---- outputs (nothing is created before this point) ---------
            if (!o->out_dir.empty()) create_output_dir("--out-dir", o->out_dir);
            std::unique_ptr<SideBySide> video;
            if (!o->video.empty())
                video = std::make_unique<SideBySide>(o->video, timing.fps, roi, p.D);
            std::vector<tb::FrameRecord> done;
            json head = {{"source", source->describe()},
                         {"calibration", o->calib},
                         {"size", {size.width, size.height}},
                         {"roi", {roi.x0, roi.y0, roi.w, roi.h}},
                         {"params", algo_params_json(p)},
                         {"machine",
                          {{"pes", cfg.pes},
                           {"clock_mhz", cfg.clock_mhz},
                           {"mem_bytes", cfg.mem_bytes},
                           {"ext_bytes", cfg.ext_bytes}}},
                         {"timing",
                          {{"fps", timing.fps},
                           {"frame_ms", timing.frame_ms()},
                           {"line_us", timing.line_us},
                           {"deadline_ms", timing.deadline_ms}}},
                         {"model", "tlm"}};
            auto write_logs = [&](const char* state) {
                if (json_path.empty() && csv_path.empty()) return;
                const Summary s = summarize(done);
                json j = head;
                j["state"] = state;  // running, complete, interrupted, stopped-by-error
                j["frames"] = json::array();
                for (const auto& r : done) j["frames"].push_back(record_json(r));
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
                if (!json_path.empty()) v::write_text_atomic(json_path, j.dump(2) + "\n");
                if (!csv_path.empty()) v::write_text_atomic(csv_path, records_csv(done));
            };
            write_logs("running");  // fails early on an unwritable log path

            Progress progress("frames", static_cast<size_t>(std::max(source->count(), 0)));
            auto last_log = std::chrono::steady_clock::now();
            setup.stop_requested = [] { return interrupt::requested(); };
            setup.on_frame = [&](const tb::FrameOutput& f) {
                const tb::FrameRecord& r = f.record;
                done.push_back(r);
                char line[512];
                if (r.status == "bad-frame") {
                    std::snprintf(line, sizeof line, "frame %d %s: BAD FRAME: %s", r.index,
                                  r.name.c_str(), r.error.c_str());
                } else if (r.status == "fault") {
                    std::snprintf(line, sizeof line, "frame %d %s: MACHINE FAULT: %s", r.index,
                                  r.name.c_str(), r.error.c_str());
                } else {
                    char acc[48] = "";
                    if (r.bad1 >= 0) std::snprintf(acc, sizeof acc, ", bad-1 %.2f%%", r.bad1);
                    std::snprintf(line, sizeof line,
                                  "frame %d %s: %s, %llu cycles = %.3f ms, stall %.3f ms, "
                                  "latency %.3f ms %s%s",
                                  r.index, r.name.c_str(),
                                  r.status == "ok" ? "bit-exact" : "MISMATCH vs golden",
                                  static_cast<unsigned long long>(r.cycles), r.compute_ms,
                                  r.stall_ms, r.latency_ms,
                                  r.deadline_met ? "(deadline met)" : "(DEADLINE MISSED)", acc);
                }
                if (!f.disparity.empty()) {
                    if (!o->out_dir.empty()) {
                        char name[32];
                        std::snprintf(name, sizeof name, "disp_%04d.png", r.index);
                        v::write_image_atomic((fs::path(o->out_dir) / name).string(), f.disparity);
                    }
                    if (video) video->add(f.left, f.disparity);
                }
                progress.step(line);
                const auto now = std::chrono::steady_clock::now();
                if (now - last_log > std::chrono::seconds(1)) {
                    write_logs("running");
                    last_log = now;
                }
            };

            interrupt::install();
            const tb::StreamResult res = tb::run_stream(*source, setup);
            progress.finish();
            const char* state = res.error         ? "stopped-by-error"
                                : res.interrupted ? "interrupted"
                                                  : "complete";
            write_logs(state);
            int video_frames = 0;
            if (video) video_frames = video->finish();

            // ---- summary -----------------------------------------------
            const Summary s = summarize(done);
            std::printf(
                "summary: %zu frame%s: %zu bit-exact, %zu mismatch, %zu bad, %zu "
                "fault%s\n",
                s.frames, s.frames == 1 ? "" : "s", s.ok, s.mismatch, s.bad, s.fault,
                res.interrupted ? " (interrupted)" : "");
            if (s.ran) {
                std::printf(
                    "  deadline %.3f ms: %zu missed of %zu; latency worst %.3f ms, "
                    "mean %.3f ms; compute mean %.3f ms\n",
                    timing.deadline_ms, s.missed, s.ran, s.worst_latency, s.mean_latency,
                    s.mean_compute);
                std::printf(
                    "  modeled throughput %.2f frames/s (camera %g fps); compute-bound "
                    "capacity %.2f frames/s\n",
                    s.throughput_fps, timing.fps, s.capacity_fps);
            }
            std::printf("  simulation: %.3f s wall, %.2f frames/s, modeled/wall = %.3f\n",
                        res.wall_s,
                        res.wall_s > 0 ? static_cast<double>(s.frames) / res.wall_s : 0.0,
                        res.wall_s > 0 ? res.modeled_end_ms / 1e3 / res.wall_s : 0.0);
            if (!json_path.empty()) std::printf("  log -> %s\n", json_path.c_str());
            if (!csv_path.empty()) std::printf("  log -> %s\n", csv_path.c_str());
            if (!o->out_dir.empty())
                std::printf("  disparity maps -> %s/disp_NNNN.png\n", o->out_dir.c_str());
            if (video) std::printf("  video (%d frames) -> %s\n", video_frames, o->video.c_str());
            if (res.error) std::rethrow_exception(res.error);
            if (res.interrupted) return static_cast<int>(kExitInterrupted);
            if (s.mismatch) return static_cast<int>(kExitMismatch);
            if (s.bad || s.fault) return static_cast<int>(kExitItemErrors);
            return static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
