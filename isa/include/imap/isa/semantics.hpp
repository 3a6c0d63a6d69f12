// Per-lane semantics of the PE instructions, written once. The executor's
// lane loops instantiate these with a compile-time opcode (so the loops
// vectorise); a signal-level PE model can call the run-time dispatchers
// alu_lane() / compare_lane() for one PE. Everything is 8-bit arithmetic on
// purpose: the carry of an 8-bit add is (r < a), not a widened sum, which
// keeps the loops in byte vectors.
#pragma once

#include <cstdint>

#include "imap/isa/opcodes.hpp"

namespace imap::isa::sem {

struct LaneOut {
    uint8_t r;  // result byte
    uint8_t c;  // carry flag after the operation (unchanged if the op keeps C)
};

// True for the ALU ops that write the carry flag.
constexpr bool writes_carry(Op o) {
    switch (o) {
        case Op::ADD:
        case Op::ADC:
        case Op::SUB:
        case Op::SBC:
        case Op::ADDI:
        case Op::ADCI:
        case Op::SUBI:
        case Op::SBCI:
        case Op::SHLI:
        case Op::SHRI:
        case Op::ROLC:
        case Op::RORC:
        case Op::SHLV:
        case Op::SHRV:
            return true;
        default:
            return false;
    }
}

// Two-operand ALU and shifter: a = ra lane, b = rb lane or the immediate
// (for shifts: the shift amount 0..7), c = carry-in lane (0 or 1).
template <Op O>
constexpr LaneOut alu(uint8_t a, uint8_t b, uint8_t c) {
    if constexpr (O == Op::ADD || O == Op::ADDI) {
        const uint8_t r = static_cast<uint8_t>(a + b);
        return {r, static_cast<uint8_t>(r < a)};
    } else if constexpr (O == Op::ADC || O == Op::ADCI) {
        // a + b + c >= 256 <=> r < a, or r == a with a carry in.
        const uint8_t r = static_cast<uint8_t>(a + b + c);
        return {r, static_cast<uint8_t>((r < a) | ((r == a) & c))};
    } else if constexpr (O == Op::SUB || O == Op::SUBI) {
        return {static_cast<uint8_t>(a - b), static_cast<uint8_t>(a < b)};
    } else if constexpr (O == Op::SBC || O == Op::SBCI) {
        // borrow = a < b + c
        return {static_cast<uint8_t>(a - b - c), static_cast<uint8_t>((a < b) | ((a == b) & c))};
    } else if constexpr (O == Op::AND || O == Op::ANDI) {
        return {static_cast<uint8_t>(a & b), c};
    } else if constexpr (O == Op::OR || O == Op::ORI) {
        return {static_cast<uint8_t>(a | b), c};
    } else if constexpr (O == Op::XOR || O == Op::XORI) {
        return {static_cast<uint8_t>(a ^ b), c};
    } else if constexpr (O == Op::MIN || O == Op::MINI) {
        return {a < b ? a : b, c};
    } else if constexpr (O == Op::MAX || O == Op::MAXI) {
        return {a > b ? a : b, c};
    } else if constexpr (O == Op::SHLI || O == Op::SHLV) {
        // Shift by n = 0..7 in three conditional stages (1, 2, 4) of 8-bit
        // operations, so a per-lane amount (shlv) vectorises and a constant
        // amount folds to one shift. C = the last bit out of the last active
        // stage = bit 8 - n of a; n = 0 leaves the value and C unchanged.
        const unsigned n = b & 7u;
        uint8_t r = a, co = c;
        co = (n & 1u) ? static_cast<uint8_t>(r >> 7) : co;
        r = (n & 1u) ? static_cast<uint8_t>(r << 1) : r;
        co = (n & 2u) ? static_cast<uint8_t>((r >> 6) & 1u) : co;
        r = (n & 2u) ? static_cast<uint8_t>(r << 2) : r;
        co = (n & 4u) ? static_cast<uint8_t>((r >> 4) & 1u) : co;
        r = (n & 4u) ? static_cast<uint8_t>(r << 4) : r;
        return {r, co};
    } else if constexpr (O == Op::SHRI || O == Op::SHRV) {
        // As above; C = bit n - 1 of a.
        const unsigned n = b & 7u;
        uint8_t r = a, co = c;
        co = (n & 1u) ? static_cast<uint8_t>(r & 1u) : co;
        r = (n & 1u) ? static_cast<uint8_t>(r >> 1) : r;
        co = (n & 2u) ? static_cast<uint8_t>((r >> 1) & 1u) : co;
        r = (n & 2u) ? static_cast<uint8_t>(r >> 2) : r;
        co = (n & 4u) ? static_cast<uint8_t>((r >> 3) & 1u) : co;
        r = (n & 4u) ? static_cast<uint8_t>(r >> 4) : r;
        return {r, co};
    } else if constexpr (O == Op::ROLC) {
        return {static_cast<uint8_t>((a << 1) | c), static_cast<uint8_t>(a >> 7)};
    } else if constexpr (O == Op::RORC) {
        return {static_cast<uint8_t>((a >> 1) | (c << 7)), static_cast<uint8_t>(a & 1u)};
    } else {
        static_assert(O == Op::ADD, "not an ALU op");
        return {0, 0};
    }
}

// Comparator: T = a op b (unsigned).
template <Op O>
constexpr uint8_t compare(uint8_t a, uint8_t b) {
    if constexpr (O == Op::CEQ || O == Op::CEQI)
        return a == b;
    else if constexpr (O == Op::CNE || O == Op::CNEI)
        return a != b;
    else if constexpr (O == Op::CLTU || O == Op::CLTUI)
        return a < b;
    else if constexpr (O == Op::CLEU || O == Op::CLEUI)
        return a <= b;
    else if constexpr (O == Op::CGTU || O == Op::CGTUI)
        return a > b;
    else if constexpr (O == Op::CGEU || O == Op::CGEUI)
        return a >= b;
    else {
        static_assert(O == Op::CEQ, "not a compare op");
        return 0;
    }
}

// Run-time dispatch for a single lane (signal-level models, tests).
// Precondition: `o` is an ALU/shifter op (writes_carry or a logic/min/max op);
// other opcodes return {a, c}.
LaneOut alu_lane(Op o, uint8_t a, uint8_t b, uint8_t c);
// Precondition: `o` is a compare op; other opcodes return 0.
uint8_t compare_lane(Op o, uint8_t a, uint8_t b);

}  // namespace imap::isa::sem
