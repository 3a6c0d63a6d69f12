#include "imap/rtl/lockstep.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <array>
#include <chrono>
#include <cstring>
#include <deque>
#include <sstream>
#include <stdexcept>

#include "imap/isa/assembler.hpp"

namespace imap::rtl {

namespace {

// A fast 64-bit hash of a byte block (four independent multiply-xor chains).
uint64_t hash_bytes(const uint8_t* p, size_t n) {
    constexpr uint64_t k = 0x9E3779B97F4A7C15ull;
    uint64_t h[4] = {k ^ n, k * 3, k * 5, k * 7};
    size_t i = 0;
    for (; i + 32 <= n; i += 32)
        for (int j = 0; j < 4; ++j) {
            uint64_t v;
            std::memcpy(&v, p + i + 8 * static_cast<size_t>(j), 8);
            h[j] = (h[j] ^ v) * 0xff51afd7ed558ccdull;
            h[j] ^= h[j] >> 29;
        }
    uint64_t r = h[0] ^ (h[1] * 31) ^ (h[2] * 131) ^ (h[3] * 1031);
    for (; i < n; ++i) r = (r ^ p[i]) * 0x100000001b3ull;
    r ^= r >> 33;
    r *= 0xc4ceb9fe1a85ec53ull;
    return r ^ (r >> 29);
}

struct Record {
    uint64_t index = 0, cycle_before = 0, cycle_after = 0, word = 0;
    uint32_t pc = 0, pc_after = 0, phase = 0;
    bool halted = false;
    int msp = 0, csp = 0;
    std::array<uint32_t, isa::kCpRegs> creg{};
    std::vector<uint8_t> lanes;  // regs | C | T | M, P bytes each
    uint64_t mem_hash = 0, ext_hash = 0, param_hash = 0;
};

class Lockstep;

// One model's recorder: tracks which memories an instruction wrote and
// records the state every interval-th instruction.
class Side {
  public:
    Side(Lockstep& ls, int id) : ls_(ls), id_(id) {}
    void retire(const isa::Machine& m, const isa::TraceEvent& e, uint64_t index);

  private:
    Lockstep& ls_;
    int id_;
    bool mem_dirty_ = true, ext_dirty_ = true, param_dirty_ = true;
    uint64_t mem_hash_ = 0, ext_hash_ = 0, param_hash_ = 0;
};

class Lockstep {
  public:
    Lockstep(uint64_t interval, int P, int NR)
        : interval_(interval),
          P_(static_cast<size_t>(P)),
          NR_(static_cast<size_t>(NR)),
          tlm_(*this, 0),
          rtl_(*this, 1) {}
    uint64_t interval() const { return interval_; }
    void push(int side, Record&& r);

    bool diverged = false;
    Divergence div;
    uint64_t compared = 0;
    std::deque<Record> q[2];
    Side& side(int i) { return i == 0 ? tlm_ : rtl_; }

  private:
    void compare(const Record& t, const Record& r);
    void diverge(const Record& t, const std::string& what, int64_t pe, uint64_t tv, uint64_t rv);

