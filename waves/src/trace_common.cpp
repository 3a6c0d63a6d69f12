#include "imap/waves/trace_common.hpp"

#include <algorithm>
#include <cstdio>

#include "imap/isa/assembler.hpp"
#include "imap/waves/isa_trace.hpp"

namespace imap::waves::detail {

int bits_for(uint64_t max_value) {
    int b = 1;
    while (b < 64 && (max_value >> b) != 0) ++b;
    return b;
}

std::string pe_scope(int pe, int pes) {
    const int digits = static_cast<int>(std::to_string(std::max(pes - 1, 0)).size());
    std::string n = std::to_string(pe);
    return "pe" +
           std::string(static_cast<size_t>(std::max(0, digits - static_cast<int>(n.size()))), '0') +
           n;
}

std::string gtkw_path_of(const std::string& vcd) {
    const size_t slash = vcd.find_last_of('/');
    const size_t dot = vcd.find_last_of('.');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
        return vcd.substr(0, dot) + ".gtkw";
    return vcd + ".gtkw";
}

std::string base_name(const std::string& p) {
    const size_t slash = p.find_last_of('/');
    return slash == std::string::npos ? p : p.substr(slash + 1);
}

VcdOptions vcd_options(const isa::MachineConfig& cfg, const TraceSelection& sel, const char* kind) {
    VcdOptions o;
    o.timescale = clock_scale(cfg.clock_mhz).timescale;
    o.limit_bytes = sel.limit_bytes;
    o.limit_name = sel.limit_name;
    char c[160];
    std::snprintf(
        c, sizeof c, "imap-vision %s: %d PEs at %g MHz, one clock cycle = %llu time units", kind,
        cfg.pes, cfg.clock_mhz, static_cast<unsigned long long>(clock_scale(cfg.clock_mhz).period));
    o.comment = c;
    return o;
}

DisasmCache::DisasmCache(const isa::Program& prog)
    : prog_(prog), text_(prog.code.size()), have_(prog.code.size(), false) {}

const std::string& DisasmCache::text(uint32_t pc) {
    static const std::string none;
    if (pc >= text_.size()) return none;
    if (!have_[pc]) {
        std::string t;
        try {
            t = isa::disassemble_word(prog_.code[pc]);
        } catch (const std::exception&) {
            t = "?";
        }
        // Collapse white space so the text fits the signal.
        std::string c;
        for (const char ch : t) {
            const bool sp = ch == ' ' || ch == '\t';
            if (sp && (c.empty() || c.back() == ' ')) continue;
            c.push_back(sp ? ' ' : ch);
        }
        while (!c.empty() && c.back() == ' ') c.pop_back();
        text_[pc] = c;
        have_[pc] = true;
    }
    return text_[pc];
}

PeSignals declare_pe(VcdWriter& w, const TraceSelection& sel, int pe, int pes, int nregs,
                     int addr_bits, int ext_bits) {
    PeSignals s;
    s.pe = pe;
    w.push_scope(pe_scope(pe, pes));
    if (sel.regs) {
        for (int r = 0; r < nregs; ++r) s.r.push_back(w.add_wire("r" + std::to_string(r), 8));
        s.c = w.add_wire("C", 1);
        s.t = w.add_wire("T", 1);
    }
    if (sel.mask) s.m = w.add_wire("M", 1);
    if (sel.mem) {
        s.we = w.add_wire("mem_we", 1);
        s.addr = w.add_wire("mem_addr", addr_bits);
        s.data = w.add_wire("mem_data", 8);
        if (ext_bits > 0) {
            s.ext_we = w.add_wire("ext_we", 1);
            s.ext_addr = w.add_wire("ext_addr", ext_bits);
            s.ext_data = w.add_wire("ext_data", 8);
        }
    }
    if (sel.ring) {
        s.ring_we = w.add_wire("ring_we", 1);
        s.ring_data = w.add_wire("ring_data", 8);
    }
    w.pop_scope();
    return s;
}

void view_pe(GtkwSave& g, const VcdWriter& w, const TraceSelection& sel, const PeSignals& s,
             bool ext, bool first) {
    const std::string name = "PE " + std::to_string(s.pe);
    g.begin_group(name);
    if (sel.mem) {
        g.add_signal(w.full_name(s.we), Format::Bin);
        g.add_signal(w.full_name(s.addr), Format::Hex);
        g.add_signal(w.full_name(s.data), Format::Hex);
        if (ext) {
            g.add_signal(w.full_name(s.ext_we), Format::Bin);
            g.add_signal(w.full_name(s.ext_addr), Format::Hex);
            g.add_signal(w.full_name(s.ext_data), Format::Hex);
        }
    }
    if (sel.ring) {
        g.add_signal(w.full_name(s.ring_we), Format::Bin);
        g.add_signal(w.full_name(s.ring_data), Format::Hex);
    }
    if (sel.mask) g.add_signal(w.full_name(s.m), Format::Bin);
    if (sel.regs) {
        g.add_signal(w.full_name(s.c), Format::Bin);
        g.add_signal(w.full_name(s.t), Format::Bin);
        g.begin_group(name + " registers", !first);
        for (const SignalId r : s.r) g.add_signal(w.full_name(r), Format::Hex);
        g.end_group();
    }
    g.end_group();
}

}  // namespace imap::waves::detail
