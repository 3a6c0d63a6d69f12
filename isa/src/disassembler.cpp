// The disassembler: Program -> assembler text that re-assembles to the same
// code words (labels for branch targets, .phase names when available).
#include <cctype>
#include <cinttypes>
#include <cstdio>
#include <functional>
#include <set>
#include <stdexcept>

#include "imap/isa/assembler.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"

namespace imap::isa {

namespace {

bool valid_name(const std::string& s) {
    if (s.empty()) return false;
    if (!(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_' || s[0] == '$'))
        return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$'))
            return false;
    std::string l;
    for (char c : s) l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (l == "ext") return false;
    if ((l[0] == 'r' || l[0] == 'c') && l.size() > 1) {
        bool digits = true;
        for (size_t i = 1; i < l.size(); ++i)
            digits = digits && std::isdigit(static_cast<unsigned char>(l[i]));
        if (digits) return false;
    }
    return true;
}

std::string r(unsigned n) {
    return "r" + std::to_string(n);
}
std::string c(unsigned n) {
    return "c" + std::to_string(n);
}
std::string offset_suffix(int64_t off) {
    if (off > 0) return " + " + std::to_string(off);
    if (off < 0) return " - " + std::to_string(-off);
    return "";
}
std::string mem(uint8_t base, uint32_t imm) {
    const int64_t off = as_signed(imm);
    if (base == kNoBase) return "[#" + std::to_string(off) + "]";
    return "[" + c(base) + offset_suffix(off) + "]";
}

using Namer = std::function<std::string(uint32_t)>;

std::string format(uint64_t word, const Namer& target) {
    const Word x = Word::decode(word);
    const OpInfo& info = *op_info(x.op);
    const std::string mn(info.mnemonic);
    const std::string i8 = "#" + std::to_string(x.imm);
    const std::string i32 = "#" + std::to_string(as_signed(x.imm));
    std::string o;
    switch (info.format) {
        case Format::None:
            break;
        case Format::Rrr:
            o = r(x.rd) + ", " + r(x.ra) + ", " + r(x.rb);
            break;
        case Format::Rri8:
        case Format::Rsh:
        case Format::Ring:
            o = r(x.rd) + ", " + r(x.ra) + ", " + i8;
            break;
        case Format::Rr:
            o = r(x.rd) + ", " + r(x.ra);
            break;
        case Format::Ri8:
        case Format::Rk:
            o = r(x.rd) + ", " + i8;
            break;
        case Format::Cmp:
            o = r(x.ra) + ", " + r(x.rb);
            break;
        case Format::Cmpi:
            o = r(x.ra) + ", " + i8;
            break;
        case Format::R:
            o = r(x.rd);
            break;
        case Format::Rc:
            o = r(x.rd) + ", " + c(x.ra);
            break;
        case Format::Rck:
            o = r(x.rd) + ", " + c(x.ra) + ", " + i8;
            break;
        case Format::Ld:
            o = r(x.rd) + ", " + mem(x.rb, x.imm);
            break;
        case Format::Ldx: {
            o = r(x.rd) + ", [" + r(x.ra);
            if (!(x.imm & kLdxNoHigh)) o += ":" + r(x.rb);
            if (x.imm & kLdxUseCp) o += " + " + c((x.imm >> kLdxCpShift) & 15u);
            o += offset_suffix(ldx_offset(x.imm)) + "]";
            break;
        }
        case Format::Xfer:
            o = mem(x.rb, x.imm) + ", ext[" + c(x.ra) + "], " + c(x.rd);
            break;
        case Format::Stat:
            o = c(x.rd);
            break;
        case Format::Ci:
            o = c(x.rd) + ", " + i32;
            break;
        case Format::Cc:
            o = c(x.rd) + ", " + c(x.ra);
            break;
        case Format::Ccc:
            o = c(x.rd) + ", " + c(x.ra) + ", " + c(x.rb);
            break;
        case Format::Cci:
            o = c(x.rd) + ", " + c(x.ra) + ", " + i32;
            break;
        case Format::Csh:
            o = c(x.rd) + ", " + c(x.ra) + ", " + i8;
            break;
        case Format::Cmem:
            o = c(x.rd) + ", " + mem(x.rb, x.imm);
            break;
        case Format::J:
            o = target(x.imm);
            break;
        case Format::Bcc:
            o = c(x.ra) + ", " + c(x.rb) + ", " + target(x.imm);
            break;
        case Format::B1:
            o = c(x.ra) + ", " + target(x.imm);
            break;
        case Format::Video:
            o = "#" + std::to_string(x.rd) + ", " + mem(x.rb, x.imm) + ", " + c(x.ra & 15u) + ", " +
                c(x.ra >> 4);
            break;
        case Format::Phase:
            o = i8;
            break;
    }
    return o.empty() ? mn : mn + " " + o;
}

std::string hex_word(uint64_t w) {
    char b[32];
    // Numbers in the assembler are signed 64-bit: a word with the top bit set
    // is written as the complement of one without it.
    if (w >> 63)
        std::snprintf(b, sizeof b, ".word ~0x%016" PRIx64, ~w);
    else
        std::snprintf(b, sizeof b, ".word 0x%016" PRIx64, w);
    return b;
}

}  // namespace

std::string disassemble_word(uint64_t w) {
    const std::string why = check_word(w);
    if (!why.empty()) throw std::invalid_argument("invalid instruction word: " + why);
    return format(w, [](uint32_t t) { return std::to_string(t); });
}

std::string disassemble(const Program& p, const DisasmOptions& opt) {
    const uint32_t n = static_cast<uint32_t>(p.code.size());
    // Labels: the program's own (valid names), plus L<pc> for other targets.
    std::map<uint32_t, std::vector<std::string>> at;
    std::set<std::string> used;
    for (const auto& [name, pc] : p.symbols)
        if (valid_name(name) && pc <= n) {
            at[pc].push_back(name);
            used.insert(name);
        }
    for (uint32_t pc = 0; pc < n; ++pc) {
        const uint64_t w = p.code[pc];
        if (!check_word(w).empty()) continue;
        const Word x = Word::decode(w);
        const Format f = op_info(x.op)->format;
        if (f != Format::J && f != Format::Bcc && f != Format::B1) continue;
        if (x.imm > n || at.count(x.imm)) continue;
        std::string name = "L" + std::to_string(x.imm);
        while (used.count(name)) name += "_";
        used.insert(name);
        at[x.imm].push_back(name);
    }
    const Namer target = [&](uint32_t t) {
        auto it = at.find(t);
        return it != at.end() ? it->second.front() : std::to_string(t);
    };
    // Phase names are usable when they re-create the same ids.
    bool names_ok = !p.phases.empty() && p.phases[0] == "default";
    {
        std::set<std::string> seen;
        for (const std::string& s : p.phases)
            names_ok = names_ok && valid_name(s) && seen.insert(s).second;
    }

    std::string out = "; IMAP-VISION program: " + std::to_string(n) + " instructions, " +
                      std::to_string(p.phases.size()) + " phases\n";
    if (names_ok)
        for (size_t i = 1; i < p.phases.size(); ++i) out += ".defphase " + p.phases[i] + "\n";
    for (uint32_t pc = 0; pc <= n; ++pc) {
        auto it = at.find(pc);
        if (it != at.end())
            for (const std::string& l : it->second) out += l + ":\n";
        if (pc == n) break;
        const uint64_t w = p.code[pc];
        std::string text;
        if (!check_word(w).empty()) {
            text = hex_word(w);
        } else {
            const Word x = Word::decode(w);
            if (x.op == static_cast<uint8_t>(Op::PHASE) && names_ok && x.imm < p.phases.size())
                text = ".phase " + p.phases[x.imm];
            else
                text = format(w, target);
        }
        std::string line = "        " + text;
        if (opt.comments) {
            if (line.size() < 48)
                line.resize(48, ' ');
            else
                line += ' ';
            line += "; " + std::to_string(pc);
            const std::string loc = p.location(pc);
            if (!loc.empty()) line += "  " + loc;
        }
        out += line + "\n";
    }
    return out;
}

}  // namespace imap::isa
