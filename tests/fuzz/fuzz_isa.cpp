#include "fuzz_isa.hpp"

#include <algorithm>
#include <cctype>
#include <new>
#include <set>
#include <typeinfo>

#include "imap/isa/isa.hpp"

namespace imap::fuzz {

namespace {

// ---------------------------------------------------------------------------
// Running a program on a small machine

isa::MachineConfig small_config() {
    isa::MachineConfig c;
    c.pes = 4;
    c.mem_bytes = 64;
    c.ext_bytes = 64;
    c.watchdog_cycles = 20000;
    return c;
}

// The part of a LoadError / Fault message after its location prefix
// ("... word 0x...: " / "... cycle N: "), so that outcome classes do not
// depend on file names.
std::string after(const std::string& s, const std::string& marker) {
    const size_t m = s.find(marker);
    if (m == std::string::npos) return s;
    const size_t c = s.find(": ", m);
    return c == std::string::npos ? s : s.substr(c + 2);
}

struct RunOutcome {
    std::string what;
    uint64_t cycles = 0;
    uint32_t pc = 0;
    std::string multiline;  // a LoadError / Fault message on several lines
};

std::string if_multiline(const char* what) {
    return std::string(what).find('\n') == std::string::npos ? "" : what;
}

// Loads and runs `p` on a fresh small machine with 8x4 video images. Any
// exception other than LoadError (at load) and Fault (while running) is a
// violation and propagates.
RunOutcome run_small(const isa::Program& p) {
    isa::Machine m(small_config());
    isa::ImageVideoPort video;
    for (int k = 0; k < 2; ++k) {
        video.input[k].width = 8;
        video.input[k].height = 4;
        video.input[k].pixels.assign(32, static_cast<uint8_t>(17 * k + 3));
        video.make_output(k, 8, 4);
    }
    m.set_video(&video);
    try {
        m.load(p);
    } catch (const isa::LoadError& e) {
        return {signature("LoadError", after(e.what(), "word 0x")), 0, e.pc(),
                if_multiline(e.what())};
    }
    try {
        m.run();
        return {"halt", m.cycles(), m.pc(), ""};
    } catch (const isa::Fault& f) {
        return {signature("Fault", after(f.what(), ", cycle ")), f.cycle(), f.pc(),
                if_multiline(f.what())};
    }
}

// Shared by both targets: disassembly re-assembles to the same program,
// and two runs on fresh machines agree. Returns the run outcome, or sets
// *violation.
std::string round_trip_and_run(const isa::Program& p, std::string* violation) {
    std::string dis;
    try {
        dis = isa::disassemble(p);
    } catch (const std::exception& e) {
        *violation = std::string("disassemble threw: ") + e.what();
        return "disassemble threw";
    }
    isa::Program q;
    try {
        q = isa::assemble_string(dis, "disasm.s");
    } catch (const isa::AsmError& e) {
        *violation = "the disassembly does not re-assemble: " + e.diagnostics().front().str();
        return "round trip failed";
    }
    if (q.code != p.code) {
        size_t pc = 0;
        while (pc < p.code.size() && pc < q.code.size() && p.code[pc] == q.code[pc]) ++pc;
        *violation = "re-assembled code differs from the original at pc " + std::to_string(pc) +
                     " (" + std::to_string(p.code.size()) + " vs " + std::to_string(q.code.size()) +
                     " words)";
        return "round trip failed";
    }
    // Phase names come back when they are usable names (docs/isa.md §7).
    bool names_ok = !p.phases.empty() && p.phases[0] == "default";
    std::set<std::string> seen;
    for (const std::string& s : p.phases) {
        bool ok = !s.empty() &&
                  (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_' || s[0] == '$');
        for (char c : s)
            ok = ok &&
                 (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$');
        std::string l;
        for (char c : s) l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const bool reg = l.size() > 1 && (l[0] == 'r' || l[0] == 'c') &&
                         std::all_of(l.begin() + 1, l.end(), [](char c) {
                             return std::isdigit(static_cast<unsigned char>(c));
                         });
        names_ok = names_ok && ok && !reg && l != "ext" && seen.insert(s).second;
    }
    if (names_ok && q.phases != p.phases) {
        *violation = "re-assembled phase table differs (" + std::to_string(p.phases.size()) +
                     " vs " + std::to_string(q.phases.size()) + " phases)";
        return "round trip failed";
    }
    const RunOutcome a = run_small(p);
    const RunOutcome b = run_small(p);
    if (a.what != b.what || a.cycles != b.cycles || a.pc != b.pc) {
        *violation = "two runs of the same program differ: '" + a.what + "' at cycle " +
                     std::to_string(a.cycles) + " vs '" + b.what + "' at cycle " +
                     std::to_string(b.cycles);
        return "nondeterministic";
    }
    if (!a.multiline.empty()) *violation = "message on several lines: " + a.multiline;
    if (a.pc > p.code.size()) {
        *violation = "outcome '" + a.what + "' names pc " + std::to_string(a.pc) +
                     " beyond the program (" + std::to_string(p.code.size()) + " words)";
    }
    return a.what;
}

// ---------------------------------------------------------------------------
// Text mutations for the assembler

using Text = std::string;

std::vector<Text> lines_of(const Text& t) {
    std::vector<Text> out;
    size_t b = 0;
    while (b <= t.size()) {
        const size_t e = t.find('\n', b);
        if (e == Text::npos) {
            out.push_back(t.substr(b));
            break;
        }
        out.push_back(t.substr(b, e - b));
        b = e + 1;
    }
    return out;
}

Text join(const std::vector<Text>& v) {
    Text s;
    for (size_t i = 0; i < v.size(); ++i) s += (i ? "\n" : "") + v[i];
    return s;
}

bool word_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$';
}

// [begin, end) of the token around a random position (a word or one char).
std::pair<size_t, size_t> random_token(Rng& rng, const Text& t) {
    if (t.empty()) return {0, 0};
    size_t p = rng.index(t.size());
    if (!word_char(t[p])) return {p, p + 1};
    size_t b = p, e = p;
    while (b > 0 && word_char(t[b - 1])) --b;
    while (e < t.size() && word_char(t[e])) ++e;
    return {b, e};
}

// Positions of every maximal token matching `pred` (on the token text).
template <class Pred>
std::vector<std::pair<size_t, size_t>> tokens_where(const Text& t, Pred pred) {
    std::vector<std::pair<size_t, size_t>> out;
    for (size_t i = 0; i < t.size();) {
        if (!word_char(t[i])) {
            ++i;
            continue;
        }
        size_t e = i;
        while (e < t.size() && word_char(t[e])) ++e;
        if (pred(t.substr(i, e - i))) out.emplace_back(i, e);
        i = e;
    }
    return out;
}

bool is_number(const Text& s) {
    return !s.empty() && std::isdigit(static_cast<unsigned char>(s[0]));
}
bool is_register(const Text& s) {
    if (s.size() < 2 || (std::tolower(static_cast<unsigned char>(s[0])) != 'r' &&
                         std::tolower(static_cast<unsigned char>(s[0])) != 'c'))
        return false;
    return std::all_of(s.begin() + 1, s.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

const std::vector<Text>& dictionary() {
    static const std::vector<Text> d = {
        ".rept 3",
        ".rept 0",
        ".endr",
        ".if 1",
        ".if 0",
        ".if X > 2",
        ".elif 1",
        ".else",
        ".endif",
        ".ifdef X",
        ".ifndef X",
        ".macro M a, b",
        ".macro N",
        ".endm",
        "M r1, r2",
        "M [c1 + 1], (2, 3)",
        "N",
        ".equ X 5",
        ".equ X, 6",
        ".set Y 0",
        ".set Y Y + 1",
        ".reg acc, r3",
        ".reg cnt, c2",
        ".phase p1",
        ".phase default",
        ".defphase p2",
        ".word 0x0000000000000001",
        ".word -1",
        ".word lbl",
        ".error \"stop\"",
        "lbl: nop",
        "lbl:",
        "a: b: c: halt",
        "jmp lbl",
        "call lbl",
        "ret",
        "halt",
        "nop",
        "loop c1, lbl",
        "bz c1, 99999",
        "beq c0, c0, 0",
        "bne c1, c2, lbl + 1",
        "cli c1, #3",
        "cli c15, #-2147483648",
        "caddi c1, c1, #4294967295",
        "cshli c1, c2, #31",
        "add r1, r2, r3",
        "addi r1, r1, #-128",
        "shli r1, r2, #7",
        "ld r0, [c1 + 4]",
        "st r0, [#63]",
        "ld r0, [c2 - 1]",
        "ldx r1, [r2:r3 + c4 - 2]",
        "stx r1, [r2 + 1]",
        "stx r1, [r2 + c1 + 8388607]",
        "xld [c1], ext[c2], c3",
        "xst [#0], ext[c0], c1",
        "rxl r1, r2, #1",
        "rxr r1, r2, #65535",
        "mif",
        "melse",
        "mend",
        "mall",
        "rany c5",
        "rall c6",
        "vin #0, [c1], c2, c3",
        "vout #1, [#0], c2, c3",
        "cld c1, [#255]",
        "cst c1, [c2 + 1]",
        "ceqi r1, #255",
        "cltui r7, #5",
        "pidx r7, #3",
        "lcb r1, c2, #3",
        "lp\\@: nop",
        "\\a",
        "# comment",
        "; comment",
        "",
    };
    return d;
}

const std::vector<Text>& huge_numbers() {
    static const std::vector<Text> n = {"0",
                                        "1",
                                        "-1",
                                        "7",
                                        "8",
                                        "255",
                                        "256",
                                        "-129",
                                        "65535",
                                        "65536",
                                        "1000000",
                                        "1000001",
                                        "8388608",
                                        "16777216",
                                        "2147483647",
                                        "2147483648",
                                        "-2147483649",
                                        "4294967295",
                                        "4294967296",
                                        "9223372036854775807",
                                        "9223372036854775808",
                                        "18446744073709551616",
                                        "99999999999999999999999999",
                                        "0x7fffffffffffffff",
                                        "0xffffffffffffffff",
                                        "0b11111111111111111111111111111111",
                                        "(1 << 63)",
                                        "(1 << 64)",
                                        "(-9223372036854775807 - 1) / -1",
                                        "(-9223372036854775807 - 1) % -1",
                                        "(-9223372036854775807 - 1) * -1",
                                        "-(-9223372036854775807 - 1)",
                                        "1 / 0",
                                        "(0 - 1) >> 63"};
    return n;
}

// Wraps `inner` in `depth` levels of one of several nesting forms.
Text nest(Rng& rng, const Text& inner, size_t depth) {
    Text s;
    switch (rng.below(4)) {
        case 0:
            s.assign(depth, '(');
            s += inner;
            s.append(depth, ')');
            break;
        case 1:
            s.assign(depth, '-');
            s += inner;
            break;
        case 2:
            for (size_t i = 0; i < depth; ++i) s += "~!"[i % 2];
            s += inner;
            break;
        default:
            for (size_t i = 0; i < depth; ++i) s += "(1+";
            s += inner;
            s.append(depth, ')');
            break;
    }
    return s;
}

size_t random_depth(Rng& rng) {
    static const size_t depths[] = {2, 10, 64, 65, 100, 257, 1000, 5000, 40000};
    return depths[rng.index(sizeof depths / sizeof depths[0])];
}

constexpr size_t kMaxText = 200000;

void mutate_text_once(Rng& rng, Text& t, const std::vector<Bytes>& corpus) {
    std::vector<Text> L = lines_of(t);
    auto other_line = [&]() -> Text {
        const Bytes& o = rng.pick(corpus);
        const std::vector<Text> ol = lines_of(Text(o.begin(), o.end()));
        return rng.pick(ol);
    };
    switch (rng.below(15)) {
        case 0: {  // a byte-level edit
            Bytes b(t.begin(), t.end());
            mutate_bytes(rng, b, corpus, kMaxText, 2);
            t.assign(b.begin(), b.end());
            return;
        }
        case 1:  // delete a line
            if (L.size() > 1) L.erase(L.begin() + static_cast<std::ptrdiff_t>(rng.index(L.size())));
            break;
        case 2:  // insert a line of this or another input
            L.insert(L.begin() + static_cast<std::ptrdiff_t>(rng.index(L.size() + 1)),
                     rng.chance(50) ? rng.pick(L) : other_line());
            break;
        case 3:  // insert a dictionary line
            L.insert(L.begin() + static_cast<std::ptrdiff_t>(rng.index(L.size() + 1)),
                     rng.pick(dictionary()));
            break;
        case 4: {  // splice with another input at line boundaries
            const Bytes& o = rng.pick(corpus);
            const std::vector<Text> ol = lines_of(Text(o.begin(), o.end()));
            L.resize(rng.index(L.size() + 1));
            L.insert(L.end(), ol.begin() + static_cast<std::ptrdiff_t>(rng.index(ol.size())),
                     ol.end());
            break;
        }
        case 5: {  // duplicate a token
            const auto [b, e] = random_token(rng, t);
            t.insert(e, (rng.chance(50) ? " " : "") + t.substr(b, e - b));
            return;
        }
        case 6: {  // a number becomes a huge / boundary one
            const auto nums = tokens_where(t, is_number);
            const Text n = rng.pick(huge_numbers());
            if (nums.empty()) {
                t.insert(rng.index(t.size() + 1), n);
            } else {
                const auto [b, e] = rng.pick(nums);
                t.replace(b, e - b, n);
            }
            return;
        }
        case 7: {  // deep expression nesting around a number
            const auto nums = tokens_where(t, is_number);
            if (nums.empty()) return;
            const auto [b, e] = rng.pick(nums);
            t.replace(b, e - b, nest(rng, t.substr(b, e - b), random_depth(rng)));
            return;
        }
        case 8: {  // deep block nesting around a range of lines
            const size_t depth = std::min<size_t>(random_depth(rng), 2000);
            const size_t a = rng.index(L.size() + 1), z = a + rng.index(L.size() - a + 1);
            const int kind = static_cast<int>(rng.below(3));
            std::vector<Text> out(L.begin(), L.begin() + static_cast<std::ptrdiff_t>(a));
            if (kind == 2) {  // a chain of macros, each expanding the previous one
                out.push_back(".macro F0");
                out.insert(out.end(), L.begin() + static_cast<std::ptrdiff_t>(a),
                           L.begin() + static_cast<std::ptrdiff_t>(z));
                out.push_back(".endm");
                for (size_t i = 1; i <= depth; ++i) {
                    out.push_back(".macro F" + std::to_string(i));
                    out.push_back("F" + std::to_string(i - 1));
                    out.push_back(".endm");
                }
                out.push_back("F" + std::to_string(depth));
            } else {
                for (size_t i = 0; i < depth; ++i) out.push_back(kind == 0 ? ".rept 1" : ".if 1");
                out.insert(out.end(), L.begin() + static_cast<std::ptrdiff_t>(a),
                           L.begin() + static_cast<std::ptrdiff_t>(z));
                for (size_t i = 0; i < depth; ++i) out.push_back(kind == 0 ? ".endr" : ".endif");
            }
            out.insert(out.end(), L.begin() + static_cast<std::ptrdiff_t>(z), L.end());
            L.swap(out);
            break;
        }
        case 9: {  // another mnemonic at the start of a line
            if (L.empty()) break;
            Text& l = L[rng.index(L.size())];
            size_t b = 0;
            while (b < l.size() && (l[b] == ' ' || l[b] == '\t')) ++b;
            size_t e = b;
            while (e < l.size() && word_char(l[e])) ++e;
            const auto& ops = isa::all_ops();
            l.replace(b, e - b, std::string(ops[rng.index(ops.size())].mnemonic));
            break;
        }
        case 10: {  // another register number
            const auto regs = tokens_where(t, is_register);
            if (regs.empty()) return;
            static const char* nums[] = {"0", "1", "15", "16", "63", "64", "255", "256", "999999"};
            const auto [b, e] = rng.pick(regs);
            t.replace(b + 1, e - b - 1, nums[rng.index(sizeof nums / sizeof nums[0])]);
            return;
        }
        case 11:  // swap two lines
            if (L.size() > 1) std::swap(L[rng.index(L.size())], L[rng.index(L.size())]);
            break;
        case 12: {  // repeat a block of lines
            if (L.empty()) break;
            const size_t a = rng.index(L.size());
            const size_t len = 1 + rng.index(std::min<size_t>(8, L.size() - a));
            const std::vector<Text> blk(L.begin() + static_cast<std::ptrdiff_t>(a),
                                        L.begin() + static_cast<std::ptrdiff_t>(a + len));
            const size_t times = 1 + rng.index(50);
            for (size_t i = 0; i < times; ++i)
                L.insert(L.begin() + static_cast<std::ptrdiff_t>(a), blk.begin(), blk.end());
            break;
        }
        case 13: {  // a syntax character somewhere
            static const char syn[] = "#[](),:;\"\\.-+~!<>=&|^*/%@\t$";
            t.insert(t.begin() + static_cast<std::ptrdiff_t>(rng.index(t.size() + 1)),
                     syn[rng.index(sizeof syn - 1)]);
            return;
        }
        default: {  // a very long line or name
            const size_t n = std::min<size_t>(random_depth(rng) * 4, 100000);
            Text s = rng.chance(50) ? Text(n, 'a') : ".equ " + Text(n, 'z') + " 1";
            L.insert(L.begin() + static_cast<std::ptrdiff_t>(rng.index(L.size() + 1)), s);
            break;
        }
    }
    t = join(L);
}

// ---------------------------------------------------------------------------
// Program mutations

// FNV-1a as in the file format (docs/isa.md §8), to repair the checksum.
void fix_checksum(Bytes& b) {
    if (b.size() < 4) return;
    uint32_t h = 2166136261u;
    for (size_t i = 0; i + 4 < b.size(); ++i) h = (h ^ b[i]) * 16777619u;
    for (int i = 0; i < 4; ++i)
        b[b.size() - 4 + static_cast<size_t>(i)] = static_cast<uint8_t>(h >> (8 * i));
}

// A random instruction that is valid on the small machine most of the time.
uint64_t random_instruction(Rng& rng, uint32_t n_code) {
    const auto& ops = isa::all_ops();
    const isa::OpInfo& op = ops[rng.index(ops.size())];
    isa::Word w;
    w.op = static_cast<uint8_t>(op.op);
    auto reg = [&] { return static_cast<uint8_t>(rng.below(rng.chance(90) ? 16 : 70)); };
    auto small = [&](uint32_t hi) { return static_cast<uint32_t>(rng.below(hi + 1)); };
    switch (op.format) {
        case isa::Format::None:
            break;
        case isa::Format::Rrr:
            w.rd = reg(), w.ra = reg(), w.rb = reg();
            break;
        case isa::Format::Rri8:
            w.rd = reg(), w.ra = reg(), w.imm = small(255);
            break;
        case isa::Format::Rr:
        case isa::Format::Ring:
            w.rd = reg(), w.ra = reg();
            w.imm = op.format == isa::Format::Ring ? 1 + small(9) : 0;
            break;
        case isa::Format::Ri8:
            w.rd = reg(), w.imm = small(255);
            break;
        case isa::Format::Rsh:
            w.rd = reg(), w.ra = reg(), w.imm = small(7);
            break;
        case isa::Format::Cmp:
            w.ra = reg(), w.rb = reg();
            break;
        case isa::Format::Cmpi:
            w.ra = reg(), w.imm = small(255);
            break;
        case isa::Format::R:
            w.rd = reg();
            break;
        case isa::Format::Rc:
            w.rd = reg(), w.ra = static_cast<uint8_t>(small(15));
            break;
        case isa::Format::Rck:
            w.rd = reg(), w.ra = static_cast<uint8_t>(small(15)), w.imm = small(3);
            break;
        case isa::Format::Rk:
            w.rd = reg(), w.imm = small(3);
            break;
        case isa::Format::Ld:
        case isa::Format::Cmem:
            w.rd = op.format == isa::Format::Ld ? reg() : static_cast<uint8_t>(small(15));
            w.rb = rng.chance(50) ? isa::kNoBase : static_cast<uint8_t>(small(15));
            w.imm = rng.chance(80) ? small(70) : static_cast<uint32_t>(rng.next());
            break;
        case isa::Format::Ldx:
            w.rd = reg(), w.ra = reg();
            w.imm = isa::kLdxNoHigh | small(70);
            if (rng.chance(30)) w.imm |= isa::kLdxUseCp | (small(15) << isa::kLdxCpShift);
            if (rng.chance(30)) w.imm &= ~isa::kLdxNoHigh, w.rb = reg();
            break;
        case isa::Format::Xfer:
            w.rd = static_cast<uint8_t>(small(15)), w.ra = static_cast<uint8_t>(small(15));
            w.rb = rng.chance(50) ? isa::kNoBase : static_cast<uint8_t>(small(15));
            w.imm = small(70);
            break;
        case isa::Format::Stat:
        case isa::Format::Ci:
            w.rd = static_cast<uint8_t>(small(15));
            if (op.format == isa::Format::Ci)
                w.imm = rng.chance(70) ? small(80) : static_cast<uint32_t>(rng.next());
            break;
        case isa::Format::Cc:
        case isa::Format::Ccc:
        case isa::Format::Cci:
        case isa::Format::Csh:
            w.rd = static_cast<uint8_t>(small(15)), w.ra = static_cast<uint8_t>(small(15));
            if (op.format == isa::Format::Ccc) w.rb = static_cast<uint8_t>(small(15));
            if (op.format == isa::Format::Cci) w.imm = small(80);
            if (op.format == isa::Format::Csh) w.imm = small(31);
            break;
        case isa::Format::J:
        case isa::Format::Bcc:
        case isa::Format::B1:
            w.ra = op.format == isa::Format::J ? 0 : static_cast<uint8_t>(small(15));
            w.rb = op.format == isa::Format::Bcc ? static_cast<uint8_t>(small(15)) : 0;
            w.imm = small(n_code);
            break;
        case isa::Format::Video:
            w.rd = static_cast<uint8_t>(small(1));
            w.ra = static_cast<uint8_t>(small(255));
            w.rb = rng.chance(50) ? isa::kNoBase : static_cast<uint8_t>(small(15));
            w.imm = small(70);
            break;
        case isa::Format::Phase:
            w.imm = small(4);
            break;
    }
    return w.encode();
}

const std::vector<std::string>& odd_strings() {
    static const std::vector<std::string> s = {
        "",     "default", "main", "a b",      "x\nhalt", "semi;colon", "r5",     "ext", ".dot",
        "halt", "L3",      "L3_",  "\xff\xfe", "name$1",  "with\"q",    "tab\tx", "lbl", "9lives"};
    return s;
}

void mutate_program_struct(Rng& rng, isa::Program& p) {
    const uint32_t n = static_cast<uint32_t>(p.code.size());
    const int steps = 1 + static_cast<int>(rng.below(3));
    for (int s = 0; s < steps; ++s) {
        switch (rng.below(12)) {
            case 0:
            case 1:
            case 2:  // replace a word by a random instruction
                if (!p.code.empty()) p.code[rng.index(p.code.size())] = random_instruction(rng, n);
                break;
            case 3: {  // insert a random instruction
                const size_t at = rng.index(p.code.size() + 1);
                p.code.insert(p.code.begin() + static_cast<std::ptrdiff_t>(at),
                              random_instruction(rng, n + 1));
                if (!p.source_map.empty())
                    p.source_map.insert(p.source_map.begin() + static_cast<std::ptrdiff_t>(at),
                                        isa::SourceLoc{0, static_cast<uint32_t>(rng.below(100))});
                break;
            }
            case 4:  // delete a word
                if (!p.code.empty()) {
                    const size_t at = rng.index(p.code.size());
                    p.code.erase(p.code.begin() + static_cast<std::ptrdiff_t>(at));
                    if (at < p.source_map.size())
                        p.source_map.erase(p.source_map.begin() + static_cast<std::ptrdiff_t>(at));
                }
                break;
            case 5: {  // one field of a word
                if (p.code.empty()) break;
                uint64_t& w = p.code[rng.index(p.code.size())];
                const int byte = static_cast<int>(rng.below(8));
                const uint64_t v = rng.chance(50) ? rng.below(256) : rng.below(20);
                w = (w & ~(uint64_t{0xff} << (8 * byte))) | (v << (8 * byte));
                break;
            }
            case 6:  // a phase name
                if (rng.chance(50) || p.phases.empty())
                    p.phases.push_back(rng.pick(odd_strings()));
                else
                    p.phases[rng.index(p.phases.size())] = rng.pick(odd_strings());
                break;
            case 7:  // a symbol
                p.symbols[rng.pick(odd_strings()) + (rng.chance(50) ? "" : std::to_string(s))] =
                    static_cast<uint32_t>(rng.below(n + 2));
                break;
            case 8:  // a source file name
                if (!p.files.empty()) p.files[rng.index(p.files.size())] = rng.pick(odd_strings());
                break;
            case 9:  // a source map entry
                if (!p.source_map.empty()) {
                    isa::SourceLoc& l = p.source_map[rng.index(p.source_map.size())];
                    l.line = static_cast<uint32_t>(rng.chance(50) ? rng.below(3) : rng.next());
                    l.file = static_cast<uint32_t>(rng.below(p.files.size() + 1));
                }
                break;
            case 10:  // drop the source map
                p.source_map.clear();
                p.files.clear();
                break;
            default: {  // a fresh short program
                p.code.clear();
                p.source_map.clear();
                p.files.clear();
                const uint32_t len = 1 + static_cast<uint32_t>(rng.below(24));
                for (uint32_t i = 0; i < len; ++i) p.code.push_back(random_instruction(rng, len));
                p.code.push_back(isa::Word{static_cast<uint8_t>(isa::Op::HALT)}.encode());
                break;
            }
        }
    }
}

}  // namespace

Result check_asm(const Bytes& in) {
    const std::string text(in.begin(), in.end());
    isa::Program p;
    try {
        p = isa::assemble_string(text, "fuzz.s");
    } catch (const isa::AsmError& e) {
        const auto& d = e.diagnostics();
        if (d.empty()) return {"AsmError", "AsmError without diagnostics"};
        for (const isa::Diagnostic& x : d)
            if (x.message.empty() || x.message.find('\n') != std::string::npos)
                return {"AsmError", "diagnostic empty or on several lines: '" + x.str() + "'"};
        // A .error directive reports its own (fuzzed) text: one class.
        const std::vector<Text> lines = lines_of(text);
        const isa::Diagnostic& f = d.front();
        if (f.file == "fuzz.s" && f.line >= 1 && static_cast<size_t>(f.line) <= lines.size()) {
            Text l = lines[static_cast<size_t>(f.line) - 1];
            for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            if (l.find(".error") != Text::npos) return {"AsmError: .error directive", ""};
        }
        return {signature("AsmError", f.message), ""};
    } catch (const std::bad_alloc&) {
        return {"bad_alloc", "assemble_string threw std::bad_alloc"};
    } catch (const std::exception& e) {
        return {"other exception",
                std::string("assemble_string threw ") + typeid(e).name() + ": " + e.what()};
    }
    if (p.source_map.size() != p.code.size())
        return {"assembled", "source map has " + std::to_string(p.source_map.size()) +
                                 " entries for " + std::to_string(p.code.size()) + " words"};
    std::string violation;
    const std::string run = round_trip_and_run(p, &violation);
    return {"assembled, " + run, violation};
}

void mutate_asm(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    Text t(b.begin(), b.end());
    const int steps = 1 + static_cast<int>(rng.below(3));
    for (int i = 0; i < steps; ++i) mutate_text_once(rng, t, corpus);
    if (t.size() > kMaxText) t.resize(kMaxText);
    b.assign(t.begin(), t.end());
}

Result check_program(const Bytes& bytes) {
    isa::Program p;
    try {
        p = isa::deserialize(bytes, "fuzz.bin");
    } catch (const isa::FormatError& e) {
        const std::string w = e.what();
        if (w.find('\n') != std::string::npos)
            return {"FormatError", "FormatError message on several lines: " + w};
        return {signature("FormatError", after(w, "bad program file")), ""};
    } catch (const std::bad_alloc&) {
        return {"bad_alloc", "deserialize threw std::bad_alloc"};
    } catch (const std::exception& e) {
        return {"other exception",
                std::string("deserialize threw ") + typeid(e).name() + ": " + e.what()};
    }
    // Serializing the parsed program gives a file that parses to the same tables.
    try {
        const isa::Program q = isa::deserialize(isa::serialize(p), "again.bin");
        if (q.code != p.code || q.phases != p.phases || q.symbols != p.symbols)
            return {"parsed", "serialize(deserialize(file)) does not parse to the same program"};
    } catch (const std::exception& e) {
        return {"parsed", std::string("serialize(deserialize(file)) is rejected: ") + e.what()};
    }
    std::string violation;
    const std::string run = round_trip_and_run(p, &violation);
    return {"parsed, " + run, violation};
}

void mutate_program(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    const uint64_t how = rng.below(10);
    if (how < 4) {  // bytes, checksum repaired
        mutate_bytes(rng, b, corpus, 1 << 20, 4);
        fix_checksum(b);
    } else if (how < 9) {  // structured
        isa::Program p;
        try {
            p = isa::deserialize(b, "m.bin");
        } catch (const isa::FormatError&) {
            try {
                p = isa::deserialize(rng.pick(corpus), "seed.bin");
            } catch (const isa::FormatError&) {
                p.code = {isa::Word{static_cast<uint8_t>(isa::Op::HALT)}.encode()};
                p.phases = {"default"};
            }
        }
        mutate_program_struct(rng, p);
        b = isa::serialize(p, rng.chance(80));
        if (rng.chance(20)) {  // and a byte edit in the header or the tables
            mutate_bytes(rng, b, corpus, 1 << 20, 1);
            fix_checksum(b);
        }
    } else {  // bytes, checksum left as it is
        mutate_bytes(rng, b, corpus, 1 << 20, 4);
    }
}

}  // namespace imap::fuzz
