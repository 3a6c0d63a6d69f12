// Assembler: encodings, expressions, directives, macros, includes, -D,
// diagnostics with exact file:line:col, and asm -> disasm -> asm round trips.
#define BOOST_TEST_MODULE isa_assembler
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <random>

#include "helpers.hpp"

using namespace isatest;
namespace fs = std::filesystem;

namespace {

uint64_t one(const std::string& src) {
    const Program p = assemble_string(src, "one.s");
    BOOST_REQUIRE_EQUAL(p.code.size(), 1u);
    return p.code[0];
}

// All diagnostics of a failing assembly, one per line.
std::string errors(const std::string& src, const AsmOptions& opt = {}) {
    try {
        assemble_string(src, "e.s", opt);
    } catch (const AsmError& e) {
        return e.what();
    }
    return "assembled";
}

struct TempDir {
    fs::path dir;
    TempDir() {
        std::random_device rd;
        dir = fs::temp_directory_path() / ("imap_isa_test_" + std::to_string(rd()));
        fs::create_directories(dir);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path p = dir / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }
};

uint32_t cp_after(const std::string& src, int reg, const AsmOptions& opt = {}) {
    Machine m(small());
    m.load(assemble_string(src, "r.s", opt));
    m.run();
    return m.cp(reg);
}

}  // namespace

BOOST_AUTO_TEST_CASE(encodings) {
    BOOST_CHECK_EQUAL(one("add r1, r2, r3"), 0x03020140ull);
    BOOST_CHECK_EQUAL(one("ADD R1, R2, R3"), 0x03020140ull);
    BOOST_CHECK_EQUAL(one("li r5, #-1"), 0x000000FF00000561ull);
    BOOST_CHECK_EQUAL(one("cli c1, #-2"), 0xFFFFFFFE00000108ull);
    BOOST_CHECK_EQUAL(one("ld r1, [c2 - 4]"), 0xFFFFFFFC02000190ull);
    BOOST_CHECK_EQUAL(one("st r7, [#7]"), 0x0000000780000791ull);
    BOOST_CHECK_EQUAL(one("ldx r1, [r2:r3 + c4 + 5]"), 0x1400000503020192ull);
    BOOST_CHECK_EQUAL(one("ldx r1, [r2 - 1]"), 0x20FFFFFF00020192ull);
    BOOST_CHECK_EQUAL(one("xld [c3 + 1], ext[c1], c2"), 0x0000000103010294ull);
    BOOST_CHECK_EQUAL(one("vin #1, [c4 + 3], c2, c3"), 0x00000003043201C0ull);
    BOOST_CHECK_EQUAL(one("rxl r1, r0, #300"), 0x0000012C000001A0ull);
    BOOST_CHECK_EQUAL(one("beq c1, c2, 0"), 0x0000000002010021ull);
    BOOST_CHECK_EQUAL(one("ceqi r4, #9"), 0x0000000900040088ull);
    BOOST_CHECK_EQUAL(one("mif"), 0xB0ull);
    BOOST_CHECK_EQUAL(one(".word 0x123456789"), 0x123456789ull);
}

BOOST_AUTO_TEST_CASE(expressions_and_constants) {
    const std::string src = R"(
        .equ X (1 + 2) * 3 << 1     ; 18
        .equ Y, 1 + 2 * 3           ; 7
        .equ Z -7 / 2               ; -3
        .equ W 1 << 4 | 1           ; 17
        .equ Q 10 > 3 && 2 == 2     ; 1
        .equ H 0xFF & ~0x0F         ; 0xF0
        .equ B 0b101 % 3            ; 2
        cli c0, #X
        cli c1, #Y
        cli c2, #Z
        cli c3, #W
        cli c4, #Q
        cli c5, #H
        cli c6, #B
        cli c7, #end - start        ; forward labels
    start:
        nop
        nop
    end:
        halt)";
    Machine m(small());
    m.load(assemble_string(src));
    m.run();
    BOOST_CHECK_EQUAL(m.cp(0), 18u);
    BOOST_CHECK_EQUAL(m.cp(1), 7u);
    BOOST_CHECK_EQUAL(m.cp(2), static_cast<uint32_t>(-3));
    BOOST_CHECK_EQUAL(m.cp(3), 17u);
    BOOST_CHECK_EQUAL(m.cp(4), 1u);
    BOOST_CHECK_EQUAL(m.cp(5), 0xF0u);
    BOOST_CHECK_EQUAL(m.cp(6), 2u);
    BOOST_CHECK_EQUAL(m.cp(7), 2u);
    const Program p = assemble_string(src);
    BOOST_CHECK_EQUAL(p.symbols.at("start"), 8u);
    BOOST_CHECK_EQUAL(p.symbols.count("X"), 0u);  // only labels are in the symbol table
}

