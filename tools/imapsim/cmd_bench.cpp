// imapsim bench: simulation speed and firmware quality on the headline case
// (ROI 128x128, D = 64, bidir, vote on, 256 PEs at 40 MHz), each model run
// in its own process, medians over --runs: one frame per model (imapsim run)
// and a headline stream (imapsim stream --synthetic N), whose per-frame log
// times the TLM model and the golden of the same frames in the same process.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "child.hpp"
#include "cli_common.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/synth.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;

namespace {

struct BenchOptions {
    std::string json;
    int runs = 3;
    int stream_frames = 30;  // 0: no stream case
};

double median(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    const size_t n = x.size();
    return n == 0 ? 0.0 : (n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]));
}

struct ModelTimes {
    bool available = false;
    uint64_t cycles = 0;
    double modeled_ms = 0;
    std::vector<double> wall_s;
    nlohmann::json phases;
    nlohmann::json relayout;  // measured re-layout cycles and the plan's lower bound
    nlohmann::json bounds;    // the machine's bound per phase (docs/firmware.md 11)
    uint64_t bound_cycles = 0;
};

// Runs `imapsim run --model M --report F` (the headline case is run's
// default) `runs` times in child processes.
ModelTimes time_model(const std::string& model, int runs) {
    ModelTimes t;
    const std::string rep = (std::filesystem::temp_directory_path() /
                             ("imapsim-bench-" + std::to_string(::getpid()) + ".json"))
                                .string();
    for (int i = 0; i < runs; ++i) {
        std::printf("  %s run %d/%d ...\n", model.c_str(), i + 1, runs);
        std::fflush(stdout);
        const ChildResult c = run_self({"run", "--model", model, "--report", rep});
        if (c.exit_code != 0)
            throw UserError("bench: imapsim run --model " + model + " failed (exit " +
                                std::to_string(c.exit_code) + "):\n" + c.output,
                            kExitInternal);
        std::ifstream in(rep);
        const nlohmann::json j = nlohmann::json::parse(in);
        if (!j.at("bit_exact").get<bool>())
            throw UserError("bench: model " + model + " is not bit-exact", kExitMismatch);
        t.cycles = j.at("cycles").get<uint64_t>();
        t.modeled_ms = j.at("modeled_ms").get<double>();
        t.wall_s.push_back(j.at("wall_s").get<double>());
        t.phases = j.at("phases");
        t.relayout = j.at("relayout");
        t.bounds = j.at("bounds");
        t.bound_cycles = j.at("bound_cycles").get<uint64_t>();
    }
    std::filesystem::remove(rep);
    t.available = true;
    return t;
}

// The stream case: per run, the medians over its frames of the model's and
// the golden's wall time per frame (FrameRecord::model_wall_s /
// golden_wall_s), and the run's cycles / model seconds.
struct StreamTimes {
    bool available = false;
    int frames = 0;
    std::vector<double> model_ms, golden_ms, ratio, cycles_per_s;  // one entry per run
};

StreamTimes time_stream(int frames, int runs) {
    StreamTimes t;
    if (frames <= 0) return t;
    const std::string log = (std::filesystem::temp_directory_path() /
                             ("imapsim-bench-stream-" + std::to_string(::getpid()) + ".json"))
                                .string();
    for (int i = 0; i < runs; ++i) {
        std::printf("  stream (%d frames) run %d/%d ...\n", frames, i + 1, runs);
        std::fflush(stdout);
        const ChildResult c =
            run_self({"stream", "--synthetic", std::to_string(frames), "--json", log});
        if (c.exit_code != 0)
            throw UserError("bench: imapsim stream --synthetic " + std::to_string(frames) +
                                " failed (exit " + std::to_string(c.exit_code) + "):\n" + c.output,
                            kExitInternal);
        std::ifstream in(log);
        const nlohmann::json j = nlohmann::json::parse(in);
        std::vector<double> m, g;
        double cycles = 0, model_s = 0;
        for (const auto& f : j.at("frames")) {
            if (f.at("status").get<std::string>() != "ok")
                throw UserError("bench: stream frame " + std::to_string(f.at("index").get<int>()) +
                                    " is not bit-exact (" + f.at("status").get<std::string>() + ")",
                                kExitMismatch);
            m.push_back(f.at("model_wall_s").get<double>() * 1e3);
            g.push_back(f.at("golden_wall_s").get<double>() * 1e3);
            cycles += f.at("cycles").get<double>();
            model_s += f.at("model_wall_s").get<double>();
        }
        t.frames = static_cast<int>(m.size());
        t.model_ms.push_back(median(m));
        t.golden_ms.push_back(median(g));
        t.ratio.push_back(median(m) / median(g));
        t.cycles_per_s.push_back(model_s > 0 ? cycles / model_s : 0.0);
    }
    std::filesystem::remove(log);
    t.available = true;
    return t;
}

