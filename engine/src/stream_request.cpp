// imapsim stream's request: from the flags as given (Request) to the
// testbench's setup (checked flags and output paths, the opened source, the
// planned firmware and the camera timing) and the head of the per-frame log.
#include "imap/engine/stream_request.hpp"

#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "imap/engine/error.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"

namespace imap::engine::stream {

namespace fs = std::filesystem;
namespace g = imap::golden;
namespace fw = imap::firmware;
namespace tb = imap::testbench;

namespace {

// The flags of the outputs: every path can be written, before any work (the
// logs are first written a second into the stream).
Outputs outputs_of(const Request& r) {
    // The side-by-side video is Motion-JPEG in an AVI container; any other
    // name would get a file of the wrong type (OpenCV picks the container
    // from the name, e.g. one JPEG frame for ".png").
    if (!r.video.empty() && lower_extension(r.video) != ".avi")
        throw Error("--video '" + r.video +
                    "': the side-by-side video is Motion-JPEG in AVI: use a name ending in .avi");
    if (r.out_color && r.out_dir.empty())
        throw Error("--out-color needs --out-dir (the maps are written there)");
    check_output_dir("--out-dir", r.out_dir);
    // A file inside --out-dir: its folder is created with it, and checked above.
    auto check_file = [&](const char* flag, const std::string& path) {
        if (file_in_folder(path, r.out_dir)) return;
        check_output_file(flag, path, false);
    };
    check_file("--json", r.json_log);
    check_file("--csv", r.csv_log);
    check_file("--video", r.video);
    Outputs out{r.out_dir, r.video, r.json_log, r.csv_log, r.out_color};
    if (!r.out_dir.empty()) {
        if (out.json_path.empty()) out.json_path = (fs::path(r.out_dir) / "stream.json").string();
        if (out.csv_path.empty()) out.csv_path = (fs::path(r.out_dir) / "stream.csv").string();
    }
    return out;
}

}  // namespace

Prepared prepare(const Request& r) {
    const int nsrc = !r.frames_dir.empty() + !r.synthetic.empty() +
                     (!r.left_video.empty() || !r.right_video.empty());
    if (nsrc != 1)
        throw Error(
            "give exactly one source: --frames DIR, --left-video L --right-video R, or "
            "--synthetic N");
    if (r.left_video.empty() != r.right_video.empty())
        throw Error("--left-video and --right-video must be given together");
    g::Roi roi;
    bool has_roi = false;
    const g::Params p = algo_params(r.algo, &roi, &has_roi);
    isa::MachineConfig cfg = machine_config(r.machine);
    // The stream's testbench is the camera: a timed camera sets its line
    // period, and the machine's vin does not wait again.
    const isa::BoardTiming camera = cfg.board;
    cfg.board.camera_pixel_mhz = 0;
    if (camera.camera_timed() && !r.line_us.empty())
        throw Error(
            "--line-us and a timed camera (--camera, camera_pixel_mhz) both set the line "
            "period: give one");
    tb::StreamTiming timing;
    timing.fps = parse_real_flag("--fps", r.fps, 0, 100000, true);
    if (!r.deadline_ms.empty())
        timing.deadline_ms = parse_real_flag("--deadline-ms", r.deadline_ms, 0, 1e9, true);
    if (!r.line_us.empty()) timing.line_us = parse_real_flag("--line-us", r.line_us, 0, 1e9, true);
    tlm::TlmConfig tcfg;
    if (!r.quantum_ns.empty())
        tcfg.quantum_ns = parse_real_flag("--quantum-ns", r.quantum_ns, 0, 1e9, true);
    SourceSpec spec;
    spec.max_frames =
        r.max_frames.empty()
            ? 0
            : static_cast<int>(parse_int_flag("--max-frames", r.max_frames, 1, 1000000000));
    Prepared pr;
    pr.outputs = outputs_of(r);

    spec.frames_dir = r.frames_dir;
    spec.left_video = r.left_video;
    spec.right_video = r.right_video;
    spec.calib = r.calib;
    if (r.frames_dir.empty() && r.left_video.empty()) {
        spec.synthetic = static_cast<int>(parse_int_flag("--synthetic", r.synthetic, 1, 1000000));
        parse_size_flag("--size", r.size, 16, 4096, &spec.width, &spec.height);
        spec.seed = static_cast<uint64_t>(parse_int_flag("--seed", r.seed, 0, INT64_MAX));
    }
    pr.opened = open_source(spec);
    const cv::Size size = pr.opened.size;
    if (!has_roi) roi = {0, 0, size.width, size.height};
    try {
        g::validate(p, roi, size.width, size.height);
        if (camera.camera_timed())
            timing.line_us = (size.width + camera.camera_hblank_px) / camera.camera_pixel_mhz;
        timing.resolve(size.height);
    } catch (const g::ParamError& e) {
        throw Error(e.what());
    } catch (const std::invalid_argument& e) {
        throw Error(e.what());
    }

    // The firmware.
    tb::StreamSetup& setup = pr.setup;
    setup.params = p;
    setup.roi = roi;
    setup.size = size;
    try {
        setup.plan = fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        throw Error(e.what());
    }
    setup.program = fw::assemble_frame(p, setup.plan);
    setup.machine = cfg;
    setup.tlm = tcfg;
    setup.timing = timing;
    return pr;
}

nlohmann::json log_head(const Request& r, const Prepared& pr) {
    const tb::StreamSetup& s = pr.setup;
    return {{"source", pr.opened.source->describe()},
            {"calibration", r.calib},
            {"size", {s.size.width, s.size.height}},
            {"roi", {s.roi.x0, s.roi.y0, s.roi.w, s.roi.h}},
            {"params", algo_params_json(s.params)},
            {"machine",
             {{"pes", s.machine.pes},
              {"clock_mhz", s.machine.clock_mhz},
              {"mem_bytes", s.machine.mem_bytes},
              {"ext_bytes", s.machine.ext_bytes}}},
            {"timing",
             {{"fps", s.timing.fps},
              {"frame_ms", s.timing.frame_ms()},
              {"line_us", s.timing.line_us},
              {"deadline_ms", s.timing.deadline_ms}}},
            {"model", "tlm"}};
}

}  // namespace imap::engine::stream
