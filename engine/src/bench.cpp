// The benchmark (bench.hpp): child runs of imapsim timed and read back from
// their reports and logs, the golden timed in process, the derived figures.
#include "imap/engine/bench.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/machine.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/synth.hpp"

namespace imap::engine::bench {

namespace g = imap::golden;
namespace v = imap::vision;

namespace {

// `c.exe args...`, its exit code and output; Error (exit 4) naming `what` on failure.
std::string run_child(const Config& c, std::vector<std::string> args, const std::string& what) {
    args.insert(args.begin(), c.exe);
    const Captured r = run_capture(args);
    if (!r.started) throw std::runtime_error("cannot start " + c.exe);
    if (r.exit_code != 0)
        throw Error(
            "bench: " + what + " failed (exit " + std::to_string(r.exit_code) + "):\n" + r.output,
            kExitInternal);
    return r.output;
}

std::string temp_file(const std::string& stem) {
    return (std::filesystem::temp_directory_path() / (stem + std::to_string(::getpid()) + ".json"))
        .string();
}

}  // namespace

double median(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    const size_t n = x.size();
    return n == 0 ? 0.0 : (n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]));
}

std::string spread(const std::vector<double>& v, const char* fmt) {
    char a[64], b[64], c[64];
    std::snprintf(a, sizeof a, fmt, median(v));
    std::snprintf(b, sizeof b, fmt, *std::min_element(v.begin(), v.end()));
    std::snprintf(c, sizeof c, fmt, *std::max_element(v.begin(), v.end()));
    return std::string(a) + "  (" + b + " .. " + c + ")";
}

