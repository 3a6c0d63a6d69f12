// The yosys synthesis of the PE and the CP (generic gates) made by the
// build, and the array's area for a configuration (the what-if sweep's area
// column).
#define BOOST_TEST_MODULE rtl_synth
#include <boost/test/unit_test.hpp>

#include "imap/rtl/area.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(pe_and_cp_are_synthesized) {
    const rtl::SynthFigures& s = rtl::synthesis();
    BOOST_REQUIRE(s.available);
    BOOST_TEST_MESSAGE("PE " << s.pe.cells << " cells (" << s.pe.flops << " flops), "
                             << s.pe.memory_bits << " memory bits; CP " << s.cp.cells << " cells, "
                             << s.cp.memory_bits << " memory bits; " << s.tool);
    // a PE: an 8-bit datapath with a 16 x 8 register file and 1 KB of memory
    BOOST_CHECK_GT(s.pe.cells, 500u);
    BOOST_CHECK_LT(s.pe.cells, 20000u);
    BOOST_CHECK_GT(s.pe.flops, 20u);
    BOOST_CHECK_EQUAL(s.pe.memory_bits, 16u * 8u + 1024u * 8u);
    BOOST_CHECK_GT(s.cp.cells, s.pe.cells);
    BOOST_CHECK_GE(s.cp.memory_bits, 65536u * 64u);  // the instruction memory
    BOOST_CHECK(s.tool.find("Yosys") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(array_area_scales_with_the_pe_count) {
    isa::MachineConfig cfg;
    const rtl::SynthFigures& s = rtl::synthesis();
    cfg.pes = 256;
    const rtl::ArrayArea a = rtl::array_area(cfg);
    cfg.pes = 128;
    const rtl::ArrayArea b = rtl::array_area(cfg);
    BOOST_CHECK_EQUAL(a.cells, 256 * s.pe.cells + s.cp.cells);
    BOOST_CHECK_EQUAL(a.cells - b.cells, 128 * s.pe.cells);
    BOOST_CHECK_EQUAL(a.memory_bits - b.memory_bits, 128u * (16u * 8u + 1024u * 8u));
    BOOST_CHECK_EQUAL(a.ext_bits, 256ull * 65536ull * 8ull);
}
