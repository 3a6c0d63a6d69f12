#include "child.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace imapsim {

std::string self_exe() {
    return std::filesystem::read_symlink("/proc/self/exe").string();
}

ChildResult run_self(const std::vector<std::string>& args) {
    char tmpl[] = "/tmp/imapsim-child-XXXXXX";
    const int fd = mkstemp(tmpl);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for a child's output");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fd, 1);
    posix_spawn_file_actions_adddup2(&fa, fd, 2);
    const std::string exe = self_exe();
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(exe.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fd);
    ChildResult r;
    if (rc == 0) {
        int st = 0;
        while (waitpid(pid, &st, 0) < 0) {
        }
        r.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    }
    std::ifstream in(tmpl);
    std::ostringstream os;
    os << in.rdbuf();
    r.output = os.str();
    std::remove(tmpl);
    if (rc != 0) throw std::runtime_error("cannot start " + exe);
    return r;
}

}  // namespace imapsim
