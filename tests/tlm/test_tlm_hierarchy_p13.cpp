// (b) the hierarchy for a PE count that is not a power of two (13), built
// from the runtime configuration, and the same program as the bare machine
// at a clock whose period is not a whole number of ns.
#define BOOST_TEST_MODULE tlm_hierarchy_p13
#include <boost/test/unit_test.hpp>

#include "tlm_test_util.hpp"

using namespace tlmtest;

BOOST_AUTO_TEST_CASE(hierarchy_and_state_p13) {
    isa::MachineConfig cfg = config(13);
    cfg.clock_mhz = 33.0;  // 30.303 ns -> 30303 ps at the 1 ps resolution
    const isa::Program prog = isa::assemble_string(kProgram, "p13.s");
    itlm::TlmConfig tc;
    tc.quantum_ns = 250;
    itlm::TlmSystem top("top", cfg, prog, tc);
    for (const auto& [i, v] : kParams) top.set_param(i, v);
    const auto left = image(10, 3, 5), right = image(10, 3, 77);
    top.set_input(0, left);
    top.set_input(1, right);
    top.make_output(0, kOutW, kOutH);
    top.make_output(1, kOutW, kOutH);

    for (int p = 0; p < 13; ++p) {
        const std::string n = "top.array.pe_" + std::to_string(p);
        BOOST_TEST_CONTEXT(n) {
            auto* pe = dynamic_cast<itlm::Pe*>(sc_core::sc_find_object(n.c_str()));
            BOOST_REQUIRE(pe);
            BOOST_CHECK_EQUAL(pe->index(), p);
            BOOST_CHECK(sc_core::sc_find_object((n + ".socket").c_str()));
        }
    }
    BOOST_CHECK(sc_core::sc_find_object("top.array.pe_13") == nullptr);
    BOOST_CHECK(sc_core::sc_find_object("top.array.mem"));
    BOOST_CHECK(sc_core::sc_find_object("top.ring"));
    BOOST_CHECK(sc_core::sc_find_object("top.maskbus"));

    sc_core::sc_start();
    top.rethrow_if_faulted();
    const auto ref = run_reference(cfg, prog, left, right);
    check_same_state(top.machine(), *ref->m);
    for (int p = 0; p < 2; ++p) BOOST_CHECK(top.output(p).pixels == ref->video.output[p].pixels);
    // The per-PE views read the machine's lanes.
    auto* pe12 = dynamic_cast<itlm::Pe*>(sc_core::sc_find_object("top.array.pe_12"));
    BOOST_REQUIRE(pe12);
    BOOST_CHECK_EQUAL(pe12->reg(5), ref->m->reg(12, 5));
    BOOST_CHECK_EQUAL(pe12->mem(3), ref->m->mem_read(12, 3));

    const itlm::TlmRunResult r = top.result();
    BOOST_CHECK(itlm::clock_period(cfg) == sc_core::sc_time(30303, sc_core::SC_PS));
    BOOST_CHECK(sc_core::sc_time_stamp() == sc_core::sc_time(30303.0 * r.cycles, sc_core::SC_PS));
    BOOST_CHECK_EQUAL(r.ring.lane_bytes, r.ring.hops * 13u);
}
