// A fault injected into the RTL design only (XOR into r5 of PE 3 right
// after instruction 20, through the testbench's backdoor) is caught by the
// lockstep comparison at the next retired instruction and reported with the
// instruction, PE, register and both values; the waves of the cycles before
// it are written by the traced replay of the design, with a GTKWave view.
// With the checker's full compares every 8 instructions, a fault in r6 (which
// the following instructions do not name) is caught by the next full
// compare, and the report says so (built with
// RTL_TEST_PERIODIC=1: SystemC elaborates once per process). Built with
// RTL_TEST_FST=1, the same on 16 PEs with the default FST divergence waves:
// the configuration's own model (FST tracing compiled in, off) is the one
// that replays the window.
#define BOOST_TEST_MODULE rtl_lockstep_inject
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rtl_test_util.hpp"

using namespace rtltest;
namespace fs = std::filesystem;

#ifndef RTL_TEST_PERIODIC
#define RTL_TEST_PERIODIC 0
#endif
#ifndef RTL_TEST_FST
#define RTL_TEST_FST 0
#endif

#if !RTL_TEST_PERIODIC
BOOST_AUTO_TEST_CASE(injected_fault_is_caught_with_waves) {
    const isa::MachineConfig cfg = rtl_config(RTL_TEST_FST ? 16 : 8);
    const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
    const auto left = image(10, 3, 1), right = image(10, 3, 90);
    // The state of r5 of PE 3 right after instruction 21 (bare machine).
    isa::Machine m(cfg);
    m.load(prog);
    for (const auto& [i, v] : kParams) m.set_param(i, v);
    isa::ImageVideoPort video;
    video.input[0] = left;
    video.input[1] = right;
    video.make_output(0, kOutW, kOutH);
    video.make_output(1, kOutW, kOutH);
    m.set_video(&video);
    for (int i = 0; i <= 21; ++i) m.step();
    const uint8_t good = m.reg(3, 5);

    rtl::LockstepConfig lc;
    lc.rtl.inject = rtl::parse_fault_injection("20:3:r5:0x24");
    BOOST_CHECK_EQUAL(lc.rtl.inject.reg, 5);
    BOOST_CHECK_THROW(rtl::parse_fault_injection("20:3:r5"), isa::ConfigError);
    BOOST_CHECK_THROW(rtl::parse_fault_injection("x:3:r5:1"), isa::ConfigError);
    const fs::path dir = fs::temp_directory_path() / ("rtl-inject-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    if (RTL_TEST_FST)
        BOOST_CHECK_EQUAL(fs::path(lc.divergence_waves).extension(), ".fst");  // the default
    lc.divergence_waves = (dir / (RTL_TEST_FST ? "div.fst" : "div.vcd")).string();
    lc.waves_cycles = 30;
    rtl::OutputImages out;
    const rtl::LockstepResult r =
        rtl::run_lockstep(cfg, prog, kParams, left, right, kOutW, kOutH, &out, lc);
    BOOST_REQUIRE(r.diverged);
    const rtl::Divergence& d = r.divergence;
    BOOST_TEST_MESSAGE(d.message());
    BOOST_CHECK_EQUAL(d.instruction, 21u);
    BOOST_CHECK_EQUAL(d.what, "r5");
    BOOST_CHECK_EQUAL(d.pe, 3);
    BOOST_CHECK_EQUAL(d.tlm_value, good);
    BOOST_CHECK_EQUAL(d.rtl_value, uint64_t(good ^ 0x24));
    BOOST_CHECK_EQUAL(d.pc, m.pc() - 1);
    BOOST_CHECK(!d.disassembly.empty());
    BOOST_CHECK(d.message().find("PE 3") != std::string::npos);
    // the waves of the machine cycles before it, with the design's signals
    BOOST_CHECK(d.message().find("-> " + lc.divergence_waves) != std::string::npos);
    BOOST_REQUIRE(fs::exists(lc.divergence_waves));
    BOOST_CHECK(fs::exists(dir / "div.gtkw"));
    BOOST_CHECK(!fs::exists(lc.divergence_waves + ".part"));
    auto read = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    };
    const std::string waves = read(lc.divergence_waves);
    if (RTL_TEST_FST) {
        // an FST file: its first block is the header (block type 0), and
        // the view names the design's signals
        BOOST_REQUIRE_GT(waves.size(), 100u);
        BOOST_CHECK_EQUAL(int(waves[0]), 0);
        const std::string view = read(dir / "div.gtkw");
        BOOST_CHECK(view.find("u_cp") != std::string::npos);
        BOOST_CHECK(view.find("g_pe[3]") != std::string::npos);
    } else {
        BOOST_CHECK(waves.find("$scope module u_cp $end") != std::string::npos);
        BOOST_CHECK(waves.find(" mcycle ") != std::string::npos);
        BOOST_CHECK(waves.find("$scope module g_pe[3] $end") != std::string::npos);
    }
    fs::remove_all(dir);
}
#else
BOOST_AUTO_TEST_CASE(injected_fault_is_caught_by_the_periodic_full_compare) {
    const isa::MachineConfig cfg = rtl_config(8);
    const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
    const auto left = image(10, 3, 1), right = image(10, 3, 90);
    rtl::LockstepConfig lc;
    lc.rtl.inject = rtl::parse_fault_injection("20:3:r6:0x24");
    lc.divergence_waves = "";
    lc.full_compare_every = 8;  // full compares after instructions 7, 15, 23, ...
    rtl::OutputImages out;
    const rtl::LockstepResult r =
        rtl::run_lockstep(cfg, prog, kParams, left, right, kOutW, kOutH, &out, lc);
    BOOST_REQUIRE(r.diverged);
    const rtl::Divergence& d = r.divergence;
    BOOST_TEST_MESSAGE(d.message());
    BOOST_CHECK_EQUAL(d.what, "r6");
    BOOST_CHECK_EQUAL(d.pe, 3);
    // instructions 21 (rall c5) and 22 (cgeui r7) do not name r6: the full
    // compare after instruction 23 finds it and says which instructions can
    // have written it
    BOOST_CHECK_EQUAL(d.instruction, 23u);
    BOOST_CHECK(d.detail.find("full-state compare every 8 instructions") != std::string::npos);
    BOOST_CHECK(d.detail.find("instructions 16..23") != std::string::npos);
}
#endif
