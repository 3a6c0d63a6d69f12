// The what-if engine of `imapsim sweep` and `imapsim table1` (docs/whatif.md):
// a list of points (values of machine and algorithm parameters), each planned
// in-process (what does not fit is an answer, not an error) and, when it
// fits, run on a model as a job (`imapsim run`) by an executor; rows in point
// order with the dominant phase of each, CSV and JSON, knees of the curves
// explained by the phases that change, and the plot.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "imap/engine/executor.hpp"
#include "imap/engine/plot.hpp"
#include "imap/engine/result.hpp"
#include "imap/engine/run_dir.hpp"
#include "imap/engine/values.hpp"
#include "imap/golden/params.hpp"

namespace imap::engine::sweep {

enum class AxisKind { Machine, Algo, RoiSize };

// One parameter of the sweep and its values (text, as on a command line).
struct Axis {
    std::string name;  // pes, clock_mhz, mem_bytes, roi_size, D, mode, ring_hop, ...
    std::string flag;  // as the user gave it: "--pes", "--set ring_hop", "--roi-size"
    AxisKind kind = AxisKind::Algo;
    std::vector<std::string> values;
};

// Builds an axis from a flag's text: parses the list and checks every value
// (range, syntax) on its own; engine::Error names the flag. `name` is a
// machine parameter name (MachineConfig::set), an algorithm parameter (D,
// km, kb, gb, Wo, Wd, mode) or roi_size.
Axis make_axis(const std::string& name, const std::string& flag, const std::string& text);

// A value of an axis on a numeric plot axis (NaN if it is not a number).
double numeric_value(const Axis& a, const std::string& v);

// Where the images come from.
struct Input {
    std::string left, right;    // empty: the built-in synthetic scene, generated at the ROI size
    uint64_t seed = 1;          // synthetic scene seed
    int width = 0, height = 0;  // size of the given images
    // ROI with images: `roi` if has_fixed_roi, else the roi_size axis centred
    // in the image, else the whole image.
    bool has_fixed_roi = false;
    golden::Roi roi;
    std::string describe() const;
};

struct Spec {
    std::string command = "sweep";  // names the run folder and the messages
    std::vector<Axis> fixed;        // one value each
    std::vector<Axis> swept;        // two or more values each, in command-line order
    // Points as value indices into swept[i].values; empty = the full product.
    std::vector<std::vector<size_t>> points;
    // The algorithm parameters the axes do not set, and the child flags that
    // give them (e.g. --seed-col C --vote on --frame cyc --fill).
    golden::Params base;
    std::vector<std::string> base_args;
    nlohmann::json fixed_algorithm = nlohmann::json::object();  // for the JSON report
    std::string model = "tlm";
    bool dry_run = false;
    Input input;
};

// The full cartesian product (refused beyond kMaxPoints with a message that
// names the axes and their sizes).
std::vector<std::vector<size_t>> product(const std::vector<Axis>& swept);

enum class Status {
    Ok,           // ran, bit-exact with the golden
    Mismatch,     // ran, the map differs from the golden
    DoesNotFit,   // the memory plan does not fit the point's machine (an answer)
    CannotRun,    // invalid combination or a firmware limit (an answer)
    Planned,      // --dry-run: fits, not run
    Error,        // the run failed (fault, crash, timeout, cancelled, no report)
    Interrupted,  // the run was stopped by the Ctrl-C
};
const char* status_name(Status s);
inline std::ostream& operator<<(std::ostream& o, Status s) {
    return o << status_name(s);
}

struct Row {
    std::vector<std::string> values;  // per swept axis
    Status status = Status::Error;
    std::string message;
    int64_t local_bytes = -1;      // local memory needed per PE (-1: not plannable)
    int64_t ext_bytes = -1;        // external memory needed per PE
    int job = -1;                  // index of its job in Plan::jobs (-1: not run)
    std::optional<RunResult> run;  // the job's result, once it finished
    bool ran() const { return run && run->ran(); }
    double fps() const { return ran() && run->modeled_ms > 0 ? 1000.0 / run->modeled_ms : 0.0; }
};

// The quantity `--y` chooses: the column the table adds (and the summary's
// best point) and the plot's y axis. Time is the default (the table and
// plot as they always were).
enum class Metric { Time, Energy, Power, Edp, Area };
inline constexpr const char* kMetricNames = "time, energy, power, edp, area";
const char* metric_name(Metric m);                             // "time", "energy", ...
std::optional<Metric> metric_from_name(const std::string& s);  // nullopt if unknown
// The metric's value for a row that ran: modeled ms, energy per frame (uJ),
// average power over the frame (mW), energy x delay (uJ x ms) or area
// (cells); NaN when the row has none (not run, no energy or area reported).
double metric_value(const Row& r, Metric m);
// Whether the row ran at a clock above the design's Fmax (its report's
// "design_fmax"; docs/rtl.md, "Place and route (iCE40)"): the table marks
// it and the summary counts it.
bool clock_above_fmax(const Row& r);

// Every point planned: the rows that are answers already, the jobs to run.
struct Plan {
    std::string command = "sweep", model = "tlm";
    bool dry_run = false;
    std::string input;  // Input::describe()
    bool synthetic = true;
    std::vector<Axis> swept, fixed;
    nlohmann::json fixed_params = nlohmann::json::object();  // "fixed" of the JSON report
    std::vector<std::string> phase_names;                    // program order
    std::vector<Row> rows;                                   // one per point, in point order
    std::vector<Job> jobs;  // the runnable points (none with dry_run)
    // What the table highlights (--y): a display choice, not saved with the
    // plan (a resumed sweep takes the --y of its own command line).
    Metric y = Metric::Time;
};

// Plans every point in-process (engine::Error for an invalid Spec).
Plan plan(const Spec& s);

nlohmann::json to_json(const Plan& p);
Plan plan_from_json(const nlohmann::json& j);  // engine::Error when it is not a sweep plan

// A knee of a modeled-time curve: where its log-log slope changes by more
// than kKneeSlopeChange, with the phases that explain it.
inline constexpr double kKneeSlopeChange = 0.5;
struct Knee {
    std::string series;  // the other swept axes' values ("" with one axis)
    std::string x;       // the axis value at the knee
    double xv = 0, y_ms = 0;
    double slope_before = 0, slope_after = 0;
    std::string phase_before, phase_after;  // the phase whose cycles change most on each side
    std::string explanation;                // one sentence, printed, in the JSON and on the plot
    std::string label;                      // a short form for the plot
};

struct Result {
    std::vector<Row> rows;  // finished points (and the answers), in point order
    size_t total = 0;       // points of the sweep
    size_t not_run = 0;     // points not finished because of the interrupt
    bool interrupted = false;
    std::vector<std::string> phase_names;
    double wall_s = 0;
    size_t reused = 0;   // results taken from the run folder (--resume)
    std::string logs;    // folder of the kept logs, empty if removed
    std::string x_axis;  // the axis the knees were looked for along
    std::vector<Knee> knees;
    size_t count(Status s) const;
    size_t ran() const { return count(Status::Ok) + count(Status::Mismatch); }
    // 130 if interrupted; 5 if a row is an error or no point ran (or, with
    // --dry-run, none fits); 1 if a point is not bit-exact; else 0.
    int exit_code(bool dry_run) const;
};

// What the command prints while the sweep runs.
struct Hooks {
    std::function<bool()> stop_requested = [] { return false; };
    std::function<void(const std::string&)> row = [](const std::string&) {};   // a finished row
    std::function<void(const std::string&)> note = [](const std::string&) {};  // a note line
    std::function<void(const std::string&)> status = [](const std::string&) {};
};

// The header lines (command, points, executor, input, fixed values, column
// names) and the table's row format.
std::vector<std::string> header_lines(const Plan& p, const Executor* ex);
std::string row_line(const Plan& p, const Row& r);

// Runs the plan's jobs on `ex` (resume: only those without a definitive
// result in `dir`), prints rows in point order through hooks.row as they
// finish, finds the knees along axis `x_axis` (index into swept), and
// returns the result. The summary is summary_lines().
Result run(const Plan& p, Executor& ex, RunDir& dir, Manifest& m, const ExecContext& ctx,
           Hooks& hooks, bool resume, size_t x_axis = 0);
std::vector<std::string> summary_lines(const Plan& p, const Result& r);

// Knees of every series along swept axis `x_axis` (numeric axes only).
std::vector<Knee> find_knees(const Plan& p, const std::vector<Row>& rows, size_t x_axis);

// CSV: one column per swept axis, cycles, modeled_ms, fps, status, message,
// bit_exact, wall_s, local_bytes_per_pe, ext_bytes_per_pe, dominant_phase,
// dominant_share, area_cells, area_memory_bits (empty unless the model
// reports its area), one column per phase (phase_<name>), bound_cycles,
// efficiency, bound_<name> per bounded phase, energy_uj, power_mw, edp
// (uJ x ms). An interrupted sweep ends with one row of status
// "sweep-interrupted".
std::string to_csv(const Plan& p, const Result& r);
// JSON: the same rows, the swept and fixed parameters, the knees, the summary.
nlohmann::json to_json(const Plan& p, const Result& r);

// The plot of the plan's metric (Plan::y; default modeled frame time)
// against swept axis `x_axis`, one series per combination of the other swept
// axes; for time, the real-time lines, the machine's bound and the knees.
// Returns false (nothing to draw) when no point ran bit-exact with a value.
bool make_figure(const Plan& p, const Result& r, size_t x_axis, plot::Figure* f);

// Pareto view (--pareto): the rows that ran bit-exact with an energy, and of
// them the Pareto-optimal ones by modeled time and energy per frame: no other
// such row is at most as slow and uses at most as much energy while being
// better in one of the two. Indices into `rows`, in row order.
std::vector<size_t> pareto_rows(const std::vector<Row>& rows);
// The text listing: a heading line and one line per Pareto-optimal point.
std::vector<std::string> pareto_lines(const Plan& p, const Result& r);
// Time against energy, one point per design point (point size by area when
// every point has one, otherwise a note says so), the Pareto-optimal points
// circled, labelled and joined. False when no point ran with an energy.
bool make_pareto_figure(const Plan& p, const Result& r, plot::Figure* f);

// CSV field quoting (RFC 4180).
std::string csv_field(const std::string& s);

}  // namespace imap::engine::sweep
