#include "child.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
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

pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log) {
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> av;
    for (const std::string& a : argv) av.push_back(const_cast<char*>(a.c_str()));
    av.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, av[0], &fa, nullptr, av.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        std::ofstream(log, std::ios::app)
            << "imapsim: error: cannot start " << argv[0] << ": " << std::strerror(rc) << "\n";
        return -1;
    }
    return pid;
}

std::string shell_quote(const std::string& s) {
    if (!s.empty() && s.find_first_of(" \t\n'\"\\$`*?;&|<>()") == std::string::npos) return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string command_line(const std::vector<std::string>& argv) {
    std::string s;
    for (const auto& a : argv) s += (s.empty() ? "" : " ") + shell_quote(a);
    return s;
}

std::string child_log_message(const std::string& log) {
    std::ifstream in(log);
    std::string line, last, msg;
    while (std::getline(in, line)) {
        if (line.rfind("imapsim: ", 0) == 0 && msg.empty()) msg = line.substr(9);
        if (!line.empty()) last = line;
    }
    return msg.empty() ? last : msg;
}

}  // namespace imapsim
