#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/waves/isa_trace.hpp"

namespace imap::waves {

namespace {

constexpr uint64_t kViewCycles = 16;

}  // namespace

using detail::base_name;
using detail::bits_for;
using detail::kInstrChars;
using detail::kPhaseChars;

double IsaTracer::estimate_bytes(const TraceSelection& sel, uint64_t cycles) {
    return static_cast<double>(cycles) * (kBytesPerPeCycle * static_cast<double>(sel.pes.size()) +
                                          (sel.cp ? kCpBytesPerCycle : 0.0));
}

std::string IsaTracer::gtkw_path() const {
    return detail::gtkw_path_of(path_);
}

IsaTracer::IsaTracer(const std::string& vcd_path, const isa::MachineConfig& cfg,
                     const isa::Program& prog, const TraceSelection& sel)
    : path_(vcd_path),
      cfg_(cfg),
      prog_(prog),
      sel_(sel),
      clk_(clock_scale(cfg.clock_mhz)),
      w_(vcd_path, detail::vcd_options(cfg, sel, "ISA-level trace")),
      g_(base_name(vcd_path)),
      disasm_(prog) {
    nregs_ = std::min(cfg.pe_regs, 16);
    const int addr_bits = bits_for(cfg.mem_bytes > 0 ? cfg.mem_bytes - 1 : 0);
    const int pc_bits = bits_for(prog.code.empty() ? 0 : prog.code.size() - 1);

    if (sel_.regs) detail::check_groups(sel_, nregs_);

    w_.push_scope("top");
    w_.push_scope("cp");
    if (sel_.cp) {
        // The machine cycle as a number (time = cycle x clock period).
        cycle_ = w_.add_wire("cycle", bits_for(cfg.watchdog_cycles));
        phase_ = w_.add_text("phase", kPhaseChars);
        pc_ = w_.add_wire("pc", pc_bits);
        op_ = w_.add_text("op", detail::kOpChars);
        args_ = w_.add_text("args", detail::kArgsChars);
        instr_ = w_.add_text("instr", kInstrChars);
        for (int i = 0; i < isa::kCpRegs; ++i)
            creg_.push_back(w_.add_wire("c" + std::to_string(i), 32));
    }
    if (sel_.mask) {
        msp_ = w_.add_wire("mask_depth", 8);
        active_ = w_.add_wire("active_pes", bits_for(static_cast<uint64_t>(cfg.pes)));
    }
    w_.pop_scope();
    for (const int p : sel_.pes)
        pes_.push_back(detail::declare_pe(w_, sel_, p, cfg.pes, nregs_, addr_bits, 0));
    w_.pop_scope();

    // The view: CP first, then one group per PE (its registers in a
    // sub-group, open for the first PE only).
    if (sel_.cp || sel_.mask) {
        g_.begin_group("CP");
        if (sel_.cp) {
            g_.add_signal(w_.full_name(cycle_), Format::Dec);
            g_.add_signal(w_.full_name(phase_), Format::Ascii);
            g_.add_signal(w_.full_name(pc_), Format::Hex);
            // The mnemonic fits one cycle at the opening zoom; the
            // operands and the whole text need a closer zoom.
            g_.add_signal(w_.full_name(op_), Format::Ascii);
            g_.add_signal(w_.full_name(args_), Format::Ascii);
            g_.add_signal(w_.full_name(instr_), Format::Ascii);
        }
        if (sel_.mask) {
            g_.add_signal(w_.full_name(msp_), Format::Dec);
            g_.add_signal(w_.full_name(active_), Format::Dec);
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
        detail::view_pe(g_, w_, sel_, s, false, first);
        first = false;
    }
    w_.begin();
}

IsaTracer::~IsaTracer() {
    if (!done_) w_.abandon();
}

void IsaTracer::sample_state(const isa::Machine& m) {
    if (sel_.cp)
        for (int i = 0; i < isa::kCpRegs; ++i) w_.change(creg_[i], m.cp(i));
    if (sel_.mask) {
        w_.change(msp_, static_cast<uint64_t>(m.mask_stack_size()));
        w_.change(active_, static_cast<uint64_t>(m.active_pes()));
    }
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

void IsaTracer::on_instruction(const isa::Machine& m, const isa::TraceEvent& e) {
    if (e.cycle_before < sel_.t0 || e.cycle_before >= sel_.t1 || done_) return;
    if (w_.limit_reached()) return;
    const uint64_t tb = e.cycle_before * clk_.period;
    const uint64_t ta = e.cycle_after * clk_.period;
    ++traced_;
    w_.set_time(tb);
    if (!started_) {
        started_ = true;
        first_time_ = tb;
        sample_state(m);
    }
    const uint32_t ph = m.current_phase();
    if (sel_.cp) {
        w_.change(cycle_, e.cycle_before);
        w_.change(pc_, e.pc);
        w_.change_text(op_, disasm_.mnemonic(e.pc));
        w_.change_text(args_, disasm_.operands(e.pc));
        w_.change_text(instr_, disasm_.text(e.pc));
        if (ph != last_phase_) w_.change_text(phase_, prog_.phase_name(ph));
    }
    if (ph != last_phase_) {
        if (last_phase_ != UINT32_MAX) g_.add_marker(tb, prog_.phase_name(ph));
        last_phase_ = ph;
    }
    // Strobes: high during the instruction that writes, with its address and
    // data; dropped at its end (a following write raises them again at the
    // same time stamp, so back-to-back writes show as one long strobe).
    const isa::Word w = isa::Word::decode(e.word);
    const bool st = w.op == static_cast<uint8_t>(isa::Op::ST);
    const bool stx = w.op == static_cast<uint8_t>(isa::Op::STX);
    const bool ring =
        w.op == static_cast<uint8_t>(isa::Op::RXL) || w.op == static_cast<uint8_t>(isa::Op::RXR);
    if ((sel_.mem && (st || stx)) || (sel_.ring && ring)) {
        const uint8_t* M = m.mask_lanes();
        for (const detail::PeSignals& s : pes_) {
            if (sel_.mem && (st || stx)) {
                int64_t addr = 0;
                if (st) {
                    addr = (w.rb == isa::kNoBase ? 0 : static_cast<int64_t>(m.cp(w.rb))) +
                           isa::as_signed(w.imm);
                } else {
                    const int64_t lo = m.reg_lanes(w.ra)[s.pe];
                    const int64_t hi = (w.imm & isa::kLdxNoHigh) ? 0 : m.reg_lanes(w.rb)[s.pe];
                    addr = (hi << 8 | lo) + isa::ldx_offset(w.imm);
                    if (w.imm & isa::kLdxUseCp)
                        addr += m.cp(static_cast<int>((w.imm >> isa::kLdxCpShift) & 15u));
                }
                w_.change(s.we, M[s.pe]);
                w_.change(s.addr, static_cast<uint64_t>(addr));
                w_.change(s.data, m.reg_lanes(w.rd)[s.pe]);
            }
            if (sel_.ring && ring) {
                w_.change(s.ring_we, M[s.pe]);
                w_.change(s.ring_data, m.reg_lanes(w.rd)[s.pe]);
            }
        }
    }
    // The cycle counter counts every cycle of a multi-cycle instruction.
    if (sel_.cp)
        for (uint64_t c = e.cycle_before + 1; c < e.cycle_after && !w_.limit_reached(); ++c) {
            w_.set_time(c * clk_.period);
            w_.change(cycle_, c);
        }
    w_.set_time(ta);
    if (sel_.cp) w_.change(cycle_, e.cycle_after);
    for (const detail::PeSignals& s : pes_) {
        if (sel_.mem) w_.change(s.we, 0);
        if (sel_.ring) w_.change(s.ring_we, 0);
    }
    sample_state(m);
    last_cycle_ = e.cycle_after;
}

void IsaTracer::finish(uint64_t end_cycle) {
    if (done_) return;
    const uint64_t end = std::min(end_cycle, sel_.t1 == UINT64_MAX ? end_cycle : sel_.t1);
    w_.finish(std::max(end, last_cycle_) * clk_.period);
    // The view opens on the first kViewCycles of the window, where the
    // instruction texts are readable (Zoom Best Fit shows all of it).
    const uint64_t span = started_ ? std::clamp<uint64_t>(last_cycle_ * clk_.period - first_time_,
                                                          1, kViewCycles * clk_.period)
                                   : 1;
    g_.set_view(first_time_, span);
    done_ = true;
    // The VCD is complete: a view that cannot be written does not cost it.
    try {
        g_.write(gtkw_path());
    } catch (const WaveError& e) {
        gtkw_error_ = e.what();
    }
}

}  // namespace imap::waves
