// (a) A program that exercises ALU, memory, ring, mask, status, external
// memory and video, run through run_tlm on P = 8, leaves exactly the state a
// bare isa::Machine leaves; (e) the kernel's time at the end is cycles x
// clock period; run_tlm refuses a second call in the same process.
#define BOOST_TEST_MODULE tlm_equivalence
#include <boost/test/unit_test.hpp>

#include "tlm_test_util.hpp"

using namespace tlmtest;

BOOST_AUTO_TEST_CASE(run_tlm_matches_bare_machine_and_time) {
    const isa::MachineConfig cfg = config(8);
    const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
    const auto left = image(10, 3, 1), right = image(10, 3, 90);
    const auto ref = run_reference(cfg, prog, left, right);
    BOOST_REQUIRE(ref->m->halted());

    itlm::TlmConfig tc;
    tc.quantum_ns = 100;  // 4 cycles at 40 MHz: many quantum ends inside the program
    itlm::OutputImages out;
    const itlm::TlmRunResult r =
        itlm::run_tlm(cfg, prog, kParams, left, right, kOutW, kOutH, &out, tc);

    BOOST_REQUIRE(r.machine);
    check_same_state(*r.machine, *ref->m);
    BOOST_CHECK(r.halted);
    BOOST_CHECK_EQUAL(r.cycles, ref->m->cycles());
    BOOST_CHECK(r.phase_cycles == ref->m->phase_cycles());
    BOOST_CHECK_EQUAL(r.phase_cycles.size(), 4u);  // default, load, compute, out
    BOOST_CHECK_EQUAL(r.stats.instructions, ref->m->stats().instructions);
    BOOST_CHECK_CLOSE(r.modeled_ms, r.cycles / 40e3, 1e-9);
    for (int p = 0; p < 2; ++p) {
        BOOST_CHECK_EQUAL(out.image[p].width, kOutW);
        BOOST_CHECK(out.image[p].pixels == ref->video.output[p].pixels);
    }
    // The output really carries data (not two equally empty images).
    BOOST_CHECK(out.image[0].pixels != std::vector<uint8_t>(out.image[0].pixels.size(), 0));

    // Components: the ring and the mask bus saw every ring / status instruction.
    const isa::Stats& s = r.stats;
    BOOST_CHECK_EQUAL(r.ring.transfers, count(s, isa::Op::RXL) + count(s, isa::Op::RXR));
    BOOST_CHECK_EQUAL(r.ring.left, count(s, isa::Op::RXL));
    BOOST_CHECK_EQUAL(r.ring.hops, 3u + 11u + 1u + 2u);
    BOOST_CHECK_EQUAL(r.ring.lane_bytes, r.ring.hops * 8u);
    BOOST_CHECK_EQUAL(r.maskbus.reductions, count(s, isa::Op::RANY) + count(s, isa::Op::RALL));
    BOOST_CHECK_EQUAL(r.maskbus.any, 3u);
    BOOST_CHECK_EQUAL(r.maskbus.mask_commands, 5u);  // mif mif mend melse mend
    BOOST_CHECK_EQUAL(r.video.lines_in, 3u);
    BOOST_CHECK_EQUAL(r.video.lines_out, 3u);
    BOOST_CHECK(r.video_dmi);
    BOOST_CHECK_GT(r.chunks, 1u);
    BOOST_CHECK_GT(r.syncs, r.video.lines_in + r.video.lines_out);
    BOOST_CHECK_CLOSE(r.quantum_ns, 100.0, 1e-9);

    // (e) Modeled time: sc_time_stamp() == cycles x period (25 ns at 40 MHz).
    BOOST_CHECK(sc_core::sc_time_stamp() == sc_core::sc_time(25.0 * r.cycles, sc_core::SC_NS));
    BOOST_CHECK(sc_core::sc_time_stamp() ==
                itlm::cycles_to_time(r.cycles, itlm::clock_period(cfg)));
    BOOST_CHECK_CLOSE(r.sim_time_s, r.cycles * 25e-9, 1e-9);

    // One elaboration per process.
    try {
        itlm::run_tlm(cfg, prog, kParams, left, right, kOutW, kOutH, nullptr);
        BOOST_FAIL("second run_tlm did not throw");
    } catch (const std::logic_error& e) {
        BOOST_TEST_MESSAGE(e.what());
        BOOST_CHECK(std::string(e.what()).find("once per process") != std::string::npos);
    }
}
