// imapsim run: the main job. Runs the DP firmware on a model of the array
// (default: the built-in synthetic scene), compares the disparity map with
// the golden bit for bit and reports cycles, modeled time and phases.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/score.hpp"
#include "imap/vision/synth.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;
namespace fw = imap::firmware;
namespace isa = imap::isa;

namespace {
struct RunOptions {
    std::string left, right, out, report;
    std::string model = kDefaultModel;
    uint64_t seed = 1;
    std::string size = "160x128";
    AlgoFlags algo;
    MachineFlags machine;
    RtlFlags rtl;
    WaveFlags waves;
};

}  // namespace

Subcommand register_run(CLI::App& app) {
    auto o = std::make_shared<RunOptions>();
    CLI::App* sub = app.add_subcommand(
        "run",
        "Run the DP firmware on a model of the array and check it against the golden "
        "(default: the built-in synthetic scene)");
    sub->add_option("--left", o->left, "left image (default: synthetic scene)");
    sub->add_option("--right", o->right, "right image");
    sub->add_option("--out", o->out, "write the model's disparity map here");
    sub->add_option("--report", o->report, "write a JSON report here");
    sub->add_option("--model", o->model, "model to run: " + model_names())->capture_default_str();
    sub->add_option("--seed", o->seed, "synthetic scene seed")->capture_default_str();
    sub->add_option("--size", o->size, "synthetic scene size WxH")->capture_default_str();
    add_algo_flags(sub, o->algo);
    add_machine_flags(sub, o->machine);
    add_rtl_flags(sub, o->rtl);
    add_wave_flags(sub, o->waves);

    return {sub, [o]() {
                g::Roi roi;
                bool has_roi = false;
                const g::Params p = parse_algo_flags(o->algo, &roi, &has_roi);
                const isa::MachineConfig cfg = parse_machine_flags(o->machine);
                check_model_name(o->model);
                check_output_file("--out", o->out, true);
                check_output_file("--report", o->report, false);
                check_output_file("--vcd", o->waves.vcd, false);
                cv::Mat L, R, gt;
                std::string source;
                if (o->left.empty() != o->right.empty())
                    throw UserError("--left and --right must be given together");
                if (!o->left.empty()) {
                    L = v::load_grey8(o->left, "left image");
                    R = v::load_grey8(o->right, "right image");
                    source = o->left + " + " + o->right;
                } else {
                    int w = 0, h = 0;
                    char x = 0;
                    if (std::sscanf(o->size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' ||
                        w < 2 || h < 1 || w > 4096 || h > 4096)
                        throw UserError("invalid value '" + o->size +
                                        "' for --size: expected WxH with W in 2..4096, H in "
                                        "1..4096");
                    v::SynthScene sc = v::make_synth_scene(o->seed, w, h);
                    L = sc.left;
                    R = sc.right;
                    gt = sc.gt;
                    source = "synthetic scene seed " + std::to_string(o->seed) + " " + o->size;
                    if (!has_roi && w >= 128 && h >= 128) {
                        roi = {(w - 128) / 2, (h - 128) / 2, 128, 128};  // the headline ROI
                        has_roi = true;
                    }
                }
                if (L.size() != R.size())
                    throw UserError("left and right images differ in size: " + o->left + " is " +
                                    std::to_string(L.cols) + "x" + std::to_string(L.rows) + ", " +
                                    o->right + " is " + std::to_string(R.cols) + "x" +
                                    std::to_string(R.rows));
                if (!has_roi) roi = {0, 0, L.cols, L.rows};
                try {
                    g::validate(p, roi, L.cols, L.rows);
                } catch (const g::ParamError& e) {
                    throw UserError(e.what());
                }
                const g::ImageView lv = v::view_of(L), rv = v::view_of(R);

                std::printf("imapsim run: %s, ROI %d,%d,%dx%d, D=%d, %s, vote %s, frame %s\n",
                            source.c_str(), roi.x0, roi.y0, roi.w, roi.h, p.D, g::to_string(p.mode),
                            p.vote ? "on" : "off", g::to_string(p.frame));
                std::printf(
                    "  machine: %d PEs at %g MHz, %u B local + %u B external per PE, "
                    "model %s\n",
                    cfg.pes, cfg.clock_mhz, cfg.mem_bytes, cfg.ext_bytes, o->model.c_str());
                std::fflush(stdout);

                const auto tg = std::chrono::steady_clock::now();
                const g::DisparityMap want = g::compute(p, lv, rv, roi);
                const double golden_ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - tg)
                        .count();

                set_rtl_flags(o->rtl);
                ModelRun run = run_model(o->model, p, roi, lv, rv, cfg, &o->waves);
                const fw::FrameResult& r = run.result;
                const Comparison cmp = compare_maps(r.map, want);
                print_run_summary(run, cmp, cfg, golden_ms);
                if (!gt.empty()) {
                    g::Params pl = p;
                    pl.frame = g::Frame::Left;
                    const g::DisparityMap ml = g::compute(pl, lv, rv, roi, true);
                    std::printf("  golden bad-1 vs ground truth (left frame, filled): %.2f%%\n",
                                v::bad_percent_roi(ml, gt, roi));
                }
                if (!o->out.empty()) {
                    cv::Mat out(r.map.height, r.map.width, CV_8UC1,
                                const_cast<uint8_t*>(r.map.data.data()));
                    v::write_image_atomic(o->out, out);
                    std::printf("  disparity map -> %s\n", o->out.c_str());
                }
                if (!o->report.empty()) {
                    nlohmann::json j = run_report(run, cmp, p, roi, cfg, golden_ms);
                    j["source"] = source;
                    v::write_text_atomic(o->report, j.dump(2) + "\n");
                    std::printf("  report -> %s\n", o->report.c_str());
                }
                return cmp.equal ? static_cast<int>(kExitOk) : static_cast<int>(kExitMismatch);
            }};
}

}  // namespace imapsim
