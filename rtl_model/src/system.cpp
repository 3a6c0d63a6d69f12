#include "imap/rtl/system.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <atomic>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include "imap/isa/interconnect.hpp"
#include "imap/waves/cycle_trace.hpp"

namespace imap::rtl {

namespace {
template <typename T>
void put(sc_core::sc_signal<T>& s, const T& v, uint64_t& writes) {
    if (s.read() != v) {
        s.write(v);
        ++writes;
    }
}
uint32_t cp_base(const isa::Machine& m, uint8_t r) {
    return r == isa::kNoBase ? 0u : m.cp(r);
}
}  // namespace

// ---------------------------------------------------------------------------

CpBus::CpBus(sc_core::sc_module_name name)
    : sc_module(name),
      pc("pc"),
      instr("instr"),
      opcode("opcode"),
      valid("valid"),
      bubble("bubble"),
      halted("halted"),
      phase("phase"),
      creg("creg", isa::kCpRegs) {}

PeSignals::PeSignals(sc_core::sc_module_name name, int idx, const std::vector<int>& regs)
    : sc_module(name),
      index(idx),
      r("r"),
      c("c"),
      t("t"),
      m("m", true),
      mem_we("mem_we"),
      mem_addr("mem_addr"),
      mem_wdata("mem_wdata"),
      ext_we("ext_we"),
      ext_addr("ext_addr"),
      ext_wdata("ext_wdata") {
    r.init(regs.size(), [&](const char*, size_t i) {
        return new sc_core::sc_signal<uint8_t>(("r" + std::to_string(regs[i])).c_str());
    });
}

Ring::Ring(sc_core::sc_module_name name, int pes, int first, int count)
    : sc_module(name),
      link("link"),
      busy("busy"),
      hop("hop"),
      up("up"),
      P_(pes),
      first_(first),
      count_(count),
      src_(static_cast<size_t>(pes)),
      scratch_(static_cast<size_t>(pes)),
      shadow_(static_cast<size_t>(count), 0) {
    link.init(static_cast<size_t>(count), [&](const char*, size_t i) {
        return new sc_core::sc_signal<uint8_t>(
            ("link_" + std::to_string(first + static_cast<int>(i))).c_str());
    });
}

void Ring::shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, int P, int hops,
                 bool towards_higher) {
    // Keep the source row for the hop-by-hop display, then the ISA's ring.
    std::memcpy(src_.data(), src, static_cast<size_t>(P));
    towards_higher_ = towards_higher;
    ++transfers_;
    isa::ring_shift(dst, src, mask, scratch_.data(), static_cast<size_t>(P),
                    static_cast<size_t>(hops), towards_higher);
}

void Ring::show_hop(uint32_t h, uint64_t& writes) {
    if (!busy_) {
        busy_ = true;
        busy.write(true);
        ++writes;
    }
    put(up, towards_higher_, writes);
    hop_ = h;
    hop.write(h);
    ++writes;
    // In hop h every PE drives the value it holds after h - 1 hops.
    const size_t P = static_cast<size_t>(P_);
    const size_t s = static_cast<size_t>(h - 1) % P;
    for (int i = 0; i < count_; ++i) {
        const size_t p = static_cast<size_t>(first_ + i);
        const uint8_t v = towards_higher_ ? src_[(p + P - s) % P] : src_[(p + s) % P];
        if (v != shadow_[static_cast<size_t>(i)]) {
            shadow_[static_cast<size_t>(i)] = v;
            link[static_cast<size_t>(i)].write(v);
            ++writes;
        }
    }
}

void Ring::idle(uint64_t& writes) {
    if (busy_) {
        busy_ = false;
        busy.write(false);
        ++writes;
    }
}

MaskBus::MaskBus(sc_core::sc_module_name name)
    : sc_module(name),
      any("any"),
      all("all", true),
      reduce_on("reduce"),
      active("active"),
      depth("depth") {}

