// AddressSanitizer and SystemC's coroutines.
//
// SystemC 2.3.4 (the Debian package) tells ASan about every coroutine switch
// made when a thread yields (__sanitizer_start/finish_switch_fiber), but not
// about the switch back to the main stack made when a thread ends. After a
// simulation whose threads ended, ASan still takes an ended thread's stack
// for the current one; an exception thrown afterwards on the main stack (a
// machine fault rethrown by run_tlm, a user error) then skips ASan's stack
// cleanup ("ASan is ignoring requested __asan_handle_no_return", google/
// sanitizers issue 189) and the next check in the unwound frames reports a
// false stack-buffer-overflow. Every runner calls this right after
// sc_start() returns: it re-declares the main thread's stack to ASan. A
// method process that may throw inside the simulation (it runs on the main
// stack, after threads have yielded or ended) calls it on entry: the
// RTL bench's clock, whose reference model raises the machine's faults.
// Without ASan it does nothing; with ASan it costs two calls once the
// stack is known.
#pragma once

namespace imap::tlm {

void declare_main_stack_to_sanitizer();

}  // namespace imap::tlm
