// The executor: decode once at load into a handler table, then one indirect
// call per instruction. PE instructions are single loops over the lanes with
// the mask applied by blending (dst = M ? result : dst), so GCC vectorises
// them; the per-lane semantics come from semantics.hpp.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>

#include "imap/isa/encoding.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/semantics.hpp"

namespace imap::isa {

namespace {

constexpr uint32_t kZeroCp = 16;    // index of the always-zero CP slot (absolute addresses)
constexpr uint8_t kFlagNoHigh = 1;  // ldx / stx: single-byte offset register
constexpr uint8_t kFlagPeWork = 2;  // ALU / memory / ring: counts towards PE utilisation

// k is 0x00 or 0xFF: x where k is set, old elsewhere.
inline uint8_t blend(uint8_t k, uint8_t x, uint8_t old) {
    return static_cast<uint8_t>((x & k) | (old & static_cast<uint8_t>(~k)));
}
inline uint8_t lane_mask(uint8_t m) {
    return static_cast<uint8_t>(-m);
}

// Every lane loop reads and writes only element p of its P-byte rows, and two
// rows are either the same row (rd == ra) or disjoint, so no iteration depends
// on another: `ivdep` says exactly that and spares the run-time alias checks
// GCC would otherwise add before vectorising.
#if defined(__GNUC__) && !defined(__clang__)
#define IMAP_LANE_LOOP _Pragma("GCC ivdep")
#else
#define IMAP_LANE_LOOP
#endif

std::string hex64(uint64_t w) {
    char b[24];
    std::snprintf(b, sizeof b, "0x%016llx", static_cast<unsigned long long>(w));
    return b;
}

}  // namespace

// ---------------------------------------------------------------------------
// Instruction semantics. Every handler is Exec::exec<Op>; families share the
// lane-loop shapes below.
struct Exec {
    using Cfg = MachineConfig;

    static int64_t cpv(const Machine& m, uint32_t r) { return as_signed(m.creg_[r]); }

    static int64_t mem_addr(Machine& m, const Decoded& d, const char* mn) {
        const int64_t a = cpv(m, d.b) + d.imm;
        if (a < 0 || a >= static_cast<int64_t>(m.cfg_.mem_bytes))
            m.fault(std::string(mn) + ": address " + std::to_string(a) +
                        " out of range (local memory is " + std::to_string(m.cfg_.mem_bytes) +
                        " bytes per PE: 0.." + std::to_string(m.cfg_.mem_bytes - 1) + ", all PEs)",
                    Fault::kNone, a);
        return a;
    }