BOOST_AUTO_TEST_CASE(comments) {
    const Program p = assemble_string(
        "# a full-line comment\n"
        "   # indented\n"
        "li r1, #5 # trailing\n"
        "li r2, #6 ; trailing\n"
        "li r3, #7;tight\n"
        "; nothing\n");
    BOOST_REQUIRE_EQUAL(p.code.size(), 3u);
    BOOST_CHECK_EQUAL(Word::decode(p.code[2]).imm, 7u);
}

BOOST_AUTO_TEST_CASE(conditionals_and_defines) {
    const std::string src = R"(
        .ifndef N
        .equ N 64
        .endif
        .if N > 100
          cli c0, #1
        .elif N > 50
          cli c0, #2
        .else
          cli c0, #3
        .endif
        .ifdef N
          cli c1, #N
        .endif
        .if 0
          this line is never assembled ###
          .if 1
          .else
          .endif
        .endif
        halt)";
    BOOST_CHECK_EQUAL(cp_after(src, 0), 2u);
    BOOST_CHECK_EQUAL(cp_after(src, 1), 64u);
    AsmOptions opt;
    opt.defines["N"] = 128;
    BOOST_CHECK_EQUAL(cp_after(src, 0, opt), 1u);
    BOOST_CHECK_EQUAL(cp_after(src, 1, opt), 128u);
    opt.defines["N"] = 10;
    BOOST_CHECK_EQUAL(cp_after(src, 0, opt), 3u);
    // -D and an unconditional .equ of the same name disagree.
    opt.defines["N"] = 128;
    BOOST_CHECK_EQUAL(errors(".equ N 64\nhalt", opt),
                      "e.s:1:6: error: symbol 'N' already defined (-D N=128)");
    BOOST_CHECK_EQUAL(errors(".equ N 128\nhalt", opt), "assembled");
}

