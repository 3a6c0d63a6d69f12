// engine.model_run: the firmware run through the library (run_model) on the
// core model for a small frame, checked against the golden reference, and the
// run report's fields against the plan and the run; the flag values and the
// machine settings; compare_maps on a planted difference.
#define BOOST_TEST_MODULE engine_model_run
#include <boost/test/unit_test.hpp>
#include <numeric>

#include "imap/engine/error.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/model_run.hpp"
#include "imap/engine/models.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/synth.hpp"

namespace e = imap::engine;
namespace g = imap::golden;
namespace v = imap::vision;

namespace {

struct Frame {
    v::SynthScene sc = v::make_synth_scene(3, 32, 8);
    g::Params p;
    g::Roi roi{0, 0, 32, 8};
    imap::isa::MachineConfig cfg;
    Frame() {
        p.D = 8;
        e::MachineSettings m;
        m.pes = "8";
        cfg = e::machine_config(m);
    }
};

}  // namespace

BOOST_AUTO_TEST_CASE(core_run_matches_the_golden) {
    Frame f;
    const g::ImageView l = v::view_of(f.sc.left), r = v::view_of(f.sc.right);
    const e::ModelRun run = e::run_model("core", f.p, f.roi, l, r, f.cfg);
    const g::DisparityMap want = g::compute(f.p, l, r, f.roi);
    BOOST_TEST(run.model == "core");
    BOOST_TEST(run.divergence.empty());
    BOOST_REQUIRE(run.result.map.width == 32);
    BOOST_REQUIRE(run.result.map.height == 8);
    BOOST_TEST(run.result.map.data == want.data, boost::test_tools::per_element());
    const e::Comparison cmp = e::compare_maps(run.result.map, want);
    BOOST_TEST(cmp.equal);
    BOOST_TEST(cmp.differing == 0u);
}

BOOST_AUTO_TEST_CASE(report_fields_agree_with_the_plan_and_the_run) {
    Frame f;
    const g::ImageView l = v::view_of(f.sc.left), r = v::view_of(f.sc.right);
    const e::ModelRun run = e::run_model("core", f.p, f.roi, l, r, f.cfg);
    const g::DisparityMap want = g::compute(f.p, l, r, f.roi);
    const nlohmann::json j =
        e::run_report(run, e::compare_maps(run.result.map, want), f.p, f.roi, f.cfg, 1.5);
    BOOST_TEST(j.at("bit_exact").get<bool>());
    BOOST_TEST(j.at("golden_ms").get<double>() == 1.5);
    const uint64_t cycles = j.at("cycles").get<uint64_t>();
    BOOST_TEST(cycles == run.result.cycles);
    uint64_t phase_sum = 0;
    for (const auto& [k, c] : j.at("phases").items()) phase_sum += c.get<uint64_t>();
    BOOST_TEST(phase_sum == cycles);
    uint64_t bound_sum = 0;
    for (const auto& [k, c] : j.at("bounds").items()) bound_sum += c.get<uint64_t>();
    BOOST_TEST(j.at("bound_cycles").get<uint64_t>() == bound_sum);
    BOOST_TEST(bound_sum > 0u);
    BOOST_TEST(bound_sum <= cycles);
    BOOST_TEST(j.at("efficiency").get<double>() ==
               static_cast<double>(bound_sum) / static_cast<double>(cycles));
    BOOST_TEST(j.at("modeled_ms").get<double>() == static_cast<double>(cycles) / 40e3);
    const nlohmann::json& fw = j.at("params").at("firmware");
    BOOST_TEST(fw.at("words").get<size_t>() == run.program.code.size());
    BOOST_TEST(fw.at("batches").get<size_t>() == run.plan.batches.size());
    BOOST_TEST(fw.at("segments").get<int>() == 4);  // 32 columns on 8 PEs
    BOOST_TEST(j.at("params").at("machine").at("pes").get<int>() == 8);
    BOOST_TEST(j.at("params").at("algorithm").at("D").get<int>() == 8);
    BOOST_TEST(j.at("params").at("algorithm").at("roi") == nlohmann::json({0, 0, 32, 8}));
    // The energy: every class adds up to the total; the tornado brackets it.
    const nlohmann::json& en = j.at("energy");
    double by_class = 0;
    for (const auto& [k, uj] : en.at("by_class").items()) by_class += uj.get<double>();
    BOOST_TEST(by_class == en.at("total_uj").get<double>(), boost::test_tools::tolerance(1e-9));
    BOOST_TEST(en.at("total_uj").get<double>() ==
                   en.at("dynamic_uj").get<double>() + en.at("static_uj").get<double>(),
               boost::test_tools::tolerance(1e-9));
    BOOST_TEST(en.at("events").at("cycles").get<uint64_t>() == cycles);
    BOOST_TEST(en.at("events_source") == "isa");
    BOOST_REQUIRE(!en.at("tornado").empty());
    for (const auto& t : en.at("tornado")) {
        BOOST_TEST(t.at("half_uj").get<double>() <= en.at("total_uj").get<double>() + 1e-12);
        BOOST_TEST(t.at("double_uj").get<double>() >= en.at("total_uj").get<double>() - 1e-12);
    }
    BOOST_TEST(!j.contains("first_difference"));
}