    // dst = M ? src : dst over all lanes.
    static void write_masked(Machine& m, uint32_t dst_off, const uint8_t* src) {
        const size_t P = static_cast<size_t>(m.P_);
        uint8_t* dst = m.lanes_.data() + dst_off;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p) dst[p] = blend(lane_mask(mk[p]), src[p], dst[p]);
    }
    static void write_masked_value(Machine& m, uint32_t dst_off, uint8_t v) {
        const size_t P = static_cast<size_t>(m.P_);
        uint8_t* dst = m.lanes_.data() + dst_off;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p) dst[p] = blend(lane_mask(mk[p]), v, dst[p]);
    }

    template <Op O>
    static void alu_rrr(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        uint8_t* L = m.lanes_.data();
        uint8_t* dst = L + d.d;
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        uint8_t* c = m.c_;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p) {
            const sem::LaneOut o = sem::alu<O>(a[p], b[p], c[p]);
            const uint8_t k = lane_mask(mk[p]);
            dst[p] = blend(k, o.r, dst[p]);
            if constexpr (sem::writes_carry(O)) c[p] = blend(k, o.c, c[p]);
        }
    }

    // Immediate shifts: the amount becomes a compile-time constant, so the
    // staged shift of semantics.hpp folds to a single shift.
    template <Op O>
    static void shift_imm(Machine& m, const Decoded& d) {
        switch (d.imm & 7) {
            case 0:
                return alu_rri<O, 0>(m, d);
            case 1:
                return alu_rri<O, 1>(m, d);
            case 2:
                return alu_rri<O, 2>(m, d);
            case 3:
                return alu_rri<O, 3>(m, d);
            case 4:
                return alu_rri<O, 4>(m, d);
            case 5:
                return alu_rri<O, 5>(m, d);
            case 6:
                return alu_rri<O, 6>(m, d);
            default:
                return alu_rri<O, 7>(m, d);
        }
    }

    // N >= 0: the immediate is the constant N.
    template <Op O, int N = -1>
    static void alu_rri(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        uint8_t* L = m.lanes_.data();
        uint8_t* dst = L + d.d;
        const uint8_t* a = L + d.a;
        const uint8_t b = N >= 0 ? static_cast<uint8_t>(N) : static_cast<uint8_t>(d.imm);
        uint8_t* c = m.c_;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p) {
            const sem::LaneOut o = sem::alu<O>(a[p], b, c[p]);
            const uint8_t k = lane_mask(mk[p]);
            dst[p] = blend(k, o.r, dst[p]);
            if constexpr (sem::writes_carry(O)) c[p] = blend(k, o.c, c[p]);
        }
    }

    template <Op O>
    static void cmp_rr(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        const uint8_t* L = m.lanes_.data();
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        uint8_t* t = m.t_;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p)
            t[p] = blend(lane_mask(mk[p]), sem::compare<O>(a[p], b[p]), t[p]);
    }

    template <Op O>
    static void cmp_ri(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        const uint8_t* a = m.lanes_.data() + d.a;
        const uint8_t b = static_cast<uint8_t>(d.imm);
        uint8_t* t = m.t_;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p)
            t[p] = blend(lane_mask(mk[p]), sem::compare<O>(a[p], b), t[p]);
    }

    // rd = sel ? ra : rb, sel = C or T lanes.
    static void select(Machine& m, const Decoded& d, const uint8_t* sel) {
        const size_t P = static_cast<size_t>(m.P_);
        uint8_t* L = m.lanes_.data();
        uint8_t* dst = L + d.d;
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        const uint8_t* mk = m.m_;
        IMAP_LANE_LOOP
        for (size_t p = 0; p < P; ++p) {
            const uint8_t v = blend(lane_mask(sel[p]), a[p], b[p]);
            dst[p] = blend(lane_mask(mk[p]), v, dst[p]);
        }
    }

    template <bool Store>
    static void ldst(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        const int64_t addr = mem_addr(m, d, Store ? "st" : "ld");
        uint8_t* row = m.mem_.data() + static_cast<size_t>(addr) * P;
        uint8_t* reg = m.lanes_.data() + d.d;
        const uint8_t* mk = m.m_;
        if constexpr (Store) {
            IMAP_LANE_LOOP
            for (size_t p = 0; p < P; ++p) row[p] = blend(lane_mask(mk[p]), reg[p], row[p]);
        } else {
            IMAP_LANE_LOOP
            for (size_t p = 0; p < P; ++p) reg[p] = blend(lane_mask(mk[p]), row[p], reg[p]);
        }
    }

    // Per-PE address: CP base + imm + (hi << 8 | lo). Only active PEs access
    // memory, and every active address is checked before anything is written.
    template <bool Store>
    static void ldstx(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        const uint8_t* L = m.lanes_.data();
        const uint8_t* lo = L + d.a;
        const uint8_t* hi = (d.flags & kFlagNoHigh) ? nullptr : L + d.b;
        const int64_t base = cpv(m, d.aux) + d.imm;
        const int64_t size = m.cfg_.mem_bytes;
        const uint8_t* mk = m.m_;
        auto addr = [&](size_t p) {
            return base + ((hi ? int64_t{hi[p]} << 8 : 0) | int64_t{lo[p]});
        };
        for (size_t p = 0; p < P; ++p) {
            if (!mk[p]) continue;
            const int64_t a = addr(p);
            if (a < 0 || a >= size)
                m.fault(std::string(Store ? "stx" : "ldx") + ": PE " + std::to_string(p) +
                            " address " + std::to_string(a) + " out of range (local memory is " +
                            std::to_string(size) + " bytes per PE: 0.." + std::to_string(size - 1) +
                            ")",
                        static_cast<int64_t>(p), a);
        }
        uint8_t* mem = m.mem_.data();
        uint8_t* reg = m.lanes_.data() + d.d;
        for (size_t p = 0; p < P; ++p) {
            if (!mk[p]) continue;
            const size_t cell = static_cast<size_t>(addr(p)) * P + p;
            if constexpr (Store)
                mem[cell] = reg[p];
            else
                reg[p] = mem[cell];
        }
    }

    template <bool Store>
    static void xfer(Machine& m, const Decoded& d) {
        const char* mn = Store ? "xst" : "xld";
        const size_t P = static_cast<size_t>(m.P_);
        if (m.cfg_.ext_bytes == 0)
            m.fault(std::string(mn) + ": external memory disabled (ext_bytes = 0)");
        const int64_t len = cpv(m, d.d);
        const int64_t ext = cpv(m, d.a);
        const int64_t loc = cpv(m, d.b) + d.imm;
        const int64_t msize = m.cfg_.mem_bytes, esize = m.cfg_.ext_bytes;
        if (len < 0)
            m.fault(std::string(mn) + ": negative length " + std::to_string(len) + " (c" +
                    std::to_string(d.d) + ")");
        if (loc < 0 || loc + len > msize)
            m.fault(std::string(mn) + ": local range " + std::to_string(loc) + ".." +
                        std::to_string(loc + len - 1) + " (" + std::to_string(len) +
                        " bytes) out of range (local memory is " + std::to_string(msize) +
                        " bytes per PE)",
                    Fault::kNone, loc < 0 ? loc : loc + len - 1);
        if (ext < 0 || ext + len > esize)
            m.fault(std::string(mn) + ": external range " + std::to_string(ext) + ".." +
                        std::to_string(ext + len - 1) + " (" + std::to_string(len) +
                        " bytes) out of range (external memory is " + std::to_string(esize) +
                        " bytes per PE)",
                    Fault::kNone, ext < 0 ? ext : ext + len - 1);
        uint8_t* lp = m.mem_.data() + static_cast<size_t>(loc) * P;
        uint8_t* ep = m.ext_.data() + static_cast<size_t>(ext) * P;
        const size_t n = static_cast<size_t>(len) * P;
        if constexpr (Store)
            std::memmove(ep, lp, n);
        else
            std::memmove(lp, ep, n);
        m.extra_ =
            m.cfg_.costs.xfer_cycles(static_cast<uint64_t>(len), P) - m.cfg_.costs.xfer_setup;
    }

    // rxl: rd(p) = ra(p - k); rxr: rd(p) = ra(p + k) (indices mod P). Every
    // PE drives the ring; only the register write is masked.
    template <bool Left>
    static void ring(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_);
        if (m.ring_) {
            m.ring_->shift(m.lanes_.data() + d.d, m.lanes_.data() + d.a, m.m_, m.P_, d.imm, Left);
            return;
        }
        ring_rotate<Left>(m.scratch_, m.lanes_.data() + d.a, P, static_cast<size_t>(d.imm));
        ring_write(m.lanes_.data() + d.d, m.scratch_, m.m_, P);
    }

    template <bool Any>
    static uint32_t status(Machine& m) {
        if (m.status_) return m.status_->reduce(m.t_, m.m_, m.P_, Any);
        return status_reduce<Any>(m.t_, m.m_, static_cast<size_t>(m.P_));
    }

    static void branch(Machine& m, const Decoded& d, bool taken) {
        if (taken) {
            m.next_pc_ = d.aux;
            m.extra_ = m.cfg_.costs.branch_taken;
        }
    }

    static void video(Machine& m, const Decoded& d, bool out) {
        const char* mn = out ? "vout" : "vin";
        const size_t P = static_cast<size_t>(m.P_);
        if (!m.video_) m.fault(std::string(mn) + ": no video port attached to the machine");
        const int64_t addr = mem_addr(m, d, mn);
        const int64_t y = cpv(m, d.aux & 15u), x = cpv(m, d.aux >> 4);
        uint8_t* row = m.mem_.data() + static_cast<size_t>(addr) * P;
        try {
            const int port = static_cast<int>(d.d), yi = static_cast<int>(y),
                      xi = static_cast<int>(x);
            const uint32_t a = static_cast<uint32_t>(addr);
            if (out) {
                if (!m.video_->write_row(port, yi, xi, a, m.P_))
                    m.video_->write_line(port, yi, xi, row, m.P_);
            } else if (!m.video_->read_row(port, yi, xi, a, m.P_)) {
                m.video_->read_line(port, yi, xi, m.scratch_, m.P_);
                std::memcpy(row, m.scratch_, P);
            }
        } catch (const std::exception& e) {
            m.fault(std::string(mn) + " port " + std::to_string(d.d) + " line " +
                    std::to_string(y) + " column " + std::to_string(x) + ": " + e.what());
        }
    }

    static void end_of_program(Machine& m, const Decoded&) {
        m.fault("the PC ran past the end of the program (" + std::to_string(m.prog_.code.size()) +
                " instructions) without halt");
    }

    template <Op O>
    static void exec(Machine& m, const Decoded& d) {
        constexpr Format F = format_of(O);
        [[maybe_unused]] const size_t P = static_cast<size_t>(m.P_);
        [[maybe_unused]] auto& c = m.creg_;
        if constexpr (O == Op::CSEL || O == Op::TSEL) {
            select(m, d, O == Op::CSEL ? m.c_ : m.t_);
        } else if constexpr (F == Format::Rrr || O == Op::ROLC || O == Op::RORC) {
            alu_rrr<O>(m, d);  // rolc / rorc: b lane unused (decoded as ra)
        } else if constexpr (F == Format::Rsh) {
            shift_imm<O>(m, d);
        } else if constexpr (F == Format::Rri8) {
            alu_rri<O>(m, d);
        } else if constexpr (F == Format::Cmp) {
            cmp_rr<O>(m, d);
        } else if constexpr (F == Format::Cmpi) {
            cmp_ri<O>(m, d);
        } else if constexpr (O == Op::MOV) {
            write_masked(m, d.d, m.lanes_.data() + d.a);
        } else if constexpr (O == Op::LI) {
            write_masked_value(m, d.d, static_cast<uint8_t>(d.imm));
        } else if constexpr (O == Op::LC || O == Op::LCB) {
            write_masked_value(m, d.d, static_cast<uint8_t>(c[d.a] >> (8 * d.imm)));
        } else if constexpr (O == Op::PIDX) {
            write_masked(m, d.d, m.pidx_ + static_cast<size_t>(d.imm) * P);
        } else if constexpr (O == Op::SETC) {
            write_masked(m, d.d, m.c_);
        } else if constexpr (O == Op::SETT) {
            write_masked(m, d.d, m.t_);
        } else if constexpr (O == Op::TC || O == Op::TNOT) {
            uint8_t* t = m.t_;
            const uint8_t* cf = m.c_;
            const uint8_t* mk = m.m_;
            IMAP_LANE_LOOP
            for (size_t p = 0; p < P; ++p) {
                const uint8_t v = O == Op::TC ? cf[p] : static_cast<uint8_t>(t[p] ^ 1u);
                t[p] = blend(lane_mask(mk[p]), v, t[p]);
            }
        } else if constexpr (O == Op::LD || O == Op::ST) {
            ldst<O == Op::ST>(m, d);
        } else if constexpr (O == Op::LDX || O == Op::STX) {
            ldstx<O == Op::STX>(m, d);
        } else if constexpr (O == Op::XLD || O == Op::XST) {
            xfer<O == Op::XST>(m, d);
        } else if constexpr (O == Op::RXL || O == Op::RXR) {
            ring<O == Op::RXL>(m, d);
        } else if constexpr (O == Op::MIF) {
            if (m.msp_ >= m.cfg_.mask_depth)
                m.fault("mif: mask stack overflow (mask_depth = " +
                        std::to_string(m.cfg_.mask_depth) + ")");
            std::memcpy(m.mstack_ + static_cast<size_t>(m.msp_) * P, m.m_, P);
            ++m.msp_;
            uint8_t* mk = m.m_;
            const uint8_t* t = m.t_;
            IMAP_LANE_LOOP
            for (size_t p = 0; p < P; ++p) mk[p] = static_cast<uint8_t>(mk[p] & t[p]);
            m.recount_active();
        } else if constexpr (O == Op::MELSE) {
            if (m.msp_ == 0) m.fault("melse: mask stack underflow (melse without mif)");
            const uint8_t* top = m.mstack_ + static_cast<size_t>(m.msp_ - 1) * P;
            uint8_t* mk = m.m_;
            IMAP_LANE_LOOP
            for (size_t p = 0; p < P; ++p) mk[p] = static_cast<uint8_t>(top[p] & (mk[p] ^ 1u));
            m.recount_active();
        } else if constexpr (O == Op::MEND) {
            if (m.msp_ == 0) m.fault("mend: mask stack underflow (mend without mif)");
            --m.msp_;
            std::memcpy(m.m_, m.mstack_ + static_cast<size_t>(m.msp_) * P, P);
            m.recount_active();
        } else if constexpr (O == Op::MALL) {
            std::memset(m.m_, 1, P);
            m.msp_ = 0;
            m.active_ = m.P_;
        } else if constexpr (O == Op::RANY || O == Op::RALL) {
            c[d.d] = status<O == Op::RANY>(m);
        } else if constexpr (O == Op::VIN || O == Op::VOUT) {
            video(m, d, O == Op::VOUT);
        } else if constexpr (O == Op::NOP) {
        } else if constexpr (O == Op::HALT) {
            m.halted_ = true;
            m.next_pc_ = m.pc_;
        } else if constexpr (O == Op::PHASE) {
            m.phase_ = static_cast<uint32_t>(d.imm);
        } else if constexpr (O == Op::CLI) {
            c[d.d] = static_cast<uint32_t>(d.imm);
        } else if constexpr (O == Op::CMOV) {
            c[d.d] = c[d.a];
        } else if constexpr (F == Format::Ccc || F == Format::Cci || F == Format::Csh) {
            const uint32_t a = c[d.a];
            const uint32_t b = F == Format::Ccc ? c[d.b] : static_cast<uint32_t>(d.imm);
            uint32_t r = 0;
            if constexpr (O == Op::CADD || O == Op::CADDI)
                r = a + b;
            else if constexpr (O == Op::CSUB || O == Op::CSUBI)
                r = a - b;
            else if constexpr (O == Op::CAND || O == Op::CANDI)
                r = a & b;
            else if constexpr (O == Op::COR || O == Op::CORI)
                r = a | b;
            else if constexpr (O == Op::CXOR || O == Op::CXORI)
                r = a ^ b;
            else if constexpr (O == Op::CSHLI)
                r = a << b;
            else if constexpr (O == Op::CSHRI)
                r = a >> b;
            else if constexpr (O == Op::CSRAI)
                r = (a & 0x80000000u) ? ~(~a >> b) : a >> b;
            c[d.d] = r;
        } else if constexpr (O == Op::CLD || O == Op::CST) {
            const int64_t a = cpv(m, d.b) + d.imm;
            if (a < 0 || a >= kParamWords)
                m.fault(std::string(O == Op::CLD ? "cld" : "cst") + ": param block address " +
                            std::to_string(a) + " out of range 0.." +
                            std::to_string(kParamWords - 1),
                        Fault::kNone, a);
            if constexpr (O == Op::CLD)
                c[d.d] = m.params_[static_cast<size_t>(a)];
            else
                m.params_[static_cast<size_t>(a)] = c[d.d];
        } else if constexpr (O == Op::JMP) {
            branch(m, d, true);
        } else if constexpr (O == Op::BEQ) {
            branch(m, d, c[d.a] == c[d.b]);
        } else if constexpr (O == Op::BNE) {
            branch(m, d, c[d.a] != c[d.b]);
        } else if constexpr (O == Op::BLT) {
            branch(m, d, as_signed(c[d.a]) < as_signed(c[d.b]));
        } else if constexpr (O == Op::BGE) {
            branch(m, d, as_signed(c[d.a]) >= as_signed(c[d.b]));
        } else if constexpr (O == Op::BZ) {
            branch(m, d, c[d.a] == 0);
        } else if constexpr (O == Op::BNZ) {
            branch(m, d, c[d.a] != 0);
        } else if constexpr (O == Op::LOOP) {
            c[d.a] -= 1;
            branch(m, d, c[d.a] != 0);
        } else if constexpr (O == Op::CALL) {
            if (m.csp_ >= m.cfg_.call_depth)
                m.fault("call: return stack overflow (call_depth = " +
                        std::to_string(m.cfg_.call_depth) + ")");
            m.cstack_[static_cast<size_t>(m.csp_++)] = m.pc_ + 1;
            branch(m, d, true);
        } else if constexpr (O == Op::RET) {
            if (m.csp_ == 0) m.fault("ret: return stack underflow (ret without call)");
            m.next_pc_ = m.cstack_[static_cast<size_t>(--m.csp_)];
            m.extra_ = m.cfg_.costs.branch_taken;
        } else {
            static_assert(O == Op::NOP, "opcode without semantics");
        }
    }
};

