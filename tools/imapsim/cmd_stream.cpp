// imapsim stream: the streaming testbench (docs/stream.md). Frames from a
// folder of numbered pairs, two video files or the built-in synthetic
// sequence, optionally rectified with a calibration file, stream line by line
// into the TLM model at camera timing; every disparity map is checked against
// the golden. Per-frame log (JSON + CSV), disparity PNGs, a side-by-side video.
// The engine (source, outputs, logs) is imap/engine/stream.hpp, the checks
// of the flags and the planned firmware stream_request.hpp's; this file
// gathers the flags and prints.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/engine/stream.hpp"
#include "imap/engine/stream_request.hpp"
#include "imap/testbench/frame_source.hpp"
#include "imap/testbench/stream.hpp"
#include "imap/vision/image_io.hpp"
#include "interrupt.hpp"
#include "model_runner.hpp"
#include "progress.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace tb = imap::testbench;
namespace es = imap::engine::stream;

using StreamOptions = es::Request;

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
    sub->add_flag("--fail-on-deadline", o->fail_on_deadline,
                  "exit 5 when a frame misses its deadline (the stream still runs to the end)")
        ->group(tim);
    sub->add_option("--quantum-ns", o->quantum_ns, "TLM global quantum [default: 10000]")
        ->group(tim);
    const char* out = "Outputs";
    sub->add_option("--out-dir", o->out_dir,
                    "write disp_NNNN.png per frame and the logs stream.json / stream.csv here")
        ->group(out);
    sub->add_flag("--out-color", o->out_color,
                  "with --out-dir: also disp_NNNN_color.png per frame, colour-mapped (occluded: "
                  "white), as run --out-color")
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
            es::Prepared pr = es::prepare(*o);
            const std::unique_ptr<tb::FrameSource>& source = pr.opened.source;
            const cv::Size size = pr.opened.size;
            const g::Params& p = pr.setup.params;
            const g::Roi& roi = pr.setup.roi;
            const imap::isa::MachineConfig& cfg = pr.setup.machine;
            const tb::StreamTiming& timing = pr.setup.timing;
            const std::string &json_path = pr.outputs.json_path, &csv_path = pr.outputs.csv_path;
            std::printf("imapsim stream: %s\n", source->describe().c_str());
            std::printf("  calibration: %s\n", pr.opened.calib_note.c_str());
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
            Progress progress("frames", static_cast<size_t>(std::max(source->count(), 0)));
            es::Hooks hooks;
            hooks.stop_requested = [] { return interrupt::requested(); };
            hooks.frame = [&](const std::string& line) { progress.step(line); };
            interrupt::install();
            const es::Outcome run =
                es::run(*source, pr.setup, pr.outputs, es::log_head(*o, pr), hooks);
            progress.finish();
            const tb::StreamResult& res = run.result;
            const int video_frames = run.video_frames;

            // ---- summary -----------------------------------------------
            const es::Summary& s = run.summary;
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
                    "  modeled throughput %.2f frames/s (camera %g fps: at most that); "
                    "compute-bound capacity %.2f frames/s\n",
                    s.throughput_fps, timing.fps, s.capacity_fps);
                if (s.missed && !o->fail_on_deadline)
                    std::printf(
                        "  note: %zu frame%s missed the deadline; --fail-on-deadline makes that "
                        "exit 5\n",
                        s.missed, s.missed == 1 ? "" : "s");
            }
            std::printf("  simulation: %.3f s wall, %.2f frames/s, modeled/wall = %.3f\n",
                        res.wall_s,
                        res.wall_s > 0 ? static_cast<double>(s.frames) / res.wall_s : 0.0,
                        res.wall_s > 0 ? res.modeled_end_ms / 1e3 / res.wall_s : 0.0);
            if (!json_path.empty()) std::printf("  log -> %s\n", json_path.c_str());
            if (!csv_path.empty()) std::printf("  log -> %s\n", csv_path.c_str());
            if (!o->out_dir.empty())
                std::printf("  disparity maps -> %s/disp_NNNN.png%s\n", o->out_dir.c_str(),
                            o->out_color ? " (colour-mapped: disp_NNNN_color.png)" : "");
            if (!o->video.empty())
                std::printf("  video (%d frames) -> %s\n", video_frames, o->video.c_str());
            if (res.error) std::rethrow_exception(res.error);
            const int rc = run.exit_code(o->fail_on_deadline);
            if (rc == kExitItemErrors && o->fail_on_deadline && s.missed)
                std::fprintf(stderr,
                             "imapsim: error: %zu of %zu frames missed the %.3f ms deadline "
                             "(--fail-on-deadline)\n",
                             s.missed, s.ran, timing.deadline_ms);
            return rc;
        }};
}

}  // namespace imapsim
