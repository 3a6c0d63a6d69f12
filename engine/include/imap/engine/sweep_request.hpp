// The request of `imapsim sweep` as its flags give it: the axes in
// command-line order, the algorithm parameters that are not axes, the input
// images and the outputs; building the engine's Spec from it (the checks
// and messages imapsim prints) and writing the outputs of a finished sweep.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "imap/engine/flag_values.hpp"
#include "imap/engine/sweep.hpp"

namespace imap::engine::sweep {

struct Request {
    // Axis flags in command-line order: ("--pes", "8..64*2"), ("--set",
    // "ring_hop=1,2"), ("--camera", "ideal,ntsc"), ... A flag given twice
    // appears twice (the same flag again is ignored, --set excepted).
    std::vector<std::pair<std::string, std::string>> axes;
    AlgoSettings algo;  // the algorithm flags (its D, km, ... are axes)
    std::string model = "tlm";
    bool dry_run = false;
    std::string left, right, roi_size;
    uint64_t seed = 1;
    bool plot = false;  // --plot given (needs a swept axis)
    std::string x;      // --x
};

// The Spec of a new sweep: its axes checked and split into fixed and swept,
// the base parameters and the input images checked (engine::Error, exit 2).
Spec build_spec(const Request& r);

// The index of --x in `swept` (0 when empty); engine::Error naming the axes.
size_t x_index(const std::vector<Axis>& swept, const std::string& x);

// --plot-size WxH: engine::Error unless W in 300..4000, H in 200..4000.
void check_plot_size(const std::string& s);

// The outputs of a finished sweep.
struct Outputs {
    std::string csv, json, plot, plot_size = "900x600";
    bool pareto = false;
};
// Writes them; returns the lines to print ("  csv -> FILE", ...) and in
// `warning` the warning when the plot has no point to draw ("" otherwise).
std::vector<std::string> write_outputs(const Outputs& o, const Plan& plan, const Result& r,
                                       size_t xi, std::string* warning);

}  // namespace imap::engine::sweep