namespace {

Handler handler_of(uint8_t code) {
    switch (code) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc) \
    case code:                                  \
        return &Exec::exec<Op::id>;
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
        default:
            return nullptr;
    }
}

}  // namespace

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

Machine::Machine(const MachineConfig& cfg) : cfg_(cfg) {
    cfg_.validate();
    P_ = cfg_.pes;
    NR_ = static_cast<size_t>(cfg_.pe_regs);
    const size_t P = static_cast<size_t>(P_);
    const size_t depth = static_cast<size_t>(cfg_.mask_depth);
    lanes_.assign((NR_ + 3 + depth + 4 + 1) * P, 0);
    uint8_t* base = lanes_.data();
    c_ = base + NR_ * P;
    t_ = c_ + P;
    m_ = t_ + P;
    mstack_ = m_ + P;
    pidx_ = mstack_ + depth * P;
    scratch_ = pidx_ + 4 * P;
    for (size_t k = 0; k < 4; ++k)
        for (size_t p = 0; p < P; ++p) pidx_[k * P + p] = static_cast<uint8_t>(p >> (8 * k));
    mem_.assign(static_cast<size_t>(cfg_.mem_bytes) * P, 0);
    ext_.assign(static_cast<size_t>(cfg_.ext_bytes) * P, 0);
    cstack_.assign(static_cast<size_t>(cfg_.call_depth), 0);
    Program empty;
    empty.code.push_back(Word{static_cast<uint8_t>(Op::HALT)}.encode());
    empty.phases.push_back("default");
    load(empty);
}

