// (c) A machine fault (address out of range) stops the simulation and comes
// out of run_tlm as the original isa::Fault, message intact (PC, source
// location, cycle). Afterwards no second model can be built in the process.
#define BOOST_TEST_MODULE tlm_fault
#include <boost/test/unit_test.hpp>

#include "tlm_test_util.hpp"

using namespace tlmtest;

BOOST_AUTO_TEST_CASE(fault_propagates_with_pc) {
    const isa::MachineConfig cfg = config(8);
    const isa::Program prog = isa::assemble_string(R"(
        cli c1, #60
        nop
        ld r0, [c1 + 10]        ; address 70 of 64
        halt
)",
                                                   "fault.s");
    const auto img = image(8, 2, 3);
    try {
        itlm::run_tlm(cfg, prog, {}, img, img, 8, 2, nullptr);
        BOOST_FAIL("run_tlm did not throw");
    } catch (const isa::Fault& f) {
        const std::string what = f.what();
        BOOST_TEST_MESSAGE(what);
        BOOST_CHECK_EQUAL(f.pc(), 2u);
        BOOST_CHECK_EQUAL(f.address(), 70);
        BOOST_CHECK_EQUAL(f.cycle(), 2u);
        BOOST_CHECK(what.find("fault at pc 2 (fault.s:4), cycle 2") != std::string::npos);
        BOOST_CHECK(what.find("ld: address 70 out of range") != std::string::npos);
    }
    BOOST_CHECK(sc_core::sc_get_status() != sc_core::SC_ELABORATION);
    BOOST_CHECK_THROW(itlm::TlmSystem("again", cfg, prog), std::logic_error);
}
