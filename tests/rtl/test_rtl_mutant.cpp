// The mutation check: the mutation-check model (8 PEs) with one planted bug
// (the first argument after "--": test_rtl_mutant -- adc_carry;
// imap::rtl::mutants() lists them) runs the random suite until the lockstep
// comparison catches it. "none" runs the same model with no bug selected and
// must pass. A second argument "sparse" turns the checker's periodic full
// compares off: the bug must then be caught by the comparison of what each
// instruction names (its rd register, the flags, its memory rows) or the
// final state alone. One executable, one CTest test per bug and mode
// (tests/rtl/CMakeLists.txt).
#define BOOST_TEST_MODULE rtl_mutant
#include <boost/test/unit_test.hpp>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(planted_bug_is_caught) {
    const auto& ts = boost::unit_test::framework::master_test_suite();
    BOOST_REQUIRE_MESSAGE(ts.argc == 2 || (ts.argc == 3 && std::string(ts.argv[2]) == "sparse"),
                          "usage: test_rtl_mutant -- <planted bug name or none> [sparse]");
    const std::string name = ts.argv[1];
    const bool sparse = ts.argc == 3;
    rtl::SuiteOptions o;
    o.seed = 1000;  // the random suite's programs
    o.mutant = name;
    o.programs = name == "none" ? 40 : 300;
    o.stop_at_divergence = name != "none";
    if (sparse) o.full_compare_every = uint64_t{1} << 40;
    const rtl::SuiteResult r = rtl::run_random_suite(o);
    if (name == "none") {
        for (const std::string& f : r.failures) BOOST_ERROR(f);
        BOOST_CHECK_EQUAL(r.passed, r.programs);
        return;
    }
    BOOST_REQUIRE_MESSAGE(r.caught, "planted bug " << name << " was not caught by " << r.programs
                                                   << " random programs");
    std::printf(
        "mutant %s%s: caught in program %d at instruction %llu, after %llu instructions "
        "in all\n  %s\n",
        name.c_str(), sparse ? " (sparse compare)" : "", r.caught_program,
        static_cast<unsigned long long>(r.caught_instruction),
        static_cast<unsigned long long>(r.instructions_to_catch), r.caught_message.c_str());
}
