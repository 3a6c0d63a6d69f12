// The machine: decode once at load into handlers and straight-line runs,
// then a run loop that executes a run at a time (one indirect call per
// instruction; cycle, phase and statistics bookkeeping once per run). The
// handlers themselves are in exec.cpp, one table per SIMD path.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "exec.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/machine.hpp"

namespace imap::isa {

using detail::kChunk;
using detail::kFlagNoHigh;
using detail::kFlagPeWork;
using detail::kZeroCp;

namespace {

std::string hex64(uint64_t w) {
    char b[24];
    std::snprintf(b, sizeof b, "0x%016llx", static_cast<unsigned long long>(w));
    return b;
}

// Instructions after which the run loop must look at the machine again:
// control flow, the phase, the mask (and so the active PE count), variable
// cycles (xld / xst) and the video port (the host sees the cycle counter).
bool ends_run(uint8_t code) {
    switch (static_cast<Op>(code)) {
        case Op::HALT:
        case Op::PHASE:
        case Op::JMP:
        case Op::BEQ:
        case Op::BNE:
        case Op::BLT:
        case Op::BGE:
        case Op::BZ:
        case Op::BNZ:
        case Op::LOOP:
        case Op::CALL:
        case Op::RET:
        case Op::MIF:
        case Op::MELSE:
        case Op::MEND:
        case Op::MALL:
        case Op::XLD:
        case Op::XST:
        case Op::VIN:
        case Op::VOUT:
            return true;
        default:
            return false;
    }
}

size_t round_up(size_t n, size_t k) {
    return (n + k - 1) / k * k;
}

}  // namespace

// ---------------------------------------------------------------------------
// SIMD paths

const char* to_string(SimdPath p) {
    switch (p) {
        case SimdPath::Generic:
            return "generic";
        case SimdPath::Avx2:
            return "avx2";
        case SimdPath::Avx512:
            return "avx512";
    }
    return "?";
}

SimdPath simd_path_from_string(const std::string& name) {
    for (SimdPath p : {SimdPath::Generic, SimdPath::Avx2, SimdPath::Avx512})
        if (name == to_string(p)) return p;
    throw std::invalid_argument("unknown SIMD path '" + name +
                                "' (allowed: generic, avx2, avx512)");
}

std::vector<SimdPath> supported_simd_paths() {
    std::vector<SimdPath> v;
    for (SimdPath p : {SimdPath::Generic, SimdPath::Avx2, SimdPath::Avx512})
        if (detail::cpu_supports(p)) v.push_back(p);
    return v;
}

SimdPath default_simd_path() {
    if (const char* e = std::getenv("IMAP_ISA_SIMD"); e && *e) {
        const SimdPath p = simd_path_from_string(e);
        if (!detail::cpu_supports(p))
            throw std::runtime_error(std::string("IMAP_ISA_SIMD=") + e +
                                     ": this CPU cannot run that path");
        return p;
    }
    return supported_simd_paths().back();
}

// ---------------------------------------------------------------------------
// ImageVideoPort

void ImageVideoPort::make_output(int port, int width, int height) {
    if (port < 0 || port > 1) throw std::out_of_range("video port must be 0 or 1");
    output[port].width = width;
    output[port].height = height;
    output[port].pixels.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
}

void ImageVideoPort::read_line(int port, int y, int x0, uint8_t* dst, int n) {
    if (port < 0 || port > 1)
        throw std::out_of_range("no video input port " + std::to_string(port));
    const Image& im = input[port];
    if (y < 0 || y >= im.height)
        throw std::out_of_range("line outside input image " + std::to_string(port) + " (" +
                                std::to_string(im.width) + "x" + std::to_string(im.height) + ")");
    const uint8_t* row = im.pixels.data() + static_cast<size_t>(y) * static_cast<size_t>(im.width);
    for (int i = 0; i < n; ++i) {
        const int64_t x = int64_t{x0} + i;
        dst[i] = (x >= 0 && x < im.width) ? row[x] : 0;
    }
}

void ImageVideoPort::write_line(int port, int y, int x0, const uint8_t* src, int n) {
    if (port < 0 || port > 1)
        throw std::out_of_range("no video output port " + std::to_string(port));
    Image& im = output[port];
    if (y < 0 || y >= im.height)
        throw std::out_of_range("line outside output image " + std::to_string(port) + " (" +
                                std::to_string(im.width) + "x" + std::to_string(im.height) + ")");
    uint8_t* row = im.pixels.data() + static_cast<size_t>(y) * static_cast<size_t>(im.width);
    for (int i = 0; i < n; ++i) {
        const int64_t x = int64_t{x0} + i;
        if (x >= 0 && x < im.width) row[x] = src[i];
    }
}

// ---------------------------------------------------------------------------
// Machine

Machine::Block::~Block() {
    std::free(p);
}

uint8_t* Machine::Block::alloc(size_t n, size_t align) {
    std::free(p);
    p = static_cast<uint8_t*>(std::calloc(n + align, 1));
    if (!p) throw std::bad_alloc();
    const uintptr_t a = reinterpret_cast<uintptr_t>(p);
    return p + (align - a % align) % align;
}

Machine::Machine(const MachineConfig& cfg) : cfg_(cfg) {
    cfg_.validate();
    P_ = cfg_.pes;
    S_ = round_up(static_cast<size_t>(P_), kChunk);
    NR_ = static_cast<size_t>(cfg_.pe_regs);
    const size_t P = static_cast<size_t>(P_), S = S_;
    const size_t depth = static_cast<size_t>(cfg_.mask_depth);
    // regs, C, T, M, mask stack, 4 pidx rows, a zero row, 4 scratch rows
    // (ldx / stx keep a 32-bit cell index per lane there), and the lane
    // numbers as 32-bit words (4 rows)
    lanes_ = lane_block_.alloc((NR_ + 3 + depth + 4 + 1 + 4 + 4) * S, 64);
    c_ = lanes_ + NR_ * S;
    t_ = c_ + S;
    m_ = t_ + S;
    mstack_ = m_ + S;
    pidx_ = mstack_ + depth * S;
    zero_ = pidx_ + 4 * S;
    scratch_ = zero_ + S;
    lane_no_ = reinterpret_cast<uint32_t*>(scratch_ + 4 * S);
    for (size_t p = 0; p < S; ++p) lane_no_[p] = static_cast<uint32_t>(p);
    for (size_t k = 0; k < 4; ++k)
        for (size_t p = 0; p < P; ++p) pidx_[k * S + p] = static_cast<uint8_t>(p >> (8 * k));
    // Slack after the memory: row loads over the padded lanes read up to
    // S - P bytes past a row; ldx / stx park inactive lanes on its first byte
    // and the gathers load 4 bytes at a cell.
    mem_ = mem_block_.alloc(static_cast<size_t>(cfg_.mem_bytes) * P + kChunk, 64);
    ext_ = ext_block_.alloc(static_cast<size_t>(cfg_.ext_bytes) * P, 64);
    cstack_.assign(static_cast<size_t>(cfg_.call_depth), 0);
    simd_ = default_simd_path();
    Program empty;
    empty.code.push_back(Word{static_cast<uint8_t>(Op::HALT)}.encode());
    empty.phases.push_back("default");
    load(empty);
}

size_t Machine::lane_off(int r) const {
    if (r < 0 || static_cast<size_t>(r) >= NR_)
        throw std::out_of_range("PE register r" + std::to_string(r) +
                                " does not exist (pe_regs = " + std::to_string(NR_) + ")");
    return static_cast<size_t>(r) * S_;
}

void Machine::set_simd_path(SimdPath p) {
    if (!detail::cpu_supports(p))
        throw std::invalid_argument(std::string("SIMD path ") + to_string(p) +
                                    " is not supported by this CPU");
    simd_ = p;
    bind_handlers();
}

void Machine::bind_handlers() {
    for (size_t i = 0; i + 1 < code_.size(); ++i) {
        Decoded& d = code_[i];
        const bool fixed = S_ == detail::kFixedLanes;
        d.fn[0] = detail::handler_of(simd_, d.op, false, fixed);
        d.fn[1] = detail::handler_of(simd_, d.op, true, fixed);
    }
    Decoded& end = code_.back();
    end.fn[0] = end.fn[1] = detail::end_of_program_handler();
}

void Machine::load(const Program& prog) {
    const uint32_t n = static_cast<uint32_t>(prog.code.size());
    const size_t n_phases = std::max<size_t>(1, prog.phases.size());
    std::vector<Decoded> code;
    code.reserve(n + 1);
    const CostTable& k = cfg_.costs;
    for (uint32_t pc = 0; pc < n; ++pc) {
        const uint64_t w = prog.code[pc];
        auto where = [&]() {
            const std::string loc = prog.location(pc);
            return "cannot load program: pc " + std::to_string(pc) +
                   (loc.empty() ? "" : " (" + loc + ")") + ", word " + hex64(w) + ": ";
        };
        const std::string why = check_word(w);
        if (!why.empty()) throw LoadError(where() + why, pc);
        const Word x = Word::decode(w);
        const OpInfo& info = *op_info(x.op);
        const std::string mn(info.mnemonic);
        Decoded d;
        d.op = x.op;
        d.cls = static_cast<uint8_t>(info.cost_class);
        d.imm = as_signed(x.imm);
        auto pe = [&](uint8_t r, const char* field) -> uint32_t {
            if (r >= NR_)
                throw LoadError(
                    where() + mn + ": register r" + std::to_string(r) + " (field " + field +
                        ") does not exist on this machine (pe_regs = " + std::to_string(NR_) + ")",
                    pc);
            return static_cast<uint32_t>(r * S_);
        };
        auto base = [](uint8_t r) { return r == kNoBase ? kZeroCp : uint32_t{r}; };
        auto target = [&]() {
            if (x.imm >= n)
                throw LoadError(where() + mn + ": target " + std::to_string(x.imm) +
                                    " outside the program (0.." + std::to_string(n - 1) + ")",
                                pc);
            return x.imm;
        };
        switch (info.format) {
            case Format::None:
                break;
            case Format::Rrr:
                d.d = pe(x.rd, "rd");
                d.a = pe(x.ra, "ra");
                d.b = pe(x.rb, "rb");
                break;
            case Format::Rri8:
            case Format::Rsh:
            case Format::Rr:
            case Format::Ring:
                d.d = pe(x.rd, "rd");
                d.a = pe(x.ra, "ra");
                d.b = d.a;
                break;
            case Format::Ri8:
            case Format::R:
            case Format::Rk:
                d.d = pe(x.rd, "rd");
                break;
            case Format::Cmp:
                d.a = pe(x.ra, "ra");
                d.b = pe(x.rb, "rb");
                break;
            case Format::Cmpi:
                d.a = pe(x.ra, "ra");
                break;
            case Format::Rc:
            case Format::Rck:
                d.d = pe(x.rd, "rd");
                d.a = x.ra;
                break;
            case Format::Ld:
                d.d = pe(x.rd, "rd");
                d.b = base(x.rb);
                break;
            case Format::Ldx:
                if (!cfg_.indirect)
                    throw LoadError(where() + mn +
                                        ": per-PE (indirect) addressing is not available on this "
                                        "machine (parameter indirect = off)",
                                    pc);
                d.d = pe(x.rd, "rd");
                d.a = pe(x.ra, "ra");
                if (x.imm & kLdxNoHigh)
                    d.flags |= kFlagNoHigh;
                else
                    d.b = pe(x.rb, "rb");
                d.aux = (x.imm & kLdxUseCp) ? (x.imm >> kLdxCpShift) & 15u : kZeroCp;
                d.imm = ldx_offset(x.imm);
                break;
            case Format::Xfer:
                d.d = x.rd;
                d.a = x.ra;
                d.b = base(x.rb);
                break;
            case Format::Stat:
            case Format::Ci:
                d.d = x.rd;
                break;
            case Format::Cc:
            case Format::Cci:
            case Format::Csh:
                d.d = x.rd;
                d.a = x.ra;
                break;
            case Format::Ccc:
                d.d = x.rd;
                d.a = x.ra;
                d.b = x.rb;
                break;
            case Format::Cmem:
                d.d = x.rd;
                d.b = base(x.rb);
                break;
            case Format::J:
                d.aux = target();
                break;
            case Format::Bcc:
                d.a = x.ra;
                d.b = x.rb;
                d.aux = target();
                break;
            case Format::B1:
                d.a = x.ra;
                d.aux = target();
                break;
            case Format::Video:
                d.d = x.rd;
                d.aux = x.ra;
                d.b = base(x.rb);
                break;
            case Format::Phase:
                if (x.imm >= n_phases)
                    throw LoadError(where() + "phase id " + std::to_string(x.imm) +
                                        " has no name in the program (" + std::to_string(n_phases) +
                                        " phases)",
                                    pc);
                break;
        }
        switch (info.cost_class) {
            case CostClass::Alu:
                d.cost = k.alu;
                break;
            case CostClass::Mem:
                d.cost = k.mem;
                break;
            case CostClass::Indirect:
                d.cost = uint64_t{k.mem} + k.indirect_extra;
                break;
            case CostClass::Ring:
                d.cost = uint64_t{x.imm} * k.ring_hop;
                break;
            case CostClass::Mask:
                d.cost = k.mask;
                break;
            case CostClass::Status:
                d.cost = k.status;
                break;
            case CostClass::Cp:
                d.cost = k.cp;
                break;
            case CostClass::Video:
                d.cost = k.video_line;
                break;
            case CostClass::Xfer:
                d.cost = k.xfer_setup;
                break;
            case CostClass::Phase:
                d.cost = 0;
                break;
            case CostClass::Shift:
                // shli / shri by their immediate; shlv / shrv by up to 7 bits per lane
                d.cost = k.shift_cycles(info.format == Format::Rsh ? x.imm : 7u);
                break;
            case CostClass::MinMax:
                d.cost = uint64_t{k.alu} + k.minmax_extra;
                break;
        }
        const CostClass cc = info.cost_class;
        if (cc == CostClass::Alu || cc == CostClass::Mem || cc == CostClass::Indirect ||
            cc == CostClass::Ring || cc == CostClass::Shift || cc == CostClass::MinMax)
            d.flags |= kFlagPeWork;
        code.push_back(d);
    }
    Decoded end;
    end.cls = static_cast<uint8_t>(CostClass::Cp);
    code.push_back(end);

    // Straight-line runs, from the end backwards.
    std::vector<RunInfo> runs(code.size());
    for (size_t i = code.size(); i-- > 0;) {
        const Decoded& d = code[i];
        const bool last = i + 1 == code.size() || ends_run(d.op);
        const uint64_t pe = (d.flags & kFlagPeWork) ? d.cost : 0;
        RunInfo& r = runs[i];
        if (last) {
            r.end = static_cast<uint32_t>(i);
            r.len = 1;
            r.pe_cycles = pe;
        } else {
            const RunInfo& nx = runs[i + 1];
            r.end = nx.end;
            r.len = nx.len + 1;
            r.pe_cycles = pe + nx.pe_cycles;
        }
    }

    prog_ = prog;
    if (prog_.phases.empty()) prog_.phases.push_back("default");
    code_ = std::move(code);
    runs_ = std::move(runs);
    exec_rows_.clear();
    lane_rows_.clear();
    row_of_phase_.assign(prog_.phases.size(), -1);
    phase_split_ = true;
    bind_handlers();
    reset();
}

void Machine::reset() {
    const size_t P = static_cast<size_t>(P_), S = S_;
    std::memset(lanes_, 0, (NR_ + 2) * S);  // registers, C, T
    std::memset(m_, 0, S);
    std::memset(m_, 1, P);
    std::memset(mstack_, 0, static_cast<size_t>(cfg_.mask_depth) * S);
    std::memset(mem_, 0, static_cast<size_t>(cfg_.mem_bytes) * P);
    // External memory: what was written since the last reset (all of it once
    // the host holds a writable pointer).
    const size_t ext_size = static_cast<size_t>(cfg_.ext_bytes) * P;
    if (ext_all_dirty_)
        std::memset(ext_, 0, ext_size);
    else if (ext_lo_ < ext_hi_)
        std::memset(ext_ + ext_lo_, 0, std::min(ext_hi_, ext_size) - ext_lo_);
    ext_lo_ = SIZE_MAX;
    ext_hi_ = 0;
    msp_ = 0;
    active_ = P_;
    full_ = true;
    creg_.fill(0);
    csp_ = 0;
    std::fill(cstack_.begin(), cstack_.end(), 0);
    pc_ = next_pc_ = 0;
    extra_ = 0;
    halted_ = false;
    cycles_ = 0;
    phase_ = 0;
    phase_cycles_.assign(prog_.phases.size(), 0);
    for (auto& r : exec_rows_) std::fill(r.begin(), r.end(), 0);
    for (auto& r : lane_rows_) std::fill(r.begin(), r.end(), 0);
    class_extra_.fill(0);
    instructions_ = pe_cycles_ = active_lane_cycles_ = ext_bytes_ = 0;
    phase_running_.assign(prog_.phases.size(), Running{});
    phase_mark_ = Running{};
    select_phase_row();
}

void Machine::select_phase_row() {
    int32_t& r = row_of_phase_[phase_];
    if (r < 0) {
        const size_t n = code_.size() + 1;
        if ((exec_rows_.size() + 1) * n > kMaxPhaseSplitEntries && !exec_rows_.empty()) {
            r = 0;  // share: the totals stay exact, the split by phase is lost
            phase_split_ = false;
        } else {
            r = static_cast<int32_t>(exec_rows_.size());
            exec_rows_.emplace_back(n, 0);
            lane_rows_.emplace_back(n, 0);
        }
    }
    exec_diff_ = exec_rows_[static_cast<size_t>(r)].data();
    lane_diff_ = lane_rows_[static_cast<size_t>(r)].data();
}

Machine::Running Machine::running() const {
    Running x;
    x.instructions = instructions_;
    x.pe_cycles = pe_cycles_;
    x.active_lane_cycles = active_lane_cycles_;
    x.ext_bytes = ext_bytes_;
    x.class_extra = class_extra_;
    return x;
}

namespace {
// acc += now - mark
template <class R>
void add_running(R& acc, const R& now, const R& mark) {
    acc.instructions += now.instructions - mark.instructions;
    acc.pe_cycles += now.pe_cycles - mark.pe_cycles;
    acc.active_lane_cycles += now.active_lane_cycles - mark.active_lane_cycles;
    acc.ext_bytes += now.ext_bytes - mark.ext_bytes;
    for (size_t c = 0; c < acc.class_extra.size(); ++c)
        acc.class_extra[c] += now.class_extra[c] - mark.class_extra[c];
}
}  // namespace

void Machine::change_phase(uint32_t old) {
    const Running now = running();
    add_running(phase_running_[old], now, phase_mark_);
    phase_mark_ = now;
    select_phase_row();
}

void Machine::recount_active() {
    const size_t P = static_cast<size_t>(P_);
    const uint8_t* mk = m_;
    uint32_t n = 0;
    for (size_t p = 0; p < P; ++p) n += mk[p];
    active_ = static_cast<int>(n);
}

void Machine::refresh_full() {
    const size_t P = static_cast<size_t>(P_);
    const uint8_t* mk = m_;
    uint8_t all = 1;
    for (size_t p = 0; p < P; ++p) all = static_cast<uint8_t>(all & mk[p]);
    full_ = all != 0;
}

void Machine::fault(const std::string& msg, int64_t pe, int64_t address) const {
    const std::string loc = prog_.location(pc_);
    throw Fault("fault at pc " + std::to_string(pc_) + (loc.empty() ? "" : " (" + loc + ")") +
                    ", cycle " + std::to_string(cycles_) + ": " + msg,
                pc_, pe, address, cycles_);
}

void Machine::add_row(Stats& s, size_t r) const {
    const int64_t* ed = exec_rows_[r].data();
    const uint64_t* ld = lane_rows_[r].data();
    int64_t n = 0;
    uint64_t lanes = 0;
    for (size_t pc = 0; pc < code_.size(); ++pc) {
        n += ed[pc];
        lanes += ld[pc];
        if (n == 0) continue;
        const Decoded& d = code_[pc];
        const uint64_t k = static_cast<uint64_t>(n);
        s.op_counts[d.op] += k;
        s.op_lanes[d.op] += lanes;
        s.class_cycles[d.cls] += k * d.cost;
        if (d.cls == static_cast<uint8_t>(CostClass::Ring))
            s.ring_hops += k * static_cast<uint64_t>(d.imm);
    }
}

const Stats& Machine::stats() const {
    Stats s;
    s.instructions = instructions_;
    s.pe_cycles = pe_cycles_;
    s.active_lane_cycles = active_lane_cycles_;
    s.ext_bytes = ext_bytes_;
    for (size_t r = 0; r < exec_rows_.size(); ++r) add_row(s, r);
    for (size_t c = 0; c < class_extra_.size(); ++c) s.class_cycles[c] += class_extra_[c];
    if (phase_split_) {
        s.by_phase.resize(prog_.phases.size());
        for (size_t p = 0; p < s.by_phase.size(); ++p) {
            Stats& b = s.by_phase[p];
            if (row_of_phase_[p] >= 0) add_row(b, static_cast<size_t>(row_of_phase_[p]));
            Running x = phase_running_[p];
            if (p == phase_) add_running(x, running(), phase_mark_);  // the open phase
            b.instructions = x.instructions;
            b.pe_cycles = x.pe_cycles;
            b.active_lane_cycles = x.active_lane_cycles;
            b.ext_bytes = x.ext_bytes;
            for (size_t c = 0; c < x.class_extra.size(); ++c) b.class_cycles[c] += x.class_extra[c];
        }
    }
    stats_ = std::move(s);
    return stats_;
}

// One instruction, with its bookkeeping (single steps, observers, and the
// last instructions before a cycle limit).
template <bool Traced>
inline void Machine::exec_one() {
    const uint32_t pc = pc_;
    const Decoded& d = code_[pc];
    next_pc_ = pc + 1;
    extra_ = 0;
    const uint64_t before = cycles_;
    const int active_before = active_;
    const uint32_t phase = phase_;
    d.fn[full_](*this, d);
    const uint64_t c = d.cost + extra_;
    cycles_ += c;
    phase_cycles_[phase_] += c;
    class_extra_[d.cls] += extra_;
    ++exec_diff_[pc];
    --exec_diff_[pc + 1];
    lane_diff_[pc] += static_cast<uint64_t>(active_before);
    lane_diff_[pc + 1] -= static_cast<uint64_t>(active_before);
    ++instructions_;
    if (d.flags & kFlagPeWork) {
        pe_cycles_ += c;
        active_lane_cycles_ += c * static_cast<uint64_t>(active_);
    }
    pc_ = next_pc_;
    if (phase_ != phase) change_phase(phase);
    if constexpr (Traced)
        observer_->on_instruction(*this, TraceEvent{pc, prog_.code[pc], before, cycles_});
}

// The straight-line run from `start`, or its prefix up to the cycle limit
// (an instruction starts only below `limit`, as with single steps): pc_ and
// cycles_ are exact before every instruction (faults and the video port see
// them); the rest is booked once. Only the last instruction of a run can
// branch, halt, change the phase or the mask, or add variable cycles, so the
// phase, the active PE count and the handler variant are those at the start.
void Machine::exec_run(uint32_t start, uint64_t limit) {
    const RunInfo& r = runs_[start];
    const uint64_t start_cycles = cycles_;
    const uint64_t active = static_cast<uint64_t>(active_);
    const uint32_t phase = phase_;
    const int variant = full_ ? 1 : 0;
    next_pc_ = r.end + 1;
    extra_ = 0;
    const Decoded* d = code_.data() + start;
    uint32_t pc = start;
    try {
        for (;;) {
            pc_ = pc;
            d->fn[variant](*this, *d);
            cycles_ += d->cost;
            if (pc == r.end) break;
            ++pc;
            ++d;
            if (cycles_ >= limit) {  // stop before pc: book start .. pc - 1
                book_partial_run(start, pc, start_cycles, active, phase);
                pc_ = pc;
                return;
            }
        }
    } catch (...) {
        book_partial_run(start, pc, start_cycles, active, phase);
        throw;
    }
    cycles_ += extra_;
    class_extra_[d->cls] += extra_;
    phase_cycles_[phase] += cycles_ - start_cycles;
    ++exec_diff_[start];
    --exec_diff_[r.end + 1];
    lane_diff_[start] += active;
    lane_diff_[r.end + 1] -= active;
    instructions_ += r.len;
    pe_cycles_ += r.pe_cycles;
    active_lane_cycles_ += r.pe_cycles * active;
    pc_ = next_pc_;
    if (phase_ != phase) change_phase(phase);  // a `phase` marker ended the run
}

// The instructions start .. stop - 1 of a run completed (stop did not: a
// fault, or the cycle limit); none of them added variable cycles.
void Machine::book_partial_run(uint32_t start, uint32_t stop, uint64_t start_cycles,
                               uint64_t active, uint32_t phase) {
    phase_cycles_[phase] += cycles_ - start_cycles;
    if (stop == start) return;
    ++exec_diff_[start];
    --exec_diff_[stop];
    lane_diff_[start] += active;
    lane_diff_[stop] -= active;
    instructions_ += stop - start;
    // suffix sums of the same run: start .. end minus stop .. end
    const uint64_t pe = runs_[start].pe_cycles - runs_[stop].pe_cycles;
    pe_cycles_ += pe;
    active_lane_cycles_ += pe * active;
}

template <bool Traced>
RunResult Machine::run_loop(uint64_t max_cycles) {
    const uint64_t wd = cfg_.watchdog_cycles;
    const uint64_t limit = std::min(max_cycles, wd);
    refresh_full();
    if constexpr (Traced) {
        while (!halted_ && cycles_ < limit) exec_one<true>();
    } else {
        while (!halted_ && cycles_ < limit) exec_run(pc_, limit);
    }
    if (!halted_ && cycles_ >= wd)
        fault("watchdog: no halt after " + std::to_string(cycles_) +
              " cycles (watchdog_cycles = " + std::to_string(wd) + "); runaway program?");
    return {halted_ ? RunStatus::Halted : RunStatus::CycleLimit, cycles_, instructions_};
}

RunResult Machine::run(uint64_t max_cycles) {
    return observer_ ? run_loop<true>(max_cycles) : run_loop<false>(max_cycles);
}

StepResult Machine::step() {
    if (halted_) return {true, pc_, 0};
    if (cycles_ >= cfg_.watchdog_cycles)
        fault("watchdog: no halt after " + std::to_string(cycles_) + " cycles (watchdog_cycles = " +
              std::to_string(cfg_.watchdog_cycles) + "); runaway program?");
    const uint64_t before = cycles_;
    refresh_full();
    if (observer_)
        exec_one<true>();
    else
        exec_one<false>();
    return {halted_, pc_, cycles_ - before};
}

const uint8_t* Machine::mask_stack_lanes(int level) const {
    if (level < 0 || level >= msp_)
        throw std::out_of_range("mask stack level " + std::to_string(level) + " not in use (" +
                                std::to_string(msp_) + " levels)");
    return mstack_ + static_cast<size_t>(level) * S_;
}

namespace {
void check_pe(int pe, int P) {
    if (pe < 0 || pe >= P)
        throw std::out_of_range("PE " + std::to_string(pe) + " does not exist (0.." +
                                std::to_string(P - 1) + ")");
}
void check_addr(uint32_t addr, uint32_t size, const char* what) {
    if (addr >= size)
        throw std::out_of_range(std::string(what) + " address " + std::to_string(addr) +
                                " out of range (0.." + std::to_string(int64_t{size} - 1) + ")");
}
}  // namespace

uint8_t Machine::reg(int pe, int r) const {
    check_pe(pe, P_);
    return lanes_[lane_off(r) + static_cast<size_t>(pe)];
}
void Machine::set_reg(int pe, int r, uint8_t v) {
    check_pe(pe, P_);
    lanes_[lane_off(r) + static_cast<size_t>(pe)] = v;
}
uint8_t Machine::mem_read(int pe, uint32_t addr) const {
    check_pe(pe, P_);
    check_addr(addr, cfg_.mem_bytes, "local memory");
    return mem_[static_cast<size_t>(addr) * static_cast<size_t>(P_) + static_cast<size_t>(pe)];
}
void Machine::mem_write(int pe, uint32_t addr, uint8_t v) {
    check_pe(pe, P_);
    check_addr(addr, cfg_.mem_bytes, "local memory");
    mem_[static_cast<size_t>(addr) * static_cast<size_t>(P_) + static_cast<size_t>(pe)] = v;
}
uint8_t Machine::ext_read(int pe, uint32_t addr) const {
    check_pe(pe, P_);
    check_addr(addr, cfg_.ext_bytes, "external memory");
    return ext_[static_cast<size_t>(addr) * static_cast<size_t>(P_) + static_cast<size_t>(pe)];
}
void Machine::ext_write(int pe, uint32_t addr, uint8_t v) {
    check_pe(pe, P_);
    check_addr(addr, cfg_.ext_bytes, "external memory");
    const size_t i = static_cast<size_t>(addr) * static_cast<size_t>(P_) + static_cast<size_t>(pe);
    ext_[i] = v;
    note_ext_write(i, i + 1);
}
uint32_t Machine::cp(int i) const {
    if (i < 0 || i >= kCpRegs)
        throw std::out_of_range("CP register c" + std::to_string(i) + " does not exist (c0..c15)");
    return creg_[static_cast<size_t>(i)];
}
void Machine::set_cp(int i, uint32_t v) {
    if (i < 0 || i >= kCpRegs)
        throw std::out_of_range("CP register c" + std::to_string(i) + " does not exist (c0..c15)");
    creg_[static_cast<size_t>(i)] = v;
}
uint32_t Machine::param(int i) const {
    if (i < 0 || i >= kParamWords)
        throw std::out_of_range("param word " + std::to_string(i) + " out of range 0..255");
    return params_[static_cast<size_t>(i)];
}
void Machine::set_param(int i, uint32_t v) {
    if (i < 0 || i >= kParamWords)
        throw std::out_of_range("param word " + std::to_string(i) + " out of range 0..255");
    params_[static_cast<size_t>(i)] = v;
}

}  // namespace imap::isa
