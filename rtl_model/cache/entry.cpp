// One configuration of the design as a shared library of the RTL cache
// (docs/rtl.md, "Any configuration on demand"): built at run time by
// imapsim (cosim/src/rtl_cache.cpp) with this folder's CMakeLists.txt and
// loaded with dlopen. Exports only the three functions of entry_abi.hpp;
// the DPI imports of the verilated testbench call the loading process's
// implementations through the table it hands over.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include "Vimap_entry.h"
#include "Vimap_entry__Dpi.h"
#pragma GCC diagnostic pop
#include "entry_abi.hpp"
#include "model_impl.hpp"

namespace {
imap::rtl::detail::DpiTable g_dpi{};
}

extern "C" {

__attribute__((visibility("default"))) void imap_rtl_entry_info(imap::rtl::detail::EntryInfo* i) {
    i->abi = imap::rtl::detail::kEntryAbi;
    i->pes = IMAP_ENTRY_PES;
    i->mem_bytes = IMAP_ENTRY_MEM;
    i->ext_bytes = IMAP_ENTRY_EXT;
    i->trace = IMAP_ENTRY_TRACE;
    i->mutants = IMAP_ENTRY_MUTANTS;
}

__attribute__((visibility("default"))) void imap_rtl_entry_dpi(
    const imap::rtl::detail::DpiTable* t) {
    g_dpi = *t;
}

__attribute__((visibility("default"))) imap::rtl::detail::Model* imap_rtl_entry_make(
    const char* name) {
    return new imap::rtl::detail::ModelImpl<Vimap_entry, IMAP_ENTRY_TRACE>(name);
}

// The DPI imports (imap_dpi_pkg.sv), forwarded.
void imap_rtl_retire(long long index, int pc, long long word, long long cyc, long long cyc_end,
                     int phase, int creg, int cval, int msp, int csp, int active, svBit halted) {
    if (g_dpi.retire)
        g_dpi.retire(index, pc, word, cyc, cyc_end, phase, creg, cval, msp, csp, active, halted);
}
void imap_rtl_param_write(int addr, int value) {
    if (g_dpi.param_write) g_dpi.param_write(addr, value);
}
void imap_rtl_fault(int code, int pc, long long cyc, int pe, long long addr) {
    if (g_dpi.fault) g_dpi.fault(code, pc, cyc, pe, addr);
}
void imap_rtl_assert(const char* name, int pe) {
    if (g_dpi.assert_fail) g_dpi.assert_fail(name, pe);
}
int imap_rtl_vid_check(int dir_out, int port, int y) {
    return g_dpi.vid_check ? g_dpi.vid_check(dir_out, port, y) : 1;
}
int imap_rtl_vid_pixel(int port, int y, int x) {
    return g_dpi.vid_pixel ? g_dpi.vid_pixel(port, y, x) : 0;
}
long long imap_rtl_vid_ready(int port, int y, int x) {
    return g_dpi.vid_ready ? g_dpi.vid_ready(port, y, x) : 0;
}
void imap_rtl_vid_put(int port, int y, int x, int val) {
    if (g_dpi.vid_put) g_dpi.vid_put(port, y, x, val);
}

}  // extern "C"
