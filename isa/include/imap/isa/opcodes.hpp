// The IMAP-VISION instruction set: one table (an X-macro) that names every
// opcode once, with its encoding, operand format, cost class and summary.
// Everything else (decoder, handler table, assembler, disassembler, docs
// checks) is generated from or checked against this table.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace imap::isa {

// Operand formats: which of the fields rd, ra, rb, imm an instruction uses and
// how (docs/isa.md, "Encoding"). Fields an instruction does not use must be 0.
enum class Format : uint8_t {
    None,   // (no operands)
    Rrr,    // rd, ra, rb              PE registers
    Rri8,   // rd, ra, #imm8
    Rr,     // rd, ra
    Ri8,    // rd, #imm8
    Rsh,    // rd, ra, #n              n = 0..7
    Cmp,    // ra, rb                  T = ra op rb
    Cmpi,   // ra, #imm8
    R,      // rd
    Rc,     // rd, cA                  CP register in ra
    Rck,    // rd, cA, #k              k = 0..3 in imm
    Rk,     // rd, #k                  k = 0..3 in imm
    Ld,     // rd, [cB + off]          rd = data register, rb = base (or kNoBase)
    Ldx,    // rd, [ra:rb + cN + off]  per-PE address, flags in imm
    Xfer,   // [cB + off], ext[cA], cD local base rb, ext address ra, length rd
    Ring,   // rd, ra, #k              k = 1..65535 hops
    Stat,   // cD
    Ci,     // cD, #imm32
    Cc,     // cD, cA
    Ccc,    // cD, cA, cB
    Cci,    // cD, cA, #imm32
    Csh,    // cD, cA, #n              n = 0..31
    Cmem,   // cD, [cB + off]          param block, rb = base (or kNoBase)
    J,      // target                  imm = absolute PC
    Bcc,    // cA, cB, target
    B1,     // cA, target
    Video,  // #port, [cB + off], cY, cX   port in rd, ra = cY | cX << 4
    Phase,  // #id                     imm = phase id 0..65535
};
inline constexpr int kFormatCount = static_cast<int>(Format::Phase) + 1;

// For the static_assert of a table indexed by Format: one row per format, row
// i for Format(i) (rows[i].format).
template <class Row, int N>
constexpr bool one_row_per_format(const Row (&rows)[N]) {
    for (int i = 0; i < N; ++i)
        if (static_cast<int>(rows[i].format) != i) return false;
    return N == kFormatCount;
}

// Which entry of the cost table an instruction is charged (config.hpp).
enum class CostClass : uint8_t {
    Alu,       // costs.alu
    Mem,       // costs.mem
    Indirect,  // costs.mem + costs.indirect_extra
    Ring,      // k * costs.ring_hop
    Mask,      // costs.mask
    Status,    // costs.status
    Cp,        // costs.cp (+ costs.branch_taken when a branch is taken)
    Video,     // costs.video_line
    Xfer,      // costs.xfer_setup + ceil(len * P / costs.ext_bytes_per_cycle)
    Phase,     // 0 (pseudo-instruction)
    Shift,     // costs.alu + ceil(n / costs.shift_bits) - 1 (n = bits shifted, 7 for shlv/shrv)
    MinMax,    // costs.alu + costs.minmax_extra
};
inline constexpr int kCostClassCount = 12;
const char* to_string(CostClass c);