size_t Machine::lane_off(int r) const {
    if (r < 0 || static_cast<size_t>(r) >= NR_)
        throw std::out_of_range("PE register r" + std::to_string(r) +
                                " does not exist (pe_regs = " + std::to_string(NR_) + ")");
    return static_cast<size_t>(r) * static_cast<size_t>(P_);
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
        d.fn = handler_of(x.op);
        d.op = x.op;
        d.cls = static_cast<uint8_t>(info.cost_class);
        d.imm = as_signed(x.imm);
        auto pe = [&](uint8_t r, const char* field) -> uint32_t {
            if (r >= NR_)
                throw LoadError(
                    where() + mn + ": register r" + std::to_string(r) + " (field " + field +
                        ") does not exist on this machine (pe_regs = " + std::to_string(NR_) + ")",
                    pc);
            return static_cast<uint32_t>(r) * static_cast<uint32_t>(P_);
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
    end.fn = &Exec::end_of_program;
    end.cls = static_cast<uint8_t>(CostClass::Cp);
    code.push_back(end);

    prog_ = prog;
    if (prog_.phases.empty()) prog_.phases.push_back("default");
    code_ = std::move(code);
    reset();
}

void Machine::reset() {
    const size_t P = static_cast<size_t>(P_);
    std::fill(lanes_.begin(), lanes_.begin() + static_cast<std::ptrdiff_t>((NR_ + 2) * P), 0);
    std::memset(m_, 1, P);
    std::memset(mstack_, 0, static_cast<size_t>(cfg_.mask_depth) * P);
    std::fill(mem_.begin(), mem_.end(), 0);
    std::fill(ext_.begin(), ext_.end(), 0);
    msp_ = 0;
    active_ = P_;
    creg_.fill(0);
    csp_ = 0;
    std::fill(cstack_.begin(), cstack_.end(), 0);
    pc_ = next_pc_ = 0;
    extra_ = 0;
    halted_ = false;
    cycles_ = 0;
    phase_ = 0;
    phase_cycles_.assign(prog_.phases.size(), 0);
    stats_ = Stats{};
}

void Machine::recount_active() {
    const size_t P = static_cast<size_t>(P_);
    const uint8_t* mk = m_;
    uint32_t n = 0;
    for (size_t p = 0; p < P; ++p) n += mk[p];
    active_ = static_cast<int>(n);
}

void Machine::fault(const std::string& msg, int64_t pe, int64_t address) const {
    const std::string loc = prog_.location(pc_);
    throw Fault("fault at pc " + std::to_string(pc_) + (loc.empty() ? "" : " (" + loc + ")") +
                    ", cycle " + std::to_string(cycles_) + ": " + msg,
                pc_, pe, address, cycles_);
}

template <bool Traced>
inline void Machine::exec_one() {
    const uint32_t pc = pc_;
    const Decoded& d = code_[pc];
    next_pc_ = pc + 1;
    extra_ = 0;
    d.fn(*this, d);
    const uint64_t c = d.cost + extra_;
    const uint64_t before = cycles_;
    cycles_ += c;
    phase_cycles_[phase_] += c;
    stats_.class_cycles[d.cls] += c;
    ++stats_.op_counts[d.op];
    ++stats_.instructions;
    const uint64_t pe_c = (d.flags & kFlagPeWork) ? c : 0;
    stats_.pe_cycles += pe_c;
    stats_.active_lane_cycles += pe_c * static_cast<uint64_t>(active_);
    pc_ = next_pc_;
    if constexpr (Traced)
        observer_->on_instruction(*this, TraceEvent{pc, prog_.code[pc], before, cycles_});
}

template <bool Traced>
RunResult Machine::run_loop(uint64_t max_cycles) {
    const uint64_t wd = cfg_.watchdog_cycles;
    const uint64_t limit = std::min(max_cycles, wd);
    while (!halted_ && cycles_ < limit) exec_one<Traced>();
    if (!halted_ && cycles_ >= wd)
        fault("watchdog: no halt after " + std::to_string(cycles_) +
              " cycles (watchdog_cycles = " + std::to_string(wd) + "); runaway program?");
    return {halted_ ? RunStatus::Halted : RunStatus::CycleLimit, cycles_, stats_.instructions};
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
    return mstack_ + static_cast<size_t>(level) * static_cast<size_t>(P_);
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
    ext_[static_cast<size_t>(addr) * static_cast<size_t>(P_) + static_cast<size_t>(pe)] = v;
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
