// Running the imapsim binary from a test: exit code and output.
#pragma once

#include <sys/wait.h>

#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <string>

namespace clitest {

struct Result {
    int code = -1;    // exit code, -1 when killed by a signal
    std::string out;  // stdout and stderr together
};

// Runs `exe args` through the shell and waits for it; with `cwd`, in that
// folder (relative file names in `args` are taken from there).
inline Result run_program(const std::string& exe, const std::string& args,
                          const std::string& cwd = "") {
    const std::string cmd =
        (cwd.empty() ? std::string() : "cd '" + cwd + "' && ") + "'" + exe + "' " + args + " 2>&1";
    Result r;
    FILE* p = popen(cmd.c_str(), "r");
    BOOST_REQUIRE(p != nullptr);
    char buf[4096];
    size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    const int st = pclose(p);
    r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

// The same for this build's imapsim.
inline Result run(const std::string& args, const std::string& cwd = "") {
    return run_program(IMAPSIM_EXE, args, cwd);
}

}  // namespace clitest
