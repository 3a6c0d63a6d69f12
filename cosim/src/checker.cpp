#include "checker.hpp"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "imap/isa/assembler.hpp"

namespace imap::rtl::detail {

// ---------------------------------------------------------------------------
// References

StepReference::StepReference(const isa::MachineConfig& cfg, const isa::Program& prog,
                             const std::vector<std::pair<int, uint32_t>>& params, const Image& left,
                             const Image& right, int out_w, int out_h)
    : m_(cfg) {
    m_.load(prog);
    for (const auto& [i, v] : params) m_.set_param(i, v);
    video_.input[0] = left;
    video_.input[1] = right;
    video_.make_output(0, out_w, out_h);
    video_.make_output(1, out_w, out_h);
    m_.set_video(&video_);
}

bool StepReference::ready(uint64_t index) {
    while (count_ <= index && !fault_ && error_.empty() && !m_.halted()) {
        const uint32_t pc = m_.pc();
        const uint64_t c0 = m_.cycles();
        try {
            m_.step();
        } catch (const isa::Fault& f) {
            fault_ = f;
            break;
        } catch (const std::exception& e) {
            error_ = e.what();
            break;
        }
        ev_ = isa::TraceEvent{pc, m_.program().code[pc], c0, m_.cycles()};
        ++count_;
    }
    return true;
}

TlmReference::TlmReference(sc_core::sc_module_name n, tlm::TlmSystem& sys)
    : sc_core::sc_module(n), sys_(sys) {
    sys_.machine().set_observer(this);
    SC_THREAD(starter);
}

void TlmReference::starter() {
    sys_.cp.start();
    sc_core::wait(sys_.cp.done_event());
    on_done();
}

void TlmReference::on_done() {
    finished_ = true;
    if (sys_.cp.fault()) {
        try {
            std::rethrow_exception(sys_.cp.fault());
        } catch (const isa::Fault& f) {
            fault_ = f;
        } catch (const std::exception& e) {
            error_ = e.what();
        } catch (...) {
            error_ = "unknown exception in the TLM model";
        }
    }
    reached_.notify(sc_core::SC_ZERO_TIME);
}

void TlmReference::on_instruction(const isa::Machine&, const isa::TraceEvent& e) {
    ev_ = e;
    ++count_;
    reached_.notify(sc_core::SC_ZERO_TIME);
    while (released_ < count_) sc_core::wait(release_ev_);
}

bool TlmReference::ready(uint64_t index) {
    return count_ > index || finished_;
}

void TlmReference::release(uint64_t index) {
    if (index + 1 > released_) released_ = index + 1;
    release_ev_.notify(sc_core::SC_ZERO_TIME);
}

// ---------------------------------------------------------------------------
// Faults in the instruction-set model's words

isa::Fault to_fault(const FaultRecord& f, const isa::Program& prog, const isa::MachineConfig& cfg) {
    std::string mnem = "?";
    uint64_t word = 0;
    if (f.pc < prog.code.size()) {
        word = prog.code[f.pc];
        try {
            mnem = isa::disassemble_word(word);
            mnem = mnem.substr(0, mnem.find(' '));
        } catch (const std::exception&) {
            mnem = ".word";
        }
    }
    const std::string mb = std::to_string(cfg.mem_bytes), eb = std::to_string(cfg.ext_bytes);
    std::string what;
    int64_t pe = isa::Fault::kNone, addr = isa::Fault::kNone;
    switch (f.code) {
        case kFltWatchdog:
            what = "watchdog: the run exceeded watchdog_cycles = " +
                   std::to_string(cfg.watchdog_cycles) + " (runaway program?)";
            break;
        case kFltPcEnd:
            what = "the PC ran past the end of the program (" + std::to_string(prog.code.size()) +
                   " instructions)";
            break;
        case kFltIllegal:
            what = "illegal instruction word 0x" + [&] {
                std::ostringstream o;
                o << std::hex << word;
                return o.str();
            }();
            break;
        case kFltMem:
        case kFltVidMem:
            addr = f.address;
            what = mnem + ": address " + std::to_string(f.address) +
                   " out of range (local memory is " + mb + " bytes per PE: 0.." +
                   std::to_string(cfg.mem_bytes - 1) + ")";
            break;
        case kFltMemX:
            pe = f.pe;
            addr = f.address;
            what = mnem + ": PE " + std::to_string(f.pe) +
                   " address out of range (local memory is " + mb + " bytes per PE: 0.." +
                   std::to_string(cfg.mem_bytes - 1) + ")";
            break;
        case kFltParam:
            addr = f.address;
            what = mnem + ": param address " + std::to_string(f.address) + " out of range (0..255)";
            break;
        case kFltMaskOvf:
            what = "mif: mask stack overflow (mask_depth = " + std::to_string(cfg.mask_depth) + ")";
            break;
        case kFltMaskUnf:
            what = mnem + ": mask stack underflow (no open mif)";
            break;
        case kFltCallOvf:
            what =
                "call: return stack overflow (call_depth = " + std::to_string(cfg.call_depth) + ")";
            break;
        case kFltCallUnf:
            what = "ret: return stack underflow";
            break;
        case kFltExtNone:
            what = mnem + ": no external memory (ext_bytes = 0)";
            break;
        case kFltXferLen:
            what = mnem + ": negative transfer length " + std::to_string(f.address);
            break;
        case kFltXferLocal:
            addr = f.address;
            what = mnem + ": local range from " + std::to_string(f.address) +
                   " outside the local memory (" + mb + " bytes per PE)";
            break;
        case kFltXferExt:
            addr = f.address;
            what = mnem + ": external range from " + std::to_string(f.address) +
                   " outside the external memory (" + eb + " bytes per PE)";
            break;
        case kFltVidPort:
            what = mnem + ": no video image on that port";
            break;
        case kFltVidLine:
            what = mnem + ": video line outside the image";
            break;
        default:
            what = std::string("fault ") + fault_code_name(f.code);
    }
    std::string loc = prog.location(f.pc);
    std::string msg = "fault at pc " + std::to_string(f.pc) +
                      (loc.empty() ? "" : " (" + loc + ")") + ", cycle " + std::to_string(f.cycle) +
                      ": " + what + " [RTL]";
    return isa::Fault(msg, f.pc, pe, addr, f.cycle);
}

// ---------------------------------------------------------------------------
// The checker

Checker::Checker(Reference& ref, const isa::Program& prog, int pes)
    : ref_(ref), prog_(prog), prev_active_(pes) {}

Listener::Verdict Checker::diverge(const RetireRecord* r, std::string what, int64_t pe,
                                   int64_t addr, uint64_t refv, uint64_t rtlv, std::string detail) {
    diverged = true;
    Divergence& d = div;
    if (r) {
        d.instruction = r->index;
        d.pc = r->pc;
        d.word = r->word;
        d.cycle = r->cycle;
    }
    if (ref_.executed(d.instruction)) {
        d.pc = ref_.event().pc;
        d.word = ref_.event().word;
        d.cycle = ref_.event().cycle_before;
    }
    try {
        d.disassembly = isa::disassemble_word(d.word);
    } catch (const std::exception&) {
        d.disassembly = ".word";
    }
    d.what = std::move(what);
    d.pe = pe;
    d.address = addr;
    d.tlm_value = refv;
    d.rtl_value = rtlv;
    d.detail = std::move(detail);
    d.reference = ref_.name();
    return Verdict::Stop;
}

namespace {
int32_t sx(uint32_t v) {
    return static_cast<int32_t>(v);
}
}  // namespace

uint64_t Checker::auto_reg_every(int pes, int pe_regs) {
    const uint64_t n = static_cast<uint64_t>(pes) * static_cast<uint64_t>(pe_regs + 3);
    return std::max<uint64_t>(1, (n + 255) / 256);
}

uint64_t Checker::auto_mem_every(int pes, uint32_t mem_bytes) {
    const uint64_t n = static_cast<uint64_t>(pes) * mem_bytes;
    return std::max<uint64_t>(1, (n + 255) / 256);
}

namespace {
std::string lane_name(int reg, int NR) {
    return reg < NR ? "r" + std::to_string(reg) : reg == NR ? "C" : reg == NR + 1 ? "T" : "M";
}
}  // namespace

bool Checker::compare_row(const RetireRecord& r, const Backdoor& bd, int NR, int reg,
                          const std::string& detail) {
    const isa::Machine& m = ref_.machine();
    const size_t P = static_cast<size_t>(bd.P);
    row_.resize(P);
    uint8_t* got = row_.data();
    const uint8_t* want;
    if (reg < NR) {
        want = m.reg_lanes(reg);
        for (size_t p = 0; p < P; ++p) got[p] = bd.regs[p][reg];
    } else if (reg == NR) {
        want = m.carry_lanes();
        for (size_t p = 0; p < P; ++p) got[p] = *bd.carry[p] & 1u;
    } else if (reg == NR + 1) {
        want = m.test_lanes();
        for (size_t p = 0; p < P; ++p) got[p] = (*bd.st[p] >> 1) & 1u;
    } else {
        want = m.mask_lanes();
        for (size_t p = 0; p < P; ++p) got[p] = *bd.st[p] & 1u;
    }
    if (std::memcmp(want, got, P) == 0) return true;
    for (size_t p = 0; p < P; ++p)
        if (want[p] != got[p])
            return diverge(&r, lane_name(reg, NR), static_cast<int64_t>(p), -1, want[p], got[p],
                           detail),
                   false;
    return true;
}

bool Checker::compare_state(const RetireRecord& r, const Shadow& s, const Backdoor& bd,
                            const Touched& t) {
    const isa::Machine& m = ref_.machine();
    const isa::TraceEvent& e = ref_.event();
    const size_t P = static_cast<size_t>(s.P);
    if (e.pc != r.pc) return diverge(&r, "pc", -1, -1, e.pc, r.pc), false;
    if (e.word != r.word) return diverge(&r, "instruction word", -1, -1, e.word, r.word), false;
    if (e.cycle_before != r.cycle)
        return diverge(&r, "cycle", -1, -1, e.cycle_before, r.cycle,
                       "issue cycle of the instruction"),
               false;
    if (m.halted() != r.halted) return diverge(&r, "halted", -1, -1, m.halted(), r.halted), false;
    for (int i = 0; i < 16; ++i)
        if (m.cp(i) != s.creg[static_cast<size_t>(i)])
            return diverge(&r, "c" + std::to_string(i), -1, -1, m.cp(i), s.creg[i]), false;
    if (m.mask_stack_size() != s.msp)
        return diverge(&r, "mask stack depth", -1, -1, static_cast<uint64_t>(m.mask_stack_size()),
                       static_cast<uint64_t>(s.msp)),
               false;
    if (m.call_stack_size() != s.csp)
        return diverge(&r, "return stack depth", -1, -1, static_cast<uint64_t>(m.call_stack_size()),
                       static_cast<uint64_t>(s.csp)),
               false;
    if (m.current_phase() != s.phase)
        return diverge(&r, "phase", -1, -1, m.current_phase(), s.phase), false;
    // the mask bus's count of active PEs is the one before the instruction
    if (prev_active_ >= 0 && prev_active_ != r.active)
        return diverge(&r, "active PEs (mask bus)", -1, -1, static_cast<uint64_t>(prev_active_),
                       static_cast<uint64_t>(r.active), "before the instruction"),
               false;
    prev_active_ = m.active_pes();
    // PE registers and flags: what the instruction can have written (the
    // register its rd field selects in the design's 16-entry file, and the
    // flags), then every reg_every instructions all of them
    const int NR = s.NR;
    const uint32_t rd_field = (r.word >> 8) & 0xff;
    const int rd_hw = static_cast<int>(rd_field & (kHdlRegs - 1));
    if (rd_hw < NR && !compare_row(r, bd, NR, rd_hw, "")) return false;
    if (rd_field < static_cast<uint32_t>(NR) && static_cast<int>(rd_field) != rd_hw &&
        !compare_row(r, bd, NR, static_cast<int>(rd_field), ""))
        return false;
    {  // C, T, M: two gathers (T and M share the design's st_q byte)
        const isa::Machine& mm = ref_.machine();
        flags_.resize(2 * P);
        uint8_t* c = flags_.data();
        uint8_t* st = c + P;
        for (size_t p = 0; p < P; ++p) {
            c[p] = *bd.carry[p];
            st[p] = *bd.st[p];
        }
        const uint8_t* wc = mm.carry_lanes();
        const uint8_t* wt = mm.test_lanes();
        const uint8_t* wm = mm.mask_lanes();
        uint8_t bad = 0;
        for (size_t p = 0; p < P; ++p)
            bad |= static_cast<uint8_t>(((c[p] & 1u) ^ wc[p]) | (((st[p] >> 1) & 1u) ^ wt[p]) |
                                        ((st[p] & 1u) ^ wm[p]));
        if (bad)
            for (int f = NR; f < NR + 3; ++f)
                if (!compare_row(r, bd, NR, f, "")) return false;
    }
    const uint64_t re = reg_every ? reg_every : auto_reg_every(s.P, NR);
    const uint64_t me = mem_every ? mem_every : auto_mem_every(s.P, s.mem_bytes);
    auto since = [&](uint64_t every) {
        if (every <= 1) return std::string("full-state compare at every instruction");
        return "full-state compare every " + std::to_string(every) +
               " instructions: written by one of instructions " +
               std::to_string(r.index >= every ? r.index - every + 1 : 0) + ".." +
               std::to_string(r.index) + ", not as the instruction names it";
    };
    if ((r.index + 1) % re == 0) {
        ++full_reg_compares;
        const std::string d = since(re);
        for (int reg = 0; reg < NR; ++reg)
            if (!compare_row(r, bd, NR, reg, d)) return false;
    }
    // memories: the rows the instruction writes, the whole local memory every
    // mem_every instructions
    const uint8_t* mem = m.mem_data();
    const uint8_t* ext = m.ext_data();
    auto cmp_rows = [&](int64_t a0, int64_t n, bool external, const std::string& detail) {
        const int64_t lim = external ? s.ext_bytes : s.mem_bytes;
        for (int64_t a = std::max<int64_t>(a0, 0); a < std::min<int64_t>(a0 + n, lim); ++a) {
            const size_t i = static_cast<size_t>(a) * P;
            const uint8_t* w = (external ? ext : mem) + i;
            if (external) {
                const uint8_t* g = bd.ext + i;
                if (std::memcmp(w, g, P) == 0) continue;
                for (size_t p = 0; p < P; ++p)
                    if (w[p] != g[p])
                        return diverge(&r, "external memory", static_cast<int64_t>(p), a, w[p],
                                       g[p], detail),
                               false;
            } else {
                for (size_t p = 0; p < P; ++p)
                    if (w[p] != bd.mem[p][a])
                        return diverge(&r, "local memory", static_cast<int64_t>(p), a, w[p],
                                       bd.mem[p][a], detail),
                               false;
            }
        }
        return true;
    };
    auto cmp_mem = [&](int pe, uint32_t a) {
        const uint8_t w = mem[static_cast<size_t>(a) * P + static_cast<size_t>(pe)];
        const uint8_t g = bd.mem[static_cast<size_t>(pe)][a];
        if (w != g) return diverge(&r, "local memory", pe, a, w, g), false;
        return true;
    };
    if ((r.index + 1) % me == 0) {
        ++full_mem_compares;
        if (!cmp_rows(0, s.mem_bytes, false, since(me))) return false;
    }
    const uint8_t op = static_cast<uint8_t>(r.word);
    const uint32_t rd = (r.word >> 8) & 0xff, ra = (r.word >> 16) & 0xff,
                   rb = (r.word >> 24) & 0xff;
    const uint32_t imm = static_cast<uint32_t>(r.word >> 32);
    const int64_t base = rb == 128 ? 0 : sx(m.cp(static_cast<int>(rb & 15)));
    switch (op) {
        case 0x91:  // st
        case 0xC0:  // vin
            if (!cmp_rows(base + sx(imm), 1, false, "")) return false;
            break;
        case 0x94:  // xld
            if (!cmp_rows(base + sx(imm), sx(m.cp(static_cast<int>(rd & 15))), false, ""))
                return false;
            break;
        case 0x95:  // xst
            if (!cmp_rows(m.cp(static_cast<int>(ra & 15)), sx(m.cp(static_cast<int>(rd & 15))),
                          true, ""))
                return false;
            break;
        case 0x93: {  // stx
            const bool nohi = (imm >> 29) & 1u;
            const int64_t off =
                (static_cast<int64_t>(imm << 8) >> 8) +
                (((imm >> 28) & 1u) ? sx(m.cp(static_cast<int>((imm >> 24) & 15))) : 0);
            const uint8_t* lo = m.reg_lanes(static_cast<int>(ra));
            const uint8_t* hi = m.reg_lanes(static_cast<int>(rb));
            for (size_t p = 0; p < P; ++p) {
                const int64_t a = (nohi ? 0 : int64_t{hi[p]} << 8) + lo[p] + off;
                if (a >= 0 && a < s.mem_bytes &&
                    !cmp_mem(static_cast<int>(p), static_cast<uint32_t>(a)))
                    return false;
            }
            break;
        }
        default:
            break;
    }
    if (t.param || op == 0x18)
        for (int i = 0; i < 256; ++i)
            if (m.param(i) != s.param[static_cast<size_t>(i)])
                return diverge(&r, "param block", -1, i, m.param(i), s.param[i]), false;
    return true;
}

Listener::Verdict Checker::on_retire(const RetireRecord& r, const Shadow& s, const Backdoor& bd,
                                     const Touched& t) {
    if (diverged) return Verdict::Stop;
    if (!ref_.ready(r.index)) return Verdict::Wait;
    if (!ref_.executed(r.index)) {
        if (ref_.fault())
            return diverge(&r, "fault", -1, -1, 1, 0,
                           std::string("the RTL retired it, the ") + ref_.name() +
                               " model faulted: " + ref_.fault()->what());
        if (!ref_.error().empty())
            return diverge(&r, "error", -1, -1, 1, 0,
                           std::string("the ") + ref_.name() + " model stopped: " + ref_.error());
        return diverge(&r, "retired instructions", -1, -1, r.index, r.index + 1,
                       std::string("the RTL retired an instruction after the ") + ref_.name() +
                           " model halted");
    }
    if (!compare_state(r, s, bd, t)) return Verdict::Stop;
    ++compared;
    if (on_compared) on_compared(r, ref_.machine());
    if (after_compare) after_compare(r);
    ref_.release(r.index);
    return Verdict::Go;
}

Listener::Verdict Checker::on_fault(const FaultRecord& f, const Shadow&) {
    if (diverged) return Verdict::Stop;
    fault_index = f.index;
    if (!ref_.ready(f.index)) return Verdict::Wait;
    RetireRecord r;
    r.index = f.index;
    r.pc = f.pc;
    r.cycle = f.cycle;
    r.word = f.pc < prog_.code.size() ? prog_.code[f.pc] : 0;
    const std::string rtl_fault = std::string("RTL: ") + fault_code_name(f.code);
    if (ref_.executed(f.index))
        return diverge(&r, "fault", -1, -1, 0, 1,
                       rtl_fault + "; the " + ref_.name() + " model executed the instruction");
    const isa::Fault* rf = ref_.fault();
    if (!rf)
        return diverge(&r, "fault", -1, -1, 0, 1,
                       rtl_fault + "; the " + ref_.name() + " model did not fault" +
                           (ref_.error().empty() ? "" : ": " + ref_.error()));
    if (rf->pc() != f.pc) return diverge(&r, "fault pc", -1, -1, rf->pc(), f.pc, rf->what());
    if (rf->cycle() != f.cycle)
        return diverge(&r, "fault cycle", -1, -1, rf->cycle(), f.cycle, rf->what());
    if (rf->pe() != f.pe)
        return diverge(&r, "fault PE", -1, -1, static_cast<uint64_t>(rf->pe()),
                       static_cast<uint64_t>(f.pe), rtl_fault + " / " + rf->what());
    if (rf->address() != isa::Fault::kNone && rf->address() != f.address)
        return diverge(&r, "fault address", f.pe, -1, static_cast<uint64_t>(rf->address()),
                       static_cast<uint64_t>(f.address), rtl_fault + " / " + rf->what());
    ++compared;
    return Verdict::Go;
}

void Checker::final_check(const Job& job, const Shadow& s, const Backdoor& bd) {
    if (diverged) return;
    const isa::Machine& m = ref_.machine();
    RetireRecord last;
    last.index = job.instructions;
    last.cycle = job.cycles;
    if (job.fault.valid != (ref_.fault() != nullptr)) {
        diverge(&last, "fault", -1, -1, ref_.fault() != nullptr, job.fault.valid,
                "at the end of the run");
        return;
    }
    if (!job.fault.valid) {
        if (m.halted() != job.halted) {
            diverge(&last, "halted", -1, -1, m.halted(), job.halted, "at the end of the run");
            return;
        }
        if (m.cycles() != job.cycles) {
            diverge(&last, "cycles", -1, -1, m.cycles(), job.cycles, "total machine cycles");
            return;
        }
    }
    // the design's complete state (backdoor) against the reference
    const RtlStateData st = read_state(bd, s.NR);
    const size_t P = static_cast<size_t>(s.P);
    for (int reg = 0; reg < s.NR + 3; ++reg) {
        const uint8_t* want = reg < s.NR        ? m.reg_lanes(reg)
                              : reg == s.NR     ? m.carry_lanes()
                              : reg == s.NR + 1 ? m.test_lanes()
                                                : m.mask_lanes();
        for (size_t p = 0; p < P; ++p) {
            const uint8_t got = st.lanes[static_cast<size_t>(reg) * P + p];
            if (want[p] != got) {
                diverge(&last,
                        (reg < s.NR        ? "r" + std::to_string(reg)
                         : reg == s.NR     ? "C"
                         : reg == s.NR + 1 ? "T"
                                           : "M") +
                            " (final state)",
                        static_cast<int64_t>(p), -1, want[p], got);
                return;
            }
        }
    }
    auto mem_check = [&](const uint8_t* want, const std::vector<uint8_t>& got, size_t bytes,
                         const char* name) {
        for (size_t i = 0; i < bytes * P; ++i)
            if (want[i] != got[i]) {
                diverge(&last, std::string(name) + " (final state)", static_cast<int64_t>(i % P),
                        static_cast<int64_t>(i / P), want[i], got[i]);
                return false;
            }
        return true;
    };
    if (!mem_check(m.mem_data(), st.mem, s.mem_bytes, "local memory")) return;
    if (!mem_check(m.ext_data(), st.ext, s.ext_bytes, "external memory")) return;
    for (int i = 0; i < 16; ++i)
        if (m.cp(i) != st.creg[static_cast<size_t>(i)]) {
            diverge(&last, "c" + std::to_string(i) + " (final state)", -1, -1, m.cp(i), st.creg[i]);
            return;
        }
    for (int i = 0; i < 256; ++i)
        if (m.param(i) != st.param[static_cast<size_t>(i)]) {
            diverge(&last, "param block (final state)", -1, i, m.param(i), st.param[i]);
            return;
        }
}

}  // namespace imap::rtl::detail
