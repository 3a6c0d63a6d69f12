// The opcode table, the per-format rules (operand syntax, static word
// validation: which fields are registers, bases or zero, immediate ranges)
// and the run-time lane dispatchers.
#include <array>
#include <string>
#include <utility>

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

namespace {

// How check_word validates a register field of a format.
enum class Field : uint8_t {
    Zero,     // unused: must be 0
    Pe,       // r0..r63
    Cp,       // c0..c15
    Base,     // c0..c15, or kNoBase for an absolute address
    Any,      // not checked (vin/vout ra: cY | cX << 4)
    LdxHigh,  // ldx/stx rb: r0..r63, or 0 when the imm flags say no high byte
    Port,     // video port 0..1
};
// How check_word validates the imm field of a format.
enum class Imm : uint8_t {
    Zero,      // unused: must be 0
    Any,       // 32-bit value, offset or target
    Range,     // lo..hi
    LdxFlags,  // ldx/stx offset and flags
};

// Each format's operand syntax (docs, messages) and the static rules of its
// fields, in Format order.
struct FormatRules {
    Format format;
    const char* syntax;
    Field rd, ra, rb;
    Imm imm;
    uint32_t lo = 0, hi = 0;
};
using F = Field;
constexpr FormatRules kFormats[] = {
    {Format::None, "", F::Zero, F::Zero, F::Zero, Imm::Zero},
    {Format::Rrr, "rd, ra, rb", F::Pe, F::Pe, F::Pe, Imm::Zero},
    {Format::Rri8, "rd, ra, #imm8", F::Pe, F::Pe, F::Zero, Imm::Range, 0, 255},
    {Format::Rr, "rd, ra", F::Pe, F::Pe, F::Zero, Imm::Zero},
    {Format::Ri8, "rd, #imm8", F::Pe, F::Zero, F::Zero, Imm::Range, 0, 255},
    {Format::Rsh, "rd, ra, #n", F::Pe, F::Pe, F::Zero, Imm::Range, 0, 7},
    {Format::Cmp, "ra, rb", F::Zero, F::Pe, F::Pe, Imm::Zero},
    {Format::Cmpi, "ra, #imm8", F::Zero, F::Pe, F::Zero, Imm::Range, 0, 255},
    {Format::R, "rd", F::Pe, F::Zero, F::Zero, Imm::Zero},
    {Format::Rc, "rd, cA", F::Pe, F::Cp, F::Zero, Imm::Zero},
    {Format::Rck, "rd, cA, #k", F::Pe, F::Cp, F::Zero, Imm::Range, 0, 3},
    {Format::Rk, "rd, #k", F::Pe, F::Zero, F::Zero, Imm::Range, 0, 3},
    {Format::Ld, "rd, [cB + off]", F::Pe, F::Zero, F::Base, Imm::Any},
    {Format::Ldx, "rd, [ra:rb + cN + off]", F::Pe, F::Pe, F::LdxHigh, Imm::LdxFlags},
    {Format::Xfer, "[cB + off], ext[cA], cD", F::Cp, F::Cp, F::Base, Imm::Any},
    {Format::Ring, "rd, ra, #k", F::Pe, F::Pe, F::Zero, Imm::Range, 1, 65535},
    {Format::Stat, "cD", F::Cp, F::Zero, F::Zero, Imm::Zero},
    {Format::Ci, "cD, #imm32", F::Cp, F::Zero, F::Zero, Imm::Any},
    {Format::Cc, "cD, cA", F::Cp, F::Cp, F::Zero, Imm::Zero},
    {Format::Ccc, "cD, cA, cB", F::Cp, F::Cp, F::Cp, Imm::Zero},
    {Format::Cci, "cD, cA, #imm32", F::Cp, F::Cp, F::Zero, Imm::Any},
    {Format::Csh, "cD, cA, #n", F::Cp, F::Cp, F::Zero, Imm::Range, 0, 31},
    {Format::Cmem, "cD, [cB + off]", F::Cp, F::Zero, F::Base, Imm::Any},
    {Format::J, "target", F::Zero, F::Zero, F::Zero, Imm::Any},
    {Format::Bcc, "cA, cB, target", F::Zero, F::Cp, F::Cp, Imm::Any},
    {Format::B1, "cA, target", F::Zero, F::Cp, F::Zero, Imm::Any},
    {Format::Video, "#port, [cB + off], cY, cX", F::Port, F::Any, F::Base, Imm::Any},
    {Format::Phase, "#id", F::Zero, F::Zero, F::Zero, Imm::Range, 0, 65535},
};
static_assert(one_row_per_format(kFormats), "kFormats: one row per Format, in Format order");

const FormatRules& rules(Format f) {
    return kFormats[static_cast<size_t>(f)];
}

// The first rule a word breaks ("" when none), in field order rd, ra, rb, imm.
class WordCheck {
  public:
    WordCheck(const Word& x, std::string mn) : x_(x), mn_(std::move(mn)) {}

    std::string run(const FormatRules& r) {
        field("rd", x_.rd, r.rd);
        field("ra", x_.ra, r.ra);
        field("rb", x_.rb, r.rb);
        if (r.imm == Imm::Zero) {
            zero("imm", x_.imm);
        } else if (r.imm == Imm::Range) {
            if (why_.empty() && (x_.imm < r.lo || x_.imm > r.hi))
                why_ = mn_ + ": immediate " + std::to_string(x_.imm) + " out of range " +
                       std::to_string(r.lo) + ".." + std::to_string(r.hi);
        } else if (r.imm == Imm::LdxFlags) {
            zero("imm bits 30..31", x_.imm >> 30);
            if (!(x_.imm & kLdxUseCp))
                zero("imm bits 24..27 (no CP register)", (x_.imm >> 24) & 15);
        }
        return why_;
    }

  private:
    void zero(const char* f, uint32_t v) {
        if (why_.empty() && v != 0)
            why_ = mn_ + ": unused field " + f + " must be 0 (is " + std::to_string(v) + ")";
    }
    void field(const char* f, uint8_t v, Field use) {
        if (!why_.empty()) return;
        switch (use) {
            case Field::Zero:
                zero(f, v);
                break;
            case Field::LdxHigh:
                field(f, v, (x_.imm & kLdxNoHigh) ? Field::Zero : Field::Pe);
                break;
            case Field::Pe:
                if (v >= kMaxPeRegs)
                    not_a(f, v, "a PE register (r0..r" + std::to_string(kMaxPeRegs - 1) + ")");
                break;
            case Field::Cp:
                if (v >= kCpRegs) not_a(f, v, "a CP register (c0..c15)");
                break;
            case Field::Base:
                if (v >= kCpRegs && v != kNoBase)
                    not_a(f, v, "a base (c0..c15, or 128 for an absolute address)");
                break;
            case Field::Port:
                if (v > 1) why_ = mn_ + ": video port " + std::to_string(v) + " out of range 0..1";
                break;
            case Field::Any:
                break;
        }
    }
    void not_a(const char* f, uint8_t v, const std::string& what) {
        why_ = mn_ + ": field " + f + " = " + std::to_string(v) + " is not " + what;
    }

    const Word x_;
    const std::string mn_;
    std::string why_;
};

}  // namespace

const char* operand_syntax(Format f) {
    return rules(f).syntax;
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
    return WordCheck(x, std::string(info->mnemonic)).run(rules(info->format));
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
