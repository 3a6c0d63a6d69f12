#include "interrupt.hpp"

#include <signal.h>

#include <atomic>

namespace imapsim::interrupt {

namespace {
std::atomic<int> g_signal{0};

extern "C" void on_signal(int sig) {
    g_signal.store(sig);
    // The next one is not caught: a second Ctrl-C ends the process.
    struct sigaction sa {};
    sa.sa_handler = SIG_DFL;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}
}  // namespace

void install() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool requested() {
    return g_signal.load() != 0;
}

int signal_number() {
    return g_signal.load();
}

}  // namespace imapsim::interrupt
