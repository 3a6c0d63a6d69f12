#include <algorithm>
#include <cstdio>

#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/waves/cycle_trace.hpp"

namespace imap::waves {

namespace {

constexpr uint64_t kViewCycles = 16;

}  // namespace

using detail::base_name;
using detail::bits_for;
using detail::kInstrChars;
using detail::kPhaseChars;

std::string CycleTracer::gtkw_path() const {
    return detail::gtkw_path_of(path_);
}

CycleTracer::CycleTracer(const std::string& vcd_path, const isa::MachineConfig& cfg,
                         const isa::Program& prog, const TraceSelection& sel)
    : path_(vcd_path),
      cfg_(cfg),
      prog_(prog),
      sel_(sel),
      clk_(clock_scale(cfg.clock_mhz)),
      w_(vcd_path, detail::vcd_options(cfg, sel, "RTL per-cycle trace")),
      g_(base_name(vcd_path)),
      disasm_(prog) {
    nregs_ = std::min(cfg.pe_regs, 16);
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
    for (const int p : sel_.pes)
        pes_.push_back(detail::declare_pe(w_, sel_, p, cfg.pes, nregs_, addr_bits, ext_bits));
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
    for (const detail::PeSignals& s : pes_) {
        detail::view_pe(g_, w_, sel_, s, true, first);
        first = false;
    }
    w_.begin();
}

CycleTracer::~CycleTracer() {
    if (!done_) w_.abandon();
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
    for (const detail::PeSignals& s : pes_) {
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
            w_.change_text(instr_, disasm_.text(c.pc));
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
        for (const detail::PeSignals& s : pes_) {
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
        for (const detail::PeSignals& s : pes_) {
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
