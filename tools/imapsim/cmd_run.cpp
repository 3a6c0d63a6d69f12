// imapsim run: the main job. Runs the DP firmware on a model of the array
// (default: the built-in synthetic scene), compares the disparity map with
// the golden bit for bit and reports cycles, modeled time and phases. The
// input and the ground-truth score are imap/engine/run_request.hpp's.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/engine/run_request.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "imap/vision/colour.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;
namespace fw = imap::firmware;
namespace isa = imap::isa;
namespace run = imap::engine::run;

namespace {
struct RunOptions {
    std::string left, right, scene, gt, gt_scale, out, out_color, report;
    std::string emit_program, emit_defines;
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
    sub->add_option("--scene", o->scene,
                    "a scene folder (left.png, right.png, gt.png, masks; scenes.json in it or its "
                    "parent, as for eval): its images, its D (unless --D) and bad-1 against its "
                    "ground truth");
    sub->add_option("--gt", o->gt, "with --left/--right: ground truth to score against (bad-1)");
    sub->add_option("--gt-scale", o->gt_scale,
                    "ground-truth value / scale = disparity [default: --scene: scenes.json; "
                    "--gt: 1]");
    sub->add_option("--out", o->out,
                    "write the model's disparity map here (8-bit grey: the disparity, 255 = "
                    "occluded)");
    sub->add_option("--out-color", o->out_color,
                    "write the map colour-mapped here (JET from 0 = blue to D-1 = red, occluded "
                    "white; docs/scoring.md)");
    sub->add_option("--report", o->report, "write a JSON report here");
    sub->add_option("--emit-program", o->emit_program,
                    "write the program that ran here (IMAPFW01, for disasm / exec)");
    sub->add_option("--emit-defines", o->emit_defines,
                    "write its source here: the planner's constants and plan macros, including "
                    "dp.s (for asm; docs/firmware.md)");
    sub->add_option("--model", o->model, "model to run: " + model_names())->capture_default_str();
    sub->add_option("--seed", o->seed, "synthetic scene seed")->capture_default_str();
    sub->add_option("--size", o->size, "synthetic scene size WxH")->capture_default_str();
    add_algo_flags(sub, o->algo);
    add_machine_flags(sub, o->machine);
    add_rtl_flags(sub, o->rtl);
    add_wave_flags(sub, o->waves);

    return {
        sub, [o]() {
            g::Roi roi;
            bool has_roi = false;
            g::Params p = parse_algo_flags(o->algo, &roi, &has_roi);
            const isa::MachineConfig cfg = parse_machine_flags(o->machine);
            check_model_name(o->model);
            // Every output path, before any work (docs/errors.md).
            check_output_file("--out", o->out, true);
            check_output_file("--out-color", o->out_color, true);
            check_output_file("--report", o->report, false);
            check_output_file("--emit-program", o->emit_program, false);
            check_output_file("--emit-defines", o->emit_defines, false);
            check_wave_outputs(o->waves, o->model);
            imap::engine::check_distinct_outputs({{"--out", o->out},
                                                  {"--out-color", o->out_color},
                                                  {"--report", o->report},
                                                  {"--emit-program", o->emit_program},
                                                  {"--emit-defines", o->emit_defines},
                                                  {"--vcd", o->waves.vcd}});

            const run::Input in = run::load_input(
                {o->left, o->right, o->scene, o->gt, o->gt_scale, o->seed, o->size,
                 !o->algo.D.empty()},
                &p, &roi, has_roi, [](const std::string& n) { std::fputs(n.c_str(), stderr); });
            const std::string& source = in.source;
            const cv::Mat &L = in.L, &R = in.R;
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

            ModelRun run = run_model(o->model, p, roi, lv, rv, cfg, &o->waves, &o->rtl);
            if (!run.divergence.empty()) {
                // The lockstep stopped at its first divergence: the report
                // says where (written on divergence too), no map is written.
                if (!o->report.empty()) {
                    nlohmann::json j = divergence_report(run, p, roi, cfg);
                    j["source"] = source;
                    v::write_text_atomic(o->report, j.dump(2) + "\n");
                    std::printf("  report -> %s\n", o->report.c_str());
                }
                std::fflush(stdout);
                std::fprintf(stderr, "imapsim: error: %s\n", run.divergence.c_str());
                return static_cast<int>(kExitMismatch);
            }
            const fw::FrameResult& r = run.result;
            const Comparison cmp = compare_maps(r.map, want);
            print_run_summary(run, cmp, cfg, golden_ms);
            const run::Truth truth = run::score_truth(in, p, roi);
            for (const std::string& l : truth.lines) std::printf("%s\n", l.c_str());
            const cv::Mat out(r.map.height, r.map.width, CV_8UC1,
                              const_cast<uint8_t*>(r.map.data.data()));
            if (!o->out.empty()) {
                v::write_image_atomic(o->out, out);
                std::printf("  disparity map -> %s\n", o->out.c_str());
            }
            if (!o->out_color.empty()) {
                v::write_image_atomic(o->out_color, v::colorize_disparity(out, p.D));
                std::printf("  colour-mapped map -> %s (occluded: white)\n", o->out_color.c_str());
            }
            if (!o->emit_program.empty()) {
                try {
                    isa::save_program(run.program, o->emit_program);
                } catch (const std::exception& e) {
                    throw UserError("--emit-program '" + o->emit_program + "': " + e.what());
                }
                std::printf("  program (%zu instructions) -> %s\n", run.program.code.size(),
                            o->emit_program.c_str());
            }
            if (!o->emit_defines.empty()) {
                v::write_text_atomic(o->emit_defines,
                                     imap::engine::firmware_source_text(
                                         run, source, cfg, o->emit_program, o->emit_defines));
                std::printf("  firmware source (constants and plan) -> %s\n",
                            o->emit_defines.c_str());
            }
            if (!o->report.empty()) {
                nlohmann::json j =
                    run_report(run, cmp, p, roi, cfg, golden_ms, area_json(cfg), fmax_json(cfg));
                j["source"] = source;
                if (!truth.json.is_null()) j["ground_truth"] = truth.json;
                v::write_text_atomic(o->report, j.dump(2) + "\n");
                std::printf("  report -> %s\n", o->report.c_str());
            }
            return cmp.equal ? static_cast<int>(kExitOk) : static_cast<int>(kExitMismatch);
        }};
}

}  // namespace imapsim
