// The DPI-C imports of the testbench (rtl_model/verif/imap_dpi_pkg.sv): the
// trace port and the fault report (the CP's retire monitor) and the video
// line port (the board model). One bench runs at a
// time in a process; its calls go to it.
#include "bench.hpp"
#include "rtl_cache_impl.hpp"
#include "svdpi.h"

namespace imap::rtl::detail {
namespace {
Bench* g_bench = nullptr;
}
void set_dpi_bench(Bench* b) {
    g_bench = b;
}
}  // namespace imap::rtl::detail

using imap::rtl::detail::g_bench;

extern "C" {

void imap_rtl_retire(long long index, int pc, long long word, long long cyc, long long cyc_end,
                     int phase, int creg, int cval, int msp, int csp, int active, svBit halted) {
    if (!g_bench) return;
    imap::rtl::detail::RetireRecord r;
    r.index = static_cast<uint64_t>(index);
    r.pc = static_cast<uint32_t>(pc);
    r.word = static_cast<uint64_t>(word);
    r.cycle = static_cast<uint64_t>(cyc);
    r.cycle_end = static_cast<uint64_t>(cyc_end);
    r.phase = static_cast<uint32_t>(phase);
    r.creg = creg;
    r.cval = static_cast<uint32_t>(cval);
    r.msp = msp;
    r.csp = csp;
    r.active = active;
    r.halted = halted != 0;
    g_bench->dpi_retire(r);
}

void imap_rtl_param_write(int addr, int value) {
    if (g_bench) g_bench->dpi_param(addr, static_cast<uint32_t>(value));
}

void imap_rtl_fault(int code, int pc, long long cyc, int pe, long long addr) {
    if (!g_bench) return;
    imap::rtl::detail::FaultRecord f;
    f.valid = true;
    f.code = code;
    f.pc = static_cast<uint32_t>(pc);
    f.cycle = static_cast<uint64_t>(cyc);
    f.pe = pe == -1 ? -1 : static_cast<int64_t>(static_cast<uint32_t>(pe));
    f.address = static_cast<int64_t>(addr);
    g_bench->dpi_fault(f);
}

void imap_rtl_assert(const char* name, int pe) {
    if (g_bench) g_bench->dpi_assert(name, pe);
}

int imap_rtl_vid_check(int dir_out, int port, int y) {
    return g_bench ? g_bench->dpi_vid_check(dir_out, port, y) : 1;
}

int imap_rtl_vid_pixel(int port, int y, int x) {
    return g_bench ? g_bench->dpi_vid_pixel(port, y, x) : 0;
}

long long imap_rtl_vid_ready(int port, int y, int x) {
    return g_bench ? static_cast<long long>(g_bench->dpi_vid_ready(port, y, x)) : 0;
}

void imap_rtl_vid_put(int port, int y, int x, int val) {
    if (g_bench) g_bench->dpi_vid_put(port, y, x, val);
}

}  // extern "C"

namespace imap::rtl::detail {
const DpiTable& host_dpi_table() {
    static const DpiTable t{&imap_rtl_retire,    &imap_rtl_param_write, &imap_rtl_fault,
                            &imap_rtl_assert,    &imap_rtl_vid_check,   &imap_rtl_vid_pixel,
                            &imap_rtl_vid_ready, &imap_rtl_vid_put};
    return t;
}
}  // namespace imap::rtl::detail
