#include "imap/engine/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace imap::engine {

namespace fs = std::filesystem;

std::string self_exe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find the running executable (/proc/self/exe)");
    return p.string();
}

Captured run_capture(const std::vector<std::string>& argv, double timeout_s) {
    Captured r;
    if (argv.empty()) return r;
    char tmpl[] = "/tmp/imap-engine-capture-XXXXXX";
    const int fd = ::mkstemp(tmpl);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for a command's output");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, fd, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&fa, fd, STDERR_FILENO);
    std::vector<char*> av;
    for (const std::string& a : argv) av.push_back(const_cast<char*>(a.c_str()));
    av.push_back(nullptr);
    pid_t pid = -1;
    const int rc = ::posix_spawnp(&pid, av[0], &fa, nullptr, av.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    ::close(fd);
    if (rc == 0) {
        r.started = true;
        const auto t0 = std::chrono::steady_clock::now();
        int st = 0;
        while (true) {
            const pid_t w = ::waitpid(pid, &st, timeout_s > 0 ? WNOHANG : 0);
            if (w == pid) break;
            if (w < 0 && errno != EINTR) break;
            if (w == 0) {
                if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
                    timeout_s) {
                    ::kill(pid, SIGKILL);
                    ::waitpid(pid, &st, 0);
                    break;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            }
        }
        if (WIFEXITED(st)) {
            r.exit_code = WEXITSTATUS(st);
        } else if (WIFSIGNALED(st)) {
            r.signal = WTERMSIG(st);
        }
    }
    std::ifstream in(tmpl);
    std::ostringstream os;
    os << in.rdbuf();
    r.output = os.str();
    std::remove(tmpl);
    if (rc != 0) r.output += std::string("cannot start ") + argv[0] + ": " + std::strerror(rc);
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
    const int rc = ::posix_spawn(&pid, av[0], &fa, nullptr, av.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        std::ofstream(log, std::ios::app)
            << "imapsim: error: cannot start " << argv[0] << ": " << std::strerror(rc) << "\n";
        return -1;
    }
    return pid;
}

bool on_path(const std::string& name) {
    if (name.empty()) return false;
    if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0;
    const char* path = std::getenv("PATH");
    std::stringstream ss(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        const std::string p = (dir.empty() ? std::string(".") : dir) + "/" + name;
        struct stat st {};
        if (::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0)
            return true;
    }
    return false;
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

std::string log_tail(const std::string& path, size_t max_lines) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
    std::string out;
    for (size_t i = lines.size() > max_lines ? lines.size() - max_lines : 0; i < lines.size(); ++i)
        out += lines[i] + "\n";
    return out;
}

std::string shell_quote(const std::string& s) {
    if (!s.empty() && s.find_first_of(" \t\n'\"\\$`*?;&|<>()#~{}[]!") == std::string::npos)
        return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string command_line(const std::vector<std::string>& argv) {
    std::string s;
    for (const auto& a : argv) s += (s.empty() ? "" : " ") + shell_quote(a);
    return s;
}

std::string signal_name(int sig) {
    const char* s = ::strsignal(sig);
    return s ? s : ("signal " + std::to_string(sig));
}

}  // namespace imap::engine
