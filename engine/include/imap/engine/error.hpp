// Errors of the engine library and the exit codes it shares with imapsim
// (docs/errors.md). An engine::Error is a user-facing one-line message (what,
// where, the allowed range) with the exit code the command ends with.
#pragma once

#include <stdexcept>
#include <string>

namespace imap::engine {

// Exit codes of the commands built on the engine (the same numbers as imapsim's).
enum Exit : int {
    kExitOk = 0,
    kExitMismatch = 1,       // ran, but a model's output differs from the golden / a case failed
    kExitInput = 2,          // bad flags, input files or environment; nothing written
    kExitFault = 3,          // the modeled machine faulted
    kExitInternal = 4,       // unexpected internal error
    kExitItemErrors = 5,     // ran to the end, but some points failed or none could run
    kExitInterrupted = 130,  // stopped by SIGINT / SIGTERM; partial results written
};

class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what, int code = kExitInput)
        : std::runtime_error(what), code_(code) {}
    int code() const { return code_; }

  private:
    int code_;
};

}  // namespace imap::engine
