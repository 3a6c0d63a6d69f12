// A refused video transaction (line outside the input image) becomes an
// isa::Fault naming the PC and the target's reason; the quantum keeper had
// synchronised to the vin, so the kernel's time is the fault's cycle.
#define BOOST_TEST_MODULE tlm_fault_video
#include <boost/test/unit_test.hpp>

#include "tlm_test_util.hpp"

using namespace tlmtest;

BOOST_AUTO_TEST_CASE(video_fault_propagates) {
    const isa::MachineConfig cfg = config(8);
    const isa::Program prog = isa::assemble_string(R"(
        cli c1, #1
        cli c2, #0
        vin #1, [#0], c1, c2    ; fine
        cli c1, #5
        vin #1, [#1], c1, c2    ; line 5 of a 3-line image
        halt
)",
                                                   "video.s");
    try {
        itlm::run_tlm(cfg, prog, {}, image(10, 3, 0), image(10, 3, 1), 8, 2, nullptr);
        BOOST_FAIL("run_tlm did not throw");
    } catch (const isa::Fault& f) {
        const std::string what = f.what();
        BOOST_TEST_MESSAGE(what);
        BOOST_CHECK_EQUAL(f.pc(), 4u);
        BOOST_CHECK(what.find("fault at pc 4 (video.s:6)") != std::string::npos);
        BOOST_CHECK(what.find("vin port 1 line 5 column 0: line outside input image 1 (10x3)") !=
                    std::string::npos);
        BOOST_CHECK(sc_core::sc_time_stamp() == sc_core::sc_time(25.0 * f.cycle(), sc_core::SC_NS));
    }
}
