// The design's assertions (docs/rtl.md, "Assertions"). One executable, modes
// by the arguments after "--" (SystemC elaborates once per process):
//   <mutant> <assertion>  the mutation-check model with that planted bug runs
//                         the random programs on the RTL alone (no reference,
//                         no lockstep compare): the named assertion must be
//                         the first failure, and it must stop the program
//   none                  the same programs on the same model with no bug
//                         selected: no assertion fails
//   firmware              the DP firmware on the unmutated 8-PE design with
//                         every assertion checked: no assertion fails and
//                         the map is the golden's
//   report                the planted bug sub_mask trips a_pe_masked_wb in
//                         lockstep: the run stops with the lockstep's report
//                         (instruction, cycle, PC, PE, assertion) before the
//                         compare of that edge, and the waves of the 20
//                         cycles before it
//   rtl_report            the same on the RTL alone (run_rtl): an
//                         AssertionFailure, an isa::Fault (imapsim: exit 3)
#define BOOST_TEST_MODULE rtl_assert
#include <unistd.h>
#include <boost/test/unit_test.hpp>
#include <filesystem>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;

namespace {

// The mutation check's program 2 (seed 1002) with the planted bug sub_mask:
// its sub at pc 71 (instruction 70) writes r1 back on masked PE 1.
void run_report(bool lockstep) {
    const rtl::RandomProgram p = rtl::generate_program(1002);
    rtl::OutputImages out;
    if (lockstep) {
        rtl::LockstepConfig lc;
        lc.rtl.mutant = "sub_mask";
        lc.waves_cycles = 20;
        const std::string waves = (std::filesystem::temp_directory_path() /
                                   ("rtl_assert_" + std::to_string(::getpid()) + ".fst"))
                                      .string();
        lc.divergence_waves = waves;
        const rtl::LockstepResult r =
            rtl::run_lockstep(p.cfg, p.prog, p.params, p.left, p.right, p.out_w, p.out_h, &out, lc);
        BOOST_REQUIRE(r.diverged);
        const rtl::Divergence& d = r.divergence;
        BOOST_TEST_MESSAGE(d.message());
        // the assertion, at the edge the sub commits: before the lockstep
        // compare of what that edge retired
        BOOST_CHECK_EQUAL(d.assertion, "a_pe_masked_wb");
        BOOST_CHECK_EQUAL(d.instruction, 70u);
        BOOST_CHECK_EQUAL(d.pc, 71u);
        BOOST_CHECK_EQUAL(d.pe, 1);
        BOOST_CHECK_GT(d.cycle, 70u);
        BOOST_CHECK(d.message().rfind(
                        "RTL assertion a_pe_masked_wb failed at instruction 70 (cycle ", 0) == 0);
        BOOST_CHECK(d.message().find("pc 71: sub r1, r1, r4) in PE 1: a masked PE") !=
                    std::string::npos);
        // the waves of the 20 cycles before the failing edge, from a replay
        // of the same model with the same planted bug
        BOOST_CHECK_EQUAL(d.waves, "waves of machine cycles " + std::to_string(d.cycle - 20) +
                                       ".." + std::to_string(d.cycle) + " -> " + waves);
        std::error_code ec;
        BOOST_CHECK_GT(std::filesystem::file_size(waves, ec), 1000u);
        BOOST_CHECK(!ec);
        std::filesystem::remove(waves, ec);
        std::filesystem::remove(rtl::gtkw_path(waves), ec);
        // the RTL stopped at the failing edge: the sub (whose write-back
        // the assertion caught) is the last instruction the design committed
        BOOST_CHECK_EQUAL(r.instructions, 71u);
    } else {
        rtl::RtlConfig rc;
        rc.mutant = "sub_mask";
        try {
            rtl::run_rtl(p.cfg, p.prog, p.params, p.left, p.right, p.out_w, p.out_h, &out, rc);
            BOOST_ERROR("no assertion failed");
        } catch (const rtl::AssertionFailure& e) {
            BOOST_TEST_MESSAGE(e.what());
            BOOST_CHECK_EQUAL(e.assertion(), "a_pe_masked_wb");
            BOOST_CHECK_EQUAL(e.instruction(), 70u);
            BOOST_CHECK_EQUAL(e.pc(), 71u);
            BOOST_CHECK_EQUAL(e.pe(), 1);
            BOOST_CHECK(std::string(e.what()).find("RTL assertion a_pe_masked_wb failed") == 0);
        }
    }
}

}  // namespace

BOOST_AUTO_TEST_CASE(assertions) {
    const auto& ts = boost::unit_test::framework::master_test_suite();
    BOOST_REQUIRE_MESSAGE(ts.argc == 2 || ts.argc == 3,
                          "usage: test_rtl_assert -- <mutant> <assertion> | none | firmware | "
                          "report | rtl_report");
    const std::string mode = ts.argv[1];
    if (mode == "report" || mode == "rtl_report") {
        run_report(mode == "report");
        return;
    }
    if (mode == "firmware") {
        const FirmwareCase c = firmware_case(8, 7, 8, true, g::Mode::Bidir);
        isa::MachineConfig cfg;
        cfg.pes = 8;
        const g::DisparityMap want = g::compute(c.p, c.frame.left(), c.frame.right(), c.roi);
        rtl::OutputImages out;
        const rtl::RtlRunResult r = rtl::run_rtl(
            cfg, c.prog, fw::param_block(c.plan), fw::to_video_image(c.frame.left()),
            fw::to_video_image(c.frame.right()), c.roi.w, c.roi.h, &out);  // throws on a failure
        BOOST_CHECK(r.halted);
        BOOST_CHECK(out.image[0].pixels == want.data);
        return;
    }
    rtl::SuiteOptions o;
    o.seed = 1000;  // the mutation check's programs
    o.mutant = mode;
    o.lockstep = false;
    o.programs = mode == "none" ? 100 : 300;
    o.stop_at_divergence = mode != "none";
    const rtl::SuiteResult r = rtl::run_random_suite(o);
    if (mode == "none") {
        for (const std::string& f : r.failures) BOOST_ERROR(f);
        BOOST_CHECK_EQUAL(r.passed, r.programs);
        BOOST_CHECK_EQUAL(r.programs, 100);
        return;
    }
    BOOST_REQUIRE_MESSAGE(ts.argc == 3, "usage: test_rtl_assert -- <mutant> <assertion>");
    const std::string want = ts.argv[2];
    BOOST_REQUIRE_MESSAGE(r.caught, "planted bug " << mode << ": no assertion failed in "
                                                   << r.programs << " random programs");
    BOOST_CHECK_MESSAGE(r.caught_assertion == want, "planted bug " << mode << ": expected " << want
                                                                   << ", got " << r.caught_message);
    std::printf("mutant %s: %s in program %d at instruction %llu\n  %s\n", mode.c_str(),
                r.caught_assertion.c_str(), r.caught_program,
                static_cast<unsigned long long>(r.caught_instruction), r.caught_message.c_str());
}
