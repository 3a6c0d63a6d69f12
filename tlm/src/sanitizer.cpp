#include "imap/tlm/sanitizer.hpp"

#include <pthread.h>

#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)
#define IMAP_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IMAP_ASAN 1
#endif
#endif
#ifdef IMAP_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace imap::tlm {

void declare_main_stack_to_sanitizer() {
#ifdef IMAP_ASAN
    // The main thread's stack never moves: look it up once (for the main
    // thread, pthread_getattr_np reads /proc/self/maps), so that a method
    // process may call this on every activation.
    static void* bottom = nullptr;
    static size_t size = 0;
    if (size == 0) {
        pthread_attr_t a;
        if (pthread_getattr_np(pthread_self(), &a) != 0) return;
        pthread_attr_getstack(&a, &bottom, &size);
        pthread_attr_destroy(&a);
    }
    void* fake_stack = nullptr;
    __sanitizer_start_switch_fiber(&fake_stack, bottom, size);
    __sanitizer_finish_switch_fiber(fake_stack, nullptr, nullptr);
#endif
}

}  // namespace imap::tlm
