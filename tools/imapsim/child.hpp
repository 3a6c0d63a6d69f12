// Running imapsim itself as a child process: SystemC elaborates once per
// process, so every model run that needs its own elaboration is a child.
#pragma once

#include <sys/types.h>

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

// Starts argv (argv[0] = the program's path) without waiting: standard input
// from /dev/null, standard output and error into the file `log`. Returns the
// pid, or -1 when the process cannot be started (the reason is appended to
// `log` as an "imapsim: error: ..." line).
pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log);

// The line of a child's log that says what went wrong: its first
// "imapsim: ..." line without that prefix (e.g. "error: machine fault: ..."),
// else its last non-empty line, else "".
std::string child_log_message(const std::string& log);

// A word quoted for a POSIX shell (unchanged when it needs no quotes), and a
// whole command line of such words (for "rerun with" hints in reports).
std::string shell_quote(const std::string& s);
std::string command_line(const std::vector<std::string>& argv);

}  // namespace imapsim