    uint64_t interval_;
    size_t P_, NR_;
    Side tlm_, rtl_;
};

void Side::retire(const isa::Machine& m, const isa::TraceEvent& e, uint64_t index) {
    switch (static_cast<isa::Op>(static_cast<uint8_t>(e.word))) {
        case isa::Op::ST:
        case isa::Op::STX:
        case isa::Op::XLD:
        case isa::Op::VIN:
            mem_dirty_ = true;
            break;
        case isa::Op::XST:
            ext_dirty_ = true;
            break;
        case isa::Op::CST:
            param_dirty_ = true;
            break;
        default:
            break;
    }
    if (index % ls_.interval() != 0 && !m.halted()) return;
    const size_t P = static_cast<size_t>(m.pes());
    const isa::MachineConfig& c = m.config();
    if (mem_dirty_) mem_hash_ = hash_bytes(m.mem_data(), size_t{c.mem_bytes} * P);
    if (ext_dirty_) ext_hash_ = hash_bytes(m.ext_data(), size_t{c.ext_bytes} * P);
    if (param_dirty_)
        param_hash_ = hash_bytes(reinterpret_cast<const uint8_t*>(m.params().data()),
                                 sizeof(uint32_t) * m.params().size());
    mem_dirty_ = ext_dirty_ = param_dirty_ = false;
    Record r;
    r.index = index;
    r.cycle_before = e.cycle_before;
    r.cycle_after = e.cycle_after;
    r.word = e.word;
    r.pc = e.pc;
    r.pc_after = m.pc();
    r.phase = m.current_phase();
    r.halted = m.halted();
    r.msp = m.mask_stack_size();
    r.csp = m.call_stack_size();
    for (int i = 0; i < isa::kCpRegs; ++i) r.creg[static_cast<size_t>(i)] = m.cp(i);
    const size_t NR = static_cast<size_t>(c.pe_regs);
    r.lanes.resize((NR + 3) * P);
    // One P-byte row per register (the machine pads its rows: they are not
    // adjacent).
    for (size_t i = 0; i < NR; ++i)
        std::memcpy(r.lanes.data() + i * P, m.reg_lanes(static_cast<int>(i)), P);
    std::memcpy(r.lanes.data() + NR * P, m.carry_lanes(), P);
    std::memcpy(r.lanes.data() + (NR + 1) * P, m.test_lanes(), P);
    std::memcpy(r.lanes.data() + (NR + 2) * P, m.mask_lanes(), P);
    r.mem_hash = mem_hash_;
    r.ext_hash = ext_hash_;
    r.param_hash = param_hash_;
    ls_.push(id_, std::move(r));
}

void Lockstep::push(int side, Record&& r) {
    if (diverged) return;
    std::deque<Record>& other = q[1 - side];
    if (other.empty()) {
        q[side].push_back(std::move(r));
        return;
    }
    const Record o = std::move(other.front());
    other.pop_front();
    ++compared;
    if (side == 0)
        compare(r, o);
    else
        compare(o, r);
}

void Lockstep::diverge(const Record& t, const std::string& what, int64_t pe, uint64_t tv,
                       uint64_t rv) {
    diverged = true;
    div.instruction = t.index;
    div.cycle = t.cycle_before;
    div.pc = t.pc;
    div.word = t.word;
    div.disassembly = isa::disassemble_word(t.word);
    div.what = what;
    div.pe = pe;
    div.tlm_value = tv;
    div.rtl_value = rv;
    sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                            sc_core::SC_DO_NOTHING);
    sc_core::sc_stop();
}

void Lockstep::compare(const Record& t, const Record& r) {
    if (t.index != r.index) return diverge(t, "instruction index", -1, t.index, r.index);
    if (t.pc != r.pc) return diverge(t, "pc", -1, t.pc, r.pc);
    if (t.word != r.word) return diverge(t, "instruction word", -1, t.word, r.word);
    if (t.cycle_before != r.cycle_before)
        return diverge(t, "cycles before", -1, t.cycle_before, r.cycle_before);
    if (t.cycle_after != r.cycle_after)
        return diverge(t, "cycles", -1, t.cycle_after, r.cycle_after);
    if (t.halted != r.halted) return diverge(t, "halted", -1, t.halted, r.halted);
    if (t.pc_after != r.pc_after) return diverge(t, "next pc", -1, t.pc_after, r.pc_after);
    for (size_t i = 0; i < t.creg.size(); ++i)
        if (t.creg[i] != r.creg[i])
            return diverge(t, "c" + std::to_string(i), -1, t.creg[i], r.creg[i]);
    if (t.csp != r.csp)
        return diverge(t, "call stack depth", -1, static_cast<uint64_t>(t.csp),
                       static_cast<uint64_t>(r.csp));
    if (t.msp != r.msp)
        return diverge(t, "mask stack depth", -1, static_cast<uint64_t>(t.msp),
                       static_cast<uint64_t>(r.msp));
    if (t.phase != r.phase) return diverge(t, "phase", -1, t.phase, r.phase);
    if (t.lanes != r.lanes) {
        // Rows of P bytes: r0 .. r(NR-1), C, T, M; report the first differing lane.
        for (size_t j = 0; j < NR_ + 3; ++j)
            for (size_t p = 0; p < P_; ++p) {
                const size_t i = j * P_ + p;
                if (t.lanes[i] == r.lanes[i]) continue;
                const std::string what = j < NR_        ? "r" + std::to_string(j)
                                         : j == NR_     ? "C"
                                         : j == NR_ + 1 ? "T"
                                                        : "M";
                return diverge(t, what, static_cast<int64_t>(p), t.lanes[i], r.lanes[i]);
            }
    }
    if (t.mem_hash != r.mem_hash) return diverge(t, "local memory", -1, t.mem_hash, r.mem_hash);
    if (t.ext_hash != r.ext_hash) return diverge(t, "external memory", -1, t.ext_hash, r.ext_hash);
    if (t.param_hash != r.param_hash)
        return diverge(t, "param block", -1, t.param_hash, r.param_hash);
}

// Adapters: the TLM machine's observer and the RTL array's retire hook.
struct TlmTap : isa::Observer {
    explicit TlmTap(Side& s) : side(s) {}
    void on_instruction(const isa::Machine& m, const isa::TraceEvent& e) override {
        side.retire(m, e, index++);
    }
    Side& side;
    uint64_t index = 0;
};
struct RtlTap : RetireHook {
    explicit RtlTap(Side& s) : side(s) {}
    void on_retire(const isa::Machine& m, const isa::TraceEvent& e, uint64_t index) override {
        side.retire(m, e, index);
    }
    Side& side;
};

// Final state: everything the per-instruction records do not cover exactly.
void final_compare(const isa::Machine& t, const isa::Machine& r, const OutputImages& tout,
                   const OutputImages& rout, uint64_t last_index, Divergence& d, bool& diverged) {
    auto set = [&](const std::string& what, int64_t pe, int64_t addr, uint64_t tv, uint64_t rv) {
        diverged = true;
        d.instruction = last_index;
        d.cycle = t.cycles();
        d.pc = t.pc();
        d.word = t.pc() < t.program().code.size() ? t.program().code[t.pc()] : 0;
        d.disassembly = isa::disassemble_word(d.word);
        d.what = what;
        d.pe = pe;
        d.address = addr;
        d.tlm_value = tv;
        d.rtl_value = rv;
    };
    const size_t P = static_cast<size_t>(t.pes());
    if (t.cycles() != r.cycles()) return set("cycles (final)", -1, -1, t.cycles(), r.cycles());
    if (t.stats().instructions != r.stats().instructions)
        return set("instructions (final)", -1, -1, t.stats().instructions, r.stats().instructions);
    if (t.phase_cycles() != r.phase_cycles()) return set("phase cycles (final)", -1, -1, 0, 0);
    if (t.stats().class_cycles != r.stats().class_cycles)
        return set("class cycles (final)", -1, -1, 0, 0);
    const struct {
        const char* name;
        const uint8_t *a, *b;
        size_t bytes;
    } mems[] = {{"local memory", t.mem_data(), r.mem_data(), size_t{t.config().mem_bytes} * P},
                {"external memory", t.ext_data(), r.ext_data(), size_t{t.config().ext_bytes} * P}};
    for (const auto& mm : mems)
        for (size_t i = 0; i < mm.bytes; ++i)
            if (mm.a[i] != mm.b[i])
                return set(mm.name, static_cast<int64_t>(i % P), static_cast<int64_t>(i / P),
                           mm.a[i], mm.b[i]);
    for (int port = 0; port < 2; ++port)
        if (tout.image[port].pixels != rout.image[port].pixels)
            return set("video output " + std::to_string(port), -1, -1, 0, 0);
}

}  // namespace

