// The request of `imapsim exec` as its flags give it, and its checks before
// the run (a bad flag never costs a run): the machine, the model, the
// parameters, the PE dump, the outputs and the video inputs, with the
// messages imapsim prints. Reading the program and running it is exec.hpp's.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "imap/engine/exec.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/models.hpp"

namespace imap::engine::exec {

// The flags of imapsim exec, as given.
struct Request {
    std::string program, left, right, out_left, out_size, report;
    std::string dump_pes, dump_mem;
    std::string model;
    std::vector<std::string> params, defines;
    MachineSettings machine;
    WaveOptions waves;
};

// The checked request: the machine, the inputs and what to dump at the end.
struct Checked {
    isa::MachineConfig cfg;
    Inputs in;
    std::vector<int> dump_pes;
    std::pair<uint32_t, uint32_t> mem_range{0, 0};
};
// Checks every flag but the program (engine::Error, exit 2) and loads the
// images; `check_waves` (models.hpp's check_wave_outputs of r.waves) is
// called after the output files, before the images are read.
Checked check(const Request& r, const std::function<void()>& check_waves);

}  // namespace imap::engine::exec
