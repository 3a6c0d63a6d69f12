// The configurations of the design in this build: PE count and memory
// sizes are HDL parameters, so a configuration that was not verilated is
// refused with the exact command that builds it (never replaced by
// another), and run-time parameters beyond the HDL's sizes are refused with
// what is needed and what the design has.
#define BOOST_TEST_MODULE rtl_configs
#include <boost/test/unit_test.hpp>

#include "rtl_test_util.hpp"

using namespace rtltest;

namespace {
std::string refusal(const isa::MachineConfig& cfg, bool waves = false) {
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
    BOOST_CHECK_EQUAL(refusal(cfg, true), "");  // the traced variant
    const auto list = rtl::built_configurations();
    BOOST_CHECK(std::find(list.begin(), list.end(), "p8_m1024_x65536") != list.end());
}

BOOST_AUTO_TEST_CASE(unbuilt_configuration_says_what_to_run) {
    isa::MachineConfig cfg;
    cfg.pes = 77;
    BOOST_CHECK(!rtl::has_configuration(cfg));
    const std::string m = refusal(cfg);
    BOOST_TEST_MESSAGE(m);
    BOOST_CHECK(m.find("no configuration pes=77 mem_bytes=1024 ext_bytes=65536") !=
                std::string::npos);
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
    cfg.pes = 16;  // fast, but no traced variant
    BOOST_CHECK(refusal(cfg, true).find("-DIMAP_RTL_TRACE_CONFIGS=") != std::string::npos);
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
    cfg.costs.ext_bytes_per_cycle = 33;  // > 4 rows x 8 PEs
    BOOST_CHECK(refusal(cfg).find("ext_bytes_per_cycle = 33") != std::string::npos);
    cfg.costs.ext_bytes_per_cycle = 32;
    BOOST_CHECK_EQUAL(refusal(cfg), "");
    BOOST_CHECK_THROW(rtl::check_runnable(cfg, false, false, 70000), isa::ConfigError);
}
