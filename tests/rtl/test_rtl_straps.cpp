// The strap sweep of the random suite (GenOptions::strap_sweep; its own
// process: SystemC elaborates once per process).
#define BOOST_TEST_MODULE rtl_straps
#include <boost/test/unit_test.hpp>
#include <cstdio>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

// The strap sweep: one instruction of every cost class under costs near the
// top of their range (0x55555 / 0xAAAAA cycles), every pe_regs, mask_depth,
// call_depth and watchdog bit the design can hold flipped between
// consecutive programs, in lockstep with the instruction-set model (the
// cycle count compared at every instruction): a cost truncated or a strap
// bit dropped anywhere in the design's cost arithmetic diverges here.
BOOST_AUTO_TEST_CASE(strap_sweep_agrees_with_the_isa) {
    rtl::SuiteOptions o;
    o.seed = 7002;   // = 0 mod 6: the programs take the values in list order
    o.programs = 3;  // the first program's straps are the reset values (no toggle);
                     // the next two flip every bit (lists of 2 and 3 values)
    o.gen.strap_sweep = true;
    const rtl::SuiteResult r = rtl::run_random_suite(o);
    for (const std::string& f : r.failures) BOOST_ERROR(f);
    BOOST_CHECK_EQUAL(r.passed, o.programs);
    // the costs were near the top of the range: a program of ~30
    // instructions takes millions of cycles
    BOOST_CHECK_GT(r.cycles, uint64_t{3} * 5'000'000);
    std::printf("strap sweep: %d programs, %llu instructions, %llu cycles, %.1f s\n", r.programs,
                static_cast<unsigned long long>(r.instructions),
                static_cast<unsigned long long>(r.cycles), r.wall_s);
}
