// Instruction word layout: 64 bits, little-endian,
//   byte 0 opcode | byte 1 rd | byte 2 ra | byte 3 rb | bytes 4..7 imm (32 bits)
// i.e. word = opcode | rd << 8 | ra << 16 | rb << 24 | imm << 32.
#pragma once

#include <cstdint>
#include <string>

namespace imap::isa {

inline constexpr int kMaxPeRegs = 64;  // register fields accept r0..r63
inline constexpr int kCpRegs = 16;     // c0..c15
inline constexpr int kParamWords = 256;
inline constexpr uint8_t kNoBase = 0x80;  // base field value of an absolute [#addr] operand

// Ldx/Stx imm field: signed 24-bit offset, optional CP register, optional high byte.
inline constexpr uint32_t kLdxOffsetMask = 0x00FFFFFFu;
inline constexpr int kLdxCpShift = 24;            // bits 24..27: CP register
inline constexpr uint32_t kLdxUseCp = 1u << 28;   // add the CP register
inline constexpr uint32_t kLdxNoHigh = 1u << 29;  // single-byte offset register (rb must be 0)
inline constexpr int32_t kLdxOffsetMin = -(1 << 23);
inline constexpr int32_t kLdxOffsetMax = (1 << 23) - 1;

struct Word {
    uint8_t op = 0;
    uint8_t rd = 0;
    uint8_t ra = 0;
    uint8_t rb = 0;
    uint32_t imm = 0;

    constexpr uint64_t encode() const {
        return uint64_t{op} | uint64_t{rd} << 8 | uint64_t{ra} << 16 | uint64_t{rb} << 24 |
               uint64_t{imm} << 32;
    }
    static constexpr Word decode(uint64_t w) {
        Word x;
        x.op = static_cast<uint8_t>(w);
        x.rd = static_cast<uint8_t>(w >> 8);
        x.ra = static_cast<uint8_t>(w >> 16);
        x.rb = static_cast<uint8_t>(w >> 24);
        x.imm = static_cast<uint32_t>(w >> 32);
        return x;
    }
};

// Sign-extends the 24-bit offset of an ldx/stx imm field.
constexpr int32_t ldx_offset(uint32_t imm) {
    const int32_t v = static_cast<int32_t>(imm & kLdxOffsetMask);
    return v >= (1 << 23) ? v - (1 << 24) : v;
}

// Two's-complement reinterpretation without implementation-defined casts.
constexpr int32_t as_signed(uint32_t v) {
    return v >= 0x80000000u ? static_cast<int32_t>(v - 0x80000000u) + INT32_MIN
                            : static_cast<int32_t>(v);
}

// Static (configuration-independent) validity of a word: known opcode, unused
// fields zero, register fields in r0..r63 / c0..c15, immediates in range.
// Returns an empty string when valid, otherwise the reason.
std::string check_word(uint64_t w);

}  // namespace imap::isa
