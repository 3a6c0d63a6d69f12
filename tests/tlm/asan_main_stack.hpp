// SystemC 2.3.4 (the Debian package) tells AddressSanitizer about every
// coroutine switch made when a thread yields (sc_cor_pkg_qt::yield calls
// __sanitizer_start/finish_switch_fiber), but not about the switch made
// when a thread ends (sc_cor_pkg_qt::abort). After the CP thread has ended,
// ASan therefore still takes the ended thread's stack for the current one;
// when an exception is then thrown on the main stack (run_tlm rethrows the
// machine's Fault there), ASan skips the stack cleanup it does before
// unwinding ("WARNING: ASan is ignoring requested __asan_handle_no_return",
// see google/sanitizers issue 189), the unwound frames stay poisoned and the
// next check in them reports a false stack-buffer-overflow.
//
// Instantiated next to the model, this module re-declares the main thread's
// stack to ASan when the simulation ends (end_of_simulation runs on the
// main stack, after the threads, before sc_start returns). Without ASan it
// does nothing. docs/testing.md, "Sanitizers".
#pragma once

#include <pthread.h>

#include <systemc>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define IMAP_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/common_interface_defs.h>
#define IMAP_TEST_ASAN 1
#endif
#endif

namespace tlmtest {

// Declares the calling thread's own stack as the current one to ASan.
inline void asan_declare_main_stack() {
#ifdef IMAP_TEST_ASAN
    pthread_attr_t a;
    if (pthread_getattr_np(pthread_self(), &a) != 0) return;
    void* bottom = nullptr;
    size_t size = 0;
    pthread_attr_getstack(&a, &bottom, &size);
    pthread_attr_destroy(&a);
    void* fake_stack = nullptr;
    __sanitizer_start_switch_fiber(&fake_stack, bottom, size);
    __sanitizer_finish_switch_fiber(fake_stack, nullptr, nullptr);
#endif
}

struct AsanMainStack : sc_core::sc_module {
    explicit AsanMainStack(sc_core::sc_module_name n = "asan_main_stack") : sc_module(n) {}
    void end_of_simulation() override { asan_declare_main_stack(); }
};

}  // namespace tlmtest