uint32_t MaskBus::reduce(const uint8_t* t, const uint8_t* mask, int P, bool want_any) {
    const size_t n = static_cast<size_t>(P);
    any_v = isa::status_reduce<true>(t, mask, n) != 0;
    all_v = isa::status_reduce<false>(t, mask, n) != 0;
    pending = true;
    return want_any ? any_v : all_v;
}

// ---------------------------------------------------------------------------
// top.array: the clocked process.

Array::Array(sc_core::sc_module_name name, isa::Machine& m, const RtlConfig& rcfg, CpBus& cp,
             Ring& ring, MaskBus& maskbus)
    : sc_module(name),
      clk("clk"),
      pe("pe"),
      m_(m),
      rcfg_(rcfg),
      cp_(cp),
      ring_(ring),
      mb_(maskbus) {
    first_ = rcfg_.traced_first(m.config());
    count_ = rcfg_.traced_count(m.config());
    regs_ = rcfg_.traced_regs(m.config());
    pe.init(static_cast<size_t>(count_), [&](const char*, size_t i) {
        const int p = first_ + static_cast<int>(i);
        return new PeSignals(("pe_" + std::to_string(p)).c_str(), p, regs_);
    });
    shadow_.assign((regs_.size() + 3) * static_cast<size_t>(count_), 0);
    // M starts at 1 (reset state; the signal is constructed with 1).
    std::memset(shadow_.data() + (regs_.size() + 2) * static_cast<size_t>(count_), 1,
                static_cast<size_t>(count_));
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
}

void Array::stop() {
    if (stopped_) return;
    if (may_stop_ && !fault_ && !may_stop_()) return;
    stopped_ = true;
    sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                            sc_core::SC_DO_NOTHING);
    sc_core::sc_stop();
}

void Array::tick() {
    if (done_) {
        stop();
        return;
    }
    try {
        traced_edge_ = false;
        cycle();
        if (rcfg_.cycle_tracer && traced_edge_) trace_cycle(edges_ - 1);
    } catch (...) {
        fault_ = std::current_exception();
        done_ = true;
        stop();
    }
}

void Array::cycle() {
    const uint64_t edge = edges_++;
    end_strobes();
    tmem_ = 0;
    if (k_ + 1 < cost_) {
        ++k_;
        traced_edge_ = true;
        continue_instruction();
        return;
    }
    ring_.idle(writes_);
    if (m_.halted()) {
        done_ = true;
        finished_ = true;
        put(cp_.halted, true, writes_);
        stop();
        return;
    }
    if (m_.cycles() != edge)
        throw std::logic_error("imap::rtl: internal error: machine at cycle " +
                               std::to_string(m_.cycles()) + " on clock edge " +
                               std::to_string(edge));
    issue();
}

