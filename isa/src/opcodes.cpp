// The opcode table, static word validation and the run-time lane dispatchers.
#include <array>
#include <string>

#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/isa/semantics.hpp"

namespace imap::isa {

namespace {

const std::vector<OpInfo>& table() {
    static const std::vector<OpInfo> t = {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc) \
    OpInfo{Op::id, mn, Format::fmt, CostClass::cls, doc},
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
    };
    return t;
}

const std::array<const OpInfo*, 256>& by_code() {
    static const std::array<const OpInfo*, 256> a = [] {
        std::array<const OpInfo*, 256> r{};
        for (const OpInfo& i : table()) r[static_cast<uint8_t>(i.op)] = &i;
        return r;
    }();
    return a;
}

}  // namespace

const char* to_string(CostClass c) {
    switch (c) {
        case CostClass::Alu:
            return "alu";
        case CostClass::Mem:
            return "mem";
        case CostClass::Indirect:
            return "indirect";
        case CostClass::Ring:
            return "ring";
        case CostClass::Mask:
            return "mask";
        case CostClass::Status:
            return "status";
        case CostClass::Cp:
            return "cp";
        case CostClass::Video:
            return "video";
        case CostClass::Xfer:
            return "xfer";
        case CostClass::Phase:
            return "phase";
        case CostClass::Shift:
            return "shift";
        case CostClass::MinMax:
            return "minmax";
    }
    return "?";
}

const OpInfo* op_info(uint8_t code) {
    return by_code()[code];
}

const OpInfo* op_by_name(std::string_view mnemonic) {
    for (const OpInfo& i : table())
        if (i.mnemonic == mnemonic) return &i;
    return nullptr;
}

const std::vector<OpInfo>& all_ops() {
    return table();
}

const char* operand_syntax(Format f) {
    switch (f) {
        case Format::None:
            return "";
        case Format::Rrr:
            return "rd, ra, rb";
        case Format::Rri8:
            return "rd, ra, #imm8";
        case Format::Rr:
            return "rd, ra";
        case Format::Ri8:
            return "rd, #imm8";
        case Format::Rsh:
            return "rd, ra, #n";
        case Format::Cmp:
            return "ra, rb";
        case Format::Cmpi:
            return "ra, #imm8";
        case Format::R:
            return "rd";
        case Format::Rc:
            return "rd, cA";
        case Format::Rck:
            return "rd, cA, #k";
        case Format::Rk:
            return "rd, #k";
        case Format::Ld:
            return "rd, [cB + off]";
        case Format::Ldx:
            return "rd, [ra:rb + cN + off]";
        case Format::Xfer:
            return "[cB + off], ext[cA], cD";
        case Format::Ring:
            return "rd, ra, #k";
        case Format::Stat:
            return "cD";
        case Format::Ci:
            return "cD, #imm32";
        case Format::Cc:
            return "cD, cA";
        case Format::Ccc:
            return "cD, cA, cB";
        case Format::Cci:
            return "cD, cA, #imm32";
        case Format::Csh:
            return "cD, cA, #n";
        case Format::Cmem:
            return "cD, [cB + off]";
        case Format::J:
            return "target";
        case Format::Bcc:
            return "cA, cB, target";
        case Format::B1:
            return "cA, target";
        case Format::Video:
            return "#port, [cB + off], cY, cX";
        case Format::Phase:
            return "#id";
    }
    return "?";
}

