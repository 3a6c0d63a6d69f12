// Shared pieces of the engine tests: a temporary folder per test program.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace enginetest {

inline std::filesystem::path tmpdir() {
    static const std::filesystem::path d = [] {
        std::filesystem::path p = std::filesystem::temp_directory_path() /
                                  ("imap-engine-test-" + std::to_string(::getpid()));
        std::filesystem::create_directories(p);
        return p;
    }();
    return d;
}

// Removes the folder when the test program ends (BOOST_TEST_GLOBAL_FIXTURE).
struct Cleanup {
    ~Cleanup() {
        std::error_code ec;
        std::filesystem::remove_all(tmpdir(), ec);
    }
};

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace enginetest
