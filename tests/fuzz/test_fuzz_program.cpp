// Fuzzing the IMAPFW01 program loader (docs/testing.md): mutants of
// corpus/program/*.bin must parse or fail with FormatError; what parses
// must round-trip and load (or fail with LoadError) and run to halt or a
// Fault on a small machine.
#define BOOST_TEST_MODULE fuzz_program
#include "fuzz_isa.hpp"
#include "fuzz_test.hpp"
#include "imap/isa/isa.hpp"

using namespace imap::fuzz;

BOOST_AUTO_TEST_CASE(seeds_are_valid_programs) {
    const std::vector<Bytes> s = seeds("program");
    BOOST_REQUIRE_GE(s.size(), 4u);
    size_t halted = 0;
    for (const Bytes& b : s) {
        const Result r = check_program(b);
        BOOST_CHECK_MESSAGE(r.outcome.rfind("parsed, ", 0) == 0, r.outcome);
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
        halted += r.outcome == "parsed, halt";
    }
    // All but the full firmware (which needs more memory than the small
    // machine has) run to halt.
    BOOST_CHECK_EQUAL(halted, s.size() - 1);
}

// Every saved reproducer; two were found by this fuzzer (file contents
// echoed into messages and comments with their newlines):
// - newline_in_file_name.bin: a source-map file name with a newline split the
//   disassembly's comment, so the disassembly did not re-assemble (and load
//   errors and faults naming the location spanned two lines);
// - newline_in_symbol_name.bin: the FormatError naming a symbol beyond the
//   code spanned two lines.
BOOST_AUTO_TEST_CASE(regressions) {
    const auto r = replay_regressions("program", check_program);
    BOOST_REQUIRE_GE(r.size(), 2u);
    BOOST_CHECK_EQUAL(r.at("newline_in_file_name.bin").result.outcome, "parsed, halt");
    BOOST_CHECK_EQUAL(r.at("newline_in_symbol_name.bin").result.outcome,
                      "FormatError: symbol '_' at PC N beyond the code");
}

// Control characters of names read from a program file are shown as '?'.
BOOST_AUTO_TEST_CASE(names_from_the_file_stay_on_one_line) {
    namespace isa = imap::isa;
    isa::Program p;
    p.code = {isa::Word{static_cast<uint8_t>(isa::Op::CLI), 1, 0, 0, 60}.encode(),
              isa::Word{static_cast<uint8_t>(isa::Op::LD), 0, 0, 1, 10}.encode(),
              isa::Word{static_cast<uint8_t>(isa::Op::HALT)}.encode()};
    p.phases = {"default"};
    p.files = {"dir\nx.s\r"};
    p.files[0][3] = '\n';
    p.files[0][8] = '\r';
    p.source_map = {{0, 1}, {0, 2}, {0, 3}};
    BOOST_CHECK_EQUAL(p.location(1), "dir?x.s?:2");
    const std::string text = isa::disassemble(p);
    BOOST_CHECK(isa::assemble_string(text, "rt.s").code == p.code);
    isa::MachineConfig cfg;
    cfg.pes = 4;
    cfg.mem_bytes = 64;
    isa::Machine m(cfg);
    m.load(p);
    try {
        m.run();
        BOOST_FAIL("no fault");
    } catch (const isa::Fault& f) {
        BOOST_CHECK_MESSAGE(std::string(f.what()).find("(dir?x.s?:2)") != std::string::npos,
                            f.what());
    }
    isa::Program q = p;
    q.symbols["a\tb\nc"] = 9;
    try {
        isa::deserialize(isa::serialize(q), "q.bin");
        BOOST_FAIL("accepted");
    } catch (const isa::FormatError& e) {
        BOOST_CHECK_EQUAL(std::string(e.what()),
                          "bad program file 'q.bin': symbol 'a?b?c' at PC 9 beyond the code");
    }
}

BOOST_AUTO_TEST_CASE(fuzz) {
    run_campaign("program", ".bin", seeds("program"), mutate_program, check_program);
}
