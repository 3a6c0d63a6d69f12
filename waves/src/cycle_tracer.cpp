#include <algorithm>
#include <cstdio>

#include "imap/isa/assembler.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/waves/cycle_trace.hpp"

namespace imap::waves {

namespace {

constexpr int kInstrChars = 32;
constexpr int kPhaseChars = 16;
constexpr uint64_t kViewCycles = 16;

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

VcdOptions vcd_options(const isa::MachineConfig& cfg, const TraceSelection& sel) {
    VcdOptions o;
    o.timescale = clock_scale(cfg.clock_mhz).timescale;
    o.limit_bytes = sel.limit_bytes;
    o.limit_name = sel.limit_name;
    char c[160];
    std::snprintf(c, sizeof c,
                  "imap-vision RTL per-cycle trace: %d PEs at %g MHz, one clock cycle = %llu "
                  "time units",
                  cfg.pes, cfg.clock_mhz,
                  static_cast<unsigned long long>(clock_scale(cfg.clock_mhz).period));
    o.comment = c;
    return o;
}

}  // namespace

std::string CycleTracer::gtkw_path() const {
    return gtkw_path_of(path_);
}

CycleTracer::CycleTracer(const std::string& vcd_path, const isa::MachineConfig& cfg,
                         const isa::Program& prog, const TraceSelection& sel)
    : path_(vcd_path),
      cfg_(cfg),
      prog_(prog),
      sel_(sel),
      clk_(clock_scale(cfg.clock_mhz)),
      w_(vcd_path, vcd_options(cfg, sel)),
      g_(base_name(vcd_path)) {
    nregs_ = std::min(cfg.pe_regs, 16);
    disasm_.resize(prog.code.size());
    have_disasm_.assign(prog.code.size(), false);
    const int addr_bits = bits_for(cfg.mem_bytes > 0 ? cfg.mem_bytes - 1 : 0);
    const int ext_bits = bits_for(cfg.ext_bytes > 0 ? static_cast<uint64_t>(cfg.ext_bytes - 1) : 0);
    const int pc_bits = bits_for(prog.code.empty() ? 0 : prog.code.size() - 1);

    w_.push_scope("top");
    w_.push_scope("cp");
    if (sel_.cp) {
        phase_ = w_.add_text("phase", kPhaseChars);
        pc_ = w_.add_wire("pc", pc_bits);
        instr_ = w_.add_text("instr", kInstrChars);
        valid_ = w_.add_wire("valid", 1);
        bubble_ = w_.add_wire("bubble", 1);
        for (int i = 0; i < isa::kCpRegs; ++i)
            creg_.push_back(w_.add_wire("c" + std::to_string(i), 32));
    }
    if (sel_.mask) {
        msp_ = w_.add_wire("mask_depth", 8);
        active_ = w_.add_wire("active_pes", bits_for(static_cast<uint64_t>(cfg.pes)));
        reduce_ = w_.add_wire("reduce", 1);
        any_ = w_.add_wire("any", 1);
        all_ = w_.add_wire("all", 1);
    }
    if (sel_.ring) {
        busy_ = w_.add_wire("ring_busy", 1);
        hop_ = w_.add_wire("ring_hop", bits_for(static_cast<uint64_t>(cfg.pes)));
        up_ = w_.add_wire("ring_up", 1);
    }
    w_.pop_scope();
    for (const int p : sel_.pes) {
        PeSig s{};
        s.pe = p;
        w_.push_scope(pe_scope(p, cfg.pes));
        if (sel_.regs) {
            for (int r = 0; r < nregs_; ++r) s.r.push_back(w_.add_wire("r" + std::to_string(r), 8));
            s.c = w_.add_wire("C", 1);
            s.t = w_.add_wire("T", 1);
        }
        if (sel_.mask) s.m = w_.add_wire("M", 1);
        if (sel_.mem) {
            s.we = w_.add_wire("mem_we", 1);
            s.addr = w_.add_wire("mem_addr", addr_bits);
            s.data = w_.add_wire("mem_data", 8);
            s.ext_we = w_.add_wire("ext_we", 1);
            s.ext_addr = w_.add_wire("ext_addr", ext_bits);
            s.ext_data = w_.add_wire("ext_data", 8);
        }
        if (sel_.ring) {
            s.ring_we = w_.add_wire("ring_we", 1);
            s.ring_data = w_.add_wire("ring_data", 8);
        }
        w_.pop_scope();
        pes_.push_back(std::move(s));
    }
    w_.pop_scope();

    // The view: as IsaTracer's (CP first, then one group per PE).
    if (sel_.cp || sel_.mask || sel_.ring) {
        g_.begin_group("CP");
        if (sel_.cp) {
            g_.add_signal(w_.full_name(phase_), Format::Ascii);
            g_.add_signal(w_.full_name(pc_), Format::Hex);
            g_.add_signal(w_.full_name(instr_), Format::Ascii);
            g_.add_signal(w_.full_name(valid_), Format::Bin);
            g_.add_signal(w_.full_name(bubble_), Format::Bin);
        }
        if (sel_.mask) {
            g_.add_signal(w_.full_name(msp_), Format::Dec);
            g_.add_signal(w_.full_name(active_), Format::Dec);
            g_.add_signal(w_.full_name(reduce_), Format::Bin);
            g_.add_signal(w_.full_name(any_), Format::Bin);
            g_.add_signal(w_.full_name(all_), Format::Bin);
        }
        if (sel_.ring) {
            g_.add_signal(w_.full_name(busy_), Format::Bin);
            g_.add_signal(w_.full_name(hop_), Format::Dec);
            g_.add_signal(w_.full_name(up_), Format::Bin);
        }
        if (sel_.cp) {
            g_.begin_group("CP registers", true);
            for (const SignalId c : creg_) g_.add_signal(w_.full_name(c), Format::Hex);
            g_.end_group();
        }
        g_.end_group();
    }
    bool first = true;
    for (const PeSig& s : pes_) {
        const std::string name = "PE " + std::to_string(s.pe);
        g_.begin_group(name);
        if (sel_.mem) {
            g_.add_signal(w_.full_name(s.we), Format::Bin);
            g_.add_signal(w_.full_name(s.addr), Format::Hex);
            g_.add_signal(w_.full_name(s.data), Format::Hex);
            g_.add_signal(w_.full_name(s.ext_we), Format::Bin);
            g_.add_signal(w_.full_name(s.ext_addr), Format::Hex);
            g_.add_signal(w_.full_name(s.ext_data), Format::Hex);
        }
        if (sel_.ring) {
            g_.add_signal(w_.full_name(s.ring_we), Format::Bin);
            g_.add_signal(w_.full_name(s.ring_data), Format::Hex);
        }
        if (sel_.mask) g_.add_signal(w_.full_name(s.m), Format::Bin);
        if (sel_.regs) {
            g_.add_signal(w_.full_name(s.c), Format::Bin);
            g_.add_signal(w_.full_name(s.t), Format::Bin);
            g_.begin_group(name + " registers", !first);
            for (const SignalId r : s.r) g_.add_signal(w_.full_name(r), Format::Hex);
            g_.end_group();
        }
        g_.end_group();
        first = false;
    }
    w_.begin();
}

CycleTracer::~CycleTracer() {
    if (!done_) w_.abandon();
}

const std::string& CycleTracer::text_of(uint32_t pc) {
    static const std::string none;
    if (pc >= disasm_.size()) return none;
    if (!have_disasm_[pc]) {
        std::string t;
        try {
            t = isa::disassemble_word(prog_.code[pc]);
        } catch (const std::exception&) {
            t = "?";
        }
        std::string c;
        for (const char ch : t) {
            const bool sp = ch == ' ' || ch == '\t';
            if (sp && (c.empty() || c.back() == ' ')) continue;
            c.push_back(sp ? ' ' : ch);
        }
        while (!c.empty() && c.back() == ' ') c.pop_back();
        disasm_[pc] = c;
        have_disasm_[pc] = true;
    }
    return disasm_[pc];
}

void CycleTracer::sample_state(const isa::Machine& m, bool pes) {
    if (sel_.cp)
        for (int i = 0; i < isa::kCpRegs; ++i) w_.change(creg_[i], m.cp(i));
    if (sel_.mask) {
        w_.change(msp_, static_cast<uint64_t>(m.mask_stack_size()));
        w_.change(active_, static_cast<uint64_t>(m.active_pes()));
    }
    if (!pes) return;
    const uint8_t* C = m.carry_lanes();
    const uint8_t* T = m.test_lanes();
    const uint8_t* M = m.mask_lanes();
    for (const PeSig& s : pes_) {
        if (sel_.regs) {
            for (int r = 0; r < nregs_; ++r) w_.change(s.r[r], m.reg_lanes(r)[s.pe]);
            w_.change(s.c, C[s.pe]);
            w_.change(s.t, T[s.pe]);
        }
        if (sel_.mask) w_.change(s.m, M[s.pe]);
    }
}

void CycleTracer::on_cycle(const isa::Machine& m, const CycleInfo& c) {
    if (done_ || c.cycle < sel_.t0 || c.cycle >= sel_.t1) return;
    if (w_.limit_reached()) return;
    const uint64_t t = c.cycle * clk_.period;
    ++traced_;
    w_.set_time(t);
    const bool first = !started_;
    if (first) {
        started_ = true;
        first_time_ = t;
    }
    // Machine state as the RTL signals show it: an instruction's results
    // appear on its issue edge.
    if (first || c.issue) sample_state(m, first || c.pe_state);
    const uint32_t ph = m.current_phase();
    if (sel_.cp) {
        if (first || c.issue) {
            w_.change(pc_, c.pc);
            w_.change_text(instr_, text_of(c.pc));
        }
        w_.change(valid_, c.issue);
        w_.change(bubble_, c.bubble);
        if (ph != last_phase_) w_.change_text(phase_, prog_.phase_name(ph));
    }
    if (ph != last_phase_) {
        if (last_phase_ != UINT32_MAX) g_.add_marker(t, prog_.phase_name(ph));
        last_phase_ = ph;
    }
    if (sel_.mask) {
        w_.change(reduce_, c.reduce);
        if (c.reduce) {
            w_.change(any_, c.any);
            w_.change(all_, c.all);
        }
    }
    const size_t P = static_cast<size_t>(m.pes());
    const uint8_t* M = m.mask_lanes();
    if (sel_.ring) {
        w_.change(busy_, c.ring_busy);
        if (c.ring_busy) {
            w_.change(hop_, c.ring_hop);
            w_.change(up_, c.ring_up);
        }
        const bool hop = c.ring_busy && c.ring_src && c.ring_hop > 0;
        const size_t sh = hop ? static_cast<size_t>(c.ring_hop - 1) % P : 0;
        for (const PeSig& s : pes_) {
            w_.change(s.ring_we, hop);
            if (hop) {
                const size_t p = static_cast<size_t>(s.pe);
                w_.change(s.ring_data,
                          c.ring_up ? c.ring_src[(p + P - sh) % P] : c.ring_src[(p + sh) % P]);
            }
        }
    }
    if (sel_.mem) {
        using Mem = CycleInfo::Mem;
        const bool local = c.mem == Mem::Row || c.mem == Mem::RowMasked || c.mem == Mem::Stx;
        const bool ext = c.mem == Mem::Ext;
        int64_t stx_base = 0;
        isa::Word w{};
        if (c.mem == Mem::Stx) {
            w = isa::Word::decode(c.word);
            stx_base = ((w.imm & isa::kLdxUseCp)
                            ? int64_t{isa::as_signed(m.cp((w.imm >> isa::kLdxCpShift) & 15u))}
                            : 0) +
                       isa::ldx_offset(w.imm);
        }
        for (const PeSig& s : pes_) {
            const size_t p = static_cast<size_t>(s.pe);
            bool we = false;
            if (local && (c.mem == Mem::Row || M[p])) {
                uint32_t a = c.mem_addr;
                if (c.mem == Mem::Stx) {
                    const int64_t lo = m.reg_lanes(w.ra)[p];
                    const int64_t hi = (w.imm & isa::kLdxNoHigh) ? 0 : m.reg_lanes(w.rb)[p];
                    a = static_cast<uint32_t>(stx_base + (hi << 8 | lo));
                }
                we = true;
                w_.change(s.addr, a);
                w_.change(s.data, m.mem_read(static_cast<int>(p), a));
            }
            w_.change(s.we, we);
            if (ext) {
                w_.change(s.ext_addr, c.mem_addr);
                w_.change(s.ext_data, m.ext_data()[size_t{c.mem_addr} * P + p]);
            }
            w_.change(s.ext_we, ext);
        }
    }
    last_cycle_ = c.cycle + 1;
}

void CycleTracer::finish(uint64_t end_cycle) {
    if (done_) return;
    const uint64_t end = std::min(end_cycle, sel_.t1 == UINT64_MAX ? end_cycle : sel_.t1);
    w_.finish(std::max(end, last_cycle_) * clk_.period);
    const uint64_t span = started_ ? std::clamp<uint64_t>(last_cycle_ * clk_.period - first_time_,
                                                          1, kViewCycles * clk_.period)
                                   : 1;
    g_.set_view(first_time_, span);
    try {
        g_.write(gtkw_path());
    } catch (...) {
        std::remove(path_.c_str());
        done_ = true;
        throw;
    }
    done_ = true;
}

}  // namespace imap::waves