void Array::issue() {
    const std::vector<uint64_t>& code = m_.program().code;
    uint32_t pc = 0;
    for (;;) {
        pc = m_.pc();
        const uint64_t word = pc < code.size() ? code[pc] : 0;
        const uint64_t before = m_.cycles();
        mb_.pending = false;
        const isa::StepResult s = m_.step();
        const uint64_t index = index_++;
        if (rcfg_.inject.enabled && index == rcfg_.inject.instruction) apply_injection();
        if (hook_) hook_->on_retire(m_, isa::TraceEvent{pc, word, before, m_.cycles()}, index);
        w_ = isa::Word::decode(word);
        cost_ = s.cycles;
        k_ = 0;
        if (s.cycles == 0) {
            if (s.halted) {
                // A zero-cost halt (costs.cp = 0): done on this edge.
                done_ = finished_ = true;
                put(cp_.halted, true, writes_);
                update_cp_regs();
                stop();
                return;
            }
            continue;  // zero-cost (phase): the next instruction issues on the same edge
        }
        break;
    }
    const isa::OpInfo* info = isa::op_info(w_.op);
    cls_ = info ? info->cost_class : isa::CostClass::Cp;
    pc_ = pc;
    word_ = pc < code.size() ? code[pc] : 0;
    traced_edge_ = true;
    pe_state_ = cls_ != isa::CostClass::Cp && cls_ != isa::CostClass::Phase;
    // The broadcast bus: the instruction just issued.
    put(cp_.pc, pc, writes_);
    cp_.instr.write(w_.encode());
    cp_.opcode.write(w_.op);
    writes_ += 2;
    valid_ = true;
    cp_.valid.write(true);
    ++writes_;
    put(cp_.phase, m_.current_phase(), writes_);
    update_cp_regs();
    if (cls_ != isa::CostClass::Cp && cls_ != isa::CostClass::Phase) update_pe_state();

    const auto op = static_cast<isa::Op>(w_.op);
    switch (op) {
        case isa::Op::ST:
        case isa::Op::VIN:
            strobe_row(false, cp_base(m_, w_.rb) + static_cast<uint32_t>(isa::as_signed(w_.imm)));
            break;
        case isa::Op::STX: {
            const int64_t base =
                ((w_.imm & isa::kLdxUseCp)
                     ? int64_t{isa::as_signed(m_.cp((w_.imm >> isa::kLdxCpShift) & 15u))}
                     : 0) +
                isa::ldx_offset(w_.imm);
            const uint8_t* lo = m_.reg_lanes(w_.ra);
            const uint8_t* hi = (w_.imm & isa::kLdxNoHigh) ? nullptr : m_.reg_lanes(w_.rb);
            const uint8_t* mk = m_.mask_lanes();
            tmem_ = static_cast<uint8_t>(waves::CycleInfo::Mem::Stx);
            for (int i = 0; i < count_; ++i) {
                const int p = first_ + i;
                if (!mk[p]) continue;
                const int64_t a = base + ((hi ? int64_t{hi[p]} << 8 : 0) | int64_t{lo[p]});
                PeSignals& s = pe[static_cast<size_t>(i)];
                s.mem_we.write(true);
                put(s.mem_addr, static_cast<uint32_t>(a), writes_);
                put(s.mem_wdata, m_.mem_read(p, static_cast<uint32_t>(a)), writes_);
                ++writes_;
                mem_strobe_ = true;
            }
            break;
        }
        case isa::Op::XLD:
        case isa::Op::XST:
            xlen_ = isa::as_signed(m_.cp(w_.rd));
            xext_ = isa::as_signed(m_.cp(w_.ra));
            xloc_ = isa::as_signed(cp_base(m_, w_.rb)) + isa::as_signed(w_.imm);
            break;
        default:
            break;
    }
    if (mb_.pending) {
        put(mb_.any, mb_.any_v, writes_);
        put(mb_.all, mb_.all_v, writes_);
        mb_.reduce_on.write(true);
        ++writes_;
        reduce_ = true;
    }
    if (cls_ == isa::CostClass::Mask) {
        put(mb_.active, m_.active_pes(), writes_);
        put(mb_.depth, m_.mask_stack_size(), writes_);
    }
    continue_instruction();
}

// Per-cycle activity of the instruction in flight (k_ = 0 on the issue cycle).
void Array::continue_instruction() {
    const isa::CostTable& ct = m_.config().costs;
    switch (cls_) {
        case isa::CostClass::Ring:
            if (ct.ring_hop > 0)
                ring_.show_hop(static_cast<uint32_t>(k_ / ct.ring_hop + 1), writes_);
            break;
        case isa::CostClass::Xfer:
            if (k_ >= ct.xfer_setup) {
                // byte b of every PE has crossed the shared path after
                // ceil((b + 1) * P / ext_bytes_per_cycle) cycles
                const uint64_t P = static_cast<uint64_t>(m_.pes());
                const int64_t b =
                    static_cast<int64_t>((k_ - ct.xfer_setup) * ct.ext_bytes_per_cycle / P);
                if (b < xlen_) {
                    if (w_.op == static_cast<uint8_t>(isa::Op::XLD))
                        strobe_row(false, static_cast<uint32_t>(xloc_ + b));
                    else
                        strobe_row(true, static_cast<uint32_t>(xext_ + b));
                }
            }
            break;
        case isa::CostClass::Cp:
            if (k_ >= ct.cp && !bubble_) {
                bubble_ = true;
                cp_.bubble.write(true);
                ++writes_;
            }
            break;
        default:
            break;
    }
}