// "median (min..max)" of per-run figures.
std::string spread(const std::vector<double>& v, const char* fmt) {
    char a[64], b[64], c[64];
    std::snprintf(a, sizeof a, fmt, median(v));
    std::snprintf(b, sizeof b, fmt, *std::min_element(v.begin(), v.end()));
    std::snprintf(c, sizeof c, fmt, *std::max_element(v.begin(), v.end()));
    return std::string(a) + "  (" + b + " .. " + c + ")";
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
    return {
        sub, [o]() {
            check_output_file("--json", o->json, false);  // before the runs, not after them
            std::printf(
                "imapsim bench: headline case (synthetic scene, ROI 128x128, D=64, "
                "bidir, vote on, 256 PEs, 40 MHz), %d run(s) per model\n",
                o->runs);
            std::printf("  executor SIMD path: %s\n",
                        imap::isa::to_string(imap::isa::default_simd_path()));
            const ModelTimes tlm = time_model("tlm", o->runs);
            ModelTimes rtl, lock;
            if (model_names().find("rtl") != std::string::npos) {
                rtl = time_model("rtl", o->runs);
                lock = time_model("lockstep", o->runs);
            }
            const StreamTimes st = time_stream(o->stream_frames, o->runs);

            // golden, in process, on the same inputs as run's default
            const v::SynthScene sc = v::make_synth_scene(1, 160, 128);
            g::Params p;
            const g::Roi roi{16, 0, 128, 128};
            std::vector<double> gms;
            for (int i = 0; i < 5 * o->runs; ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                const g::DisparityMap m =
                    g::compute(p, v::view_of(sc.left), v::view_of(sc.right), roi);
                gms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
                if (m.data.empty()) return static_cast<int>(kExitInternal);
            }
            const double golden_ms = median(gms);

            int64_t nodes = 0;  // valid DP states of the frame
            for (int i = 0; i < roi.w; ++i) nodes += g::levels_at(i, roi.w, p.D);
            nodes *= roi.h;
            const double per_pe = static_cast<double>(nodes) / 256.0;
            const double tlm_wall = median(tlm.wall_s);
            const double realtime = tlm.modeled_ms / 1e3 / tlm_wall;
            const double tlm_cps = static_cast<double>(tlm.cycles) / tlm_wall;
            const double rtl_wall = rtl.available ? median(rtl.wall_s) : 0.0;
            const double rtl_cps = rtl.available ? static_cast<double>(rtl.cycles) / rtl_wall : 0.0;
            const double lock_cps =
                lock.available ? static_cast<double>(lock.cycles) / median(lock.wall_s) : 0.0;

            std::printf("\n  modeled time            %10.3f ms   (paper: 85 ms)\n", tlm.modeled_ms);
            std::printf("  cycles                  %10llu\n",
                        static_cast<unsigned long long>(tlm.cycles));
            std::printf("  cycles per DP node/PE   %10.1f      (%lld DP nodes, %.0f per PE)\n",
                        static_cast<double>(tlm.cycles) / per_pe, static_cast<long long>(nodes),
                        per_pe);
            // Issue targets of the firmware: the forward pass per valid state
            // and per PE, and the re-layout against the ring's lower bound.
            const double fwd = tlm.phases.value("forward", 0.0);
            const double rl_in = tlm.relayout.value("in_cycles", 0.0);
            const double rl_out = tlm.relayout.value("out_cycles", 0.0);
            const double bd_in = tlm.relayout.value("in_lower_bound", 0.0);
            const double bd_out = tlm.relayout.value("out_lower_bound", 0.0);
            std::printf("  forward cycles/state/PE %10.1f      (forward phase %.0f cycles)\n",
                        fwd / per_pe, fwd);
            std::printf("  re-layout in            %10.0f      (ring lower bound %.0f: %.2fx)\n",
                        rl_in, bd_in, bd_in > 0 ? rl_in / bd_in : 0.0);
            std::printf("  re-layout out           %10.0f      (ring lower bound %.0f: %.2fx)\n",
                        rl_out, bd_out, bd_out > 0 ? rl_out / bd_out : 0.0);
            std::printf("  phase / machine bound   ");
            for (const auto& [ph, b] : tlm.bounds.items())
                std::printf(" %s %.2fx", ph.c_str(),
                            tlm.phases.value(ph, 0.0) / std::max(1.0, b.get<double>()));
            std::printf("\n  machine bound           %10llu      (frame at %.1f%% of it)\n",
                        static_cast<unsigned long long>(tlm.bound_cycles),
                        100.0 * static_cast<double>(tlm.bound_cycles) /
                            static_cast<double>(std::max<uint64_t>(1, tlm.cycles)));
            std::printf("  TLM wall                %10.4f s    (median)\n", tlm_wall);
            std::printf("  TLM modeled/wall        %10.2f      (>= 1: faster than the board)\n",
                        realtime);
            std::printf("  TLM cycles/s            %10.3g\n", tlm_cps);
            if (rtl.available) {
                std::printf(
                    "  RTL cycles/s            %10.3g      (full headline run, %llu "
                    "cycles)\n",
                    rtl_cps, static_cast<unsigned long long>(rtl.cycles));
                std::printf("  TLM/RTL speed           %10.1f\n", tlm_cps / rtl_cps);
                std::printf(
                    "  lockstep cycles/s       %10.3g      (TLM and RTL compared at "
                    "every instruction)\n",
                    lock_cps);
                print_rtl_area();
            } else {
                std::printf("  RTL                     not built in this binary\n");
            }
            std::printf("  golden wall             %10.3f ms   (median)\n", golden_ms);
            std::printf(
                "  TLM wall / golden wall  %10.2f      (one cold frame against a warm golden)\n",
                tlm_wall * 1e3 / golden_ms);
            if (st.available) {
                std::printf(
                    "  stream, %d frames, per frame, median over frames; median (min .. max) "
                    "over %d run(s):\n",
                    st.frames, o->runs);
                std::printf("    TLM wall              %s ms\n",
                            spread(st.model_ms, "%.3f").c_str());
                std::printf("    golden wall           %s ms\n",
                            spread(st.golden_ms, "%.3f").c_str());
                std::printf(
                    "    TLM wall / golden wall %s   (<= 1: the model keeps up with "
                    "the golden)\n",
                    spread(st.ratio, "%.2f").c_str());
                std::printf("    TLM cycles/s          %s\n",
                            spread(st.cycles_per_s, "%.3g").c_str());
            }

            if (!o->json.empty()) {
                nlohmann::json j;
                j["modeled_ms"] = tlm.modeled_ms;
                j["cycles"] = tlm.cycles;
                j["cycles_per_dp_node"] = static_cast<double>(tlm.cycles) / per_pe;
                j["dp_nodes"] = nodes;
                j["tlm_wall_s"] = tlm_wall;
                j["realtime_factor"] = realtime;
                j["tlm_cycles_per_s"] = tlm_cps;
                j["rtl_cycles_per_s"] = rtl.available ? nlohmann::json(rtl_cps) : nlohmann::json();
                j["tlm_over_rtl"] =
                    rtl.available ? nlohmann::json(tlm_cps / rtl_cps) : nlohmann::json();
                j["lockstep_cycles_per_s"] =
                    lock.available ? nlohmann::json(lock_cps) : nlohmann::json();
                j["golden_ms"] = golden_ms;
                j["tlm_over_golden"] = tlm_wall * 1e3 / golden_ms;
                j["phases"] = tlm.phases;
                j["forward_cycles_per_state"] = fwd / per_pe;
                j["relayout"] = tlm.relayout;
                j["bounds"] = tlm.bounds;
                j["bound_cycles"] = tlm.bound_cycles;
                j["runs"] = o->runs;
                j["simd_path"] = imap::isa::to_string(imap::isa::default_simd_path());
                if (st.available) {
                    nlohmann::json s;
                    s["frames"] = st.frames;
                    s["tlm_ms_per_frame"] = st.model_ms;
                    s["golden_ms_per_frame"] = st.golden_ms;
                    s["tlm_over_golden"] = st.ratio;
                    s["tlm_cycles_per_s"] = st.cycles_per_s;
                    s["tlm_over_golden_median"] = median(st.ratio);
                    j["stream"] = s;
                }
                v::write_text_atomic(o->json, j.dump(2) + "\n");
                std::printf("  -> %s\n", o->json.c_str());
            }
            return static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