// X(ID, mnemonic, opcode, Format, CostClass, summary)
#define IMAP_ISA_OPCODES(X)                                                                    \
    /* control processor */                                                                    \
    X(NOP, "nop", 0x00, None, Cp, "no operation")                                              \
    X(HALT, "halt", 0x01, None, Cp, "stop the program")                                        \
    X(PHASE, "phase", 0x02, Phase, Phase, "zero-cost: charge following cycles to phase #id")   \
    X(CLI, "cli", 0x08, Ci, Cp, "cD = imm32")                                                  \
    X(CMOV, "cmov", 0x09, Cc, Cp, "cD = cA")                                                   \
    X(CADD, "cadd", 0x0A, Ccc, Cp, "cD = cA + cB (mod 2^32)")                                  \
    X(CADDI, "caddi", 0x0B, Cci, Cp, "cD = cA + imm32")                                        \
    X(CSUB, "csub", 0x0C, Ccc, Cp, "cD = cA - cB")                                             \
    X(CSUBI, "csubi", 0x0D, Cci, Cp, "cD = cA - imm32")                                        \
    X(CAND, "cand", 0x0E, Ccc, Cp, "cD = cA & cB")                                             \
    X(CANDI, "candi", 0x0F, Cci, Cp, "cD = cA & imm32")                                        \
    X(COR, "cor", 0x10, Ccc, Cp, "cD = cA | cB")                                               \
    X(CORI, "cori", 0x11, Cci, Cp, "cD = cA | imm32")                                          \
    X(CXOR, "cxor", 0x12, Ccc, Cp, "cD = cA ^ cB")                                             \
    X(CXORI, "cxori", 0x13, Cci, Cp, "cD = cA ^ imm32")                                        \
    X(CSHLI, "cshli", 0x14, Csh, Cp, "cD = cA << n")                                           \
    X(CSHRI, "cshri", 0x15, Csh, Cp, "cD = cA >> n (logical)")                                 \
    X(CSRAI, "csrai", 0x16, Csh, Cp, "cD = cA >> n (arithmetic)")                              \
    X(CLD, "cld", 0x17, Cmem, Cp, "cD = param[cB + off]")                                      \
    X(CST, "cst", 0x18, Cmem, Cp, "param[cB + off] = cD")                                      \
    X(JMP, "jmp", 0x20, J, Cp, "jump")                                                         \
    X(BEQ, "beq", 0x21, Bcc, Cp, "branch if cA == cB")                                         \
    X(BNE, "bne", 0x22, Bcc, Cp, "branch if cA != cB")                                         \
    X(BLT, "blt", 0x23, Bcc, Cp, "branch if cA < cB (signed)")                                 \
    X(BGE, "bge", 0x24, Bcc, Cp, "branch if cA >= cB (signed)")                                \
    X(BZ, "bz", 0x25, B1, Cp, "branch if cA == 0")                                             \
    X(BNZ, "bnz", 0x26, B1, Cp, "branch if cA != 0")                                           \
    X(LOOP, "loop", 0x27, B1, Cp, "cA -= 1; branch if cA != 0")                                \
    X(CALL, "call", 0x28, J, Cp, "push return PC, jump")                                       \
    X(RET, "ret", 0x29, None, Cp, "pop return PC, jump")                                       \
    /* PE ALU, register-register */                                                            \
    X(ADD, "add", 0x40, Rrr, Alu, "rd = ra + rb; C = carry")                                   \
    X(ADC, "adc", 0x41, Rrr, Alu, "rd = ra + rb + C; C = carry")                               \
    X(SUB, "sub", 0x42, Rrr, Alu, "rd = ra - rb; C = borrow")                                  \
    X(SBC, "sbc", 0x43, Rrr, Alu, "rd = ra - rb - C; C = borrow")                              \
    X(AND, "and", 0x44, Rrr, Alu, "rd = ra & rb")                                              \
    X(OR, "or", 0x45, Rrr, Alu, "rd = ra | rb")                                                \
    X(XOR, "xor", 0x46, Rrr, Alu, "rd = ra ^ rb")                                              \
    X(MIN, "min", 0x47, Rrr, MinMax, "rd = min(ra, rb) (unsigned)")                            \
    X(MAX, "max", 0x48, Rrr, MinMax, "rd = max(ra, rb) (unsigned)")                            \
    /* PE ALU, register-immediate */                                                           \
    X(ADDI, "addi", 0x50, Rri8, Alu, "rd = ra + imm; C = carry")                               \
    X(ADCI, "adci", 0x51, Rri8, Alu, "rd = ra + imm + C; C = carry")                           \
    X(SUBI, "subi", 0x52, Rri8, Alu, "rd = ra - imm; C = borrow")                              \
    X(SBCI, "sbci", 0x53, Rri8, Alu, "rd = ra - imm - C; C = borrow")                          \
    X(ANDI, "andi", 0x54, Rri8, Alu, "rd = ra & imm")                                          \
    X(ORI, "ori", 0x55, Rri8, Alu, "rd = ra | imm")                                            \
    X(XORI, "xori", 0x56, Rri8, Alu, "rd = ra ^ imm")                                          \
    X(MINI, "mini", 0x57, Rri8, MinMax, "rd = min(ra, imm)")                                   \
    X(MAXI, "maxi", 0x58, Rri8, MinMax, "rd = max(ra, imm)")                                   \
    /* PE moves and selects */                                                                 \
    X(MOV, "mov", 0x60, Rr, Alu, "rd = ra")                                                    \
    X(LI, "li", 0x61, Ri8, Alu, "rd = imm8")                                                   \
    X(LC, "lc", 0x62, Rc, Alu, "rd = low byte of cA (broadcast)")                              \
    X(LCB, "lcb", 0x63, Rck, Alu, "rd = byte k of cA (broadcast)")                             \
    X(PIDX, "pidx", 0x64, Rk, Alu, "rd = byte k of the PE index")                              \
    X(SETC, "setc", 0x65, R, Alu, "rd = C")                                                    \
    X(SETT, "sett", 0x66, R, Alu, "rd = T")                                                    \
    X(CSEL, "csel", 0x67, Rrr, Alu, "rd = C ? ra : rb")                                        \
    X(TSEL, "tsel", 0x68, Rrr, Alu, "rd = T ? ra : rb")                                        \
    /* PE shifter */                                                                           \
    X(SHLI, "shli", 0x70, Rsh, Shift, "rd = ra << n; C = last bit out (n > 0)")                \
    X(SHRI, "shri", 0x71, Rsh, Shift, "rd = ra >> n; C = last bit out (n > 0)")                \
    X(ROLC, "rolc", 0x72, Rr, Alu, "rd = ra << 1 | C; C = ra bit 7")                           \
    X(RORC, "rorc", 0x73, Rr, Alu, "rd = ra >> 1 | C << 7; C = ra bit 0")                      \
    X(SHLV, "shlv", 0x74, Rrr, Shift, "rd = ra << (rb & 7); C as shli")                        \
    X(SHRV, "shrv", 0x75, Rrr, Shift, "rd = ra >> (rb & 7); C as shri")                        \
    /* PE comparator -> T */                                                                   \
    X(CEQ, "ceq", 0x80, Cmp, Alu, "T = ra == rb")                                              \
    X(CNE, "cne", 0x81, Cmp, Alu, "T = ra != rb")                                              \
    X(CLTU, "cltu", 0x82, Cmp, Alu, "T = ra < rb")                                             \
    X(CLEU, "cleu", 0x83, Cmp, Alu, "T = ra <= rb")                                            \
    X(CGTU, "cgtu", 0x84, Cmp, Alu, "T = ra > rb")                                             \
    X(CGEU, "cgeu", 0x85, Cmp, Alu, "T = ra >= rb")                                            \
    X(CEQI, "ceqi", 0x88, Cmpi, Alu, "T = ra == imm")                                          \
    X(CNEI, "cnei", 0x89, Cmpi, Alu, "T = ra != imm")                                          \
    X(CLTUI, "cltui", 0x8A, Cmpi, Alu, "T = ra < imm")                                         \
    X(CLEUI, "cleui", 0x8B, Cmpi, Alu, "T = ra <= imm")                                        \
    X(CGTUI, "cgtui", 0x8C, Cmpi, Alu, "T = ra > imm")                                         \
    X(CGEUI, "cgeui", 0x8D, Cmpi, Alu, "T = ra >= imm")                                        \
    X(TC, "tc", 0x8E, None, Alu, "T = C")                                                      \
    X(TNOT, "tnot", 0x8F, None, Alu, "T = !T")                                                 \
    /* PE memory */                                                                            \
    X(LD, "ld", 0x90, Ld, Mem, "rd = mem[cB + off] (broadcast address)")                       \
    X(ST, "st", 0x91, Ld, Mem, "mem[cB + off] = rd (broadcast address)")                       \
    X(LDX, "ldx", 0x92, Ldx, Indirect, "rd = mem[(rb << 8 | ra) + cN + off] (per-PE address)") \
    X(STX, "stx", 0x93, Ldx, Indirect, "mem[(rb << 8 | ra) + cN + off] = rd (per-PE address)") \
    X(XLD, "xld", 0x94, Xfer, Xfer, "mem[cB + off ..] = ext[cA ..], cD bytes, all PEs")        \
    X(XST, "xst", 0x95, Xfer, Xfer, "ext[cA ..] = mem[cB + off ..], cD bytes, all PEs")        \
    /* shift ring */                                                                           \
    X(RXL, "rxl", 0xA0, Ring, Ring, "rd(p) = ra(p - k mod P): data moves k PEs up")            \
    X(RXR, "rxr", 0xA1, Ring, Ring, "rd(p) = ra(p + k mod P): data moves k PEs down")          \
    /* mask bus */                                                                             \
    X(MIF, "mif", 0xB0, None, Mask, "push M; M = M & T")                                       \
    X(MELSE, "melse", 0xB1, None, Mask, "M = top & !M")                                        \
    X(MEND, "mend", 0xB2, None, Mask, "M = pop")                                               \
    X(MALL, "mall", 0xB3, None, Mask, "M = 1 on all PEs; empty the mask stack")                \
    X(RANY, "rany", 0xB4, Stat, Status, "cD = OR of T over active PEs")                        \
    X(RALL, "rall", 0xB5, Stat, Status, "cD = AND of T over active PEs (1 if none)")           \
    /* video line I/O */                                                                       \
    X(VIN, "vin", 0xC0, Video, Video, "mem row [cB + off] = input line cY from column cX")     \
    X(VOUT, "vout", 0xC1, Video, Video, "output line cY from column cX = mem row [cB + off]")

enum class Op : uint8_t {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc) id = code,
    IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
};

struct OpInfo {
    Op op;
    std::string_view mnemonic;
    Format format;
    CostClass cost_class;
    std::string_view summary;
};

constexpr Format format_of(Op op) {
    switch (op) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc) \
    case Op::id:                                \
        return Format::fmt;
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
    }
    return Format::None;
}

constexpr CostClass cost_class_of(Op op) {
    switch (op) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc) \
    case Op::id:                                \
        return CostClass::cls;
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
    }
    return CostClass::Cp;
}

// nullptr when `code` is not an opcode.
const OpInfo* op_info(uint8_t code);
inline const OpInfo* op_info(Op op) {
    return op_info(static_cast<uint8_t>(op));
}
// nullptr when `mnemonic` (lower case) is not an instruction.
const OpInfo* op_by_name(std::string_view mnemonic);
// Every opcode, in table order.
const std::vector<OpInfo>& all_ops();
// Operand syntax of a format for docs and messages, e.g. "rd, ra, #imm8".
const char* operand_syntax(Format f);

}  // namespace imap::isa
