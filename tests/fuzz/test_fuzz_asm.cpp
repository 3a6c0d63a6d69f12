// Fuzzing the assembler (docs/testing.md): mutants of corpus/asm/*.s must
// assemble or fail with AsmError, and what assembles must round-trip
// through the disassembler and run on a small machine.
#define BOOST_TEST_MODULE fuzz_asm
#include "fuzz_isa.hpp"
#include "fuzz_test.hpp"
#include "imap/isa/isa.hpp"

using namespace imap::fuzz;

BOOST_AUTO_TEST_CASE(seeds_are_valid_programs) {
    const std::vector<Bytes> s = seeds("asm");
    BOOST_REQUIRE_GE(s.size(), 8u);
    for (const Bytes& b : s) {
        const Result r = check_asm(b);
        BOOST_CHECK_MESSAGE(r.outcome.rfind("assembled", 0) == 0, r.outcome);
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
    }
}

// The fast reproducers, replayed by fuzz.asm:
// - deep_parentheses.s: 32768 nested parentheses overflowed the stack of the
//   recursive expression parser (see also deep_expression_nesting_is_an_error);
// - word_top_bit.s: the disassembly of words with bit 63 set did not
//   re-assemble (see words_with_the_top_bit_round_trip).
BOOST_AUTO_TEST_CASE(regressions) {
    const auto r = replay_regressions("asm", check_asm);
    BOOST_REQUIRE_GE(r.size(), 2u);
    BOOST_CHECK_EQUAL(r.at("deep_parentheses.s").result.outcome,
                      "AsmError: expression nested too deeply (more than N levels)");
    // Assembles and round-trips; its first word (op 0xff) is no instruction.
    BOOST_CHECK_EQUAL(r.at("word_top_bit.s").result.outcome,
                      "assembled, LoadError: unknown opcode Nxff");
}

// The reproducers that run into the expansion budget (several seconds each),
// replayed by fuzz.asm_slow (label long): inputs of a few hundred bytes to
// 2 KB that ran for minutes because the budget did not count the work of
// re-scanning nested blocks (nested_rept_rescan.s), of long lines
// (long_line_rept.s) or of many tokens on a line (token_dense_rept.s). Each
// now ends with the budget error within seconds.
BOOST_AUTO_TEST_CASE(slow_regressions) {
    // 5 to 14 s each in Release, up to four times that in the sanitizer
    // build on a busy machine: the hang guard is 300 s here.
    const auto r = replay_regressions("asm-slow", check_asm, 300);
    BOOST_REQUIRE_GE(r.size(), 3u);
    for (const auto& [name, x] : r) {
        BOOST_CHECK_MESSAGE(
            x.result.outcome.rfind("AsmError: expansion too large: more than N work units", 0) == 0,
            name << ": " << x.result.outcome);
    }
}

BOOST_AUTO_TEST_CASE(fuzz) {
    run_campaign("asm", ".s", seeds("asm"), mutate_asm, check_asm);
}

// Found by this fuzzer: deep parentheses overflowed the stack of the
// recursive expression parser. Nesting is now limited (256 levels) and
// reported as an error at the line and column where it happens.
BOOST_AUTO_TEST_CASE(deep_expression_nesting_is_an_error) {
    auto diag = [](const std::string& src) -> std::string {
        try {
            imap::isa::assemble_string(src, "deep.s");
        } catch (const imap::isa::AsmError& e) {
            return e.diagnostics().front().str();
        }
        return "assembled";
    };
    // The 257th opening parenthesis is at column 12 + 256.
    for (const size_t depth : {257u, 100000u}) {
        const std::string parens = std::string(depth, '(') + "1" + std::string(depth, ')');
        BOOST_CHECK_EQUAL(diag("  cli c0, #" + parens + "\n  halt\n"),
                          "deep.s:1:" + std::to_string(12 + 256) +
                              ": error: expression nested too deeply (more than 256 levels)");
        BOOST_CHECK_NE(
            diag(".equ X " + std::string(depth * 4, '-') + "1\n").find("nested too deeply"),
            std::string::npos);
    }
    // 255 levels of parentheses (plus the operand) are fine and keep their value.
    const std::string ok = std::string(255, '(') + "7 * 6" + std::string(255, ')');
    const imap::isa::Program p = imap::isa::assemble_string("  cli c0, #" + ok + "\n  halt\n");
    BOOST_CHECK_EQUAL(imap::isa::Word::decode(p.code.at(0)).imm, 42u);
}

// Found by this fuzzer: words with bit 63 set were disassembled as
// `.word 0xffff...`, which the assembler refuses (numbers are signed 64-bit).
BOOST_AUTO_TEST_CASE(words_with_the_top_bit_round_trip) {
    imap::isa::Program p;
    p.phases = {"default"};
    p.code = {~uint64_t{0}, uint64_t{1} << 63, (uint64_t{1} << 63) | 0x40, ~uint64_t{0} >> 1};
    const std::string text = imap::isa::disassemble(p);
    BOOST_TEST_MESSAGE(text);
    const imap::isa::Program q = imap::isa::assemble_string(text, "rt.s");
    BOOST_CHECK(q.code == p.code);
}
