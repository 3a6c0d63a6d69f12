// The place-and-route figures of the design (scripts/rtl-pnr.sh, checked in
// as rtl_model/synth/pnr_ice40.json and embedded by the build): they parse,
// name the device, and state the Fmax against a clock; bad figures are
// rejected with the field named.
#define BOOST_TEST_MODULE rtl_pnr
#include <boost/test/unit_test.hpp>
#include <stdexcept>
#include <string>

#include "imap/rtl/pnr.hpp"

namespace rtl = imap::rtl;

BOOST_AUTO_TEST_CASE(embedded_figures_parse_and_name_the_device) {
    const rtl::PnrFigures& f = rtl::place_and_route();
    BOOST_REQUIRE(f.available);
    BOOST_TEST_MESSAGE(f.configuration << " on " << f.technology << ": " << f.pe.lut4 << " LUT4, "
                                       << f.pe.ff << " FF, " << f.pe.bram << " BRAM, Fmax "
                                       << f.fmax_mhz << " MHz; CP " << f.cp.lut4 << " LUT4; "
                                       << f.tool);
    BOOST_TEST(f.technology.rfind("iCE40 ", 0) == 0u, f.technology);
    BOOST_TEST(!f.package.empty());
    BOOST_TEST(f.tool.find("nextpnr-ice40") != std::string::npos, f.tool);
    BOOST_TEST(f.configuration.find("PE") != std::string::npos, f.configuration);
    BOOST_TEST(f.pe.lut4 > 0u);
    BOOST_TEST(f.pe.ff > 0u);
    BOOST_TEST(f.logic_cells <= f.logic_cells_available);  // it fits the device
    // the CP: synthesized; the text says whether it fits
    BOOST_TEST(f.cp.lut4 > 0u);
    BOOST_TEST(f.cp.bram > 0u);  // its instruction memory is block RAM (registered read)
    BOOST_TEST(f.cp_fits == (f.cp.lut4 <= f.logic_cells_available));
    BOOST_TEST(f.fmax_mhz > 1.0);
    BOOST_TEST(f.fmax_mhz < 500.0);  // an iCE40 runs nothing near 500 MHz
    // the local memory of 1 KB is the eight banks in block RAMs, not in
    // flip-flops (its 8,192 bits would be 8,192 flip-flops), in the placed
    // PE and in the PE synthesized alone
    BOOST_TEST(f.pe.bram == 8u);
    BOOST_TEST(f.pe1k.bram == 8u);
    BOOST_TEST(f.pe1k.ff < 8192u);
    BOOST_TEST(f.pe.ff < 8192u);
    // the whole chip (2 PEs): synthesized; whether it fits
    BOOST_TEST(f.chip.lut4 > f.cp.lut4 / 2);
    BOOST_TEST(f.chip.bram >= 2 * 8u);  // two PEs' banks at least
    BOOST_TEST(f.chip_fits == (f.chip.lut4 <= f.logic_cells_available));
}

BOOST_AUTO_TEST_CASE(figures_are_of_this_design) {
    // an HDL change without a new run of scripts/rtl-pnr.sh fails here
    const rtl::PnrFigures& f = rtl::place_and_route();
    BOOST_REQUIRE(f.available);
    BOOST_TEST(f.hdl_sha256.size() == 64u);
    BOOST_TEST(f.hdl_sha256 == rtl::design_sha256(),
               "the place-and-route figures (rtl_model/synth/pnr_ice40.json) are of another "
               "design: run scripts/rtl-pnr.sh");
}

BOOST_AUTO_TEST_CASE(the_fmax_against_a_clock) {
    const rtl::PnrFigures& f = rtl::place_and_route();
    BOOST_REQUIRE(f.available);
    const double below = f.fmax_mhz / 2, above = f.fmax_mhz * 2;
    BOOST_TEST(!rtl::above_fmax(f, below));
    BOOST_TEST(!rtl::above_fmax(f, f.fmax_mhz));  // at Fmax: reached
    BOOST_TEST(rtl::above_fmax(f, above));
    const std::string a = rtl::fmax_text(f, above), b = rtl::fmax_text(f, below);
    BOOST_TEST(a.rfind("design Fmax: ", 0) == 0u, a);
    BOOST_TEST(a.find(f.technology) != std::string::npos, a);
    BOOST_TEST(a.find("clock is above it") != std::string::npos, a);
    BOOST_TEST((a.find("at most") != std::string::npos) == !f.cp_fits, a);
    BOOST_TEST(b.find("clock is within it") != std::string::npos, b);
    BOOST_TEST(rtl::fmax_text(rtl::PnrFigures{}, 40).empty());
    BOOST_TEST(!rtl::above_fmax(rtl::PnrFigures{}, 1e9));
}

namespace {
std::string figures(const std::string& pe) {
    return R"({"technology": "iCE40 HX8K", "package": "ct256",
               "tools": {"nextpnr": "nextpnr-ice40 0.4"},
               "configuration": {"text": "one PE of 32 bytes; the CP does not fit"},
               "pe": )" +
           pe + R"(, "cp": {"lut4": 9000, "ff": 2000, "bram": 6, "fits": false},
               "pe_1k": {"lut4": 100, "ff": 9000, "bram": 0}})";
}
void rejected(const std::string& text, const std::string& what) {
    try {
        rtl::parse_pnr(text);
        BOOST_ERROR("accepted: " << text);
    } catch (const std::runtime_error& e) {
        BOOST_TEST(std::string(e.what()).find(what) != std::string::npos, e.what());
    }
}
}  // namespace

BOOST_AUTO_TEST_CASE(bad_figures_name_the_field) {
    const std::string ok =
        R"({"lut4": 10, "ff": 5, "bram": 1, "logic_cells": 12, "logic_cells_available": 7680,
            "fmax_mhz": 30.5})";
    BOOST_TEST(rtl::parse_pnr(figures(ok)).fmax_mhz == 30.5);
    rejected(figures(R"({"lut4": 10, "ff": 5, "logic_cells": 12, "logic_cells_available": 7680})"),
             "pe.fmax_mhz");
    rejected(figures(R"({"lut4": 10, "ff": 5, "logic_cells": 12, "logic_cells_available": 7680,
                         "fmax_mhz": 0})"),
             "pe.fmax_mhz");
    rejected(figures(R"({"ff": 5, "logic_cells": 12, "logic_cells_available": 7680,
                         "fmax_mhz": 3})"),
             "pe.lut4");
    // the chip's figures are optional; when present, they are checked
    std::string chip = figures(ok);
    chip.insert(chip.rfind('}'),
                R"(, "chip": {"lut4": 12000, "ff": 2400, "bram": 22, "fits": false})");
    const rtl::PnrFigures c = rtl::parse_pnr(chip);
    BOOST_TEST(c.chip.lut4 == 12000u);
    BOOST_TEST(c.chip.bram == 22u);
    BOOST_TEST(!c.chip_fits);
    BOOST_TEST(rtl::parse_pnr(figures(ok)).chip.lut4 == 0u);
    std::string bad_chip = figures(ok);
    bad_chip.insert(bad_chip.rfind('}'), R"(, "chip": {"ff": 2400})");
    rejected(bad_chip, "chip.lut4");
    rejected("{", "not JSON");
    rejected(R"({"package": "ct256"})", "technology");
}
