// Running imapsim itself as a child process: SystemC elaborates once per
// process, so every model run that needs its own elaboration is a child.
#pragma once

#include <string>
#include <vector>

namespace imapsim {

struct ChildResult {
    int exit_code = -1;  // -1: did not exit normally (signal)
    std::string output;  // stdout and stderr together
};

// Path of the running imapsim binary.
std::string self_exe();

// Runs `self_exe() args...` and waits for it; output is captured.
ChildResult run_self(const std::vector<std::string>& args);

}  // namespace imapsim
