// Child processes: imapsim runs every model elaboration in its own process
// (SystemC elaborates once per process), and the Slurm executor drives the
// batch system's commands (sbatch, squeue, scancel, sacct).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace imap::engine {

// Path of the running executable (/proc/self/exe).
std::string self_exe();

struct Captured {
    int exit_code = -1;  // -1: did not exit normally (signal) or did not start
    int signal = 0;      // the signal that ended it
    bool started = false;
    std::string output;  // stdout and stderr together
};

// Runs argv (argv[0] a path, or a name looked up on PATH) to completion with
// standard input from /dev/null and captures its output. With timeout_s > 0 the
// process is killed (SIGKILL) after that long (exit_code -1, signal 9).
Captured run_capture(const std::vector<std::string>& argv, double timeout_s = 0);

// Starts argv (argv[0] = the program's path) without waiting: standard input
// from /dev/null, standard output and error into the file `log`. Returns the
// pid, or -1 when the process cannot be started (the reason is appended to
// `log` as an "imapsim: error: ..." line).
pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log);

// True when `name` is an executable file on PATH (or a path to one).
bool on_path(const std::string& name);

// The line of a child's log that says what went wrong: its first
// "imapsim: ..." line without that prefix (e.g. "error: machine fault: ..."),
// else its last non-empty line, else "".
std::string child_log_message(const std::string& log);

// The last `max_lines` lines of a text file ("" if it cannot be read).
std::string log_tail(const std::string& path, size_t max_lines);

// A word quoted for a POSIX shell (unchanged when it needs no quotes), and a
// whole command line of such words (for "rerun with" hints in reports).
std::string shell_quote(const std::string& s);
std::string command_line(const std::vector<std::string>& argv);

// "Segmentation fault" for 11, ...
std::string signal_name(int sig);

}  // namespace imap::engine