BOOST_AUTO_TEST_CASE(a_planted_difference_is_found) {
    g::DisparityMap a;
    a.width = 4;
    a.height = 3;
    a.data.assign(12, 2);
    g::DisparityMap b = a;
    b.data[6] = 5;  // (2, 1)
    b.data[11] = 7;
    const e::Comparison c = e::compare_maps(b, a);
    BOOST_TEST(!c.equal);
    BOOST_TEST(c.differing == 2u);
    BOOST_TEST(c.first_x == 2);
    BOOST_TEST(c.first_y == 1);
    BOOST_TEST(c.model_value == 5);
    BOOST_TEST(c.golden_value == 2);
}

BOOST_AUTO_TEST_CASE(a_frame_that_does_not_fit_is_an_input_error) {
    Frame f;
    f.p.D = 8;
    e::MachineSettings m;
    m.pes = "8";
    m.mem_bytes = "64";
    const imap::isa::MachineConfig small = e::machine_config(m);
    const g::ImageView l = v::view_of(f.sc.left), r = v::view_of(f.sc.right);
    try {
        e::run_model("core", f.p, f.roi, l, r, small);
        BOOST_FAIL("expected an engine::Error");
    } catch (const e::Error& err) {
        BOOST_TEST(err.code() == e::kExitInput);
    }
}

BOOST_AUTO_TEST_CASE(flag_values_and_machine_settings) {
    BOOST_TEST(e::camera_pixel_mhz("ideal") == "0");
    BOOST_TEST(e::camera_pixel_mhz("ntsc") == "12.2727");
    BOOST_TEST(e::camera_pixel_mhz("pixel-clock:12.5") == "12.5");
    for (const char* bad :
         {"pixel-clock:0", "pixel-clock:-3", "pixel-clock:abc", "pixel-clock:", "pal"})
        BOOST_CHECK_THROW(e::camera_pixel_mhz(bad), e::Error);
    BOOST_TEST(e::parse_int_flag("--n", "42", 0, 100) == 42);
    BOOST_CHECK_THROW(e::parse_int_flag("--n", "101", 0, 100), e::Error);
    BOOST_CHECK_THROW(e::parse_int_flag("--n", "4x", 0, 100), e::Error);
    BOOST_TEST(e::parse_real_flag("--r", "2.5", 0, 10, true) == 2.5);
    BOOST_CHECK_THROW(e::parse_real_flag("--r", "0", 0, 10, true), e::Error);
    int w = 0, h = 0;
    e::parse_size_flag("--size", "32x8", 1, 64, &w, &h);
    BOOST_TEST(w == 32);
    BOOST_TEST(h == 8);
    e::MachineSettings m;
    m.pes = "16";
    m.clock_mhz = "80";
    m.camera = "pixel-clock:10";
    m.sets = {"ring_hop=2"};
    const imap::isa::MachineConfig cfg = e::machine_config(m);
    BOOST_TEST(cfg.pes == 16);
    BOOST_TEST(cfg.clock_mhz == 80.0);
    BOOST_TEST(cfg.board.camera_pixel_mhz == 10.0);
    m.sets = {"ring_hop"};
    BOOST_CHECK_THROW(e::machine_config(m), e::Error);
    m.sets = {"no_such_parameter=1"};
    BOOST_CHECK_THROW(e::machine_config(m), e::Error);
}

// The design's Fmax (docs/rtl.md, "Place and route (iCE40)"): the run
// summary's RTL lines and the report's "design_fmax" state it against the
// clock, above it at 1000 MHz, within it at 1 MHz.
BOOST_AUTO_TEST_CASE(the_report_and_summary_carry_the_design_fmax) {
    Frame f;
    const g::ImageView l = v::view_of(f.sc.left), r = v::view_of(f.sc.right);
    const e::ModelRun run = e::run_model("core", f.p, f.roi, l, r, f.cfg);
    const g::DisparityMap want = g::compute(f.p, l, r, f.roi);
    for (const double clock : {1.0, 1000.0}) {
        imap::isa::MachineConfig cfg = f.cfg;
        cfg.clock_mhz = clock;
        const nlohmann::json fmax = e::fmax_json(cfg);
        BOOST_REQUIRE(fmax.is_object());  // this build has the RTL and the figures
        const nlohmann::json j = e::run_report(run, e::compare_maps(run.result.map, want), f.p,
                                               f.roi, cfg, 1.5, e::area_json(cfg), fmax);
        const nlohmann::json& d = j.at("design_fmax");
        BOOST_TEST(d.at("mhz").get<double>() > 1.0);
        BOOST_TEST(d.at("clock_mhz").get<double>() == clock);
        BOOST_TEST(d.at("clock_above").get<bool>() == (clock > 500));
        BOOST_TEST(d.at("technology").get<std::string>().rfind("iCE40", 0) == 0u);
        const std::vector<std::string> lines = e::rtl_area_lines(clock);
        BOOST_REQUIRE_EQUAL(lines.size(), 2u);
        BOOST_TEST(lines[1] == "  RTL " + d.at("text").get<std::string>());
        BOOST_TEST(lines[1].find(clock > 500 ? "clock is above it" : "clock is within it") !=
                       std::string::npos,
                   lines[1]);
    }
}
