// The configurations of the design in this build: PE count and memory
// sizes are HDL parameters, so a configuration that was not verilated is
// refused with the exact command that builds it (never replaced by
// another), and run-time parameters beyond the HDL's sizes are refused with
// what is needed and what the design has. With building on demand off
// (IMAP_RTL_CACHE=off; the RTL cache itself is tested by cli.rtl_cache).
#define BOOST_TEST_MODULE rtl_configs
#include <boost/test/unit_test.hpp>
#include <cstdlib>

#include "rtl_test_util.hpp"

using namespace rtltest;

namespace {
// the refusals below are those of a process without the RTL cache
const bool kCacheOff = [] {
    ::setenv("IMAP_RTL_CACHE", "off", 1);
    return true;
}();
// waves: 0 none, 1 VCD, 2 FST (rtl::waves_format)
std::string refusal(const isa::MachineConfig& cfg, int waves = 0) {
    try {
        rtl::check_runnable(cfg, waves);
    } catch (const isa::ConfigError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

BOOST_AUTO_TEST_CASE(built_configurations_run) {
    isa::MachineConfig cfg;
    cfg.pes = 8;
    BOOST_CHECK(rtl::has_configuration(cfg));
    BOOST_CHECK_EQUAL(refusal(cfg), "");
    BOOST_CHECK_EQUAL(refusal(cfg, 1), "");  // the VCD variant (IMAP_RTL_TRACE_CONFIGS)
    BOOST_CHECK_EQUAL(refusal(cfg, 2), "");  // FST
    BOOST_CHECK_EQUAL(rtl::waves_format(""), 0);
    BOOST_CHECK_EQUAL(rtl::waves_format("w.vcd"), 1);
    BOOST_CHECK_EQUAL(rtl::waves_format("d/w.fst"), 2);
    const auto list = rtl::built_configurations();
    BOOST_CHECK(std::find(list.begin(), list.end(), "p8_m1024_x65536 (VCD waves)") != list.end());
    BOOST_CHECK(std::find(list.begin(), list.end(), "p8_m1024_x65536 (FST waves)") != list.end() ||
                std::find(list.begin(), list.end(), "p8_m1024_x65536") != list.end());
}

BOOST_AUTO_TEST_CASE(unbuilt_configuration_says_what_to_run) {
    isa::MachineConfig cfg;
    cfg.pes = 77;
    BOOST_CHECK(!rtl::has_configuration(cfg));
    const std::string m = refusal(cfg);
    BOOST_TEST_MESSAGE(m);
    BOOST_CHECK(kCacheOff);
    BOOST_CHECK(m.find("no configuration pes=77 mem_bytes=1024 ext_bytes=65536") !=
                std::string::npos);
    BOOST_CHECK(m.find("building on demand is off (IMAP_RTL_CACHE=off)") != std::string::npos);
    BOOST_CHECK(m.find("-DIMAP_RTL_EXTRA_CONFIGS=\"") != std::string::npos);
    BOOST_CHECK(m.find("77:1024:65536\"") != std::string::npos);
    BOOST_CHECK(m.find("cmake --build") != std::string::npos);
    cfg.pes = 8;
    cfg.mem_bytes = 512;
    BOOST_CHECK(refusal(cfg).find("8:512:65536") != std::string::npos);
    // an unbuilt configuration never runs on another one
    cfg.mem_bytes = 1024;
    cfg.pes = 77;
    BOOST_CHECK_THROW(rtl::run_rtl(cfg, isa::assemble_string("halt\n"), {}, {}, {}, 0, 0, nullptr),
                      isa::ConfigError);
    // 16 PEs: no VCD variant; FST waves exactly when its model has FST
    // tracing in (IMAP_RTL_FST_ALL, the default), else the command
    cfg.pes = 16;
    BOOST_CHECK(rtl::has_configuration(cfg));
    BOOST_CHECK_EQUAL(refusal(cfg), "");
    const std::string vcd = refusal(cfg, 1);
    BOOST_TEST_MESSAGE(vcd);
    BOOST_CHECK(vcd.find("no VCD-traced configuration pes=16") != std::string::npos);
    BOOST_CHECK(vcd.find("-DIMAP_RTL_TRACE_CONFIGS=") != std::string::npos);
    BOOST_CHECK(vcd.find("16:1024:65536\"") != std::string::npos);
    const auto list = rtl::built_configurations();
    const bool fst16 =
        std::find(list.begin(), list.end(), "p16_m1024_x65536 (FST waves)") != list.end();
    const std::string fst = refusal(cfg, 2);
    BOOST_CHECK_EQUAL(fst.empty(), fst16);
    if (!fst16) BOOST_CHECK(fst.find("-DIMAP_RTL_TRACE_CONFIGS=") != std::string::npos);
    // an unbuilt configuration asked with FST waves: one command builds it
    // with them
    cfg.pes = 77;
    const std::string m77 = refusal(cfg, 2);
    BOOST_CHECK(m77.find("no configuration pes=77") != std::string::npos);
    BOOST_CHECK(m77.find("77:1024:65536\"") != std::string::npos);
    BOOST_CHECK(m77.find(fst16 ? "-DIMAP_RTL_EXTRA_CONFIGS=" : "-DIMAP_RTL_TRACE_CONFIGS=") !=
                std::string::npos);
}

BOOST_AUTO_TEST_CASE(run_time_parameters_beyond_the_hdl) {
    isa::MachineConfig cfg;
    cfg.pes = 8;
    cfg.pe_regs = 32;
    BOOST_CHECK(refusal(cfg).find("pe_regs = 32") != std::string::npos);
    cfg.pe_regs = 16;
    cfg.mask_depth = 9;
    BOOST_CHECK(refusal(cfg).find("mask_depth = 9") != std::string::npos);
    cfg.mask_depth = 8;
    cfg.call_depth = 17;
    BOOST_CHECK(refusal(cfg).find("call_depth = 17") != std::string::npos);
    cfg.call_depth = 8;
    cfg.costs.ext_bytes_per_cycle = 9;  // > 8 rows of one byte (one PE active)
    BOOST_CHECK(refusal(cfg).find("ext_bytes_per_cycle = 9") != std::string::npos);
    cfg.costs.ext_bytes_per_cycle = 8;
    BOOST_CHECK_EQUAL(refusal(cfg), "");
    BOOST_CHECK_THROW(rtl::check_runnable(cfg, false, false, 70000), isa::ConfigError);
}
