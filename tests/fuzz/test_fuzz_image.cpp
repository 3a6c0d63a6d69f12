// Fuzzing the image loader (docs/testing.md): mutants of corpus/image/*
// must load as an 8-bit grey image or fail with InputError.
#define BOOST_TEST_MODULE fuzz_image
#include "fuzz_test.hpp"
#include "fuzz_vision.hpp"

using namespace imap::fuzz;

BOOST_AUTO_TEST_CASE(seeds_load_or_are_refused_cleanly) {
    const std::vector<Bytes> s = seeds("image");
    BOOST_REQUIRE_GE(s.size(), 8u);
    size_t loaded = 0;
    for (const Bytes& b : s) {
        const Result r = check_image(b);
        BOOST_TEST_MESSAGE(r.outcome);
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
        loaded += r.outcome.rfind("loaded", 0) == 0;
    }
    // Every seed is a valid image except the 16-bit PNG and the float PFM.
    BOOST_CHECK_EQUAL(loaded, s.size() - 2);
}

BOOST_AUTO_TEST_CASE(regressions) {
    replay_regressions("image", check_image);
}

BOOST_AUTO_TEST_CASE(fuzz) {
    run_campaign("image", ".img", seeds("image"), mutate_image, check_image);
}