void Array::end_strobes() {
    if (valid_) {
        valid_ = false;
        cp_.valid.write(false);
        ++writes_;
    }
    if (bubble_ && k_ + 1 >= cost_) {
        bubble_ = false;
        cp_.bubble.write(false);
        ++writes_;
    }
    if (reduce_) {
        reduce_ = false;
        mb_.reduce_on.write(false);
        ++writes_;
    }
    if (mem_strobe_ || ext_strobe_) {
        for (auto& s : pe) {
            if (mem_strobe_) put(s.mem_we, false, writes_);
            if (ext_strobe_) put(s.ext_we, false, writes_);
        }
        mem_strobe_ = ext_strobe_ = false;
    }
}

void Array::strobe_row(bool ext, uint32_t addr) {
    const bool masked = !ext && w_.op != static_cast<uint8_t>(isa::Op::VIN) &&
                        w_.op != static_cast<uint8_t>(isa::Op::XLD);
    using Mem = waves::CycleInfo::Mem;
    tmem_ = static_cast<uint8_t>(ext ? Mem::Ext : masked ? Mem::RowMasked : Mem::Row);
    tmem_addr_ = addr;
    if (count_ == 0) return;
    const size_t P = static_cast<size_t>(m_.pes());
    const uint8_t* row = (ext ? m_.ext_data() : m_.mem_data()) + size_t{addr} * P;
    const uint8_t* mk = m_.mask_lanes();
    for (int i = 0; i < count_; ++i) {
        const size_t p = static_cast<size_t>(first_ + i);
        if (masked && !mk[p]) continue;
        PeSignals& s = pe[static_cast<size_t>(i)];
        if (ext) {
            put(s.ext_we, true, writes_);
            put(s.ext_addr, addr, writes_);
            put(s.ext_wdata, row[p], writes_);
        } else {
            put(s.mem_we, true, writes_);
            put(s.mem_addr, addr, writes_);
            put(s.mem_wdata, row[p], writes_);
        }
    }
    (ext ? ext_strobe_ : mem_strobe_) = true;
}

// Hands this edge's values to the cycle tracer (only when one is set).
void Array::trace_cycle(uint64_t edge) {
    waves::CycleInfo c;
    c.cycle = edge;
    c.issue = valid_;
    c.pc = pc_;
    c.word = word_;
    c.bubble = bubble_;
    c.pe_state = valid_ && pe_state_;
    c.ring_busy = ring_.in_transfer();
    c.ring_hop = ring_.current_hop();
    c.ring_up = ring_.towards_higher();
    c.ring_src = ring_.source();
    c.mem = static_cast<waves::CycleInfo::Mem>(tmem_);
    c.mem_addr = tmem_addr_;
    c.reduce = reduce_;
    c.any = mb_.any_v;
    c.all = mb_.all_v;
    rcfg_.cycle_tracer->on_cycle(m_, c);
}

void Array::update_pe_state() {
    const size_t n = static_cast<size_t>(count_);
    if (n == 0) return;
    const size_t nr = regs_.size();
    auto row = [&](size_t j) -> const uint8_t* {
        if (j < nr) return m_.reg_lanes(regs_[j]) + first_;
        if (j == nr) return m_.carry_lanes() + first_;
        if (j == nr + 1) return m_.test_lanes() + first_;
        return m_.mask_lanes() + first_;
    };
    for (size_t j = 0; j < nr + 3; ++j) {
        const uint8_t* src = row(j);
        uint8_t* sh = shadow_.data() + j * n;
        if (std::memcmp(src, sh, n) == 0) continue;
        for (size_t i = 0; i < n; ++i) {
            if (src[i] == sh[i]) continue;
            sh[i] = src[i];
            PeSignals& s = pe[i];
            if (j < nr)
                s.r[j].write(src[i]);
            else if (j == nr)
                s.c.write(src[i] != 0);
            else if (j == nr + 1)
                s.t.write(src[i] != 0);
            else
                s.m.write(src[i] != 0);
            ++writes_;
        }
    }
}

