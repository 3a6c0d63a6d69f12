// imapsim bench: simulation speed and firmware quality on the headline case
// (ROI 128x128, D = 64, bidir, vote on, 256 PEs at 40 MHz). Its flags and
// its printed figures; the benchmark is the engine's (imap/engine/bench.hpp).
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "imap/engine/bench.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/result.hpp"
#include "imap/isa/machine.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace v = imap::vision;
namespace bench = imap::engine::bench;

namespace {

struct BenchOptions {
    std::string json;
    int runs = 3;
    int stream_frames = 30;  // 0: no stream case
};

void print_figures(const bench::Figures& f, int runs) {
    const bench::ModelTimes& t = f.model;
    const bench::StreamTimes& st = f.stream;
    std::printf("\n  modeled time            %10.3f ms   (paper: 85 ms)\n", t.modeled_ms);
    std::printf("  cycles                  %10llu\n", static_cast<unsigned long long>(t.cycles));
    std::printf("  cycles per DP node/PE   %10.1f      (%lld DP nodes, %.0f per PE)\n",
                static_cast<double>(t.cycles) / f.per_pe, static_cast<long long>(f.nodes),
                f.per_pe);
    // Issue targets of the firmware: the forward pass per valid state
    // and per PE, and the re-layout against the ring's lower bound.
    std::printf("  forward cycles/state/PE %10.1f      (forward phase %.0f cycles)\n",
                f.forward / f.per_pe, f.forward);
    std::printf("  re-layout in            %10.0f      (lower bound %.0f: %.2fx)\n", f.relayout_in,
                f.bound_in, f.bound_in > 0 ? f.relayout_in / f.bound_in : 0.0);
    std::printf("  re-layout out           %10.0f      (lower bound %.0f: %.2fx)\n", f.relayout_out,
                f.bound_out, f.bound_out > 0 ? f.relayout_out / f.bound_out : 0.0);
    std::printf("  phase / machine bound   ");
    for (const auto& [ph, b] : t.bounds.items())
        std::printf(" %s %.2fx", ph.c_str(),
                    t.phases.value(ph, 0.0) / std::max(1.0, b.get<double>()));
    std::printf("\n  machine bound           %10llu      (frame at %.1f%% of it)\n",
                static_cast<unsigned long long>(t.bound_cycles),
                100.0 * imap::engine::efficiency(t.bound_cycles, t.cycles));
    std::printf("  TLM wall                %10.4f s    (median)\n", f.wall);
    std::printf("  TLM modeled/wall        %10.2f      (>= 1: faster than the board)\n",
                f.realtime);
    std::printf("  TLM cycles/s            %10.3g\n", f.cycles_per_s);
    if (f.rtl.available) {
        std::printf(
            "  RTL cycles/s            %10.3g      (full headline run, %llu "
            "cycles)\n",
            f.rtl_cycles_per_s, static_cast<unsigned long long>(f.rtl.cycles));
        std::printf("  TLM/RTL speed           %10.1f\n", f.cycles_per_s / f.rtl_cycles_per_s);
        std::printf(
            "  lockstep cycles/s       %10.3g      (TLM and RTL compared at "
            "every instruction)\n",
            f.lock_cycles_per_s);
        print_rtl_area(imap::isa::MachineConfig{}.clock_mhz);  // the bench runs the defaults
    } else {
        std::printf("  RTL                     not built in this binary\n");
    }
    std::printf("  golden wall             %10.3f ms   (median)\n", f.golden_ms);
    std::printf("  TLM wall / golden wall  %10.2f      (one cold frame against a warm golden)\n",
                f.wall * 1e3 / f.golden_ms);
    if (st.available) {
        std::printf(
            "  stream, %d frames, per frame, median over frames; median (min .. max) "
            "over %d run(s):\n",
            st.frames, runs);
        std::printf("    TLM wall              %s ms\n",
                    bench::spread(st.model_ms, "%.3f").c_str());
        std::printf("    golden wall           %s ms\n",
                    bench::spread(st.golden_ms, "%.3f").c_str());
        std::printf(
            "    TLM wall / golden wall %s   (<= 1: the model keeps up with "
            "the golden)\n",
            bench::spread(st.ratio, "%.2f").c_str());
        std::printf("    TLM cycles/s          %s\n",
                    bench::spread(st.cycles_per_s, "%.3g").c_str());
    }
}

}  // namespace

Subcommand register_bench(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* sub = app.add_subcommand(
        "bench",
        "Simulation speed and firmware cycles on the headline case (each model in its "
        "own process; medians)");
    sub->add_option("--json", o->json, "write the figures as JSON");
    sub->add_option("--runs", o->runs, "runs per model (median)")
        ->check(CLI::Range(1, 50))
        ->capture_default_str();
    sub->add_option("--stream-frames", o->stream_frames,
                    "frames of the headline stream case (0: leave it out)")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    return {sub, [o]() {
                check_output_file("--json", o->json, false);  // before the runs, not after them
                std::printf(
                    "imapsim bench: headline case (synthetic scene, ROI 128x128, D=64, "
                    "bidir, vote on, 256 PEs, 40 MHz), %d run(s) per model\n",
                    o->runs);
                std::printf("  executor SIMD path: %s\n",
                            imap::isa::to_string(imap::isa::default_simd_path()));
                bench::Config c;
                c.exe = imap::engine::self_exe();
                c.rtl = model_names().find("rtl") != std::string::npos;
                c.runs = o->runs;
                c.stream_frames = o->stream_frames;
                const bench::Figures f = bench::run(c);
                print_figures(f, o->runs);
                if (!o->json.empty()) {
                    v::write_text_atomic(o->json, bench::to_json(f, o->runs).dump(2) + "\n");
                    std::printf("  -> %s\n", o->json.c_str());
                }
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
