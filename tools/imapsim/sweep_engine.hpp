// The what-if engine shared by `imapsim sweep` and `imapsim table1`
// (docs/whatif.md): a list of points (values of machine and algorithm
// parameters), each planned in-process (what does not fit is an answer, not
// an error) and, when it fits, run on a model as a child process
// `imapsim run --report R.json` (SystemC elaborates once per process), up to
// -j at a time; rows in point order, CSV and JSON, Ctrl-C handling.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.hpp"

namespace imapsim::sweep {

// What a parameter's values are: integers, real numbers or words.
enum class ValueType { Int, Real, Text };

// Parses a comma list of values and ranges: "8,16,32", "A..B" (step 1),
// "A..B:S" (additive step S), "A..B*F" (geometric, factor F), e.g. 8..1024*2.
// Ranges need numbers (integers for ValueType::Int); Text takes plain words.
// Throws UserError naming `flag`, the text and the accepted syntax.
std::vector<std::string> parse_value_list(const std::string& flag, const std::string& text,
                                          ValueType type);

enum class AxisKind { Machine, Algo, RoiSize };

// One parameter of the sweep and its values (text, as on a command line).
struct Axis {
    std::string name;  // column name: pes, clock_mhz, mem_bytes, roi_size, D, mode, ring_hop, ...
    std::string flag;  // as the user gave it: "--pes", "--set ring_hop", "--roi-size"
    AxisKind kind = AxisKind::Algo;
    std::vector<std::string> values;
};

// Builds an axis from a flag's text: parses the list and checks every value
// (range, syntax) on its own; UserError names the flag. `name` is a machine
// parameter name (MachineConfig::set), an algorithm flag name (D, km, kb,
// gb, Wo, Wd, mode) or roi_size.
Axis make_axis(const std::string& name, const std::string& flag, const std::string& text);

// A value of an axis on a numeric plot axis (NaN if it is not a number).
double numeric_value(const Axis& a, const std::string& v);

// Where the images come from.
struct Input {
    std::string left, right;  // empty: the built-in synthetic scene, generated at the ROI size
    uint64_t seed = 1;        // synthetic scene seed
    cv::Mat L, R;             // loaded images (left/right given)
    // ROI with images: fixed_roi (x0,y0,w,h) if has_fixed_roi, else the
    // roi_size axis centred in the image, else the whole image.
    bool has_fixed_roi = false;
    int roi_x0 = 0, roi_y0 = 0, roi_w = 0, roi_h = 0;
    std::string describe() const;
};

struct Spec {
    std::string command = "sweep";  // names the work folder and the messages
    std::vector<Axis> fixed;        // one value each
    std::vector<Axis> swept;        // two or more values each, in command-line order
    // Points as value indices into swept[i].values; empty = the full product.
    std::vector<std::vector<size_t>> points;
    AlgoFlags algo;  // seed-col, seed-disp, vote, frame, fill (D..Wd, mode come from the axes)
    std::string model = "tlm";
    unsigned jobs = 0;  // 0: one per core
    bool dry_run = false;
    Input input;
};

// Largest number of points a sweep accepts.
inline constexpr size_t kMaxPoints = 10000;

// The full cartesian product (refused beyond kMaxPoints with a message that
// names the axes and their sizes).
std::vector<std::vector<size_t>> product(const std::vector<Axis>& swept);

enum class Status {
    Ok,           // ran, bit-exact with the golden
    Mismatch,     // ran, the map differs from the golden
    DoesNotFit,   // the memory plan does not fit the point's machine (an answer)
    CannotRun,    // invalid combination or a firmware limit (an answer)
    Planned,      // --dry-run: fits, not run
    Error,        // the child failed (fault, crash, no report)
    Interrupted,  // the child was stopped by the Ctrl-C
};
const char* status_name(Status s);

struct Row {
    std::vector<std::string> values;  // per swept axis
    Status status = Status::Error;
    std::string message;
    bool ran = false;  // cycles, modeled_ms, phases are valid
    uint64_t cycles = 0;
    double modeled_ms = 0, fps = 0, wall_s = 0;
    bool bit_exact = false;
    int64_t local_bytes = -1;  // local memory needed per PE (-1: not plannable)
    int64_t ext_bytes = -1;    // external memory needed per PE
    std::vector<std::pair<std::string, uint64_t>> phases;
    std::string command;  // the child's command line (empty if not run)
};

struct Result {
    std::vector<Row> rows;  // finished points, in point order
    size_t total = 0;       // points of the sweep
    size_t not_run = 0;     // points not started because of the interrupt
    bool interrupted = false;
    std::vector<std::string> phase_names;  // in program order
    double wall_s = 0;
    std::string logs;  // folder of kept child logs (errors), empty if removed
    size_t count(Status s) const;
    // 130 if interrupted, else 5 if a row is an error, else 1 if a point is
    // not bit-exact, else 0.
    int exit_code() const;
};

// Runs the sweep: prints the header, one row per point (in point order, as
// they finish) through a Progress bar (unit "points"), and a summary line.
// Stops launching on Ctrl-C (interrupt::install() is called here).
Result run(const Spec& spec);

// CSV: one column per swept axis, cycles, modeled_ms, fps, status, message,
// bit_exact, wall_s, local_bytes_per_pe, ext_bytes_per_pe, one column per
// phase (phase_<name>). An interrupted sweep ends with one row of status
// "sweep-interrupted" saying how many points did not run.
std::string to_csv(const Spec& spec, const Result& r);
// JSON: the same rows, the swept and fixed parameters, the summary.
nlohmann::json to_json(const Spec& spec, const Result& r);

// CSV field quoting (RFC 4180).
std::string csv_field(const std::string& s);
// "%.3f"-style formatting into a string.
std::string fmt(const char* f, double v);

}  // namespace imapsim::sweep