ModelTimes time_model(const Config& c, const std::string& model) {
    ModelTimes t;
    const std::string rep = temp_file("imapsim-bench-");
    for (int i = 0; i < c.runs; ++i) {
        std::printf("  %s run %d/%d ...\n", model.c_str(), i + 1, c.runs);
        std::fflush(stdout);
        std::vector<std::string> args = {"run", "--model", model, "--report", rep};
        args.insert(args.end(), c.run_args.begin(), c.run_args.end());
        run_child(c, args, "imapsim run --model " + model);
        std::ifstream in(rep);
        const nlohmann::json j = nlohmann::json::parse(in);
        if (!j.at("bit_exact").get<bool>())
            throw Error("bench: model " + model + " is not bit-exact", kExitMismatch);
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

StreamTimes time_stream(const Config& c) {
    StreamTimes t;
    const int frames = c.stream_frames;
    if (frames <= 0) return t;
    const std::string log = temp_file("imapsim-bench-stream-");
    for (int i = 0; i < c.runs; ++i) {
        std::printf("  stream (%d frames) run %d/%d ...\n", frames, i + 1, c.runs);
        std::fflush(stdout);
        run_child(c, {"stream", "--synthetic", std::to_string(frames), "--json", log},
                  "imapsim stream --synthetic " + std::to_string(frames));
        std::ifstream in(log);
        const nlohmann::json j = nlohmann::json::parse(in);
        std::vector<double> m, gw;
        double cycles = 0, model_s = 0;
        for (const auto& f : j.at("frames")) {
            if (f.at("status").get<std::string>() != "ok")
                throw Error("bench: stream frame " + std::to_string(f.at("index").get<int>()) +
                                " is not bit-exact (" + f.at("status").get<std::string>() + ")",
                            kExitMismatch);
            m.push_back(f.at("model_wall_s").get<double>() * 1e3);
            gw.push_back(f.at("golden_wall_s").get<double>() * 1e3);
            cycles += f.at("cycles").get<double>();
            model_s += f.at("model_wall_s").get<double>();
        }
        t.frames = static_cast<int>(m.size());
        t.model_ms.push_back(median(m));
        t.golden_ms.push_back(median(gw));
        t.ratio.push_back(median(m) / median(gw));
        t.cycles_per_s.push_back(model_s > 0 ? cycles / model_s : 0.0);
    }
    std::filesystem::remove(log);
    t.available = true;
    return t;
}

Figures run(const Config& c) {
    Figures f;
    f.model = time_model(c, c.model);
    if (c.rtl) {
        f.rtl = time_model(c, "rtl");
        f.lock = time_model(c, "lockstep");
    }
    f.stream = time_stream(c);

    // golden, in process, on the same inputs as run's default
    const v::SynthScene sc = v::make_synth_scene(1, 160, 128);
    g::Params p;
    const g::Roi roi{16, 0, 128, 128};
    std::vector<double> gms;
    for (int i = 0; i < 5 * c.runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const g::DisparityMap m = g::compute(p, v::view_of(sc.left), v::view_of(sc.right), roi);
        gms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
        if (m.data.empty()) throw Error("bench: the golden gave no map", kExitInternal);
    }
    f.golden_ms = median(gms);

    for (int i = 0; i < roi.w; ++i) f.nodes += g::levels_at(i, roi.w, p.D);
    f.nodes *= roi.h;
    f.per_pe = static_cast<double>(f.nodes) / 256.0;
    const ModelTimes& t = f.model;
    f.wall = median(t.wall_s);
    f.realtime = t.modeled_ms / 1e3 / f.wall;
    f.cycles_per_s = static_cast<double>(t.cycles) / f.wall;
    if (f.rtl.available)
        f.rtl_cycles_per_s = static_cast<double>(f.rtl.cycles) / median(f.rtl.wall_s);
    if (f.lock.available)
        f.lock_cycles_per_s = static_cast<double>(f.lock.cycles) / median(f.lock.wall_s);
    f.forward = t.phases.value("forward", 0.0);
    f.relayout_in = t.relayout.value("in_cycles", 0.0);
    f.relayout_out = t.relayout.value("out_cycles", 0.0);
    f.bound_in = t.relayout.value("in_lower_bound", 0.0);
    f.bound_out = t.relayout.value("out_lower_bound", 0.0);
    return f;
}

nlohmann::json to_json(const Figures& f, int runs) {
    const ModelTimes& t = f.model;
    nlohmann::json j;
    j["modeled_ms"] = t.modeled_ms;
    j["cycles"] = t.cycles;
    j["cycles_per_dp_node"] = static_cast<double>(t.cycles) / f.per_pe;
    j["dp_nodes"] = f.nodes;
    j["tlm_wall_s"] = f.wall;
    j["realtime_factor"] = f.realtime;
    j["tlm_cycles_per_s"] = f.cycles_per_s;
    j["rtl_cycles_per_s"] = f.rtl.available ? nlohmann::json(f.rtl_cycles_per_s) : nlohmann::json();
    j["tlm_over_rtl"] =
        f.rtl.available ? nlohmann::json(f.cycles_per_s / f.rtl_cycles_per_s) : nlohmann::json();
    j["lockstep_cycles_per_s"] =
        f.lock.available ? nlohmann::json(f.lock_cycles_per_s) : nlohmann::json();
    j["golden_ms"] = f.golden_ms;
    j["tlm_over_golden"] = f.wall * 1e3 / f.golden_ms;
    j["phases"] = t.phases;
    j["forward_cycles_per_state"] = f.forward / f.per_pe;
    j["relayout"] = t.relayout;
    j["bounds"] = t.bounds;
    j["bound_cycles"] = t.bound_cycles;
    j["runs"] = runs;
    j["simd_path"] = isa::to_string(isa::default_simd_path());
    if (f.stream.available) {
        const StreamTimes& st = f.stream;
        nlohmann::json s;
        s["frames"] = st.frames;
        s["tlm_ms_per_frame"] = st.model_ms;
        s["golden_ms_per_frame"] = st.golden_ms;
        s["tlm_over_golden"] = st.ratio;
        s["tlm_cycles_per_s"] = st.cycles_per_s;
        s["tlm_over_golden_median"] = median(st.ratio);
        j["stream"] = s;
    }
    return j;
}

}  // namespace imap::engine::bench
