// imapsim synth: writes the built-in synthetic stereo scene (left, right and
// left-view ground truth) to a folder, or with --frames a synthetic sequence
// (left_NNNN.png, right_NNNN.png, gt_NNNN.png), with --calib-out as raw camera
// frames plus their calibration (docs/calibration.md).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli_common.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/sequence.hpp"
#include "imap/vision/synth.hpp"
#include "progress.hpp"

namespace imapsim {

namespace v = imap::vision;
namespace fs = std::filesystem;

namespace {
struct SynthOptions {
    std::string seed = "1";
    std::string size = "160x128";
    std::string out_dir;
    std::string frames;     // empty: a single scene
    std::string calib_out;  // only with --frames
};

constexpr long long kMaxFrames = 100000;
constexpr int kMinSequenceSide = 16;

uint64_t parse_seed(const std::string& text) {
    const std::string err =
        "invalid value '" + text + "' for --seed: expected an integer in 0..18446744073709551615";
    if (text.empty() || text.size() > 20 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throw UserError(err);
    errno = 0;
    char* end = nullptr;
    const unsigned long long s = std::strtoull(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0') throw UserError(err);
    return static_cast<uint64_t>(s);
}

}  // namespace

Subcommand register_synth(CLI::App& app) {
    auto o = std::make_shared<SynthOptions>();
    CLI::App* sub = app.add_subcommand(
        "synth", "Write the built-in synthetic stereo scene (left.png, right.png, gt.png)");
    sub->add_option("--seed", o->seed, "scene seed (0..2^64-1)")->capture_default_str();
    sub->add_option("--size", o->size, "image size WxH (2..4096 each)")->capture_default_str();
    sub->add_option("--out-dir", o->out_dir, "output folder (created if missing)")->required();
    sub->add_option("--frames", o->frames,
                    "write a sequence of N frames (1..100000) with moving objects: "
                    "left_NNNN.png, right_NNNN.png, gt_NNNN.png");
    sub->add_option("--calib-out", o->calib_out,
                    "with --frames: write raw (un-rectified) camera frames and their calibration "
                    "to this file (.yml, .yaml, .xml or .json)");

    return {sub, [o]() {
                const uint64_t seed = parse_seed(o->seed);
                int w = 0, h = 0;
                parse_size_flag("--size", o->size, 2, 4096, &w, &h);
                int frames = 0;
                if (!o->frames.empty()) {
                    frames = static_cast<int>(parse_int_flag("--frames", o->frames, 1, kMaxFrames));
                    if (w < kMinSequenceSide || h < kMinSequenceSide)
                        throw UserError("invalid value '" + o->size +
                                        "' for --size: a sequence (--frames) needs W and H in " +
                                        std::to_string(kMinSequenceSide) + "..4096");
                }
                if (!o->calib_out.empty()) {
                    if (frames == 0)
                        throw UserError("--calib-out needs --frames (it writes a raw sequence)");
                    const std::string ext = lower_extension(o->calib_out);
                    if (ext != ".yml" && ext != ".yaml" && ext != ".xml" && ext != ".json")
                        throw UserError("invalid value '" + o->calib_out +
                                        "' for --calib-out: expected a file name ending in .yml, "
                                        ".yaml, .xml or .json");
                    std::error_code ec;
                    if (fs::is_directory(o->calib_out, ec))
                        throw UserError("--calib-out '" + o->calib_out + "' is a folder");
                }
                create_output_dir("--out-dir", o->out_dir);
                if (frames > 0) {
                    int max_disp = 0;
                    {
                        // A bar on a terminal (a long sequence of big frames
                        // takes minutes); nothing in logs.
                        Progress progress("frames", static_cast<size_t>(frames));
                        max_disp = v::write_sequence(o->out_dir, seed, w, h, frames, o->calib_out,
                                                     [&](int) { progress.step(""); });
                    }
                    char range[32];
                    if (frames == 1)
                        std::snprintf(range, sizeof range, "0000");
                    else
                        std::snprintf(range, sizeof range, "0000..%04d", frames - 1);
                    const std::string raw =
                        o->calib_out.empty()
                            ? ""
                            : "; left/right are raw camera frames, calibration " + o->calib_out;
                    std::printf(
                        "synth: seed %llu, %dx%d, %d frame%s, disparities 0..%d (gt scale 1, left "
                        "view) -> %s/{left,right,gt}_%s.png%s\n",
                        static_cast<unsigned long long>(seed), w, h, frames, frames == 1 ? "" : "s",
                        max_disp, o->out_dir.c_str(), range, raw.c_str());
                    return static_cast<int>(kExitOk);
                }
                const v::SynthScene sc = v::make_synth_scene(seed, w, h);
                const fs::path dir(o->out_dir);
                v::write_image_atomic((dir / "left.png").string(), sc.left);
                v::write_image_atomic((dir / "right.png").string(), sc.right);
                v::write_image_atomic((dir / "gt.png").string(), sc.gt);
                std::printf(
                    "synth: seed %llu, %dx%d, disparities 0..%d (gt scale 1, left view) -> "
                    "%s/{left,right,gt}.png\n",
                    static_cast<unsigned long long>(seed), w, h, sc.max_disp, o->out_dir.c_str());
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
