// Machine parameters: validation messages, setting by name, listing.
#define BOOST_TEST_MODULE isa_config
#include <boost/test/unit_test.hpp>
#include <charconv>
#include <string>

#include "helpers.hpp"

using namespace isatest;

namespace {
std::string config_error(const std::function<void(MachineConfig&)>& f) {
    MachineConfig c;
    try {
        f(c);
        c.validate();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "valid";
}
}  // namespace

BOOST_AUTO_TEST_CASE(defaults_are_the_board) {
    const MachineConfig c;
    BOOST_CHECK_NO_THROW(c.validate());
    BOOST_CHECK_EQUAL(c.pes, 256);
    BOOST_CHECK_EQUAL(c.clock_mhz, 40.0);
    BOOST_CHECK_EQUAL(c.mem_bytes, 1024u);
    BOOST_CHECK_CLOSE(c.seconds(40000000), 1.0, 1e-12);
}

BOOST_AUTO_TEST_CASE(validation_names_parameter_value_and_range) {
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.pes = 1; }),
                      "invalid value 1 for pes: allowed 2..65536");
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.pe_regs = 65; }),
                      "invalid value 65 for pe_regs: allowed 1..64");
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.costs.alu = 0; }),
                      "invalid value 0 for alu: allowed 1..1000000 cycles");
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.clock_mhz = 0; }),
                      "invalid value 0 for clock_mhz: allowed a number > 0 and <= 100000");
    BOOST_CHECK(config_error([](MachineConfig& c) {
                    c.pes = 65536;
                    c.ext_bytes = 1 << 16;
                }).find("exceeds the model's limit") != std::string::npos);
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.set("pes", "abc"); }),
                      "invalid value 'abc' for pes: expected an integer");
    BOOST_CHECK_EQUAL(config_error([](MachineConfig& c) { c.set("mask_depth", "0"); }),
                      "invalid value 0 for mask_depth: allowed 1..255");
    BOOST_CHECK(config_error([](MachineConfig& c) {
                    c.set("warp", "9");
                }).find("unknown machine parameter 'warp'") == 0);
    BOOST_CHECK(config_error([](MachineConfig& c) {
                    c.costs.set("warp", 9);
                }).find("unknown cost parameter 'warp'") == 0);
    BOOST_CHECK_THROW(Machine{[] {
                          MachineConfig c;
                          c.pes = 1;
                          return c;
                      }()},
                      ConfigError);
}

BOOST_AUTO_TEST_CASE(set_by_name) {
    MachineConfig c;
    c.costs.set("ring_hop", 2);
    BOOST_CHECK_EQUAL(c.costs.ring_hop, 2u);
    BOOST_CHECK_EQUAL(c.costs.get("ring_hop"), 2u);
    c.set("ext_bytes_per_cycle", "3");
    c.set("shift_bits", "1");
    c.set("minmax_extra", "1");
    c.set("pes", "128");
    c.set("indirect", "off");
    c.set("clock_mhz", "33.3");
    c.set("ext_bytes", "0");
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 3u);
    BOOST_CHECK_EQUAL(c.costs.shift_bits, 1u);
    BOOST_CHECK_EQUAL(c.costs.minmax_extra, 1u);
    BOOST_CHECK_EQUAL(c.pes, 128);
    BOOST_CHECK(!c.indirect);
    BOOST_CHECK_CLOSE(c.clock_mhz, 33.3, 1e-9);
    BOOST_CHECK_EQUAL(c.ext_bytes, 0u);
    BOOST_CHECK_NO_THROW(c.validate());
}

BOOST_AUTO_TEST_CASE(every_parameter_is_listed_with_docs) {
    MachineConfig c;
    c.costs.ring_hop = 5;
    const std::vector<ParamInfo> l = c.list();
    BOOST_CHECK_EQUAL(l.size(), 9u + CostTable::fields().size() + BoardTiming::fields().size() +
                                    1u /* tech */ + EnergyTable::fields().size());
    for (const ParamInfo& p : l) {
        BOOST_CHECK(!p.name.empty());
        BOOST_CHECK(!p.doc.empty());
        BOOST_CHECK(!p.range.empty());
        BOOST_CHECK(p.group == "machine" || p.group == "cost" || p.group == "board" ||
                    p.group == "energy");
        if (p.name == "ring_hop") BOOST_CHECK_EQUAL(p.value, "5");
        if (p.name == "pes") BOOST_CHECK(!p.assumption);
        if (p.name == "pe_regs") BOOST_CHECK(p.assumption);
    }
    // Every listed name can be set back by name.
    MachineConfig d;
    for (const ParamInfo& p : l) BOOST_CHECK_NO_THROW(d.set(p.name, p.value));
    BOOST_CHECK_EQUAL(d.costs.ring_hop, 5u);
}

// Issue 13 item 6: modeled milliseconds with one rounding, so that a report
// shows 288878 cycles at 40 MHz as 7.22195 (cycles x 25 ns: at most six
// decimals), not 7.2219500000000005 (seconds() x 1000 rounds twice).
BOOST_AUTO_TEST_CASE(milliseconds_have_no_float_noise) {
    imap::isa::MachineConfig cfg;  // 40 MHz
    BOOST_TEST(cfg.milliseconds(288878) == 7.22195);
    int noisy = 0;
    for (uint64_t c = 0; c < 200000; c += 7) {
        char buf[64];
        const auto res = std::to_chars(buf, buf + sizeof buf, cfg.milliseconds(c));
        const std::string s(buf, res.ptr);
        const size_t dot = s.find('.');
        noisy += dot != std::string::npos && s.size() - dot - 1 > 6;
    }
    BOOST_TEST(noisy == 0);
}