void Array::update_cp_regs() {
    for (int i = 0; i < isa::kCpRegs; ++i) {
        const uint32_t v = m_.cp(i);
        if (v != creg_shadow_[static_cast<size_t>(i)]) {
            creg_shadow_[static_cast<size_t>(i)] = v;
            cp_.creg[static_cast<size_t>(i)].write(v);
            ++writes_;
        }
    }
}

void Array::apply_injection() {
    const FaultInjection& f = rcfg_.inject;
    uint8_t* lane = nullptr;
    switch (f.reg) {
        case FaultInjection::kRegC:
            lane = m_.carry_lanes();
            break;
        case FaultInjection::kRegT:
            lane = m_.test_lanes();
            break;
        case FaultInjection::kRegM:
            lane = m_.mask_lanes();
            break;
        default:
            lane = m_.reg_lanes(f.reg);
            break;
    }
    const uint8_t mask = f.reg < 0 ? static_cast<uint8_t>(f.mask & 1u) : f.mask;
    lane[f.pe] = static_cast<uint8_t>(lane[f.pe] ^ mask);
}

// ---------------------------------------------------------------------------

RtlSystem::RtlSystem(sc_core::sc_module_name name, const isa::MachineConfig& cfg,
                     const isa::Program& prog, const RtlConfig& rcfg)
    : sc_module(name),
      m_(std::make_shared<isa::Machine>(cfg)),
      clk("clk", tlm::clock_period(cfg), 0.5, sc_core::SC_ZERO_TIME, true),
      cp("cp"),
      ring("ring", cfg.pes, (rcfg.validate(cfg), rcfg.traced_first(cfg)), rcfg.traced_count(cfg)),
      maskbus("maskbus"),
      array("array", *m_, rcfg, cp, ring, maskbus) {
    m_->load(prog);
    m_->set_video(&video_);
    m_->set_ring(&ring);
    m_->set_status(&maskbus);
    array.clk(clk);
    maskbus.active.write(cfg.pes);
}

OutputImages RtlSystem::outputs() const {
    OutputImages o;
    o.image[0] = output(0);
    o.image[1] = output(1);
    return o;
}

void RtlSystem::rethrow_if_faulted() const {
    if (array.fault()) std::rethrow_exception(array.fault());
}

RtlRunResult RtlSystem::result() const {
    const isa::Machine& m = *m_;
    RtlRunResult r;
    static_cast<isa::ModelRun&>(r) = isa::model_run_of(m);
    r.clock_edges = array.edges();
    r.signal_writes = array.signal_writes();
    r.traced_pes = static_cast<int>(array.pe.size());
    r.sim_time_s = sc_core::sc_time_stamp().to_seconds();
    r.machine = m_;
    return r;
}

namespace detail {
void claim_process(const char* who) {
    static std::atomic<bool> used{false};
    if (used.exchange(true))
        throw std::logic_error(std::string(who) +
                               ": a second SystemC simulation in this process; SystemC elaborates "
                               "once per process, so run each RTL / lockstep simulation in its "
                               "own process");
}
}  // namespace detail

RtlRunResult run_rtl(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const RtlConfig& rcfg) {
    detail::claim_process("run_rtl");
    auto sys = std::make_unique<RtlSystem>("top", cfg, prog, rcfg);
    for (const auto& [i, v] : params) sys->set_param(i, v);
    sys->set_input(0, left);
    sys->set_input(1, right);
    sys->make_output(0, out_w, out_h);
    sys->make_output(1, out_w, out_h);
    const auto t0 = std::chrono::steady_clock::now();
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();
    const auto t1 = std::chrono::steady_clock::now();
    sys->rethrow_if_faulted();
    if (!sys->array.finished())
        throw std::runtime_error("run_rtl: the simulation ended before the program halted");
    RtlRunResult r = sys->result();
    r.wall_s = std::chrono::duration<double>(t1 - t0).count();
    if (out) *out = sys->outputs();
    return r;
}

}  // namespace imap::rtl
