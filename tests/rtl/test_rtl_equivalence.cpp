// run_rtl on a program that uses every instruction class (ALU, memory,
// per-PE addressing, ring with wrap, nested masks, status, external memory,
// video, phases, loop) leaves exactly the state and cycle count of a bare
// isa::Machine; the kernel time is cycles x period; the signal hierarchy
// exists and shows the final state; a second run_rtl in the process throws.
#define BOOST_TEST_MODULE rtl_equivalence
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

BOOST_AUTO_TEST_CASE(run_rtl_matches_bare_machine) {
    const isa::MachineConfig cfg = config(8);
    const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
    const auto left = image(10, 3, 1), right = image(10, 3, 90);
    const auto ref = run_reference(cfg, prog, left, right);
    BOOST_REQUIRE(ref->m->halted());

    // Built by hand (run_rtl destroys the hierarchy when it returns).
    rtl::RtlSystem sys("top", cfg, prog);
    for (const auto& [i, v] : kParams) sys.set_param(i, v);
    sys.set_input(0, left);
    sys.set_input(1, right);
    sys.make_output(0, kOutW, kOutH);
    sys.make_output(1, kOutW, kOutH);
    sc_core::sc_start();
    sys.rethrow_if_faulted();
    BOOST_REQUIRE(sys.array.finished());
    const rtl::RtlRunResult r = sys.result();
    rtl::OutputImages out = sys.outputs();
    BOOST_REQUIRE(r.machine);
    check_same_state(*r.machine, *ref->m);
    BOOST_CHECK(r.halted);
    BOOST_CHECK_EQUAL(r.cycles, ref->m->cycles());
    BOOST_CHECK(r.phase_cycles == ref->m->phase_cycles());
    // One clock edge per cycle, plus the edge that sees the halt completed.
    BOOST_CHECK_EQUAL(r.clock_edges, r.cycles + 1);
    BOOST_CHECK(sc_core::sc_time_stamp() ==
                itlm::cycles_to_time(r.cycles, itlm::clock_period(cfg)));
    for (int p = 0; p < 2; ++p) BOOST_CHECK(out.image[p].pixels == ref->video.output[p].pixels);
    BOOST_CHECK_EQUAL(r.traced_pes, 8);
    BOOST_CHECK_GT(r.signal_writes, 0u);

    // The signal hierarchy, holding the final state.
    for (const char* n : {"top.clk",
                          "top.cp.pc",
                          "top.cp.instr",
                          "top.cp.opcode",
                          "top.cp.valid",
                          "top.cp.bubble",
                          "top.cp.halted",
                          "top.cp.creg_4",
                          "top.array.pe_3.r5",
                          "top.array.pe_3.c",
                          "top.array.pe_3.t",
                          "top.array.pe_3.m",
                          "top.array.pe_3.mem_we",
                          "top.array.pe_3.mem_addr",
                          "top.array.pe_7.ext_we",
                          "top.ring.link_3",
                          "top.ring.busy",
                          "top.ring.hop",
                          "top.maskbus.any",
                          "top.maskbus.all",
                          "top.maskbus.reduce",
                          "top.maskbus.active"})
        BOOST_CHECK_MESSAGE(sc_core::sc_find_object(n) != nullptr, n << " exists");
    auto* r5 =
        dynamic_cast<sc_core::sc_signal<uint8_t>*>(sc_core::sc_find_object("top.array.pe_3.r5"));
    BOOST_REQUIRE(r5);
    BOOST_CHECK_EQUAL(int(r5->read()), int(ref->m->reg(3, 5)));
    auto* halted =
        dynamic_cast<sc_core::sc_signal<bool>*>(sc_core::sc_find_object("top.cp.halted"));
    BOOST_REQUIRE(halted);
    BOOST_CHECK(halted->read());
    auto* c4 =
        dynamic_cast<sc_core::sc_signal<uint32_t>*>(sc_core::sc_find_object("top.cp.creg_4"));
    BOOST_REQUIRE(c4);
    BOOST_CHECK_EQUAL(c4->read(), ref->m->cp(4));

    // Past elaboration: no second model in this process.
    BOOST_CHECK_THROW(rtl::run_rtl(cfg, prog, kParams, left, right, kOutW, kOutH, &out),
                      std::logic_error);
    BOOST_CHECK_THROW(rtl::run_rtl(cfg, prog, kParams, left, right, kOutW, kOutH, &out),
                      std::logic_error);
}
