// The assembler's operands and encoding: one instruction line -> a code
// word, through a per-format table of operand kinds (registers, immediates,
// memory operands, branch targets); each value is range-checked into its
// slot of the word now, or at the end of the source for a forward reference.
#include <cstdint>

#include "asm_internal.hpp"

namespace imap::isa::asm_detail {

namespace {

// The range and name of each Slot (in Slot order; Raw64 takes any value).
struct SlotRange {
    int64_t lo, hi;
    const char* what;
};
constexpr SlotRange kSlotRanges[] = {
    {-128, 255, "immediate"},                          // Imm8
    {0, 7, "shift count"},                             // Shift3
    {0, 3, "byte index"},                              // Byte2
    {INT32_MIN, UINT32_MAX, "immediate"},              // Imm32
    {INT32_MIN, INT32_MAX, "offset"},                  // Off32
    {0, UINT32_MAX, "branch target"},                  // Target
    {1, 65535, "hop count"},                           // RingK
    {0, 31, "shift count"},                            // Csh
    {0, 1, "video port"},                              // Port
    {0, 65535, "phase id"},                            // PhaseId
    {kLdxOffsetMin, kLdxOffsetMax, "ldx/stx offset"},  // LdxOff
    {INT64_MIN, INT64_MAX, "word"},                    // Raw64
};
static_assert(sizeof kSlotRanges / sizeof kSlotRanges[0] == static_cast<size_t>(Slot::Raw64) + 1);

// What one source operand of an instruction is and where it goes: a PE or CP
// register into field 1 (rd), 2 (ra) or 3 (rb), an immediate into a slot, a
// memory operand [cB + off] / [ra:rb + cN + off], ext[cA] (into ra), a branch
// target, or the cY, cX pair of vin/vout (packed into ra).
enum class Kind : uint8_t { Pe, Cp, Imm, Mem, MemX, Ext, Target, VideoY, VideoX };
struct Operand {
    Kind kind;
    uint8_t field = 0;
    Slot slot = Slot::Imm8;
};
constexpr Operand pe(uint8_t f) {
    return {Kind::Pe, f};
}
constexpr Operand cp(uint8_t f) {
    return {Kind::Cp, f};
}
constexpr Operand im(Slot s) {
    return {Kind::Imm, 0, s};
}
constexpr Operand kMem{Kind::Mem}, kMemX{Kind::MemX}, kExt{Kind::Ext}, kTarget{Kind::Target};

// The source operands of each format, in source order (in Format order).
struct FormatOperands {
    Format format;
    int count;
    Operand ops[4];
};
constexpr FormatOperands kFormatOperands[] = {
    {Format::None, 0, {}},
    {Format::Rrr, 3, {pe(1), pe(2), pe(3)}},
    {Format::Rri8, 3, {pe(1), pe(2), im(Slot::Imm8)}},
    {Format::Rr, 2, {pe(1), pe(2)}},
    {Format::Ri8, 2, {pe(1), im(Slot::Imm8)}},
    {Format::Rsh, 3, {pe(1), pe(2), im(Slot::Shift3)}},
    {Format::Cmp, 2, {pe(2), pe(3)}},
    {Format::Cmpi, 2, {pe(2), im(Slot::Imm8)}},
    {Format::R, 1, {pe(1)}},
    {Format::Rc, 2, {pe(1), cp(2)}},
    {Format::Rck, 3, {pe(1), cp(2), im(Slot::Byte2)}},
    {Format::Rk, 2, {pe(1), im(Slot::Byte2)}},
    {Format::Ld, 2, {pe(1), kMem}},
    {Format::Ldx, 2, {pe(1), kMemX}},
    {Format::Xfer, 3, {kMem, kExt, cp(1)}},
    {Format::Ring, 3, {pe(1), pe(2), im(Slot::RingK)}},
    {Format::Stat, 1, {cp(1)}},
    {Format::Ci, 2, {cp(1), im(Slot::Imm32)}},
    {Format::Cc, 2, {cp(1), cp(2)}},
    {Format::Ccc, 3, {cp(1), cp(2), cp(3)}},
    {Format::Cci, 3, {cp(1), cp(2), im(Slot::Imm32)}},
    {Format::Csh, 3, {cp(1), cp(2), im(Slot::Csh)}},
    {Format::Cmem, 2, {cp(1), kMem}},
    {Format::J, 1, {kTarget}},
    {Format::Bcc, 3, {cp(2), cp(3), kTarget}},
    {Format::B1, 2, {cp(2), kTarget}},
    {Format::Video, 4, {im(Slot::Port), kMem, {Kind::VideoY, 2}, {Kind::VideoX, 2}}},
    {Format::Phase, 1, {im(Slot::PhaseId)}},
};
static_assert(one_row_per_format(kFormatOperands),
              "kFormatOperands: one row per Format, in Format order");

std::vector<Range> split_operands(const std::vector<Token>& t, size_t b) {
    std::vector<Range> out;
    if (b >= t.size()) return out;
    int depth = 0;
    size_t start = b;
    for (size_t i = b; i < t.size(); ++i) {
        if (t[i].is("[") || t[i].is("("))
            ++depth;
        else if (t[i].is("]") || t[i].is(")"))
            --depth;
        else if (t[i].is(",") && depth == 0) {
            out.push_back({start, i});
            start = i + 1;
        }
    }
    out.push_back({start, t.size()});
    return out;
}

}  // namespace

size_t Assembler::emit(const Line& L, const Word& w) {
    if (code_.size() >= (1u << 24)) {
        error(L, 1, "program too large (16777216 instructions)");
        throw Stop{};
    }
    code_.push_back(w.encode());
    map_.push_back({static_cast<uint32_t>(L.file), static_cast<uint32_t>(L.line)});
    return code_.size() - 1;
}

// Stores `v` into the slot of instruction `idx`; returns "" or a range error.
std::string Assembler::apply(size_t idx, Slot s, int64_t v) {
    if (s == Slot::Raw64) {
        code_[idx] = static_cast<uint64_t>(v);
        return "";
    }
    const SlotRange& r = kSlotRanges[static_cast<size_t>(s)];
    if (v < r.lo || v > r.hi)
        return std::string(r.what) + " " + std::to_string(v) + " out of range " +
               std::to_string(r.lo) + ".." + std::to_string(r.hi);
    Word w = Word::decode(code_[idx]);
    if (s == Slot::Imm8)
        w.imm = static_cast<uint32_t>(v & 0xff);
    else if (s == Slot::Port)
        w.rd = static_cast<uint8_t>(v);
    else if (s == Slot::LdxOff)
        w.imm = (w.imm & ~kLdxOffsetMask) | (static_cast<uint32_t>(v) & kLdxOffsetMask);
    else
        w.imm = static_cast<uint32_t>(v);
    code_[idx] = w.encode();
    return "";
}

// Evaluates tokens r (as "0 <r>" when `offset`) into a slot, now or at the end.
void Assembler::value(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx,
                      bool offset) {
    std::vector<Token> ex;
    if (offset) ex.push_back({Tok::Number, "0", 0, t[r.b].col});
    ex.insert(ex.end(), t.begin() + static_cast<std::ptrdiff_t>(r.b),
              t.begin() + static_cast<std::ptrdiff_t>(r.e));
    const Lookup look = [this](const std::string& n) { return lookup(n); };
    try {
        Expr e(ex, 0, ex.size(), look);
        const int64_t v = e.parse_all();
        if (e.undef) {
            // Forward reference: freeze the symbols known now, finish at the end.
            for (Token& tk : ex)
                if (tk.kind == Tok::Ident)
                    if (auto x = lookup(tk.text)) tk = {Tok::Number, tk.text, *x, tk.col};
            fixups_.push_back({idx, s, std::move(ex), L, t[r.b].col});
            return;
        }
        const std::string err = apply(idx, s, v);
        if (!err.empty()) error(L, t[r.b].col, err);
    } catch (const ExprError& x) {
        error(L, x.col, x.msg);
    }
}

void Assembler::resolve_fixups() {
    const Lookup look = [this](const std::string& n) { return lookup(n); };
    for (const Fixup& f : fixups_) {
        try {
            Expr e(f.expr, 0, f.expr.size(), look);
            const int64_t v = e.parse_all();
            if (e.undef) {
                error(f.line, e.undef_col, "undefined symbol '" + e.undef_name + "'");
                continue;
            }
            const std::string err = apply(f.index, f.slot, v);
            if (!err.empty()) error(f.line, f.col, err);
        } catch (const ExprError& x) {
            error(f.line, x.col, x.msg);
        }
    }
}

bool Assembler::reg_token(const Line& L, const Token& tk, bool* cp, uint8_t* r) {
    if (tk.kind == Tok::Ident) {
        auto a = regs_.find(tk.text);
        if (a != regs_.end()) {
            *cp = a->second.first;
            *r = a->second.second;
            return true;
        }
        char kind;
        long num;
        if (register_like(tk.text, &kind, &num)) {
            *cp = kind == 'c';
            const long max = *cp ? kCpRegs - 1 : kMaxPeRegs - 1;
            if (num > max) {
                error(L, tk.col,
                      "no register '" + tk.text + "' (" + (*cp ? "c0..c15" : "r0..r63") + ")");
                return false;
            }
            *r = static_cast<uint8_t>(num);
            return true;
        }
    }
    error(L, tk.col, "expected a register, got '" + tk.text + "'");
    return false;
}

bool Assembler::reg(const Line& L, const std::vector<Token>& t, Range r, bool want_cp,
                    uint8_t* out) {
    if (r.empty()) return false;
    const char* what = want_cp ? "a CP register (c0..c15)" : "a PE register (r0..r63)";
    if (r.e - r.b != 1 || t[r.b].kind != Tok::Ident) {
        error(L, t[r.b].col, std::string("expected ") + what);
        return false;
    }
    bool cp;
    if (!reg_token(L, t[r.b], &cp, out)) return false;
    if (cp != want_cp) {
        error(L, t[r.b].col, std::string("expected ") + what + ", got '" + t[r.b].text + "'");
        return false;
    }
    return true;
}

void Assembler::imm(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx) {
    if (!t[r.b].is("#")) {
        error(L, t[r.b].col, "expected '#' before an immediate value");
        return;
    }
    if (r.e - r.b < 2) {
        error(L, t[r.b].col + 1, "expected a value after '#'");
        return;
    }
    value(L, t, {r.b + 1, r.e}, s, idx);
}

void Assembler::target(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
    if (t[r.b].is("#")) {
        error(L, t[r.b].col, "branch target is a label or expression, without '#'");
        return;
    }
    value(L, t, r, Slot::Target, idx);
}

bool Assembler::brackets(const Line& L, const std::vector<Token>& t, Range r, Range* in) {
    if (t[r.b].is("[") && !t[r.e - 1].is("]")) {
        error(L, t[r.e - 1].col + static_cast<int>(t[r.e - 1].text.size()),
              "missing ']' at the end of the memory operand");
        return false;
    }
    if (!t[r.b].is("[") || r.e - r.b < 2) {
        error(L, t[r.b].col, "expected a memory operand '[...]'");
        return false;
    }
    *in = {r.b + 1, r.e - 1};
    if (in->empty()) {
        error(L, t[r.b].col, "empty memory operand");
        return false;
    }
    return true;
}

// [cB], [cB + expr], [cB - expr] or [#expr]: base into rb, offset into imm.
void Assembler::mem(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
    Range in;
    if (!brackets(L, t, r, &in)) return;
    if (t[in.b].is("#")) {
        if (in.e - in.b < 2) {
            error(L, t[in.b].col + 1, "expected an address after '#'");
            return;
        }
        set_field(idx, 3, kNoBase);
        value(L, t, {in.b + 1, in.e}, Slot::Off32, idx);
        return;
    }
    bool cp = false;
    uint8_t b = 0;
    if (t[in.b].kind != Tok::Ident || !reg_token(L, t[in.b], &cp, &b)) {
        if (t[in.b].kind != Tok::Ident)
            error(L, t[in.b].col, "expected a CP base register [cN + offset] or [#address]");
        return;
    }
    if (!cp) {
        error(L, t[in.b].col,
              "the base of a broadcast address is a CP register (c0..c15), got '" + t[in.b].text +
                  "' (per-PE addresses: ldx/stx)");
        return;
    }
    set_field(idx, 3, b);
    if (in.b + 1 == in.e) return;
    if (!t[in.b + 1].is("+") && !t[in.b + 1].is("-")) {
        error(L, t[in.b + 1].col, "expected '+' or '-' after the base register");
        return;
    }
    value(L, t, {in.b + 1, in.e}, Slot::Off32, idx, true);
}

// [ra], [ra:rb], optionally "+ cN", then an optional +/- offset.
void Assembler::memx(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
    Range in;
    if (!brackets(L, t, r, &in)) return;
    size_t k = in.b;
    uint8_t lo = 0, hi = 0;
    if (!reg(L, t, {k, k + 1}, false, &lo)) return;
    ++k;
    uint32_t flags = kLdxNoHigh;
    if (k < in.e && t[k].is(":")) {
        if (k + 1 >= in.e) {
            error(L, t[k].col + 1, "expected the high-byte register after ':'");
            return;
        }
        if (!reg(L, t, {k + 1, k + 2}, false, &hi)) return;
        flags = 0;
        k += 2;
    }
    if (k + 1 < in.e && t[k].is("+") && t[k + 1].kind == Tok::Ident) {
        bool cp;
        uint8_t c;
        const bool is_reg = regs_.count(t[k + 1].text) || [&] {
            char kk;
            long nn;
            return register_like(t[k + 1].text, &kk, &nn);
        }();
        if (is_reg) {
            if (!reg_token(L, t[k + 1], &cp, &c)) return;
            if (!cp) {
                error(L, t[k + 1].col,
                      "expected a CP register after '+', got '" + t[k + 1].text + "'");
                return;
            }
            flags |= kLdxUseCp | (uint32_t{c} << kLdxCpShift);
            k += 2;
        }
    }
    Word w = Word::decode(code_[idx]);
    w.ra = lo;
    w.rb = hi;
    w.imm = flags;
    code_[idx] = w.encode();
    if (k == in.e) return;
    if (!t[k].is("+") && !t[k].is("-")) {
        error(L, t[k].col, "expected '+' or '-' before the offset");
        return;
    }
    value(L, t, {k, in.e}, Slot::LdxOff, idx, true);
}

// ext[cN]: the external address register of xld/xst, into ra.
void Assembler::ext(const Line& L, const std::vector<Token>& t, Range e, size_t idx) {
    uint8_t x = 0;
    if (e.e - e.b == 4 && t[e.b].kind == Tok::Ident && lower(t[e.b].text) == "ext" &&
        t[e.b + 1].is("[") && t[e.b + 3].is("]")) {
        if (reg(L, t, {e.b + 2, e.b + 3}, true, &x)) set_field(idx, 2, x);
    } else {
        error(L, t[e.b].col, "expected an external address ext[cN]");
    }
}

void Assembler::set_field(size_t idx, int field, uint8_t v) {
    Word w = Word::decode(code_[idx]);
    if (field == 1)
        w.rd = v;
    else if (field == 2)
        w.ra = v;
    else
        w.rb = v;
    code_[idx] = w.encode();
}

void Assembler::instruction(const Line& L, const OpInfo& info, const std::vector<Token>& t,
                            size_t k) {
    const std::vector<Range> ops = split_operands(t, k + 1);
    const FormatOperands& layout = kFormatOperands[static_cast<size_t>(info.format)];
    const int want = layout.count;
    const std::string mn(info.mnemonic);
    if (static_cast<int>(ops.size()) != want) {
        const std::string syn = operand_syntax(info.format);
        error(L, t[k].col,
              mn + " expects " + std::to_string(want) + " operand(s)" +
                  (syn.empty() ? "" : " (" + mn + " " + syn + ")") + ", got " +
                  std::to_string(ops.size()));
        return;
    }
    for (const Range& r : ops)
        if (r.empty()) {
            error(L, r.b < t.size() ? t[r.b].col : t.back().col, "empty operand");
            return;
        }
    const size_t idx = emit(L, Word{static_cast<uint8_t>(info.op)});
    uint8_t x = 0;
    bool low_ok = false;  // the cY of a video operand pair was a register
    uint8_t low = 0;
    for (int i = 0; i < want; ++i) {
        const Operand& o = layout.ops[i];
        const Range& r = ops[static_cast<size_t>(i)];
        switch (o.kind) {
            case Kind::Pe: {
                const OpInfo* imm_form = op_by_name(mn + "i");
                if (t[r.b].is("#") && imm_form != nullptr) {
                    // an immediate where the register form wants a register
                    error(L, t[r.b].col,
                          "expected a PE register (r0..r63), got an immediate: for an immediate "
                          "operand use " +
                              mn + "i (" + mn + "i " + operand_syntax(imm_form->format) + ")");
                    break;
                }
                if (reg(L, t, r, false, &x)) set_field(idx, o.field, x);
                break;
            }
            case Kind::Cp:
                if (reg(L, t, r, true, &x)) set_field(idx, o.field, x);
                break;
            case Kind::Imm:
                imm(L, t, r, o.slot, idx);
                break;
            case Kind::Mem:
                mem(L, t, r, idx);
                break;
            case Kind::MemX:
                memx(L, t, r, idx);
                break;
            case Kind::Ext:
                ext(L, t, r, idx);
                break;
            case Kind::Target:
                target(L, t, r, idx);
                break;
            case Kind::VideoY:
                low_ok = reg(L, t, r, true, &low);
                break;
            case Kind::VideoX:
                if (low_ok && reg(L, t, r, true, &x))
                    set_field(idx, o.field, static_cast<uint8_t>(low | (x << 4)));
                break;
        }
    }
}

}  // namespace imap::isa::asm_detail
