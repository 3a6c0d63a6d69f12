// Running imapsim itself as a child process (imap/engine/process.hpp holds
// the process helpers; this is the one the bench command uses).
#pragma once

#include <string>
#include <vector>

#include "imap/engine/process.hpp"

namespace imapsim {

using imap::engine::child_log_message;
using imap::engine::command_line;
using imap::engine::self_exe;
using imap::engine::shell_quote;

struct ChildResult {
    int exit_code = -1;  // -1: did not exit normally (signal)
    std::string output;  // stdout and stderr together
};

// Runs `self_exe() args...` and waits for it; output is captured.
ChildResult run_self(const std::vector<std::string>& args);

}  // namespace imapsim
