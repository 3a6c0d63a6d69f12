// A fault injected into the RTL model only (XOR into r5 of PE 3 after
// instruction 20) is caught by the lockstep comparison and reported with the
// instruction, PE, register and both values.
#define BOOST_TEST_MODULE rtl_lockstep_inject
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(injected_fault_is_caught) {
    const isa::MachineConfig cfg = config(8);
    const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
    const auto left = image(10, 3, 1), right = image(10, 3, 90);
    const auto ref = run_reference(cfg, prog, left, right);
    // The state r5 of PE 3 has right after instruction 20 (bare machine).
    isa::Machine m(cfg);
    m.load(prog);
    for (const auto& [i, v] : kParams) m.set_param(i, v);
    isa::ImageVideoPort video;
    video.input[0] = left;
    video.input[1] = right;
    video.make_output(0, kOutW, kOutH);
    video.make_output(1, kOutW, kOutH);
    m.set_video(&video);
    for (int i = 0; i <= 20; ++i) m.step();
    const uint8_t good = m.reg(3, 5);

    rtl::LockstepConfig lc;
    lc.rtl.inject = rtl::parse_fault_injection("20:3:r5:0x24");
    BOOST_CHECK_EQUAL(lc.rtl.inject.reg, 5);
    BOOST_CHECK_THROW(rtl::parse_fault_injection("20:3:r5"), isa::ConfigError);
    BOOST_CHECK_THROW(rtl::parse_fault_injection("x:3:r5:1"), isa::ConfigError);
    rtl::OutputImages out;
    const rtl::LockstepResult r =
        rtl::run_lockstep(cfg, prog, kParams, left, right, kOutW, kOutH, &out, lc);
    BOOST_REQUIRE(r.diverged);
    const rtl::Divergence& d = r.divergence;
    BOOST_TEST_MESSAGE(d.message());
    BOOST_CHECK_EQUAL(d.instruction, 20u);
    BOOST_CHECK_EQUAL(d.what, "r5");
    BOOST_CHECK_EQUAL(d.pe, 3);
    BOOST_CHECK_EQUAL(d.tlm_value, good);
    BOOST_CHECK_EQUAL(d.rtl_value, uint64_t(good ^ 0x24));
    BOOST_CHECK_EQUAL(d.pc, m.pc() - 1);
    BOOST_CHECK(!d.disassembly.empty());
    BOOST_CHECK(d.message().find("PE 3") != std::string::npos);
}
