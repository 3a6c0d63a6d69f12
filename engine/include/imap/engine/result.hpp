// The one result type of a model run (every model, every executor): what an
// `imapsim run --report R.json` child produced, as the engine reads it from
// the child's exit status, its report and its log. Sweeps, table1 and the
// regression suite all build their rows from it; the Slurm tasks write it to
// their result files; resume reads it back.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace imap::engine {

// How a run ended.
enum class Outcome : uint8_t {
    Ok,           // exit 0, report says bit-exact
    Mismatch,     // ran, the map differs from the golden (exit 1)
    InputError,   // refused (exit 2): bad parameters, does not fit, ...
    Fault,        // the modeled machine faulted (exit 3)
    Failed,       // any other end: other exit code, no or unreadable report, did not start
    Crashed,      // killed by a signal it did not ask for
    TimedOut,     // killed at a time limit (--timeout, or the batch system's)
    Cancelled,    // cancelled by the batch system (scancel, node failure, preemption)
    Interrupted,  // stopped by the user (Ctrl-C) before it finished
};
const char* outcome_name(Outcome o);
std::optional<Outcome> outcome_from_name(const std::string& s);

inline std::ostream& operator<<(std::ostream& o, Outcome x) {
    return o << outcome_name(x);
}

// Definitive answers are kept by --resume; the others are run again.
bool is_definitive(Outcome o);

struct FirstDifference {
    int x = -1, y = -1, model = 0, golden = 0;
};

// Area of the configuration, when the model reports it (the RTL model:
// report key "area": {"cells": N, "memory_bits": M}).
struct Area {
    uint64_t cells = 0;
    uint64_t memory_bits = 0;
};

// The design's Fmax from place and route against the run's clock, when the
// report has it (report key "design_fmax"; docs/rtl.md, "Place and route
// (iCE40)").
struct DesignFmax {
    double mhz = 0;
    double clock_mhz = 0;
    bool clock_above = false;  // clock_mhz > mhz
    std::string technology;    // "iCE40 HX8K"
};

// Energy of the frame, when the report has it (report key "energy",
// docs/energy.md): totals, the share of each event class (uJ) and the event
// counts behind them.
struct Energy {
    double total_uj = 0, dynamic_uj = 0, static_uj = 0;
    double power_mw = 0;                                   // average over the frame's modeled time
    std::vector<std::pair<std::string, double>> by_class;  // uJ per event class
    std::vector<std::pair<std::string, uint64_t>> events;  // event counts
    std::string events_source;                             // "isa", or where an RTL run's came from
};

struct RunResult {
    std::string model;
    Outcome outcome = Outcome::Failed;
    int exit_code = -1;   // -1: no exit status (signal, never started)
    int signal = 0;       // the signal that ended it
    std::string message;  // the child's own error line (without "error: "), or the reason

    // From the report (has_report), also for a mismatch.
    bool has_report = false;
    bool bit_exact = false;
    uint64_t differing_pixels = 0;
    std::optional<FirstDifference> first_difference;
    uint64_t cycles = 0;
    double modeled_ms = 0;
    std::vector<std::pair<std::string, uint64_t>> phases;  // in program order
    std::optional<Area> area;
    std::optional<DesignFmax> design_fmax;
    double pe_utilisation = 0;
    // The machine's bound of each phase that has one, and of the frame
    // (report keys "bounds", "bound_cycles"; docs/firmware.md section 11).
    std::vector<std::pair<std::string, uint64_t>> bounds;
    uint64_t bound_cycles = 0;
    // The energy of the frame (report key "energy").
    std::optional<Energy> energy;

    double wall_s = 0;    // wall time of the child process
    std::string where;    // "local" or "slurm job 123_4 on node1"
    std::string log;      // the child's log file
    std::string command;  // the command that reproduces the run (no --report)

    bool ran() const {
        return has_report && (outcome == Outcome::Ok || outcome == Outcome::Mismatch);
    }
    // The phase with the most cycles ("" without phases) and its share of the total.
    std::string dominant_phase() const;
    double dominant_share() const;
    // The bound of `phase` (0 when it has none); bound / cycles of the frame
    // (0 without a bound).
    uint64_t bound_of(const std::string& phase) const;
    double efficiency() const;
};

// One line saying how the run ended, e.g. "ok, bit-exact", "input error
// (exit 2): parameter D = 99 ...", "machine fault (exit 3): ...", "killed by
// signal 11 (Segmentation fault)", "not bit-exact vs golden: 3 pixels differ,
// first at (4,5): model 7, golden 6".
std::string describe(const RunResult& r);

// Reads a finished child: `wait_status` from waitpid (ignored if !started),
// its report (may be missing) and its log. `stopped` marks a child the
// engine itself stopped (Ctrl-C), `timed_out` one it killed at the time limit.
RunResult read_child(const std::string& model, bool started, int wait_status,
                     const std::string& report_path, const std::string& log_path, double wall_s,
                     bool stopped = false, bool timed_out = false);

// Fills the report fields of `r` from an `imapsim run --report` JSON; false
// (and r.message says why) when it lacks what every report has.
bool read_report(const nlohmann::json& rep, RunResult& r);

nlohmann::json to_json(const RunResult& r);
// The machine bound of the frame over its cycles (0 without a bound or
// cycles): RunResult::efficiency, the run report's "efficiency".
double efficiency(uint64_t bound_cycles, uint64_t cycles);
// The "bounds" object of a report / stored result: phase -> bound cycles.
nlohmann::json bounds_json(const std::vector<std::pair<std::string, uint64_t>>& bounds);
// The "energy" object of a report / stored result.
nlohmann::json energy_json(const Energy& e);
RunResult result_from_json(const nlohmann::json& j);  // throws std::exception on bad input

}  // namespace imap::engine