BOOST_AUTO_TEST_CASE(parse_define_values) {
    BOOST_CHECK(parse_define("N=128") == std::make_pair(std::string("N"), int64_t{128}));
    BOOST_CHECK(parse_define("km=0x10") == std::make_pair(std::string("km"), int64_t{16}));
    BOOST_CHECK(parse_define("D=2*3+1") == std::make_pair(std::string("D"), int64_t{7}));
    BOOST_CHECK(parse_define("FLAG") == std::make_pair(std::string("FLAG"), int64_t{1}));
    BOOST_CHECK(parse_define("W=-5") == std::make_pair(std::string("W"), int64_t{-5}));
    BOOST_CHECK_THROW(parse_define("1N=3"), std::invalid_argument);
    BOOST_CHECK_THROW(parse_define("r1=3"), std::invalid_argument);
    BOOST_CHECK_THROW(parse_define("N=abc"), std::invalid_argument);
    BOOST_CHECK_THROW(parse_define("N="), std::invalid_argument);
    BOOST_CHECK_THROW(parse_define("N=1/0"), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(rept_set_and_register_aliases) {
    Machine m(small());
    m.load(assemble_string(R"(
        .reg acc, r5
        .reg count, c3
        .set i 0
        .rept 4
          addi acc, acc, #i
          .set i i + 1
        .endr
        .rept 0
          garbage that is never seen
        .endr
        cli count, #i
        halt)"));
    m.run();
    BOOST_CHECK_EQUAL(m.reg(0, 5), 6);
    BOOST_CHECK_EQUAL(m.cp(3), 4u);
    BOOST_CHECK_EQUAL(m.program().code.size(), 6u);
}

BOOST_AUTO_TEST_CASE(macros_with_parameters_and_unique_labels) {
    const Program p = assemble_string(R"(
        .macro count_down reg, n
          cli \reg, #\n
        lp\@:
          loop \reg, lp\@
        .endm
        .macro add16 dl, dh, sl, sh
          add \dl, \dl, \sl
          adc \dh, \dh, \sh
        .endm
        .macro twice_add16 a, b
          add16 \a, r1, \b, r3
          add16 \a, r1, \b, r3
        .endm
        count_down c1, 3
        count_down c2, 2
        twice_add16 r0, r2
        halt)",
                                      "m.s");
    BOOST_CHECK_EQUAL(p.code.size(), 9u);
    BOOST_CHECK_EQUAL(p.symbols.size(), 2u);
    BOOST_CHECK_EQUAL(p.symbols.at("lp1"), 1u);
    BOOST_CHECK_EQUAL(p.symbols.at("lp2"), 3u);
    // The source map points into the macro body.
    BOOST_CHECK_EQUAL(p.location(1), "m.s:5");
    BOOST_CHECK_EQUAL(p.location(4), "m.s:8");
    Machine m(small());
    m.load(p);
    m.set_reg(0, 0, 0xF0);
    m.set_reg(0, 2, 0x20);
    m.run();
    BOOST_CHECK_EQUAL(m.reg(0, 0), 0x30);  // 0xF0 + 2 * 0x20 = 0x130
    BOOST_CHECK_EQUAL(m.reg(0, 1), 1);
    BOOST_CHECK_EQUAL(m.cycles(), 2u + 3 + 2 + 2 + 1 + 4 + 1);
}

BOOST_AUTO_TEST_CASE(includes_are_relative_to_the_including_file) {
    TempDir t;
    const std::string main =
        t.write("fw/main.s", ".include \"lib/a.s\"\n  cli c0, #A + B\n  halt\n");
    t.write("fw/lib/a.s", ".equ A 5\n.include \"b.s\"\n  nop\n");
    t.write("fw/lib/b.s", ".equ B 6\n");
    const Program p = assemble_file(main);
    BOOST_REQUIRE_EQUAL(p.code.size(), 3u);
    BOOST_CHECK_EQUAL(Word::decode(p.code[1]).imm, 11u);
    BOOST_CHECK_EQUAL(p.location(0), main.substr(0, main.size() - 6) + "lib/a.s:3");
    BOOST_CHECK_EQUAL(p.location(1), main + ":2");

    const std::string bad = t.write("x/main.s", "nop\n.include \"inc.s\"\n");
    const std::string inc = t.write("x/inc.s", "nop\nbogus r1\n");
    try {
        assemble_file(bad);
        BOOST_FAIL("expected errors");
    } catch (const AsmError& e) {
        BOOST_CHECK_EQUAL(e.what(), inc + ":2:1: error: unknown instruction 'bogus'");
    }
    const std::string missing = t.write("y/main.s", "\n  .include \"nope.s\"\n");
    try {
        assemble_file(missing);
        BOOST_FAIL("expected errors");
    } catch (const AsmError& e) {
        BOOST_CHECK_EQUAL(e.diagnostics().at(0).line, 2);
        BOOST_CHECK_EQUAL(e.diagnostics().at(0).col, 12);
        BOOST_CHECK(std::string(e.what()).find("cannot open include file") != std::string::npos);
    }
    const std::string rec = t.write("z/main.s", ".include \"main.s\"\n");
    BOOST_CHECK_THROW(assemble_file(rec), AsmError);
    BOOST_CHECK_THROW(assemble_file((t.dir / "absent.s").string()), AsmError);
}

BOOST_AUTO_TEST_CASE(diagnostics_have_exact_positions) {
    BOOST_CHECK_EQUAL(errors("  add r1, r2\n"),
                      "e.s:1:3: error: add expects 3 operand(s) (add rd, ra, rb), got 2");
    BOOST_CHECK_EQUAL(errors("nop\n  frob r1\n"), "e.s:2:3: error: unknown instruction 'frob'");
    BOOST_CHECK_EQUAL(errors("li r1, #300"),
                      "e.s:1:9: error: immediate 300 out of range -128..255");
    BOOST_CHECK_EQUAL(errors("jmp nowhere"), "e.s:1:5: error: undefined symbol 'nowhere'");
    BOOST_CHECK_EQUAL(errors("add r1, r64, r2"), "e.s:1:9: error: no register 'r64' (r0..r63)");
    BOOST_CHECK_EQUAL(errors("add r1, c2, r2"),
                      "e.s:1:9: error: expected a PE register (r0..r63), got 'c2'");
    // an immediate on a register form names the immediate form
    BOOST_CHECK_EQUAL(errors("add r1, r2, #1"),
                      "e.s:1:13: error: expected a PE register (r0..r63), got an immediate: for "
                      "an immediate operand use addi (addi rd, ra, #imm8)");
    // a memory operand without its closing bracket says so
    BOOST_CHECK_EQUAL(errors("ld r1, [c1 + 4"),
                      "e.s:1:15: error: missing ']' at the end of the memory operand");
    BOOST_CHECK_EQUAL(errors("ld r1, c1"), "e.s:1:8: error: expected a memory operand '[...]'");
    BOOST_CHECK_EQUAL(errors(".if 1\nnop\n"), "e.s:1:1: error: unterminated .if (missing .endif)");
    BOOST_CHECK_EQUAL(errors("nop\n.endif\n"), "e.s:2:1: error: .endif without .if");
    BOOST_CHECK_EQUAL(errors("li r1, @5"), "e.s:1:8: error: unexpected character '@'");
    BOOST_CHECK_EQUAL(errors("a: nop\na: nop"),
                      "e.s:2:1: error: symbol 'a' already defined (label at e.s:1)");
    BOOST_CHECK_EQUAL(errors("li r1, 5"), "e.s:1:8: error: expected '#' before an immediate value");
    BOOST_CHECK_EQUAL(errors("shli r1, r1, #8"),
                      "e.s:1:15: error: shift count 8 out of range 0..7");
    BOOST_CHECK_EQUAL(errors("rxl r1, r1, #0"),
                      "e.s:1:14: error: hop count 0 out of range 1..65535");
    BOOST_CHECK_EQUAL(errors(".equ A 1 / 0"), "e.s:1:10: error: division by zero");
    BOOST_CHECK_EQUAL(errors("cli c0, #(1 + 2"), "e.s:1:16: error: missing ')'");
    BOOST_CHECK_EQUAL(errors("ld r1, [r2]"),
                      "e.s:1:9: error: the base of a broadcast address is a CP register (c0..c15), "
                      "got 'r2' (per-PE addresses: ldx/stx)");
    BOOST_CHECK_EQUAL(errors("xld [c1], c2, c3"),
                      "e.s:1:11: error: expected an external address ext[cN]");
    BOOST_CHECK_EQUAL(errors("loop: nop\nr1: nop"),
                      "e.s:2:1: error: invalid label: 'r1' is a register name");
    BOOST_CHECK_EQUAL(errors("  .bogus 3"), "e.s:1:3: error: unknown directive '.bogus'");
    BOOST_CHECK_EQUAL(errors("jmp #4"),
                      "e.s:1:5: error: branch target is a label or expression, without '#'");
    BOOST_CHECK_EQUAL(errors(".rept 2\nnop\n"),
                      "e.s:1:1: error: unterminated .rept (missing .endr)");

    // Errors inside a macro expansion point at the body line and name the call.
    BOOST_CHECK_EQUAL(errors(".macro twice x\n  add \\x, \\x\n.endm\n  twice r1\n"),
                      "e.s:2:3: error: add expects 3 operand(s) (add rd, ra, rb), got 2 (in macro "
                      "'twice' expanded at e.s:4)");
    BOOST_CHECK_EQUAL(errors(".macro m a, b\n.endm\n  m r1\n"),
                      "e.s:3:3: error: macro 'm' expects 2 argument(s) (a, b), got 1");

    // .error under a condition: the firmware refuses a parameter set.
    AsmOptions opt;
    opt.defines["D"] = 100;
    BOOST_CHECK_EQUAL(
        errors(".if D > 64\n    .error \"D = 100 exceeds 64 levels\"\n.endif\nhalt", opt),
        "e.s:2:5: error: D = 100 exceeds 64 levels");
}

BOOST_AUTO_TEST_CASE(errors_are_collected_and_capped) {
    BOOST_CHECK_EQUAL(errors("frob\nadd r1\nli r1, #999\nhalt"),
                      "e.s:1:1: error: unknown instruction 'frob'\n"
                      "e.s:2:1: error: add expects 3 operand(s) (add rd, ra, rb), got 1\n"
                      "e.s:3:9: error: immediate 999 out of range -128..255");
    std::string many;
    for (int i = 0; i < 30; ++i) many += "frob\n";
    try {
        assemble_string(many, "e.s");
        BOOST_FAIL("expected errors");
    } catch (const AsmError& e) {
        BOOST_REQUIRE_EQUAL(e.diagnostics().size(), 21u);
        BOOST_CHECK_EQUAL(e.diagnostics().back().str(),
                          "e.s:20:1: error: too many errors (20), stopping");
    }
}

namespace {

// A random word that passes check_word, for every format.
uint64_t random_word(const OpInfo& i, std::mt19937& g) {
    auto pe = [&] { return static_cast<uint8_t>(g() % 64); };
    auto cp = [&] { return static_cast<uint8_t>(g() % 16); };
    auto base = [&] { return g() % 4 == 0 ? kNoBase : cp(); };
    auto u32 = [&] { return static_cast<uint32_t>(g()); };
    Word w;
    w.op = static_cast<uint8_t>(i.op);
    switch (i.format) {
        case Format::None:
            break;
        case Format::Rrr:
            w.rd = pe();
            w.ra = pe();
            w.rb = pe();
            break;
        case Format::Rri8:
            w.rd = pe();
            w.ra = pe();
            w.imm = g() % 256;
            break;
        case Format::Rr:
            w.rd = pe();
            w.ra = pe();
            break;
        case Format::Ri8:
            w.rd = pe();
            w.imm = g() % 256;
            break;
        case Format::Rsh:
            w.rd = pe();
            w.ra = pe();
            w.imm = g() % 8;
            break;
        case Format::Cmp:
            w.ra = pe();
            w.rb = pe();
            break;
        case Format::Cmpi:
            w.ra = pe();
            w.imm = g() % 256;
            break;
        case Format::R:
            w.rd = pe();
            break;
        case Format::Rc:
            w.rd = pe();
            w.ra = cp();
            break;
        case Format::Rck:
            w.rd = pe();
            w.ra = cp();
            w.imm = g() % 4;
            break;
        case Format::Rk:
            w.rd = pe();
            w.imm = g() % 4;
            break;
        case Format::Ld:
            w.rd = pe();
            w.rb = base();
            w.imm = u32();
            break;
        case Format::Ldx:
            w.rd = pe();
            w.ra = pe();
            w.imm = u32() & kLdxOffsetMask;
            if (g() % 2)
                w.imm |= kLdxNoHigh;
            else
                w.rb = pe();
            if (g() % 2) w.imm |= kLdxUseCp | uint32_t{cp()} << kLdxCpShift;
            break;
        case Format::Xfer:
            w.rd = cp();
            w.ra = cp();
            w.rb = base();
            w.imm = u32();
            break;
        case Format::Ring:
            w.rd = pe();
            w.ra = pe();
            w.imm = 1 + g() % 65535;
            break;
        case Format::Stat:
            w.rd = cp();
            break;
        case Format::Ci:
            w.rd = cp();
            w.imm = u32();
            break;
        case Format::Cc:
            w.rd = cp();
            w.ra = cp();
            break;
        case Format::Ccc:
            w.rd = cp();
            w.ra = cp();
            w.rb = cp();
            break;
        case Format::Cci:
            w.rd = cp();
            w.ra = cp();
            w.imm = u32();
            break;
        case Format::Csh:
            w.rd = cp();
            w.ra = cp();
            w.imm = g() % 32;
            break;
        case Format::Cmem:
            w.rd = cp();
            w.rb = base();
            w.imm = u32();
            break;
        case Format::J:
            w.imm = g() % 3 ? g() % 40 : u32();
            break;
        case Format::Bcc:
            w.ra = cp();
            w.rb = cp();
            w.imm = g() % 3 ? g() % 40 : u32();
            break;
        case Format::B1:
            w.ra = cp();
            w.imm = g() % 3 ? g() % 40 : u32();
            break;
        case Format::Video:
            w.rd = g() % 2;
            w.ra = static_cast<uint8_t>(g());
            w.rb = base();
            w.imm = u32();
            break;
        case Format::Phase:
            w.imm = g() % 3 ? 0 : g() % 65536;
            break;
    }
    return w.encode();
}

}  // namespace

BOOST_AUTO_TEST_CASE(round_trip_every_opcode_and_random_words) {
    std::mt19937 g(42);
    Program p;
    p.phases = {"default"};
    // Every opcode with all-zero-ish operands first, then random valid words.
    for (const OpInfo& i : all_ops()) {
        for (int k = 0; k < 40; ++k) {
            const uint64_t w = random_word(i, g);
            BOOST_REQUIRE_MESSAGE(check_word(w).empty(), i.mnemonic << ": " << check_word(w));
            p.code.push_back(w);
        }
    }
    const std::string text = disassemble(p);
    const Program q = assemble_string(text, "disasm.s");
    BOOST_REQUIRE_EQUAL(q.code.size(), p.code.size());
    for (size_t k = 0; k < p.code.size(); ++k)
        BOOST_REQUIRE_MESSAGE(q.code[k] == p.code[k],
                              "pc " << k << ": " << disassemble_word(p.code[k]));
    // Without comments, too; and single words.
    DisasmOptions plain;
    plain.comments = false;
    BOOST_CHECK(assemble_string(disassemble(p, plain)).code == p.code);
    for (size_t k = 0; k < p.code.size(); k += 7) {
        const Word w = Word::decode(p.code[k]);
        const Format f = op_info(w.op)->format;
        if (f == Format::J || f == Format::Bcc || f == Format::B1) continue;  // labels
        BOOST_CHECK_EQUAL(one(disassemble_word(p.code[k])), p.code[k]);
    }
}

BOOST_AUTO_TEST_CASE(round_trip_program_with_labels_phases_and_bad_words) {
    const Program p = assemble_string(R"(
        .phase io
        cli c0, #4
    top:
        .phase compute
        add r1, r1, r2
        loop c0, top
        call f
        .phase io
        .word 0xFFFF
        halt
    f:  ret
    end:
    )");
    const std::string text = disassemble(p);
    BOOST_CHECK(text.find(".phase compute") != std::string::npos);
    BOOST_CHECK(text.find("loop c0, top") != std::string::npos);
    BOOST_CHECK(text.find(".word 0x000000000000ffff") != std::string::npos);
    const Program q = assemble_string(text);
    BOOST_CHECK(q.code == p.code);
    BOOST_CHECK(q.phases == p.phases);
    BOOST_CHECK(q.symbols == p.symbols);
    BOOST_CHECK_THROW(disassemble_word(0xFFFF), std::invalid_argument);
    BOOST_CHECK_EQUAL(disassemble_word(one("ldx r1, [r2:r3 + c4 - 5]")),
                      "ldx r1, [r2:r3 + c4 - 5]");
    BOOST_CHECK_EQUAL(disassemble_word(one("vout #0, [#12], c1, c2")), "vout #0, [#12], c1, c2");
}

BOOST_AUTO_TEST_CASE(runaway_expansion_is_an_error) {
    const std::string e = errors(".rept 1000000\n.rept 1000000\n.endr\n.endr\n");
    BOOST_CHECK_MESSAGE(e.find("runaway .rept or macro") != std::string::npos, e);
    const std::string m = errors(".macro m\n  m\n.endm\n  m\n");
    BOOST_CHECK_MESSAGE(m.find("nesting too deep") != std::string::npos, m);
}

// Robustness: random token soup only ever yields a program or an AsmError.
BOOST_AUTO_TEST_CASE(garbage_source_never_crashes) {
    static const char* soup[] = {"add",
                                 "r1",
                                 "r99",
                                 "c3",
                                 ",",
                                 "[",
                                 "]",
                                 "#",
                                 "#5",
                                 ":",
                                 "(",
                                 ")",
                                 "1",
                                 "<<",
                                 "ext",
                                 "\"x",
                                 "\"s\"",
                                 ".if",
                                 ".endif",
                                 ".else",
                                 ".rept",
                                 ".endr",
                                 ".macro",
                                 ".endm",
                                 "\\a",
                                 "\\@",
                                 "m",
                                 "lbl:",
                                 "lbl",
                                 "+",
                                 "-",
                                 "/",
                                 "0",
                                 ".equ",
                                 ".set",
                                 "X",
                                 "ldx",
                                 "ld",
                                 "jmp",
                                 "xld",
                                 "vin",
                                 ";",
                                 " # c",
                                 ".include",
                                 ".phase",
                                 "0x",
                                 "99999999999999999999",
                                 "~",
                                 "!",
                                 "==",
                                 ".word",
                                 "loop"};
    std::mt19937 g(3);
    int ok = 0, failed = 0;
    for (int n = 0; n < 400; ++n) {
        std::string src;
        for (int l = 0; l < 8; ++l) {
            const int k = static_cast<int>(g() % 7);
            for (int t = 0; t < k; ++t) src += std::string(soup[g() % std::size(soup)]) + " ";
            src += "\n";
        }
        try {
            assemble_string(src, "g.s");
            ++ok;
        } catch (const AsmError& e) {
            ++failed;
            BOOST_REQUIRE(!e.diagnostics().empty());
            for (const Diagnostic& d : e.diagnostics()) BOOST_REQUIRE(!d.message.empty());
        }
    }
    BOOST_CHECK_GT(failed, 0);
}

// Robustness: random valid programs either fail to load (LoadError) or run to
// a halt, a cycle limit or a Fault -- never anything undefined.
BOOST_AUTO_TEST_CASE(random_programs_load_or_fault_cleanly) {
    std::mt19937 g(11);
    MachineConfig cfg = small(5);
    cfg.mem_bytes = 64;
    cfg.ext_bytes = 32;
    cfg.pe_regs = 64;
    cfg.watchdog_cycles = 5000;
    const std::vector<OpInfo>& ops = all_ops();
    int loaded = 0, faulted = 0, halted = 0;
    for (int n = 0; n < 300; ++n) {
        Program p;
        p.phases = {"default"};
        for (int k = 0; k < 24; ++k) p.code.push_back(random_word(ops[g() % ops.size()], g));
        p.code.push_back(Word{static_cast<uint8_t>(Op::HALT)}.encode());
        Machine m(cfg);
        try {
            m.load(p);
        } catch (const LoadError& e) {
            BOOST_REQUIRE(e.pc() < p.code.size());
            continue;
        }
        ++loaded;
        for (int r = 0; r < 64; ++r)
            for (int pe = 0; pe < 5; ++pe) m.set_reg(pe, r, static_cast<uint8_t>(g()));
        for (int c = 0; c < 16; ++c) m.set_cp(c, g() % 4 ? g() % 40 : static_cast<uint32_t>(g()));
        try {
            if (m.run(100000).status == RunStatus::Halted) ++halted;
        } catch (const Fault& f) {
            ++faulted;
            BOOST_REQUIRE(f.pc() < p.code.size() + 1);
        }
    }
    BOOST_TEST_MESSAGE("loaded " << loaded << ", halted " << halted << ", faulted " << faulted);
    BOOST_CHECK_GT(loaded, 0);
    BOOST_CHECK_GT(faulted, 0);
}
