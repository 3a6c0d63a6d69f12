// The constrained-random program generator's private pieces (docs/rtl.md,
// "Random suite"): the instruction encoding, the opcodes it draws from, the
// CP register roles, and the generator (Gen) whose instruction classes are
// defined in randprog*.cpp: the PE data path (randprog_pe.cpp), memory,
// transfers and video (randprog_mem.cpp), control flow, mask stack and CP
// (randprog_control.cpp), and the program's frame, machine configuration and
// endings (randprog.cpp). One random stream (rng_) is drawn in a fixed order:
// the programs of a seed depend on every draw staying where it is.
#pragma once

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "imap/rtl/random.hpp"

namespace imap::rtl::randgen {

// ---- encoding (docs/isa.md section 3) ---------------------------------------
inline uint64_t enc(uint8_t op, uint32_t rd = 0, uint32_t ra = 0, uint32_t rb = 0,
                    uint32_t imm = 0) {
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

    // The PE data path (randprog_pe.cpp).
    void pe_op();
    void alu_run(int n) {
        for (int i = 0; i < n; ++i) pe_op();
    }
    void ring_block();
    // Blocks, control flow, mask stack and CP (randprog_control.cpp).
    void block(int level);
    void mask_block(int level);
    void loop_block(int level);
    void branch_block(int level);
    void status_block();
    void cp_block();
    // Memory, external transfers and video (randprog_mem.cpp).
    void mem_block();
    void memx_block();
    void xfer_block();
    void video_block();
    void set_base(int c, uint32_t v) { emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, v)); }
    // The program's ending (randprog.cpp).
    void fault_ending();
    // GenOptions::strap_sweep (randprog.cpp).
    void strap_sweep();
};

}  // namespace imap::rtl::randgen
