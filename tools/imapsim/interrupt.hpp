// Ctrl-C handling of the long-running subcommands (stream, sweep): the first
// SIGINT / SIGTERM only sets a flag, checked between items, so that the
// command stops starting new work, writes its partial results (a valid log
// listing what finished) and exits with kExitInterrupted; a second signal
// ends the process at once (default action).
#pragma once

namespace imapsim::interrupt {

// Installs the handlers (idempotent).
void install();
// True once a SIGINT or SIGTERM arrived after install().
bool requested();
// The signal number that was received (0 if none).
int signal_number();

}  // namespace imapsim::interrupt
