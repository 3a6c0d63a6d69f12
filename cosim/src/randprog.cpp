#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>

#include "checker.hpp"
#include "imap/rtl/random.hpp"
#include "imap/tlm/sanitizer.hpp"
#include "model.hpp"
#include "support.hpp"

namespace imap::rtl {

namespace {

// ---- encoding (docs/isa.md section 3) ---------------------------------------
uint64_t enc(uint8_t op, uint32_t rd = 0, uint32_t ra = 0, uint32_t rb = 0, uint32_t imm = 0) {
    return uint64_t{op} | uint64_t{rd & 0xff} << 8 | uint64_t{ra & 0xff} << 16 |
           uint64_t{rb & 0xff} << 24 | uint64_t{imm} << 32;
}

enum : uint8_t {
    NOP = 0x00,
    HALT = 0x01,
    PHASE = 0x02,
    CLI = 0x08,
    CMOV = 0x09,
    CADD = 0x0A,
    CADDI = 0x0B,
    CSUB = 0x0C,
    CSUBI = 0x0D,
    CAND = 0x0E,
    CANDI = 0x0F,
    COR = 0x10,
    CORI = 0x11,
    CXOR = 0x12,
    CXORI = 0x13,
    CSHLI = 0x14,
    CSHRI = 0x15,
    CSRAI = 0x16,
    CLD = 0x17,
    CST = 0x18,
    JMP = 0x20,
    BEQ = 0x21,
    BNE = 0x22,
    BLT = 0x23,
    BGE = 0x24,
    BZ = 0x25,
    BNZ = 0x26,
    LOOP = 0x27,
    CALL = 0x28,
    RET = 0x29,
    ADD = 0x40,
    ADDI = 0x50,
    MOV = 0x60,
    LI = 0x61,
    LC = 0x62,
    LCB = 0x63,
    PIDX = 0x64,
    SETC = 0x65,
    SETT = 0x66,
    CSEL = 0x67,
    TSEL = 0x68,
    SHLI = 0x70,
    SHRI = 0x71,
    ROLC = 0x72,
    RORC = 0x73,
    SHLV = 0x74,
    SHRV = 0x75,
    CEQ = 0x80,
    CEQI = 0x88,
    TC = 0x8E,
    TNOT = 0x8F,
    LD = 0x90,
    ST = 0x91,
    LDX = 0x92,
    STX = 0x93,
    XLD = 0x94,
    XST = 0x95,
    RXL = 0xA0,
    RXR = 0xA1,
    MIF = 0xB0,
    MELSE = 0xB1,
    MEND = 0xB2,
    MALL = 0xB3,
    RANY = 0xB4,
    RALL = 0xB5,
    VIN = 0xC0,
    VOUT = 0xC1
};

// CP registers: c0..c7 data, c8..c10 address bases, c11 status results,
// c12..c15 loop counters.
constexpr int kBase0 = 8, kStat = 11, kLoop0 = 12;

class Gen {
  public:
    Gen(uint64_t seed, const GenOptions& o, RandomProgram& out)
        : rng_(seed * 0x9E3779B97F4A7C15ull + 1),
          board_rng_(seed * 0xD1B54A32D192ED03ull + 7),
          o_(o),
          out_(out) {}

    void run();

  private:
    std::mt19937_64 rng_;
    std::mt19937_64 board_rng_;  // board timing draws (ext_beat, camera)
    const GenOptions& o_;
    RandomProgram& out_;
    std::vector<uint64_t> code_;
    int NR_ = 16;
    int depth_ = 0;  // mif nesting
    int loops_ = 0;  // loop nesting
    int calls_ = 0;  // call nesting while generating a subroutine
    int max_mask_ = 3;
    std::vector<std::pair<size_t, int>> call_fix_;  // call sites -> subroutine
    int subs_ = 0;

    uint64_t u(uint64_t n) { return n == 0 ? 0 : rng_() % n; }
    bool chance(int pct) { return static_cast<int>(u(100)) < pct; }
    int reg() {
        return static_cast<int>(u(static_cast<uint64_t>(NR_ - 2)));
    }  // two kept for addresses
    int creg() { return static_cast<int>(u(8)); }
    void emit(uint64_t w) { code_.push_back(w); }
    size_t here() const { return code_.size(); }
    void patch(size_t at, uint32_t target) {
        code_[at] = (code_[at] & 0xffffffffull) | (uint64_t{target} << 32);
    }
    uint32_t imm8() {
        const uint64_t k = u(8);
        return k == 0 ? 0u : k == 1 ? 255u : k == 2 ? 1u : static_cast<uint32_t>(u(256));
    }
    uint32_t cval() {
        const uint64_t k = u(6);
        return k == 0   ? 0u
               : k == 1 ? 0xffffffffu
               : k == 2 ? 1u
               : k == 3 ? 0x80000000u
                        : static_cast<uint32_t>(rng_());
    }

    void pe_op();
    void alu_run(int n) {
        for (int i = 0; i < n; ++i) pe_op();
    }
    void block(int level);
    void mask_block(int level);
    void loop_block(int level);
    void branch_block(int level);
    void mem_block();
    void memx_block();
    void ring_block();
    void xfer_block();
    void status_block();
    void video_block();
    void cp_block();
    void set_base(int c, uint32_t v) { emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, v)); }
    void fault_ending();
};

