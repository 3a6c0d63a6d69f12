// The benchmark (imapsim bench): simulation speed and firmware quality on
// the headline case (ROI 128x128, D = 64, bidir, vote on, 256 PEs at 40
// MHz), each model run in its own process (`imapsim run --report`), medians
// over the runs; a headline stream (`imapsim stream --synthetic N`) whose
// per-frame log times the TLM model and the golden of the same frames; the
// golden timed in process. The figures and their JSON; printing is imapsim's.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace imap::engine::bench {

// Median of x (the mean of the middle two for an even count; 0 when empty).
double median(std::vector<double> x);
// "median  (min .. max)" of per-run figures, each printed with `fmt`.
std::string spread(const std::vector<double>& v, const char* fmt);

struct Config {
    std::string exe;                    // the imapsim binary that runs the children
    std::string model = "tlm";          // the model timed first (its figures are the headline's)
    bool rtl = false;                   // also time rtl and lockstep
    int runs = 3;                       // runs per model (medians)
    int stream_frames = 30;             // 0: no stream case
    std::vector<std::string> run_args;  // extra `imapsim run` flags (none: the headline case)
};

// One model's runs: the last run's report figures and every run's wall time.
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

// The stream case: per run, the medians over its frames of the model's and
// the golden's wall time per frame, their ratio, and cycles / model second.
struct StreamTimes {
    bool available = false;
    int frames = 0;
    std::vector<double> model_ms, golden_ms, ratio, cycles_per_s;  // one entry per run
};

struct Figures {
    ModelTimes model, rtl, lock;  // model: Config::model's
    StreamTimes stream;
    double golden_ms = 0;  // median golden wall time of the headline frame, in process
    int64_t nodes = 0;     // valid DP states of the headline frame
    double per_pe = 0;     // ... per PE of the 256
    double wall = 0, realtime = 0, cycles_per_s = 0;  // the model's
    double rtl_cycles_per_s = 0, lock_cycles_per_s = 0;
    // Issue targets: forward-phase cycles and the re-layout against the
    // ring's lower bound (from the model's report).
    double forward = 0, relayout_in = 0, relayout_out = 0, bound_in = 0, bound_out = 0;
};

// Runs `exe run --model M --report F [run_args]` `runs` times; Error (exit 4)
// when a run fails, exit 1 when it is not bit-exact.
ModelTimes time_model(const Config& c, const std::string& model);
// Runs `exe stream --synthetic N --json LOG` `runs` times (nothing for N = 0).
StreamTimes time_stream(const Config& c);

// The whole benchmark; prints one progress line per child run.
Figures run(const Config& c);

// The figures as `imapsim bench --json` writes them.
nlohmann::json to_json(const Figures& f, int runs);

}  // namespace imap::engine::bench
