// The mutation check: the mutation-check model (8 PEs) with one planted bug
// (the first argument after "--": test_rtl_mutant -- adc_carry;
// imap::rtl::mutants() lists them) runs the random suite until the lockstep
// comparison catches it. "none" runs the same model with no bug selected and
// must pass. One executable, one CTest test per bug (tests/rtl/CMakeLists.txt).
#define BOOST_TEST_MODULE rtl_mutant
#include <boost/test/unit_test.hpp>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(planted_bug_is_caught) {
    const auto& ts = boost::unit_test::framework::master_test_suite();
    BOOST_REQUIRE_MESSAGE(ts.argc == 2, "usage: test_rtl_mutant -- <planted bug name or none>");
    const std::string name = ts.argv[1];
    rtl::SuiteOptions o;
    o.seed = 1000;  // the random suite's programs
    o.mutant = name;
    o.programs = name == "none" ? 40 : 300;
    o.stop_at_divergence = name != "none";
    const rtl::SuiteResult r = rtl::run_random_suite(o);
    if (name == "none") {
        for (const std::string& f : r.failures) BOOST_ERROR(f);
        BOOST_CHECK_EQUAL(r.passed, r.programs);
        return;
    }
    BOOST_REQUIRE_MESSAGE(r.caught, "planted bug " << name << " was not caught by " << r.programs
                                                   << " random programs");
    std::printf(
        "mutant %s: caught in program %d at instruction %llu, after %llu instructions "
        "in all\n  %s\n",
        name.c_str(), r.caught_program, static_cast<unsigned long long>(r.caught_instruction),
        static_cast<unsigned long long>(r.instructions_to_catch), r.caught_message.c_str());
}