void Gen::pe_op() {
    const int d = reg(), a = reg(), b = reg();
    switch (u(12)) {
        case 0:
        case 1: {  // Rrr ALU / min / max
            static const uint8_t ops[] = {0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48};
            const int bb = chance(15) ? a : b;  // same-register operands
            emit(enc(ops[u(9)], static_cast<uint32_t>(chance(15) ? a : d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(bb)));
            break;
        }
        case 2:
        case 3: {  // Rri8
            static const uint8_t ops[] = {0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58};
            emit(enc(ops[u(9)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0, imm8()));
            break;
        }
        case 4: {  // moves and selects
            switch (u(9)) {
                case 0:
                    emit(enc(MOV, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 1:
                    emit(enc(LI, static_cast<uint32_t>(d), 0, 0, imm8()));
                    break;
                case 2:
                    emit(enc(LC, static_cast<uint32_t>(d), static_cast<uint32_t>(creg())));
                    break;
                case 3:
                    emit(enc(LCB, static_cast<uint32_t>(d), static_cast<uint32_t>(creg()), 0,
                             static_cast<uint32_t>(u(4))));
                    break;
                case 4:
                    emit(enc(PIDX, static_cast<uint32_t>(d), 0, 0, static_cast<uint32_t>(u(4))));
                    break;
                case 5:
                    emit(enc(SETC, static_cast<uint32_t>(d)));
                    break;
                case 6:
                    emit(enc(SETT, static_cast<uint32_t>(d)));
                    break;
                case 7:
                    emit(enc(CSEL, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
                default:
                    emit(enc(TSEL, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
            }
            break;
        }
        case 5:
        case 6: {  // shifter
            switch (u(6)) {
                case 0:
                    emit(enc(SHLI, static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                             static_cast<uint32_t>(u(8))));
                    break;
                case 1:
                    emit(enc(SHRI, static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                             static_cast<uint32_t>(u(8))));
                    break;
                case 2:
                    emit(enc(ROLC, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 3:
                    emit(enc(RORC, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 4:
                    emit(enc(SHLV, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
                default:
                    emit(enc(SHRV, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
            }
            break;
        }
        case 7:
        case 8: {  // comparator
            const uint64_t k = u(14);
            if (k < 6)
                emit(enc(static_cast<uint8_t>(CEQ + k), 0, static_cast<uint32_t>(a),
                         static_cast<uint32_t>(b)));
            else if (k < 12)
                emit(enc(static_cast<uint8_t>(CEQI + (k - 6)), 0, static_cast<uint32_t>(a), 0,
                         imm8()));
            else
                emit(enc(k == 12 ? TC : TNOT));
            break;
        }
        case 9:
            ring_block();
            break;
        case 10:
            mem_block();
            break;
        default: {  // a carry chain
            emit(enc(ADD, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(b)));
            emit(enc(static_cast<uint8_t>(0x41 + 2 * u(2)), static_cast<uint32_t>(reg()),
                     static_cast<uint32_t>(reg()), static_cast<uint32_t>(reg())));
            break;
        }
    }
}

void Gen::ring_block() {
    const int P = o_.pes;
    uint32_t k;
    switch (u(7)) {
        case 0:
            k = 1;
            break;
        case 1:
            k = static_cast<uint32_t>(P - 1);
            break;
        case 2:
            k = static_cast<uint32_t>(P);
            break;
        case 3:
            k = static_cast<uint32_t>(P + 1);
            break;
        case 4:
            k = static_cast<uint32_t>(2 * P + u(static_cast<uint64_t>(P)));
            break;
        case 5:
            k = chance(3) ? 65535u : static_cast<uint32_t>(3 * P + u(100));
            break;
        default:
            k = 2 + static_cast<uint32_t>(u(static_cast<uint64_t>(std::max(P - 2, 1))));
            break;
    }
    emit(enc(chance(50) ? RXL : RXR, static_cast<uint32_t>(reg()), static_cast<uint32_t>(reg()), 0,
             k));
}

void Gen::mem_block() {
    const uint32_t mem = o_.mem_bytes;
    const int c = kBase0 + static_cast<int>(u(3));
    const uint32_t base = static_cast<uint32_t>(u(mem));
    if (chance(30)) {  // absolute address
        emit(enc(chance(50) ? LD : ST, static_cast<uint32_t>(reg()), 0, 128,
                 static_cast<uint32_t>(u(mem))));
        return;
    }
    set_base(c, base);
    if (chance(40))
        emit(enc(CADDI, static_cast<uint32_t>(c), static_cast<uint32_t>(c), 0,
                 0));  // forwarded twice
    const int32_t off = static_cast<int32_t>(u(mem)) - static_cast<int32_t>(base);
    emit(enc(chance(50) ? ST : LD, static_cast<uint32_t>(reg()), 0, static_cast<uint32_t>(c),
             static_cast<uint32_t>(off)));
    if (chance(50))
        emit(enc(LD, static_cast<uint32_t>(reg()), 0, static_cast<uint32_t>(c),
                 static_cast<uint32_t>(off)));
}

void Gen::memx_block() {
    // per-PE address lo (masked to 6 bits) [+ hi * 256] [+ cN] + off, in range
    const int lo = NR_ - 2, hi = NR_ - 1;
    const uint32_t mem = o_.mem_bytes;
    // the PE index (pidx: ra is an unused field, must be 0) or a register's
    // value; the draws are sequenced, not function arguments (whose order
    // of evaluation the compiler chooses)
    if (chance(50)) {
        emit(enc(PIDX, static_cast<uint32_t>(lo), 0, 0, 0));
    } else {
        const uint32_t src = chance(50) ? 0u : static_cast<uint32_t>(reg());
        emit(enc(MOV, static_cast<uint32_t>(lo), src, 0, 0));
    }
    emit(enc(0x54, static_cast<uint32_t>(lo), static_cast<uint32_t>(lo), 0, 0x3f));  // andi
    const bool use_hi = mem >= 512 && chance(40);
    uint32_t imm = 0;
    int64_t room = static_cast<int64_t>(mem) - 64;
    if (use_hi) {
        const uint32_t h = static_cast<uint32_t>(u(std::max<uint32_t>(mem / 256 - 1, 1)));
        emit(enc(LI, static_cast<uint32_t>(hi), 0, 0, h));
        room -= 256 * h;
    } else {
        imm |= 1u << 29;
    }
    int64_t used = 0;
    if (chance(40) && room > 0) {
        const int c = kBase0 + static_cast<int>(u(3));
        const uint32_t v = static_cast<uint32_t>(u(static_cast<uint64_t>(room)));
        set_base(c, v);
        used = v;
        imm |= 1u << 28 | static_cast<uint32_t>(c) << 24;
    }
    const int64_t left = room - used;
    const int32_t off = left > 0 ? static_cast<int32_t>(u(static_cast<uint64_t>(left))) : 0;
    imm |= static_cast<uint32_t>(off) & 0xffffffu;
    emit(enc(chance(50) ? LDX : STX, static_cast<uint32_t>(reg()), static_cast<uint32_t>(lo),
             use_hi ? static_cast<uint32_t>(hi) : 0u, imm));
}

void Gen::xfer_block() {
    if (o_.ext_bytes == 0) return;
    const int P = o_.pes;
    uint32_t len;
    switch (u(6)) {
        case 0:
            len = 0;
            break;
        case 1:
            len = 1;
            break;
        case 2:
            len = 2 + static_cast<uint32_t>(u(6));
            break;
        case 3:
            len = static_cast<uint32_t>(P);
            break;
        default:
            len = static_cast<uint32_t>(u(40));
            break;
    }
    len = std::min(len, o_.mem_bytes);
    const uint32_t lb = static_cast<uint32_t>(u(o_.mem_bytes - len + 1));
    const uint32_t eb = static_cast<uint32_t>(u(std::min<uint32_t>(o_.ext_bytes, 4096) - len + 1));
    set_base(kBase0, lb);
    set_base(kBase0 + 1, eb);
    set_base(kBase0 + 2, len);
    const bool xst = chance(50);
    const uint32_t base_reg = chance(20) ? 128u : kBase0;
    const uint32_t off = chance(20) ? lb : 0u;
    // the transferred rows are mostly never-written zeros over zeros: a
    // register stored into the last local row of the range (the xst's
    // source, the xld's destination) makes a dropped or misplaced last row
    // visible
    const uint64_t last = uint64_t{base_reg == 128u ? 0u : lb} + off + len - 1;
    // a transfer under a narrower mask (its own mif .. mend): the row stored
    // before it differs from the other memory's in the PEs it masks, so a
    // masked PE whose bytes move, or a cost counting them, shows
    const bool narrow = depth_ < max_mask_ && chance(40);
    if (len > 0 && last < o_.mem_bytes && (narrow || chance(60)))
        emit(enc(ST, static_cast<uint32_t>(reg()), 0, base_reg, off + len - 1));
    if (narrow) {
        emit(enc(static_cast<uint8_t>(CEQI + u(6)), 0, static_cast<uint32_t>(reg()), 0, imm8()));
        emit(enc(MIF));
        ++depth_;
    }
    emit(enc(xst ? XST : XLD, kBase0 + 2, kBase0 + 1, base_reg, off));
    if (narrow) {
        emit(enc(MEND));
        --depth_;
    }
    if (chance(30)) emit(enc(LD, static_cast<uint32_t>(reg()), 0, 128, lb));
}

void Gen::status_block() {
    emit(enc(static_cast<uint8_t>(CEQ + u(6)), 0, static_cast<uint32_t>(reg()),
             static_cast<uint32_t>(reg())));
    emit(enc(chance(50) ? RANY : RALL, kStat));
    // branch on the result over one instruction
    const size_t at = here();
    emit(enc(chance(50) ? BNZ : BZ, 0, kStat, 0, 0));
    pe_op();
    patch(at, static_cast<uint32_t>(here()));
}

void Gen::video_block() {
    const int y = static_cast<int>(u(static_cast<uint64_t>(out_.left.height)));
    const int x = chance(30) ? static_cast<int>(u(static_cast<uint64_t>(out_.left.width + 4))) : 0;
    const int cy = creg(), cx = (cy + 1 + static_cast<int>(u(7))) % 8;
    set_base(cy, static_cast<uint32_t>(y));
    set_base(cx, static_cast<uint32_t>(x));
    const uint32_t row = static_cast<uint32_t>(u(o_.mem_bytes));
    emit(enc(chance(50) ? VIN : VOUT, static_cast<uint32_t>(u(2)),
             static_cast<uint32_t>(cy | cx << 4), 128, row));
}

void Gen::cp_block() {
    const int d = creg(), a = creg(), b = creg();
    switch (u(8)) {
        case 0:
            emit(enc(CLI, static_cast<uint32_t>(d), 0, 0, cval()));
            break;
        case 1:
            emit(enc(CMOV, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
            break;
        case 2: {
            static const uint8_t ops[] = {CADD, CSUB, CAND, COR, CXOR};
            emit(enc(ops[u(5)], static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(b)));
            break;
        }
        case 3: {
            static const uint8_t ops[] = {CADDI, CSUBI, CANDI, CORI, CXORI};
            emit(enc(ops[u(5)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0, cval()));
            break;
        }
        case 4: {
            static const uint8_t ops[] = {CSHLI, CSHRI, CSRAI};
            emit(enc(ops[u(3)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                     static_cast<uint32_t>(u(32))));
            break;
        }
        case 5: {
            const uint32_t at = static_cast<uint32_t>(u(256));
            if (chance(50)) {
                emit(enc(CST, static_cast<uint32_t>(d), 0, 128, at));
            } else {
                set_base(kBase0, at / 2);
                emit(enc(CLD, static_cast<uint32_t>(d), 0, kBase0, at - at / 2));
            }
            break;
        }
        case 6:
            emit(enc(PHASE, 0, 0, 0, static_cast<uint32_t>(u(4))));
            break;
        default:
            emit(enc(NOP));
            break;
    }
}

void Gen::mask_block(int level) {
    if (depth_ >= max_mask_) {
        alu_run(1);
        return;
    }
    if (chance(70))
        emit(enc(static_cast<uint8_t>(CEQ + u(6)), 0, static_cast<uint32_t>(reg()),
                 static_cast<uint32_t>(reg())));
    else
        emit(enc(static_cast<uint8_t>(CEQI + u(6)), 0, static_cast<uint32_t>(reg()), 0, imm8()));
    emit(enc(MIF));
    ++depth_;
    alu_run(1 + static_cast<int>(u(3)));
    if (chance(40)) block(level + 1);
    if (chance(60)) {
        emit(enc(MELSE));
        alu_run(1 + static_cast<int>(u(3)));
        if (chance(25)) mask_block(level + 1);
    }
    emit(enc(MEND));
    --depth_;
}

void Gen::loop_block(int level) {
    if (loops_ >= 4) {
        alu_run(1);
        return;
    }
    const int c = kLoop0 + loops_;
    ++loops_;
    emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, 1 + static_cast<uint32_t>(u(3))));
    const uint32_t top = static_cast<uint32_t>(here());
    alu_run(1 + static_cast<int>(u(3)));
    if (chance(50)) block(level + 1);
    emit(enc(LOOP, 0, static_cast<uint32_t>(c), 0, top));
    --loops_;
}

void Gen::branch_block(int level) {
    const size_t at = here();
    switch (u(8)) {
        case 0:
            emit(enc(JMP));
            break;
        case 1:
            emit(enc(BEQ, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 2:
            emit(enc(BNE, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 3:
            emit(enc(BLT, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 4:
            emit(enc(BGE, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 5:
            emit(enc(BZ, 0, static_cast<uint32_t>(creg())));
            break;
        case 6:
            emit(enc(BNZ, 0, static_cast<uint32_t>(creg())));
            break;
        default: {  // a call to a subroutine generated after the halt
            if (calls_ < 2) {
                emit(enc(CALL));
                call_fix_.emplace_back(at, subs_++);
            } else {
                emit(enc(NOP));
            }
            return;
        }
    }
    if (chance(10)) {  // a taken branch to the next instruction
        patch(at, static_cast<uint32_t>(here()));
        return;
    }
    alu_run(1 + static_cast<int>(u(2)));
    if (chance(30)) block(level + 1);
    patch(at, static_cast<uint32_t>(here()));
}

void Gen::block(int level) {
    if (level > 3) {
        alu_run(1);
        return;
    }
    switch (u(16)) {
        case 0:
        case 1:
        case 2:
            alu_run(1 + static_cast<int>(u(5)));
            break;
        case 3:
        case 4:
            mask_block(level);
            break;
        case 5:
            loop_block(level);
            break;
        case 6:
        case 7:
            branch_block(level);
            break;
        case 8:
            mem_block();
            break;
        case 9:
            memx_block();
            break;
        case 10:
            ring_block();
            break;
        case 11:
            xfer_block();
            break;
        case 12:
            status_block();
            break;
        case 13:
            video_block();
            break;
        case 14:
            if (depth_ == 0 && chance(30))
                emit(enc(MALL));
            else
                cp_block();
            break;
        default:
            cp_block();
            break;
    }
}

void Gen::fault_ending() {
    switch (u(9)) {
        case 0:
            out_.ending = "ld out of range";
            emit(enc(LD, 0, 0, 128, o_.mem_bytes + static_cast<uint32_t>(u(5))));
            break;
        case 1: {
            out_.ending = "ldx out of range on some PEs";
            const int lo = NR_ - 2;
            emit(enc(PIDX, static_cast<uint32_t>(lo)));
            emit(enc(LDX, 0, static_cast<uint32_t>(lo), 0,
                     (1u << 29) | ((o_.mem_bytes - 2) & 0xffffff)));
            break;
        }
        case 2:
            out_.ending = "mask stack overflow";
            for (int i = 0; i <= out_.cfg.mask_depth; ++i) emit(enc(MIF));
            break;
        case 3:
            out_.ending = "ret without call";
            emit(enc(RET));
            break;
        case 4:
            out_.ending = "cld out of range";
            emit(enc(CLD, 0, 0, 128, 256 + static_cast<uint32_t>(u(10))));
            break;
        case 5:
            out_.ending = "negative transfer length";
            set_base(kBase0 + 2, 0xffffffffu);
            emit(enc(XLD, kBase0 + 2, kBase0 + 1, 128, 0));
            break;
        case 6:
            out_.ending = "video line outside the image";
            set_base(0, static_cast<uint32_t>(out_.left.height));
            emit(enc(VIN, 0, 0, 128, 0));
            break;
        case 7: {
            out_.ending = "watchdog";
            out_.cfg.watchdog_cycles = 200 + u(2000);
            const uint32_t top = static_cast<uint32_t>(here());
            emit(enc(ADD, 1, 1, 2));
            emit(enc(JMP, 0, 0, 0, top));
            break;
        }
        default:
            out_.ending = "mend on an empty stack";
            emit(enc(MALL));
            emit(enc(MEND));
            break;
    }
}

void Gen::run() {
    isa::MachineConfig& cfg = out_.cfg;
    cfg.pes = o_.pes;
    cfg.mem_bytes = o_.mem_bytes;
    cfg.ext_bytes = o_.ext_bytes;
    if (o_.vary_costs && chance(75)) {
        isa::CostTable& c = cfg.costs;
        c.alu = 1 + static_cast<uint32_t>(u(3));
        c.mem = 1 + static_cast<uint32_t>(u(3));
        c.indirect_extra = static_cast<uint32_t>(u(3));
        c.ring_hop = 1 + static_cast<uint32_t>(u(3));
        c.mask = 1 + static_cast<uint32_t>(u(2));
        c.status = 1 + static_cast<uint32_t>(u(3));
        c.cp = 1 + static_cast<uint32_t>(u(2));
        c.branch_taken = static_cast<uint32_t>(u(4));
        c.video_line = 1 + static_cast<uint32_t>(u(3));
        c.xfer_setup = static_cast<uint32_t>(u(11));
        static const uint32_t bpc[] = {1, 2, 3, 4, 5, 7, 8, 13, 16, 32};
        c.ext_bytes_per_cycle =
            std::min<uint32_t>(bpc[u(10)], static_cast<uint32_t>(detail::kHdlXrows));
        c.shift_bits = 1 + static_cast<uint32_t>(u(7));
        c.minmax_extra = static_cast<uint32_t>(u(3));
        // Board timing (a generator of its own, so that the programs of a
        // seed stay those of earlier versions): a path slower than a byte
        // per cycle, and a camera whose lines arrive while the program runs.
        auto b = [&](uint64_t n) { return board_rng_() % n; };
        if (b(3) == 0) c.ext_beat = 1 + static_cast<uint32_t>(b(4));
        if (b(4) == 0) {
            static const double pix[] = {2.5, 5, 10, 40};
            cfg.board.camera_pixel_mhz = pix[b(4)];
            cfg.board.camera_hblank_px = static_cast<double>(b(17));
        }
    }
    if (chance(20)) cfg.pe_regs = 8;
    NR_ = cfg.pe_regs;
    // images for the video port
    auto img = [&](isa::ImageVideoPort::Image& im, int w, int h) {
        im.width = w;
        im.height = h;
        im.pixels.resize(static_cast<size_t>(w) * static_cast<size_t>(h));
        for (uint8_t& p : im.pixels) p = static_cast<uint8_t>(rng_());
    };
    const int W = o_.pes + static_cast<int>(u(static_cast<uint64_t>(o_.pes))), H = 4;
    img(out_.left, W, H);
    img(out_.right, W, H);
    out_.out_w = W;
    out_.out_h = H;
    for (int i = 0; i < 8; ++i)
        if (chance(50))
            out_.params.emplace_back(static_cast<int>(u(256)), static_cast<uint32_t>(rng_()));
    // prologue: random CP and PE values
    for (int c = 0; c < 8; ++c) emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, cval()));
    for (int r = 0; r < NR_; ++r)
        emit(chance(50) ? enc(PIDX, static_cast<uint32_t>(r), 0, 0, 0)
                        : enc(ADDI, static_cast<uint32_t>(r), static_cast<uint32_t>(r ? r - 1 : 0),
                              0, imm8()));
    for (int i = 0; i < o_.blocks; ++i) block(0);
    const bool fault = chance(o_.fault_percent);
    if (fault)
        fault_ending();
    else
        out_.ending = "halt";
    emit(enc(HALT));
    // subroutines (each may call the next one, up to depth 2)
    std::vector<uint32_t> entry;
    for (int s = 0; s < subs_; ++s) {
        entry.push_back(static_cast<uint32_t>(here()));
        calls_ = 1;
        alu_run(1 + static_cast<int>(u(3)));
        if (chance(30)) block(2);
        emit(enc(RET));
    }
    calls_ = 0;
    for (const auto& [at, s] : call_fix_) patch(at, entry[static_cast<size_t>(s)]);
    out_.prog.code = code_;
    out_.prog.phases = {"default", "p1", "p2", "p3"};
}

}  // namespace

RandomProgram generate_program(uint64_t seed, const GenOptions& opt) {
    RandomProgram p;
    p.seed = seed;
    Gen g(seed, opt, p);
    g.run();
    return p;
}

// ---------------------------------------------------------------------------
// Coverage

namespace {
const char* const kFormats[] = {"none", "Rrr",  "Rri8", "Rr",  "Ri8", "Rsh",   "Cmp",
                                "Cmpi", "R",    "Rc",   "Rck", "Rk",  "Ld",    "Ldx",
                                "Xfer", "Ring", "Stat", "Ci",  "Cc",  "Ccc",   "Cci",
                                "Csh",  "Cmem", "J",    "Bcc", "B1",  "Video", "Phase"};
struct OpInfo {
    uint8_t op;
    const char* name;
    int fmt;  // index into kFormats
    bool pe;  // masked by M
};
const std::vector<OpInfo>& ops() {
    static const std::vector<OpInfo> v = {
        {0x00, "nop", 0, false},    {0x01, "halt", 0, false},   {0x02, "phase", 27, false},
        {0x08, "cli", 17, false},   {0x09, "cmov", 18, false},  {0x0A, "cadd", 19, false},
        {0x0B, "caddi", 20, false}, {0x0C, "csub", 19, false},  {0x0D, "csubi", 20, false},
        {0x0E, "cand", 19, false},  {0x0F, "candi", 20, false}, {0x10, "cor", 19, false},
        {0x11, "cori", 20, false},  {0x12, "cxor", 19, false},  {0x13, "cxori", 20, false},
        {0x14, "cshli", 21, false}, {0x15, "cshri", 21, false}, {0x16, "csrai", 21, false},
        {0x17, "cld", 22, false},   {0x18, "cst", 22, false},   {0x20, "jmp", 23, false},
        {0x21, "beq", 24, false},   {0x22, "bne", 24, false},   {0x23, "blt", 24, false},
        {0x24, "bge", 24, false},   {0x25, "bz", 25, false},    {0x26, "bnz", 25, false},
        {0x27, "loop", 25, false},  {0x28, "call", 23, false},  {0x29, "ret", 0, false},
        {0x40, "add", 1, true},     {0x41, "adc", 1, true},     {0x42, "sub", 1, true},
        {0x43, "sbc", 1, true},     {0x44, "and", 1, true},     {0x45, "or", 1, true},
        {0x46, "xor", 1, true},     {0x47, "min", 1, true},     {0x48, "max", 1, true},
        {0x50, "addi", 2, true},    {0x51, "adci", 2, true},    {0x52, "subi", 2, true},
        {0x53, "sbci", 2, true},    {0x54, "andi", 2, true},    {0x55, "ori", 2, true},
        {0x56, "xori", 2, true},    {0x57, "mini", 2, true},    {0x58, "maxi", 2, true},
        {0x60, "mov", 3, true},     {0x61, "li", 4, true},      {0x62, "lc", 9, true},
        {0x63, "lcb", 10, true},    {0x64, "pidx", 11, true},   {0x65, "setc", 8, true},
        {0x66, "sett", 8, true},    {0x67, "csel", 1, true},    {0x68, "tsel", 1, true},
        {0x70, "shli", 5, true},    {0x71, "shri", 5, true},    {0x72, "rolc", 3, true},
        {0x73, "rorc", 3, true},    {0x74, "shlv", 1, true},    {0x75, "shrv", 1, true},
        {0x80, "ceq", 6, true},     {0x81, "cne", 6, true},     {0x82, "cltu", 6, true},
        {0x83, "cleu", 6, true},    {0x84, "cgtu", 6, true},    {0x85, "cgeu", 6, true},
        {0x88, "ceqi", 7, true},    {0x89, "cnei", 7, true},    {0x8A, "cltui", 7, true},
        {0x8B, "cleui", 7, true},   {0x8C, "cgtui", 7, true},   {0x8D, "cgeui", 7, true},
        {0x8E, "tc", 0, true},      {0x8F, "tnot", 0, true},    {0x90, "ld", 12, true},
        {0x91, "st", 12, true},     {0x92, "ldx", 13, true},    {0x93, "stx", 13, true},
        {0x94, "xld", 14, true},    {0x95, "xst", 14, true},    {0xA0, "rxl", 15, true},
        {0xA1, "rxr", 15, true},    {0xB0, "mif", 0, false},    {0xB1, "melse", 0, false},
        {0xB2, "mend", 0, false},   {0xB3, "mall", 0, false},   {0xB4, "rany", 16, false},
        {0xB5, "rall", 16, false},  {0xC0, "vin", 26, false},   {0xC1, "vout", 26, false}};
    return v;
}
const OpInfo* op_info(uint8_t op) {
    for (const OpInfo& o : ops())
        if (o.op == op) return &o;
    return nullptr;
}
// Operand classes of a format (the second coordinate of the opcode bins).
std::vector<std::string> classes(int fmt) {
    switch (fmt) {
        case 1:
            return {"distinct", "rd=ra", "ra=rb"};
        case 2:
            return {"imm=0", "imm=255", "imm"};
        case 5:
            return {"n=0", "n=7", "n"};
        case 12:
            return {"absolute", "base"};
        case 13:
            return {"lo", "lo+hi", "+cN"};
        case 14:
            return {"len=0", "len>0"};
        case 15:
            return {"k<P", "k=P", "k>P"};
        case 24:
        case 25:
            return {"taken", "not taken"};
        case 26:
            return {"port0", "port1"};
        default:
            return {"-"};
    }
}
std::string klass(int fmt, uint64_t w, const isa::Machine& m, uint32_t pc, int P) {
    const uint32_t rd = (w >> 8) & 0xff, ra = (w >> 16) & 0xff, rb = (w >> 24) & 0xff;
    const uint32_t imm = static_cast<uint32_t>(w >> 32);
    switch (fmt) {
        case 1:
            return rd == ra ? "rd=ra" : ra == rb ? "ra=rb" : "distinct";
        case 2:
            return imm == 0 ? "imm=0" : imm == 255 ? "imm=255" : "imm";
        case 5:
            return imm == 0 ? "n=0" : imm == 7 ? "n=7" : "n";
        case 12:
            return rb == 128 ? "absolute" : "base";
        case 13:
            return ((imm >> 28) & 1) ? "+cN" : ((imm >> 29) & 1) ? "lo" : "lo+hi";
        case 14:
            return m.cp(static_cast<int>(rd & 15)) == 0 ? "len=0" : "len>0";
        case 15:
            return static_cast<int>(imm) < P ? "k<P" : static_cast<int>(imm) == P ? "k=P" : "k>P";
        case 24:
        case 25:
            return m.pc() != pc + 1 ? "taken" : "not taken";
        case 26:
            return rd == 0 ? "port0" : "port1";
        default:
            return "-";
    }
}
}  // namespace

Coverage::Coverage(int pes) : P_(pes) {
    for (const OpInfo& o : ops())
        for (const std::string& c : classes(o.fmt))
            for (const char* mk : o.pe ? std::vector<const char*>{"all active", "some masked"}
                                       : std::vector<const char*>{"-"})
                bins_[std::string("op/") + o.name + "/" + c + "/" + mk] = 0;
    for (const char* d : {"rxl", "rxr"})
        for (const char* k : {"1", "2..P-2", "P-1", "P", "P+1..2P", ">2P"})
            bins_[std::string("ring/") + d + "/" + k] = 0;
    for (const char* d : {"xld", "xst"})
        for (const char* k : {"0", "1", "2..7", "8..P", ">P"})
            bins_[std::string("xfer/") + d + "/" + k] = 0;
    for (int d = 0; d <= 3; ++d) bins_["mask/depth " + std::to_string(d)] = 0;
    for (const char* s : {"none active", "all active", "some masked"})
        bins_[std::string("mask/state/") + s] = 0;
    for (const char* b : {"taken to next", "backward", "forward"})
        bins_[std::string("branch/") + b] = 0;
    for (int d = 1; d <= 2; ++d) bins_["call/depth " + std::to_string(d)] = 0;
}

void Coverage::hit(const std::string& bin) {
    auto it = bins_.find(bin);
    if (it != bins_.end()) ++it->second;
}

void Coverage::sample(uint64_t w, uint32_t pc, int active_before, int mask_depth_before,
                      const isa::Machine& m) {
    const uint8_t op = static_cast<uint8_t>(w);
    const OpInfo* o = op_info(op);
    if (!o) return;
    const std::string mk = !o->pe ? "-" : active_before == P_ ? "all active" : "some masked";
    hit(std::string("op/") + o->name + "/" + klass(o->fmt, w, m, pc, P_) + "/" + mk);
    const uint32_t imm = static_cast<uint32_t>(w >> 32);
    if (op == 0xA0 || op == 0xA1) {
        const int k = static_cast<int>(imm), P = P_;
        const char* b = k == 1       ? "1"
                        : k <= P - 2 ? "2..P-2"
                        : k == P - 1 ? "P-1"
                        : k == P     ? "P"
                        : k <= 2 * P ? "P+1..2P"
                                     : ">2P";
        hit(std::string("ring/") + (op == 0xA0 ? "rxl/" : "rxr/") + b);
    }
    if (op == 0x94 || op == 0x95) {
        const uint32_t len = m.cp(static_cast<int>((w >> 8) & 15));
        const char* b = len == 0                      ? "0"
                        : len == 1                    ? "1"
                        : len <= 7                    ? "2..7"
                        : static_cast<int>(len) <= P_ ? "8..P"
                                                      : ">P";
        hit(std::string("xfer/") + (op == 0x94 ? "xld/" : "xst/") + b);
    }
    if (op >= 0xB0 && op <= 0xB3)
        hit("mask/depth " + std::to_string(std::min(mask_depth_before, 3)));
    hit(std::string("mask/state/") + (active_before == 0    ? "none active"
                                      : active_before == P_ ? "all active"
                                                            : "some masked"));
    if (op >= 0x20 && op <= 0x27 && m.pc() != pc + 1)
        hit(m.pc() < pc ? "branch/backward" : "branch/forward");
    if (op >= 0x21 && op <= 0x27 && imm == pc + 1) hit("branch/taken to next");
    if (op == 0x28) hit("call/depth " + std::to_string(std::min(m.call_stack_size(), 2)));
}

void Coverage::merge(const Coverage& o) {
    for (const auto& [b, n] : o.bins_) bins_[b] += n;
}

size_t Coverage::covered() const {
    size_t n = 0;
    for (const auto& [b, k] : bins_) n += k > 0;
    return n;
}

std::vector<std::string> Coverage::uncovered() const {
    std::vector<std::string> v;
    for (const auto& [b, k] : bins_)
        if (k == 0) v.push_back(b);
    return v;
}

std::string Coverage::table() const {
    std::map<std::string, std::pair<size_t, size_t>> g;  // group -> (covered, total)
    for (const auto& [b, k] : bins_) {
        std::string grp = b.substr(0, b.find('/'));
        if (grp == "op") {
            const size_t s2 = b.find('/', 3);
            const OpInfo* oi = nullptr;
            const std::string name = b.substr(3, s2 - 3);
            for (const OpInfo& o : ops())
                if (name == o.name) oi = &o;
            grp = std::string("op ") + (oi ? kFormats[oi->fmt] : "?");
        }
        auto& e = g[grp];
        e.first += k > 0;
        ++e.second;
    }
    std::ostringstream o;
    o << "functional coverage: " << covered() << " of " << bins() << " bins\n";
    char line[128];
    for (const auto& [grp, e] : g) {
        std::snprintf(line, sizeof line, "  %-16s %5zu / %-5zu %5.1f%%\n", grp.c_str(), e.first,
                      e.second,
                      100.0 * static_cast<double>(e.first) / static_cast<double>(e.second));
        o << line;
    }
    const std::vector<std::string> u = uncovered();
    o << "  uncovered (" << u.size() << "):";
    for (const std::string& b : u) o << " " << b;
    o << "\n";
    return o.str();
}

nlohmann::json Coverage::json() const {
    nlohmann::json j;
    j["bins"] = bins();
    j["covered"] = covered();
    nlohmann::json h = nlohmann::json::object();
    for (const auto& [b, k] : bins_) h[b] = k;
    j["hits"] = h;
    j["uncovered"] = uncovered();
    return j;
}

// ---------------------------------------------------------------------------
// The suite

SuiteResult run_random_suite(const SuiteOptions& opt) {
    using namespace detail;
    SuiteResult res;
    res.coverage = Coverage(opt.gen.pes);
    isa::MachineConfig base;
    base.pes = opt.gen.pes;
    base.mem_bytes = opt.gen.mem_bytes;
    base.ext_bytes = opt.gen.ext_bytes;
    RtlConfig rc;
    rc.mutant = opt.mutant;
    rc.validate(base);
    check_runnable(base, false, !opt.mutant.empty());
    const ConfigInfo& ci = pick_config(base, rc);
    claim_process("run_random_suite");
    tlm::detail::ElaborationGuard guard;
    Bench bench("top", ci, std::unique_ptr<Model>(ci.make("dut")), nullptr, 40.0);
    const uint32_t mut = opt.mutant.empty() ? 0 : mutant_id(opt.mutant);

    int index = -1;
    RandomProgram cur;
    std::unique_ptr<StepReference> ref;
    std::unique_ptr<Checker> chk;
    Job job;
    int active_before = opt.gen.pes, depth_before = 0;
    const auto t0 = std::chrono::steady_clock::now();
    bench.next_job = [&]() -> Job* {
        if (++index >= opt.programs || (opt.stop_at_divergence && res.caught)) return nullptr;
        cur = generate_program(opt.seed + static_cast<uint64_t>(index), opt.gen);
        job = Job();
        fill_job(job, cur.cfg, cur.prog, cur.params, cur.left, cur.right, cur.out_w, cur.out_h);
        job.mutant = mut;
        if (!opt.lockstep) return &job;  // the RTL alone (its assertions)
        ref = std::make_unique<StepReference>(cur.cfg, cur.prog, cur.params, cur.left, cur.right,
                                              cur.out_w, cur.out_h);
        chk = std::make_unique<Checker>(*ref, cur.prog, cur.cfg.pes);
        chk->reg_every = chk->mem_every = opt.full_compare_every;
        active_before = opt.gen.pes;
        depth_before = 0;
        chk->on_compared = [&](const RetireRecord& r, const isa::Machine& m) {
            res.coverage.sample(r.word, r.pc, active_before, depth_before, m);
            active_before = m.active_pes();
            depth_before = m.mask_stack_size();
        };
        job.listener = chk.get();
        return &job;
    };
    bench.job_done = [&](Job& j) {
        ++res.programs;
        if (j.assertion.valid || !opt.lockstep) {
            // an assertion of the design failed (it stopped the program),
            // or the RTL alone ran: a failure only if an assertion failed
            // or the testbench gave up
            const uint64_t n = j.instructions;
            if (j.assertion.valid || !j.error.empty()) {
                const std::string msg =
                    "program " + std::to_string(index) + " (seed " + std::to_string(cur.seed) +
                    ", ends with " + cur.ending + "): " +
                    (j.assertion.valid ? assertion_divergence(j.assertion, cur.prog).message()
                                       : j.error);
                res.failures.push_back(msg);
                if (!res.caught) {
                    res.caught = true;
                    res.caught_program = index;
                    res.caught_instruction = j.assertion.valid ? j.assertion.index : n;
                    res.instructions_to_catch = res.instructions + res.caught_instruction + 1;
                    res.caught_message = msg;
                    res.caught_assertion = j.assertion.valid ? j.assertion.name : "";
                }
            } else {
                ++res.passed;
            }
            res.instructions += n;
            res.cycles += j.cycles;
            return;
        }
        if (!chk->diverged && j.error.empty())
            chk->final_check(j, bench.shadow(), bench.backdoor());
        if (!chk->diverged && j.error.empty())
            for (int p = 0; p < 2 && !chk->diverged; ++p)
                if (j.output[p].pixels != ref->video().output[p].pixels) {
                    chk->diverged = true;
                    chk->div.what = "video output " + std::to_string(p);
                    chk->div.instruction = j.instructions;
                }
        const uint64_t n = j.instructions;
        if (chk->diverged || !j.error.empty()) {
            const std::string msg = "program " + std::to_string(index) + " (seed " +
                                    std::to_string(cur.seed) + ", ends with " + cur.ending +
                                    "): " + (j.error.empty() ? chk->div.message() : j.error);
            res.failures.push_back(msg);
            if (!res.caught) {
                res.caught = true;
                res.caught_program = index;
                res.caught_instruction = chk->div.instruction;
                res.instructions_to_catch = res.instructions + chk->div.instruction + 1;
                res.caught_message = msg;
            }
        } else {
            ++res.passed;
        }
        res.instructions += n;
        res.cycles += j.cycles;
    };
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();  // docs/testing.md (ASan and ended SystemC
                                                   // threads)
    res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

}  // namespace imap::rtl
