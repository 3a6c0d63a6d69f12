#include "child.hpp"

#include <stdexcept>

namespace imapsim {

ChildResult run_self(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {self_exe()};
    argv.insert(argv.end(), args.begin(), args.end());
    const imap::engine::Captured c = imap::engine::run_capture(argv);
    if (!c.started) throw std::runtime_error("cannot start " + argv[0]);
    return {c.exit_code, c.output};
}

}  // namespace imapsim
