// The constrained-random suite: 300 seeded programs (every opcode, operand
// class, mask state and nesting, ring distance and direction, transfer
// length, branch shape; a random cost table each; some end in a deliberate
// fault) run on the RTL design in lockstep with the instruction-set model,
// compared at every retired instruction. Prints the functional coverage and
// writes it to rtl_coverage.json (in the working directory).
#define BOOST_TEST_MODULE rtl_random
#include <boost/test/unit_test.hpp>
#include <fstream>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(random_programs_agree_with_the_isa) {
    rtl::SuiteOptions o;
    o.seed = 1000;
    o.programs = 300;
    const rtl::SuiteResult r = rtl::run_random_suite(o);
    for (const std::string& f : r.failures) BOOST_ERROR(f);
    BOOST_CHECK_EQUAL(r.programs, o.programs);
    BOOST_CHECK_EQUAL(r.passed, o.programs);
    std::printf("random suite: %d programs, %llu instructions, %llu cycles, %.1f s\n%s", r.programs,
                static_cast<unsigned long long>(r.instructions),
                static_cast<unsigned long long>(r.cycles), r.wall_s, r.coverage.table().c_str());
    nlohmann::json j = r.coverage.json();
    j["programs"] = r.programs;
    j["instructions"] = r.instructions;
    j["cycles"] = r.cycles;
    std::ofstream("rtl_coverage.json") << j.dump(1) << "\n";
    // every opcode ran; almost every bin is covered
    BOOST_CHECK_GE(static_cast<double>(r.coverage.covered()),
                   0.95 * static_cast<double>(r.coverage.bins()));
    for (const std::string& b : r.coverage.uncovered())
        BOOST_CHECK_MESSAGE(
            b.rfind("ring/", 0) != 0 && b.rfind("xfer/", 0) != 0 && b.rfind("mask/", 0) != 0,
            "uncovered " << b);
}
