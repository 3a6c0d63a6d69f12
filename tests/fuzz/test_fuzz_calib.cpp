// Fuzzing the stereo calibration loader (docs/testing.md): mutants of
// corpus/calib/*.yml|xml must load as a valid calibration or fail with
// InputError.
#define BOOST_TEST_MODULE fuzz_calib
#include "fuzz_test.hpp"
#include "fuzz_vision.hpp"

using namespace imap::fuzz;

BOOST_AUTO_TEST_CASE(seeds_are_valid_calibrations) {
    const std::vector<Bytes> s = seeds("calib");
    BOOST_REQUIRE_GE(s.size(), 4u);
    for (const Bytes& b : s) {
        const Result r = check_calib(b);
        BOOST_CHECK_MESSAGE(r.outcome.rfind("loaded", 0) == 0, r.outcome);
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
    }
}

BOOST_AUTO_TEST_CASE(regressions) {
    replay_regressions("calib", check_calib);
}

BOOST_AUTO_TEST_CASE(fuzz) {
    run_campaign("calib", ".yml", seeds("calib"), mutate_calib, check_calib);
}
