// Simulation speed of the headline frame (ROI 128x128, D = 64, bidir, vote
// on, 256 PEs at 40 MHz) without OpenCV, so that it runs under callgrind
// (docs/performance.md): a random-texture pair with two disparity planes.
//   bench_frame [frames, default 5] [core|tlm, default core] [pes, default 256]
// core: one isa::Machine, loaded once, reset per frame (as the streaming
// testbench does); tlm: one run_tlm frame (one elaboration per process).
// Every frame is checked bit for bit against the golden; prints per-frame
// wall times of the model and of the golden, and the instruction mix.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/isa.hpp"
#include "imap/tlm/tlm.hpp"

namespace isa = imap::isa;
namespace fw = imap::firmware;
namespace g = imap::golden;

namespace {

double now_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Left: random texture; right(x) = left(x + d), d = 24 in a square, 6 elsewhere.
struct Pair {
    int w = 160, h = 128;
    std::vector<uint8_t> left, right;
    explicit Pair(unsigned seed) : left(size_t(w) * h), right(size_t(w) * h) {
        std::mt19937 rng(seed);
        for (auto& v : left) v = static_cast<uint8_t>(rng());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const bool in = x >= 50 && x < 110 && y >= 30 && y < 90;
                const int xs = std::min(w - 1, x + (in ? 24 : 6));
                right[size_t(y) * w + x] = left[size_t(y) * w + xs];
            }
    }
    g::ImageView view(const std::vector<uint8_t>& v) const { return {v.data(), w, h, w}; }
};

}  // namespace

int main(int argc, char** argv) {
    const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const std::string mode = argc > 2 ? argv[2] : "core";
    isa::MachineConfig cfg;
    cfg.pes = argc > 3 ? std::atoi(argv[3]) : 256;
    g::Params p;
    const g::Roi roi{16, 0, 128, 128};
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg);
    const isa::Program prog = fw::assemble_frame(p, plan);

    std::vector<double> model_s, golden_s;
    uint64_t cycles = 0;
    isa::Stats stats;
    bool exact = true;
    if (mode == "core") {
        isa::Machine m(cfg);  // built and loaded once
        m.load(prog);
        std::printf("simd path %s\n", isa::to_string(m.simd_path()));
        for (int f = 0; f < frames; ++f) {
            const Pair pr(static_cast<unsigned>(f + 1));
            const double t0 = now_s();
            m.reset();
            for (const auto& [i, v] : fw::param_block(plan)) m.set_param(i, v);
            isa::ImageVideoPort video;
            video.input[0] = fw::to_video_image(pr.view(pr.left));
            video.input[1] = fw::to_video_image(pr.view(pr.right));
            video.make_output(0, roi.w, roi.h);
            m.set_video(&video);
            m.run();
            const double t1 = now_s();
            const g::DisparityMap want = g::compute(p, pr.view(pr.left), pr.view(pr.right), roi);
            const double t2 = now_s();
            model_s.push_back(t1 - t0);
            golden_s.push_back(t2 - t1);
            exact = exact && want.data == video.output[0].pixels;
            cycles = m.cycles();
        }
        stats = m.stats();
    } else if (mode == "tlm") {
        const Pair pr(1);
        imap::tlm::OutputImages out;
        const imap::tlm::TlmRunResult r = imap::tlm::run_tlm(
            cfg, prog, fw::param_block(plan), fw::to_video_image(pr.view(pr.left)),
            fw::to_video_image(pr.view(pr.right)), roi.w, roi.h, &out);
        const double t1 = now_s();
        const g::DisparityMap want = g::compute(p, pr.view(pr.left), pr.view(pr.right), roi);
        golden_s.push_back(now_s() - t1);
        model_s.push_back(r.wall_s);
        exact = want.data == out.image[0].pixels;
        cycles = r.cycles;
        stats = r.stats;
        std::printf("syncs %llu, chunks %llu\n", static_cast<unsigned long long>(r.syncs),
                    static_cast<unsigned long long>(r.chunks));
    } else {
        std::fprintf(stderr, "bench_frame: mode must be core or tlm, not '%s'\n", mode.c_str());
        return 2;
    }
    std::printf("%s, %d frame(s), %llu cycles, %llu instructions per frame (last)\n", mode.c_str(),
                frames, static_cast<unsigned long long>(cycles),
                static_cast<unsigned long long>(stats.instructions));
    std::printf("model  wall per frame: median %.3f ms (min %.3f)\n", median(model_s) * 1e3,
                *std::min_element(model_s.begin(), model_s.end()) * 1e3);
    std::printf("golden wall per frame: median %.3f ms (min %.3f)\n", median(golden_s) * 1e3,
                *std::min_element(golden_s.begin(), golden_s.end()) * 1e3);
    std::printf("model / golden: %.2f\n", median(model_s) / median(golden_s));
    std::printf("instruction mix (executions per frame):\n");
    std::vector<std::pair<uint64_t, int>> mix;
    for (int o = 0; o < 256; ++o)
        if (stats.op_counts[o]) mix.push_back({stats.op_counts[o], o});
    std::sort(mix.rbegin(), mix.rend());
    for (size_t i = 0; i < mix.size(); ++i)
        std::printf(
            "  %-6s %9llu\n",
            std::string(isa::op_info(static_cast<uint8_t>(mix[i].second))->mnemonic).c_str(),
            static_cast<unsigned long long>(mix[i].first));
    if (!exact) {
        std::fprintf(stderr, "bench_frame: the model's map differs from the golden\n");
        return 1;
    }
    return 0;
}
