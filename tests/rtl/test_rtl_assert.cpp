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
//   report                a fault injected into the unmutated design (M of
//                         PE 2 flipped through the backdoor right before an
//                         xld) trips a_xfer_active in lockstep: the run stops
//                         with the lockstep's report (instruction, cycle,
//                         PC, assertion) and the waves of the cycles before
//   rtl_report            the same on the RTL alone (run_rtl): an
//                         AssertionFailure, an isa::Fault (imapsim: exit 3)
#define BOOST_TEST_MODULE rtl_assert
#include <unistd.h>
#include <boost/test/unit_test.hpp>
#include <filesystem>

#include "imap/rtl/random.hpp"
#include "rtl_test_util.hpp"

using namespace rtltest;
namespace fs = std::filesystem;

namespace {

// mask of PE 2 flipped after instruction 2 (li): the CP's cached count of
// active PEs no longer matches the PEs' M bits when the xld starts
const char* kXldProgram = R"(
        cli c1, #4
        cli c2, #0
        li r0, #1
        xld [#0], ext[c2], c1
        halt
)";

void run_report(bool lockstep) {
    const isa::MachineConfig cfg = rtl_config(8);
    const isa::Program prog = isa::assemble_string(kXldProgram, "xld.s");
    const auto left = image(8, 1, 1), right = image(8, 1, 2);
    const fs::path dir = fs::temp_directory_path() / ("rtl-assert-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    rtl::OutputImages out;
    if (lockstep) {
        rtl::LockstepConfig lc;
        lc.rtl.inject = rtl::parse_fault_injection("2:2:M:1");
        lc.divergence_waves = (dir / "assert.vcd").string();
        lc.waves_cycles = 20;
        const rtl::LockstepResult r = rtl::run_lockstep(cfg, prog, {}, left, right, 8, 1, &out, lc);
        BOOST_REQUIRE(r.diverged);
        const rtl::Divergence& d = r.divergence;
        BOOST_TEST_MESSAGE(d.message());
        BOOST_CHECK_EQUAL(d.assertion, "a_xfer_active");
        BOOST_CHECK_EQUAL(d.instruction, 3u);  // the xld, in its first cycle
        BOOST_CHECK_EQUAL(d.pc, 3u);
        BOOST_CHECK_EQUAL(d.pe, -1);
        BOOST_CHECK_GT(d.cycle, 0u);
        BOOST_CHECK(d.message().rfind("RTL assertion a_xfer_active failed at instruction 3 (cycle ",
                                      0) == 0);
        BOOST_CHECK(d.message().find("pc 3: xld") != std::string::npos);
        BOOST_CHECK(d.message().find("-> " + lc.divergence_waves) != std::string::npos);
        BOOST_CHECK(fs::exists(lc.divergence_waves));
        BOOST_CHECK(fs::exists(dir / "assert.gtkw"));
        BOOST_CHECK(!fs::exists(lc.divergence_waves + ".part"));
        // the RTL stopped at the failing edge: the xld never retired
        BOOST_CHECK_EQUAL(r.instructions, 3u);
    } else {
        rtl::RtlConfig rc;
        rc.inject = rtl::parse_fault_injection("2:2:M:1");
        try {
            rtl::run_rtl(cfg, prog, {}, left, right, 8, 1, &out, rc);
            BOOST_ERROR("no assertion failed");
        } catch (const rtl::AssertionFailure& e) {
            BOOST_TEST_MESSAGE(e.what());
            BOOST_CHECK_EQUAL(e.assertion(), "a_xfer_active");
            BOOST_CHECK_EQUAL(e.instruction(), 3u);
            BOOST_CHECK_EQUAL(e.pc(), 3u);
            BOOST_CHECK_EQUAL(e.pe(), isa::Fault::kNone);
            BOOST_CHECK(std::string(e.what()).find("RTL assertion a_xfer_active failed") == 0);
        }
    }
    fs::remove_all(dir);
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