std::string check_word(uint64_t w) {
    const Word x = Word::decode(w);
    const OpInfo* info = op_info(x.op);
    auto hex = [](unsigned v) {
        static const char* d = "0123456789abcdef";
        std::string s = "0x";
        s += d[(v >> 4) & 15];
        s += d[v & 15];
        return s;
    };
    if (!info) return "unknown opcode " + hex(x.op);
    const std::string mn(info->mnemonic);
    std::string why;
    auto zero = [&](const char* f, uint32_t v) {
        if (why.empty() && v != 0)
            why = mn + ": unused field " + f + " must be 0 (is " + std::to_string(v) + ")";
    };
    auto pe = [&](const char* f, uint8_t v) {
        if (why.empty() && v >= kMaxPeRegs)
            why = mn + ": field " + f + " = " + std::to_string(v) + " is not a PE register (r0..r" +
                  std::to_string(kMaxPeRegs - 1) + ")";
    };
    auto cp = [&](const char* f, uint8_t v) {
        if (why.empty() && v >= kCpRegs)
            why =
                mn + ": field " + f + " = " + std::to_string(v) + " is not a CP register (c0..c15)";
    };
    auto base = [&](const char* f, uint8_t v) {
        if (why.empty() && v >= kCpRegs && v != kNoBase)
            why = mn + ": field " + f + " = " + std::to_string(v) +
                  " is not a base (c0..c15, or 128 for an absolute address)";
    };
    auto imm = [&](uint32_t lo, uint32_t hi) {
        if (why.empty() && (x.imm < lo || x.imm > hi))
            why = mn + ": immediate " + std::to_string(x.imm) + " out of range " +
                  std::to_string(lo) + ".." + std::to_string(hi);
    };
    switch (info->format) {
        case Format::None:
            zero("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Rrr:
            pe("rd", x.rd);
            pe("ra", x.ra);
            pe("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Rri8:
            pe("rd", x.rd);
            pe("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 255);
            break;
        case Format::Rr:
            pe("rd", x.rd);
            pe("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Ri8:
            pe("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 255);
            break;
        case Format::Rsh:
            pe("rd", x.rd);
            pe("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 7);
            break;
        case Format::Cmp:
            zero("rd", x.rd);
            pe("ra", x.ra);
            pe("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Cmpi:
            zero("rd", x.rd);
            pe("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 255);
            break;
        case Format::R:
            pe("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Rc:
            pe("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Rck:
            pe("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 3);
            break;
        case Format::Rk:
            pe("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 3);
            break;
        case Format::Ld:
            pe("rd", x.rd);
            zero("ra", x.ra);
            base("rb", x.rb);
            break;
        case Format::Ldx:
            pe("rd", x.rd);
            pe("ra", x.ra);
            if (x.imm & kLdxNoHigh)
                zero("rb", x.rb);
            else
                pe("rb", x.rb);
            zero("imm bits 30..31", x.imm >> 30);
            if (!(x.imm & kLdxUseCp)) zero("imm bits 24..27 (no CP register)", (x.imm >> 24) & 15);
            break;
        case Format::Xfer:
            cp("rd", x.rd);
            cp("ra", x.ra);
            base("rb", x.rb);
            break;
        case Format::Ring:
            pe("rd", x.rd);
            pe("ra", x.ra);
            zero("rb", x.rb);
            imm(1, 65535);
            break;
        case Format::Stat:
            cp("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Ci:
            cp("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            break;
        case Format::Cc:
            cp("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Ccc:
            cp("rd", x.rd);
            cp("ra", x.ra);
            cp("rb", x.rb);
            zero("imm", x.imm);
            break;
        case Format::Cci:
            cp("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            break;
        case Format::Csh:
            cp("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 31);
            break;
        case Format::Cmem:
            cp("rd", x.rd);
            zero("ra", x.ra);
            base("rb", x.rb);
            break;
        case Format::J:
            zero("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            break;
        case Format::Bcc:
            zero("rd", x.rd);
            cp("ra", x.ra);
            cp("rb", x.rb);
            break;
        case Format::B1:
            zero("rd", x.rd);
            cp("ra", x.ra);
            zero("rb", x.rb);
            break;
        case Format::Video:
            if (x.rd > 1) why = mn + ": video port " + std::to_string(x.rd) + " out of range 0..1";
            base("rb", x.rb);
            break;
        case Format::Phase:
            zero("rd", x.rd);
            zero("ra", x.ra);
            zero("rb", x.rb);
            imm(0, 65535);
            break;
    }
    return why;
}

namespace sem {

#define IMAP_SEM_ALU(id) \
    case Op::id:         \
        return alu<Op::id>(a, b, c)
#define IMAP_SEM_CMP(id) \
    case Op::id:         \
        return compare<Op::id>(a, b)

LaneOut alu_lane(Op o, uint8_t a, uint8_t b, uint8_t c) {
    switch (o) {
        IMAP_SEM_ALU(ADD);
        IMAP_SEM_ALU(ADC);
        IMAP_SEM_ALU(SUB);
        IMAP_SEM_ALU(SBC);
        IMAP_SEM_ALU(AND);
        IMAP_SEM_ALU(OR);
        IMAP_SEM_ALU(XOR);
        IMAP_SEM_ALU(MIN);
        IMAP_SEM_ALU(MAX);
        IMAP_SEM_ALU(ADDI);
        IMAP_SEM_ALU(ADCI);
        IMAP_SEM_ALU(SUBI);
        IMAP_SEM_ALU(SBCI);
        IMAP_SEM_ALU(ANDI);
        IMAP_SEM_ALU(ORI);
        IMAP_SEM_ALU(XORI);
        IMAP_SEM_ALU(MINI);
        IMAP_SEM_ALU(MAXI);
        IMAP_SEM_ALU(SHLI);
        IMAP_SEM_ALU(SHRI);
        IMAP_SEM_ALU(ROLC);
        IMAP_SEM_ALU(RORC);
        IMAP_SEM_ALU(SHLV);
        IMAP_SEM_ALU(SHRV);
        default:
            return {a, c};
    }
}

uint8_t compare_lane(Op o, uint8_t a, uint8_t b) {
    switch (o) {
        IMAP_SEM_CMP(CEQ);
        IMAP_SEM_CMP(CNE);
        IMAP_SEM_CMP(CLTU);
        IMAP_SEM_CMP(CLEU);
        IMAP_SEM_CMP(CGTU);
        IMAP_SEM_CMP(CGEU);
        IMAP_SEM_CMP(CEQI);
        IMAP_SEM_CMP(CNEI);
        IMAP_SEM_CMP(CLTUI);
        IMAP_SEM_CMP(CLEUI);
        IMAP_SEM_CMP(CGTUI);
        IMAP_SEM_CMP(CGEUI);
        default:
            return 0;
    }
}

#undef IMAP_SEM_ALU
#undef IMAP_SEM_CMP

}  // namespace sem
}  // namespace imap::isa
