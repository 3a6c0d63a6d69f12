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

std::string DisasmCache::mnemonic(uint32_t pc) {
    const std::string& t = text(pc);
    const size_t sp = t.find(' ');
    return sp == std::string::npos ? t : t.substr(0, sp);
}

std::string DisasmCache::operands(uint32_t pc) {
    const std::string& t = text(pc);
    const size_t sp = t.find(' ');
    return sp == std::string::npos ? std::string() : t.substr(sp + 1);
}

void check_groups(const TraceSelection& sel, int nregs) {
    for (const RegisterGroup& grp : sel.groups) {
        if (grp.name.empty() || grp.regs.empty() || grp.regs.size() > 8)
            throw WaveError("register group '" + grp.name + "': needs a name and 1..8 registers");
        for (const int r : grp.regs)
            if (r < 0 || r >= nregs)
                throw WaveError("register group '" + grp.name + "': register r" +
                                std::to_string(r) + " is not traced (r0..r" +
                                std::to_string(nregs - 1) + ")");
    }
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
        // Multi-byte values as one decimal number each: the bytes of the
        // group's registers, highest register first, bit 7 first.
        for (const RegisterGroup& grp : sel.groups) {
            std::vector<std::pair<int, std::string>> bits;
            for (auto r = grp.regs.rbegin(); r != grp.regs.rend(); ++r)
                for (int b = 0; b < 8; ++b) bits.emplace_back(b, w.full_name(s.r[*r]));
            const std::string& first_name = w.full_name(s.r[grp.regs.front()]);
            const std::string prefix = first_name.substr(0, first_name.rfind('.') + 1);
            g.add_vector(prefix + grp.name + "[" + std::to_string(8 * grp.regs.size() - 1) + ":0]",
                         bits, Format::Dec);
        }
        g.begin_group(name + " registers", !first);
        for (const SignalId r : s.r) g.add_signal(w.full_name(r), Format::Hex);
        g.end_group();
    }
    g.end_group();
}

}  // namespace imap::waves::detail