std::string Divergence::message() const {
    std::ostringstream os;
    os << "lockstep divergence at instruction " << instruction << " (cycle " << cycle << ", pc "
       << pc << ": " << disassembly << "): " << what;
    if (pe >= 0) os << " of PE " << pe;
    if (address >= 0) os << " at address " << address;
    os << ": TLM " << tlm_value << ", RTL " << rtl_value;
    return os.str();
}

void LockstepConfig::validate(const isa::MachineConfig& cfg) const {
    if (interval < 1)
        throw isa::ConfigError("lockstep interval = " + std::to_string(interval) +
                               " out of range (>= 1)");
    rtl.validate(cfg);
}

LockstepResult run_lockstep(const isa::MachineConfig& cfg, const isa::Program& prog,
                            const std::vector<std::pair<int, uint32_t>>& params,
                            const ImageInput& left, const ImageInput& right, int out_w, int out_h,
                            OutputImages* out, const LockstepConfig& lcfg) {
    cfg.validate();
    lcfg.validate(cfg);
    detail::claim_process("run_lockstep");
    auto tsys = std::make_unique<tlm::TlmSystem>("tlm", cfg, prog);
    auto rsys = std::make_unique<RtlSystem>("rtl", cfg, prog, lcfg.rtl);
    for (const auto& [i, v] : params) {
        tsys->set_param(i, v);
        rsys->set_param(i, v);
    }
    tsys->set_input(0, left);
    tsys->set_input(1, right);
    rsys->set_input(0, left);
    rsys->set_input(1, right);
    for (int port = 0; port < 2; ++port) {
        tsys->make_output(port, out_w, out_h);
        rsys->make_output(port, out_w, out_h);
    }
    Lockstep ls(lcfg.interval, cfg.pes, cfg.pe_regs);
    TlmTap ttap(ls.side(0));
    RtlTap rtap(ls.side(1));
    tsys->machine().set_observer(&ttap);
    rsys->array.set_hook(&rtap);
    const tlm::TlmSystem* tp = tsys.get();
    rsys->array.set_stop_condition([tp]() { return tp->cp.finished() || tp->cp.fault(); });

    const auto t0 = std::chrono::steady_clock::now();
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();
    const auto t1 = std::chrono::steady_clock::now();
    tsys->machine().set_observer(nullptr);

    LockstepResult res;
    res.compared = ls.compared;
    res.wall_s = std::chrono::duration<double>(t1 - t0).count();
    if (ls.diverged) {
        res.diverged = true;
        res.divergence = ls.div;
        if (res.divergence.what == "local memory" || res.divergence.what == "external memory") {
            // Only a hash was recorded: locate the first differing byte in the
            // models' current memories (both are stopped close to the point).
            const bool local = res.divergence.what == "local memory";
            const isa::Machine& a = tsys->machine();
            const isa::Machine& b = rsys->machine();
            const size_t P = static_cast<size_t>(cfg.pes);
            const size_t n = (local ? size_t{cfg.mem_bytes} : size_t{cfg.ext_bytes}) * P;
            const uint8_t* x = local ? a.mem_data() : a.ext_data();
            const uint8_t* y = local ? b.mem_data() : b.ext_data();
            for (size_t i = 0; i < n; ++i)
                if (x[i] != y[i]) {
                    res.divergence.pe = static_cast<int64_t>(i % P);
                    res.divergence.address = static_cast<int64_t>(i / P);
                    res.divergence.tlm_value = x[i];
                    res.divergence.rtl_value = y[i];
                    break;
                }
        }
    } else {
        if (rsys->array.fault()) rsys->rethrow_if_faulted();
        tsys->rethrow_if_faulted();
        if (!tsys->cp.finished() || !rsys->array.finished())
            throw std::runtime_error(
                "run_lockstep: the simulation ended before both models halted");
        if (!ls.q[0].empty() || !ls.q[1].empty()) {
            const Record& r = ls.q[0].empty() ? ls.q[1].front() : ls.q[0].front();
            res.diverged = true;
            res.divergence.instruction = r.index;
            res.divergence.cycle = r.cycle_before;
            res.divergence.pc = r.pc;
            res.divergence.word = r.word;
            res.divergence.disassembly = isa::disassemble_word(r.word);
            res.divergence.what = ls.q[0].empty() ? "instructions (RTL retired more)"
                                                  : "instructions (TLM retired more)";
        } else {
            final_compare(tsys->machine(), rsys->machine(), tsys->outputs(), rsys->outputs(),
                          rsys->array.instructions(), res.divergence, res.diverged);
        }
    }
    res.instructions = rsys->array.instructions();
    res.tlm = tsys->result();
    res.rtl = rsys->result();
    res.rtl.wall_s = res.wall_s;
    if (out) *out = tsys->outputs();
    return res;
}

}  // namespace imap::rtl
