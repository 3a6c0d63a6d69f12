// imapsim stream: the streaming testbench (docs/stream.md). Frames from a
// folder of numbered pairs, two video files or the built-in synthetic
// sequence, optionally rectified with a calibration file, stream line by line
// into the TLM model at camera timing; every disparity map is checked against
// the golden. Per-frame log (JSON + CSV), disparity PNGs, a side-by-side video.
// The engine (source, outputs, logs) is imap/engine/stream.hpp; this file
// parses the flags, plans the firmware and prints.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli_common.hpp"
#include "imap/engine/stream.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/testbench/frame_source.hpp"
#include "imap/testbench/stream.hpp"
#include "imap/vision/calib.hpp"
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
namespace es = imap::engine::stream;
using nlohmann::json;

namespace {

struct StreamOptions {
    std::string frames_dir, left_video, right_video, synthetic, calib;
    std::string fps = "25", deadline_ms, line_us;
    std::string out_dir, video, json_log, csv_log, max_frames;
    std::string seed = "1", size = "128x128";
    std::string quantum_ns;
    bool out_color = false, fail_on_deadline = false;
    AlgoFlags algo;
    MachineFlags machine;
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
            imap::isa::MachineConfig cfg = parse_machine_flags(o->machine);
            // The stream's testbench is the camera: a timed camera sets its
            // line period, and the machine's vin does not wait again.
            const imap::isa::BoardTiming camera = cfg.board;
            cfg.board.camera_pixel_mhz = 0;
            if (camera.camera_timed() && !o->line_us.empty())
                throw UserError(
                    "--line-us and a timed camera (--camera, camera_pixel_mhz) both "
                    "set the line period: give one");
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
            if (o->out_color && o->out_dir.empty())
                throw UserError("--out-color needs --out-dir (the maps are written there)");
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
            es::SourceSpec spec;
            spec.frames_dir = o->frames_dir;
            spec.left_video = o->left_video;
            spec.right_video = o->right_video;
            spec.calib = o->calib;
            spec.max_frames = max_frames;
            if (o->frames_dir.empty() && o->left_video.empty()) {
                spec.synthetic =
                    static_cast<int>(parse_int_flag("--synthetic", o->synthetic, 1, 1000000));
                parse_size_flag("--size", o->size, 16, 4096, &spec.width, &spec.height);
                spec.seed = static_cast<uint64_t>(parse_int_flag("--seed", o->seed, 0, INT64_MAX));
            }
            es::OpenedSource opened = es::open_source(spec);
            std::unique_ptr<tb::FrameSource>& source = opened.source;
            const cv::Size size = opened.size;
            const std::string& calib_note = opened.calib_note;
            if (!has_roi) roi = {0, 0, size.width, size.height};
            try {
                g::validate(p, roi, size.width, size.height);
                if (camera.camera_timed())
                    timing.line_us =
                        (size.width + camera.camera_hblank_px) / camera.camera_pixel_mhz;
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
            const json head = {{"source", source->describe()},
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
            const es::Outputs outputs{o->out_dir, o->video, json_path, csv_path, o->out_color};
            Progress progress("frames", static_cast<size_t>(std::max(source->count(), 0)));
            es::Hooks hooks;
            hooks.stop_requested = [] { return interrupt::requested(); };
            hooks.frame = [&](const std::string& line) { progress.step(line); };
            interrupt::install();
            const es::Outcome run = es::run(*source, setup, outputs, head, hooks);
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
