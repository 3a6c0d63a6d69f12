// The GTKWave view of the design's waves (docs/rtl.md, "Waves"): the
// clock and the machine cycle counter, the CP (fetch, decode, execute
// sequencer, the control word it broadcasts, its registers), the mask bus
// and ring links of the array, the transfer engine and video port, and
// the datapath of each traced PE.
#include "waves_view.hpp"

#include <filesystem>

#include "imap/waves/gtkw.hpp"

namespace imap::rtl::detail {

void write_gtkw(const WavesView& v) {
    using imap::waves::Format;
    const std::string dump = std::filesystem::path(v.waves_path).filename().string();
    imap::waves::GtkwSave g(dump);
    g.set_view(v.start_time, v.span_time);
    // the chip (imap_tb.u_chip: its ports include the board interface)
    const std::string t = v.top + ".imap_tb.u_chip.";
    const std::string cp = t + "u_cp.", arr = t + "u_array.";
    auto sig = [&](const std::string& n, Format f, const std::string& alias = "") {
        g.add_signal(n, f, alias);
    };
    auto vec = [](const std::string& n, int msb) { return n + "[" + std::to_string(msb) + ":0]"; };

    g.begin_group("clock and machine cycle");
    sig(t + "clk", Format::Bin);
    sig(t + "rst_n", Format::Bin);
    sig(vec(cp + "mcycle", 63), Format::Dec, "mcycle");
    sig(cp + "count_now", Format::Bin, "machine cycle");
    sig(cp + "halted", Format::Bin);
    sig(cp + "faulted", Format::Bin);
    g.end_group();

    g.begin_group("CP fetch / decode");
    sig(vec(cp + "f_pc", 24), Format::Dec, "F pc");
    sig(cp + "d_v", Format::Bin, "D valid");
    sig(vec(cp + "d_pc", 24), Format::Dec, "D pc");
    sig(vec(cp + "d_ir", 63), Format::Hex, "D word");
    sig(cp + "d_adv", Format::Bin, "D -> X");
    sig(cp + "d_taken", Format::Bin, "taken branch");
    g.end_group();

    g.begin_group("CP execute sequencer");
    sig(cp + "x_v", Format::Bin, "X valid");
    sig(vec(cp + "x_pc", 24), Format::Dec, "X pc");
    sig(vec(cp + "x_op", 7), Format::Hex, "X opcode");
    sig(vec(cp + "x_kind", 3), Format::Dec, "X kind (cost class)");
    sig(cp + "x_first", Format::Bin, "first cycle");
    sig(cp + "x_last", Format::Bin, "last cycle");
    sig(cp + "x_commit", Format::Bin, "commit");
    sig(vec(cp + "x_cnt", 31), Format::Dec, "cycles left");
    sig(vec(cp + "bub", 31), Format::Dec, "refill bubbles");
    sig(vec(cp + "phase_q", 15), Format::Dec, "phase");
    g.end_group();

    g.begin_group("control word (to every PE)");
    for (const char* f : {"act", "commit", "step", "first", "rd_we", "c_we", "t_we", "bimm", "up"})
        sig(cp + "cw." + f, Format::Bin, std::string("cw.") + f);
    sig(vec(cp + "cw.fn", 4), Format::Dec, "cw.fn");
    sig(vec(cp + "cw.rd", 5), Format::Dec, "cw.rd");
    sig(vec(cp + "cw.ra", 5), Format::Dec, "cw.ra");
    sig(vec(cp + "cw.rb", 5), Format::Dec, "cw.rb");
    sig(vec(cp + "cw.imm", 7), Format::Hex, "cw.imm");
    sig(vec(cp + "cw.cmp", 2), Format::Dec, "cw.cmp");
    sig(vec(cp + "cw.mask", 2), Format::Dec, "cw.mask");
    sig(vec(cp + "cw.row", 1), Format::Dec, "cw.row");
    sig(vec(cp + "cw.nrows", 3), Format::Dec, "cw.nrows");
    sig(cp + "cw.rowm", Format::Bin, "cw.rowm");
    sig(vec(cp + "cw.pre", 1), Format::Dec, "cw.pre");
    sig(vec(cp + "cwx.addr", 19), Format::Dec, "cwx.addr");
    sig(vec(cp + "cw_pre", 31), Format::Hex, "cw_pre");
    g.end_group();

    g.begin_group("CP registers", true);
    for (int i = 0; i < 16; ++i)
        sig(vec(cp + "creg[" + std::to_string(i) + "]", 31), Format::Hex, "c" + std::to_string(i));
    sig(vec(cp + "csp", 8), Format::Dec, "return stack depth");
    g.end_group();

    g.begin_group("mask bus");
    sig(vec(cp + "msp", 8), Format::Dec, "mask stack depth");
    sig(arr + "red_status", Format::Bin, "rany/rall");
    sig(arr + "any_t", Format::Bin);
    sig(arr + "all_t", Format::Bin);
    sig(arr + "red_memx", Format::Bin, "ldx/stx check");
    sig(arr + "memx_bad", Format::Bin);
    sig(vec(arr + "memx_pe", 15), Format::Dec);
    g.end_group();

    // The ring links are an unpacked array of P bytes: Verilator traces
    // arrays of at most 32 elements (--trace-max-array), so above that they
    // are not in the waves; each PE's ring register (its group) carries the
    // same byte one clock later.
    if (v.pes_total <= kTraceMaxArray) {
        g.begin_group("ring links");
        for (int p : v.pes)
            sig(vec(arr + "ring[" + std::to_string(p) + "]", 7), Format::Hex,
                "link PE " + std::to_string(p));
        g.end_group();
    }

    g.begin_group("transfer engine / video port", true);
    sig(cp + "x_setup", Format::Bin, "setup");
    sig(vec(cp + "x_brem", 47), Format::Dec, "bytes left");
    sig(vec(cp + "x_rdone", 31), Format::Dec, "rows done");
    sig(t + "xe_pf", Format::Bin);
    sig(vec(t + "xe_prow", 31), Format::Dec);
    sig(t + "xe_wr", Format::Bin);
    sig(vec(t + "xe_wrow", 31), Format::Dec);
    sig(vec(t + "xe_n", 3), Format::Dec);
    sig(t + "vid_open", Format::Bin);
    sig(t + "vid_put", Format::Bin);
    g.end_group();

    bool first = true;
    for (int p : v.pes) {
        const std::string pe = arr + "g_pe[" + std::to_string(p) + "].u_pe.";
        g.begin_group("PE " + std::to_string(p), !first);
        sig(vec(pe + "st_q", 2), Format::Bin, "oob/T/M");
        sig(pe + "c_q", Format::Bin, "C");
        sig(vec(pe + "a", 7), Format::Hex, "operand a");
        sig(vec(pe + "b", 7), Format::Hex, "operand b");
        sig(vec(pe + "res", 7), Format::Hex, "result");
        sig(pe + "wb", Format::Bin, "write-back");
        sig(vec(pe + "ring_q", 7), Format::Hex, "ring register");
        sig(pe + "mwe", Format::Bin, "mem write");
        sig(vec(pe + "ma", v.addr_bits - 1), Format::Dec, "mem address");
        sig(vec(pe + "mval", 7), Format::Hex, "mem data");
        sig(vec(pe + "xaddr_q", v.addr_bits - 1), Format::Dec, "per-PE address");
        sig(vec(pe + "mstk", v.mask_depth - 1), Format::Bin, "mask stack");
        g.begin_group("PE " + std::to_string(p) + " registers", !first);
        for (int r = 0; r < v.nregs; ++r)
            sig(vec(pe + "regs[" + std::to_string(r) + "]", 7), Format::Hex,
                "r" + std::to_string(r));
        g.end_group();
        g.end_group();
        first = false;
    }
    g.write(v.gtkw_path);
}

}  // namespace imap::rtl::detail
