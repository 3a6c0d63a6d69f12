// imapsim run from the outside: the firmware on the default model over the
// shared Middlebury scenes (ROIs and whole images), the JSON report, and the
// machine-flag errors.
#define BOOST_TEST_MODULE cli_run
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_test_util.hpp"
#include "imap/isa/board.hpp"
#include "imap/isa/energy.hpp"

namespace fs = std::filesystem;

namespace {

using clitest::Result;
using clitest::run;

std::string scene(const std::string& name) {
    const std::string d = std::string(IMAP_SHARED_DATA) + "/middlebury/" + name;
    return "--left " + d + "/left.png --right " + d + "/right.png";
}

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imapsim-cli-run-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

}  // namespace

BOOST_AUTO_TEST_CASE(middlebury_rois_bit_exact) {
    const std::pair<const char*, int> scenes[] = {
        {"tsukuba", 16}, {"venus", 20}, {"teddy", 60}, {"cones", 60}};
    for (const auto& [name, ndisp] : scenes) {
        for (const char* roi : {"100,100,128,128", "0,0,64,200"}) {
            const Result r =
                run("run " + scene(name) + " --D " + std::to_string(ndisp) + " --roi " + roi);
            BOOST_TEST_CONTEXT(name << " roi " << roi << "\n" << r.out) {
                BOOST_TEST(r.code == 0);
                BOOST_TEST(r.out.find("bit-exact vs golden: yes") != std::string::npos);
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(middlebury_whole_images_bit_exact) {
    const std::pair<const char*, int> scenes[] = {
        {"tsukuba", 16}, {"venus", 20}, {"teddy", 60}, {"cones", 60}};
    for (const auto& [name, ndisp] : scenes) {
        const Result r = run("run " + scene(name) + " --D " + std::to_string(ndisp));
        BOOST_TEST_CONTEXT(name << "\n" << r.out) {
            BOOST_TEST(r.code == 0);
            BOOST_TEST(r.out.find("bit-exact vs golden: yes") != std::string::npos);
        }
    }
}

BOOST_AUTO_TEST_CASE(report_has_the_documented_keys) {
    const fs::path d = tmpdir();
    const std::string rep = (d / "r.json").string();
    const Result r = run("run --report " + rep + " --out " + (d / "d.png").string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    std::ifstream in(rep);
    const nlohmann::json j = nlohmann::json::parse(in);
    BOOST_TEST(j.at("bit_exact").get<bool>());
    BOOST_TEST(j.at("cycles").get<uint64_t>() > 0);
    BOOST_TEST(j.at("modeled_ms").get<double>() > 0);
    BOOST_TEST(j.at("wall_s").get<double>() >= 0);
    BOOST_TEST(j.at("phases").is_object());
    BOOST_TEST(j.at("phases").at("forward").get<uint64_t>() > 0);
    // The machine's bound per phase (docs/firmware.md 11): each under its
    // phase, the frame's bound their sum, efficiency bound / cycles.
    uint64_t bsum = 0;
    for (const auto& [ph, b] : j.at("bounds").items()) {
        BOOST_TEST_INFO("bound of " << ph);
        BOOST_TEST(b.get<uint64_t>() <= j.at("phases").at(ph).get<uint64_t>());
        bsum += b.get<uint64_t>();
    }
    BOOST_TEST(j.at("bounds").contains("forward"));
    BOOST_TEST(j.at("bound_cycles").get<uint64_t>() == bsum);
    BOOST_TEST(
        j.at("efficiency").get<double>() == double(bsum) / double(j.at("cycles").get<uint64_t>()),
        boost::test_tools::tolerance(1e-9));
    BOOST_TEST(j.at("bound_basis").at("node_cycles") == 29);
    BOOST_TEST(j.at("params").at("algorithm").at("D") == 64);
    // Issue 13 item 6: machine parameters are JSON numbers (booleans for
    // on/off), each with whether it is an assumption and whether it makes
    // the machine faster than the published facts (docs/isa.md 2.2).
    const nlohmann::json& mach = j.at("params").at("machine");
    BOOST_TEST(mach.at("pes").is_number_integer());
    BOOST_TEST(mach.at("pes") == 256);
    BOOST_TEST(mach.at("clock_mhz").is_number());
    BOOST_TEST(mach.at("clock_mhz").get<double>() == 40.0);
    BOOST_TEST(mach.at("indirect").is_boolean());
    BOOST_TEST(mach.at("ring_hop") == 1);
    // (the energy preset is a name: the one text parameter)
    for (const auto& [k, val] : mach.items())
        if (k != "tech") BOOST_TEST(!val.is_string(), k);
    BOOST_TEST(mach.at("tech") == "45nm");
    const nlohmann::json& info = j.at("params").at("machine_info");
    BOOST_TEST(info.size() == mach.size());
    BOOST_TEST(info.at("pes").at("assumption") == false);
    BOOST_TEST(info.at("pe_regs").at("assumption") == true);
    BOOST_TEST(info.at("pe_regs").at("faster") == true);
    BOOST_TEST(info.at("ext_bytes").at("faster") == false);
    BOOST_TEST(r.out.find("[A+] assumed, faster than the published facts") != std::string::npos);
    BOOST_TEST(r.out.find("pe_regs 16 registers") != std::string::npos);
    // modeled_ms = cycles / 40000 exactly, without float noise in the JSON.
    const uint64_t cycles = j.at("cycles").get<uint64_t>();
    BOOST_TEST(j.at("modeled_ms").get<double>() == static_cast<double>(cycles) / 40000.0);
    const std::string ms = j.at("modeled_ms").dump();
    BOOST_TEST(ms.size() - ms.find('.') - 1 <= 6u, ms);  // cycles x 25 ns: at most 6 decimals
    BOOST_TEST(j.at("params").at("firmware").at("param_block").at("0") == 1);
    // the phases add up to the total
    uint64_t sum = 0;
    for (const auto& [k, v] : j.at("phases").items()) sum += v.get<uint64_t>();
    BOOST_TEST(sum == j.at("cycles").get<uint64_t>());
    BOOST_TEST(fs::exists(d / "d.png"));
    fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(machine_flag_errors) {
    const fs::path d = tmpdir();
    const std::string out = (d / "never.png").string();
    const std::pair<const char*, const char*> cases[] = {
        {"--pes 1", "pes"},
        {"--pes abc", "pes"},
        {"--clock-mhz 0", "clock_mhz"},
        {"--clock-mhz -5", "clock_mhz"},
        {"--mem-bytes 200", "does not fit"},
        {"--D 128 --ext-bytes 0", "does not fit"},  // the headline D = 64 spills nothing
        {"--set ring_hop=0", "ring_hop"},
        {"--set nosuch=3", "nosuch"},
        {"--set indirect=off", "indirect"},
        {"--set e_alu_pj=-1", "invalid value -1 for e_alu_pj: allowed 0..1e+06 pJ"},
        {"--set energy_scale=0", "energy_scale: allowed 0.001..10000"},
        {"--set frame_rate_hz=0",
         "invalid value 0 for frame_rate_hz: allowed 0..1e+06 Hz, exclusive of 0"},
        {"--set frame_rate_hz=2e6", "frame_rate_hz: allowed 0..1e+06 Hz, exclusive of 0"},
        {"--set s_pe_leak_uw=abc", "invalid value 'abc' for s_pe_leak_uw: expected a number"},
        {"--model nosuch", "--model"},
        {"--camera pal",
         "invalid value 'pal' for --camera: expected ideal, ntsc or pixel-clock:MHZ"},
        {"--camera pixel-clock:0", "--camera"},
        {"--set ext_mb_s=-1", "invalid value -1 for ext_mb_s: allowed 0..1e+06 MB/s"},
        {"--set ext_bus_bytes=3.5", "ext_bus_bytes: allowed whole numbers 1..1024"},
        {"--set camera_pixel_mhz=1e9", "camera_pixel_mhz: allowed 0..100000 MHz"},
        {"--set ext_beat=0", "ext_beat"},
    };
    for (const auto& [flags, needle] : cases) {
        const Result r = run(std::string("run --out ") + out + " " + flags);
        BOOST_TEST_CONTEXT(flags << "\n" << r.out) {
            BOOST_TEST(r.code == 2);
            BOOST_TEST(r.out.find(needle) != std::string::npos);
            BOOST_TEST(!fs::exists(out));
        }
    }
    fs::remove_all(d);
}

// Issue 29: every energy and board-timing parameter is range-checked on the
// command line (exit 2 naming the range, before any simulation), from the
// tables' own lists of fields.
template <class Table>
void check_ranges_on_the_command_line() {
    const fs::path d = tmpdir();
    const std::string out = (d / "never.png").string();
    for (const typename Table::Field& f : Table::fields()) {
        std::ostringstream lo, hi, bad;
        lo << f.min;
        hi << f.max;
        bad << f.max * 10;
        const Result r = run("run --out " + out + " --set " + f.name + "=" + bad.str());
        BOOST_TEST_CONTEXT(f.name << "\n" << r.out) {
            BOOST_TEST(r.code == 2);
            BOOST_TEST(r.out.find(std::string("for ") + f.name + ": allowed " + lo.str() + ".." +
                                  hi.str()) != std::string::npos);
            BOOST_TEST(!fs::exists(out));
        }
    }
    fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(every_energy_parameter_range_checked_on_the_command_line) {
    check_ranges_on_the_command_line<imap::isa::EnergyTable>();
}

BOOST_AUTO_TEST_CASE(every_board_parameter_range_checked_on_the_command_line) {
    check_ranges_on_the_command_line<imap::isa::BoardTiming>();
}

// Issue 29 item 3: the report's energy is the events times the energies of
// the report's own parameters (recomputed here from the JSON, not by the
// model's function), its parts add up, and power = energy / modeled time.
BOOST_AUTO_TEST_CASE(report_energy_is_events_times_energies) {
    const fs::path d = tmpdir();
    const std::string rep = (d / "e.json").string();
    const Result r =
        run("run --model core --pes 16 --size 48x16 --D 8 --set e_alu_pj=0.5 "
            "--set e_load_pj=2 --set mem_bytes=4096 --report " +
            rep);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(r.out.find("energy: ") != std::string::npos);
    BOOST_TEST(r.out.find("energy by class: ") != std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(rep));
    const nlohmann::json& e = j.at("energy");
    const nlohmann::json& v = e.at("events");
    const nlohmann::json& m = j.at("params").at("machine");
    auto n = [&](const char* k) { return v.at(k).get<double>(); };
    auto p = [&](const char* k) { return m.at(k).get<double>(); };
    BOOST_TEST(p("e_alu_pj") == 0.5);
    const double k = p("energy_scale");
    const double mem = std::pow(p("mem_bytes") / 1024.0, p("mem_size_exp"));  // 2
    const double dyn =
        k * (n("alu_lanes") * p("e_alu_pj") + n("minmax_lanes") * p("e_minmax_pj") +
             n("shift_lanes") * p("e_shift_pj") +
             (n("alu_lanes") + n("minmax_lanes") + n("shift_lanes")) * p("e_rf_pj") +
             n("masked_lanes") * p("e_masked_pj") +
             (n("load_lanes") * p("e_load_pj") + n("store_lanes") * p("e_store_pj")) * mem +
             n("ring_pe_hops") * p("e_ring_hop_pj") + n("mask_pe_ops") * p("e_mask_pj") +
             n("cp_instructions") * p("e_cp_pj") + n("instructions") * p("e_issue_pj") +
             n("video_bytes") * p("e_video_byte_pj")) +
        n("ext_bytes") * p("e_ext_byte_pj") + n("ext_transfers") * p("e_ext_xfer_pj");
    const double cyc = j.at("cycles").get<double>();
    const double sec = cyc / (p("clock_mhz") * 1e6);
    const double stat = n("pes") * (cyc * p("s_pe_clock_pj") * k + sec * p("s_pe_leak_uw") * 1e6) +
                        cyc * p("s_cp_clock_pj") * k + sec * p("s_cp_leak_uw") * 1e6;
    const auto tol = boost::test_tools::tolerance(1e-9);
    BOOST_TEST(n("pes") == 16.0);
    BOOST_TEST(n("cycles") == cyc);
    BOOST_TEST(n("alu_lanes") > 0.0);
    BOOST_TEST(n("load_lanes") > 0.0);
    BOOST_TEST(n("video_bytes") > 0.0);
    BOOST_TEST(e.at("dynamic_uj").get<double>() == dyn * 1e-6, tol);
    BOOST_TEST(e.at("static_uj").get<double>() == stat * 1e-6, tol);
    BOOST_TEST(e.at("total_uj").get<double>() == (dyn + stat) * 1e-6, tol);
    BOOST_TEST(e.at("by_class").at("alu").get<double>() == n("alu_lanes") * 0.5 * k * 1e-6, tol);
    double sum = 0;
    for (const auto& [c, x] : e.at("by_class").items()) sum += x.get<double>();
    BOOST_TEST(sum == e.at("total_uj").get<double>(), tol);
    // uJ / ms = mW
    BOOST_TEST(e.at("power_mw").get<double>() ==
                   e.at("total_uj").get<double>() / j.at("modeled_ms").get<double>(),
               tol);
    BOOST_TEST(e.at("events_source") == "isa");
    fs::remove_all(d);
}

// Issue 29 item 3: the energy of each phase (the report's energy.phases, the
// run's "energy by phase" lines) adds up to the frame's energy, every phase
// that ran has one, and no other name appears.
BOOST_AUTO_TEST_CASE(report_energy_by_phase_adds_up_to_the_frame) {
    const fs::path d = tmpdir();
    const std::string rep = (d / "p.json").string();
    const Result r = run("run --model core --pes 16 --size 48x16 --D 8 --report " + rep);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(r.out.find("energy by phase") != std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(rep));
    const nlohmann::json& ph = j.at("energy").at("phases");
    BOOST_REQUIRE(ph.is_object());
    BOOST_TEST(ph.size() >= 5u);
    double sum = 0;
    for (const auto& [name, uj] : ph.items()) {
        BOOST_TEST_INFO(name);
        BOOST_TEST(j.at("phases").contains(name));
        BOOST_TEST(uj.get<double>() > 0.0);
        sum += uj.get<double>();
        // printed with its share
        BOOST_TEST(r.out.find("    " + name + " ") != std::string::npos);
    }
    for (const auto& [name, cyc] : j.at("phases").items()) BOOST_TEST(ph.contains(name), name);
    BOOST_TEST(sum == j.at("energy").at("total_uj").get<double>(),
               boost::test_tools::tolerance(1e-9));
    fs::remove_all(d);
}

// Issue 29 item 3: power at the camera rate (--set frame_rate_hz), from the
// report's own energy, static energy and time; a frame slower than the
// camera's period says it cannot keep up and reports the frame-time power.
BOOST_AUTO_TEST_CASE(report_power_at_the_camera_rate) {
    const fs::path d = tmpdir();
    const std::string rep = (d / "c.json").string(), slow = (d / "s.json").string();
    const Result r =
        run("run --model core --pes 16 --size 48x16 --D 8 --set frame_rate_hz=25 "
            "--report " +
            rep);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(rep));
    const nlohmann::json& e = j.at("energy");
    const double ms = j.at("modeled_ms").get<double>(), period_ms = 1000.0 / 25;
    BOOST_REQUIRE(ms < period_ms);
    const double total = e.at("total_uj").get<double>(), stat = e.at("static_uj").get<double>();
    // uJ / ms = mW
    const double want = (total + stat / ms * (period_ms - ms)) / period_ms;
    BOOST_TEST(e.at("frame_rate_hz").get<double>() == 25.0);
    BOOST_TEST(e.at("power_camera_mw").get<double>() == want, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(e.at("camera_keeps_up").get<bool>());
    BOOST_TEST(r.out.find("power at the camera rate: ") != std::string::npos);
    BOOST_TEST(r.out.find(" at 25 fps (every 40.000 ms") != std::string::npos);
    // A rate whose period (ms / 2) the frame cannot meet.
    const std::string rate = std::to_string(static_cast<int>(2000.0 / ms));
    const Result s =
        run("run --model core --pes 16 --size 48x16 --D 8 --set frame_rate_hz=" + rate +
            " --report " + slow);
    BOOST_TEST_INFO(s.out);
    BOOST_REQUIRE(s.code == 0);
    const nlohmann::json k = nlohmann::json::parse(std::ifstream(slow));
    BOOST_TEST(!k.at("energy").at("camera_keeps_up").get<bool>());
    BOOST_TEST(k.at("energy").at("power_camera_mw").get<double>() ==
               k.at("energy").at("power_mw").get<double>());
    BOOST_TEST(s.out.find("> the camera period") != std::string::npos);
    BOOST_TEST(s.out.find("cannot keep up") != std::string::npos);
    fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(tlm_and_core_agree_on_cycles_and_phases) {
    const fs::path d = tmpdir();
    const char* configs[] = {
        "",
        "--mode single --D 32 --vote off --frame left",
        "--pes 64 --D 24 --seed-disp 3 --frame right",
        "--pes 8 --size 40x30 --D 12 --set ring_hop=2 --set xfer_setup=20",
        // board timing: a camera whose lines arrive while the frame runs,
        // and an external path of 8 bytes every 3 cycles at 300 MHz
        "--pes 8 --size 128x8 --D 96 --clock-mhz 300 --camera pixel-clock:20",
    };
    for (const char* c : configs) {
        nlohmann::json rep[2];
        const char* models[2] = {"core", "tlm"};
        for (int m = 0; m < 2; ++m) {
            const std::string file = (d / (std::string(models[m]) + ".json")).string();
            const Result r =
                run(std::string("run --model ") + models[m] + " --report " + file + " " + c);
            BOOST_TEST_CONTEXT(c << " model " << models[m] << "\n" << r.out) {
                BOOST_REQUIRE(r.code == 0);
            }
            std::ifstream in(file);
            rep[m] = nlohmann::json::parse(in);
        }
        BOOST_TEST_CONTEXT(c) {
            BOOST_TEST(rep[0].at("bit_exact").get<bool>());
            BOOST_TEST(rep[1].at("bit_exact").get<bool>());
            BOOST_TEST(rep[0].at("cycles") == rep[1].at("cycles"));
            BOOST_TEST(rep[0].at("phases") == rep[1].at("phases"));
            BOOST_TEST(rep[0].at("energy").at("events") == rep[1].at("energy").at("events"));
            BOOST_TEST(rep[0].at("energy").at("phases") == rep[1].at("energy").at("phases"));
        }
    }
    fs::remove_all(d);
}

// The quality preset (census, 5x5 window, joint) on every whole Middlebury
// scene, bit-exact: 288 to 375 lines take batches of at most 255 lines
// sharing their halo of 5 lines; at 256 PEs the lines (384 to 450 pixels)
// take two video segments, the census's codes at their edges reading the
// segment beside. At 1024 PEs the rows would fit the ring skewed, which the
// census's codes do not take over batches (its last batch read lines
// clamped at the first batch's length).
BOOST_AUTO_TEST_CASE(quality_preset_runs_whole_middlebury_scenes) {
    const std::string data = std::string(IMAP_SHARED_DATA) + "/middlebury/";
    for (const char* name : {"tsukuba", "venus", "teddy", "cones"}) {
        for (const std::string pes : {"256", "512", "1024"}) {
            const Result r = run("run --model core --preset quality --scene " + data + name +
                                 " --pes " + pes + " --mem-bytes 4096");
            BOOST_TEST_CONTEXT(name << " --pes " << pes << "\n" << r.out) {
                BOOST_TEST(r.code == 0);
                BOOST_TEST(
                    r.out.find(pes == "256" ? " batches, 2 segments" : ", 2 batches, 1 segment") !=
                    std::string::npos);
                BOOST_TEST(r.out.find("bit-exact vs golden: yes") != std::string::npos);
            }
        }
    }
}

// Issue 13 item 4: --scene takes the scene's D (tsukuba: 16, as eval) and
// prints bad-1 against its ground truth, the same numbers as eval.
BOOST_AUTO_TEST_CASE(scene_folder_gives_d_and_ground_truth_score) {
    const fs::path d = tmpdir();
    const std::string dir = std::string(IMAP_SHARED_DATA) + "/middlebury/tsukuba";
    const std::string rep = (d / "ts.json").string(), ev = (d / "ev.json").string();
    const Result r = run("run --model core --scene " + dir + " --report " + rep);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(r.out.find("D=16") != std::string::npos);
    BOOST_TEST(r.out.find("bit-exact vs golden: yes") != std::string::npos);
    BOOST_TEST(r.out.find("golden bad-1 vs ground truth (left frame, filled): nonocc") !=
               std::string::npos);
    std::ifstream in(rep);
    const nlohmann::json j = nlohmann::json::parse(in);
    BOOST_TEST(j.at("params").at("algorithm").at("D") == 16);
    const Result e = run("eval --scene " + dir + " --matcher golden --json " + ev);
    BOOST_REQUIRE_MESSAGE(e.code == 0, e.out);
    std::ifstream ein(ev);
    const nlohmann::json ej = nlohmann::json::parse(ein).at(0);
    const nlohmann::json& gt = j.at("ground_truth");
    BOOST_TEST(gt.at("bad1_nonocc").get<double>() == ej.at("nonocc").get<double>());
    BOOST_TEST(gt.at("bad1_all").get<double>() == ej.at("all").get<double>());
    BOOST_TEST(gt.at("bad1_disc").get<double>() == ej.at("disc").get<double>());
    // Issue 32 item 7: the JSON names the map that was scored (the golden's
    // left frame after the fill) and the one the run checked and wrote.
    BOOST_TEST(gt.at("scored_map").at("frame") == "left");
    BOOST_TEST(gt.at("scored_map").at("fill") == true);
    BOOST_TEST(gt.at("output_map").at("frame") == "cyc");
    BOOST_TEST(gt.at("output_map").at("fill") == false);
    BOOST_TEST(r.out.find("the model's map and --out are the cyc frame, unfilled") !=
               std::string::npos);

    // --left/--right of a scene folder without --D: a note names the scene's D.
    const Result l = run("run --model core " + scene("tsukuba") + " --roi 100,100,64,32");
    BOOST_TEST_INFO(l.out);
    BOOST_TEST(l.code == 0);
    BOOST_TEST(l.out.find("scenes.json gives ndisp 16; this run uses --D 64") != std::string::npos);
    // --gt with a scale: scored over every pixel of the ROI.
    const Result g = run("run --model core " + scene("tsukuba") + " --D 16 --roi 100,100,64,32" +
                         " --gt " + dir + "/gt.png --gt-scale 16");
    BOOST_TEST_INFO(g.out);
    BOOST_TEST(g.code == 0);
    BOOST_TEST(g.out.find("every pixel of the ROI") != std::string::npos);
    // Errors: both sources, --gt without images, --gt-scale alone.
    BOOST_TEST(run("run --scene " + dir + " " + scene("tsukuba")).code == 2);
    BOOST_TEST(run("run --gt " + dir + "/gt.png").code == 2);
    BOOST_TEST(run("run --gt-scale 4").code == 2);
    fs::remove_all(d);
}

// Issue 13 item 3: the program that ran and its constants can be written,
// re-assembled from the firmware sources by hand, disassembled, and run with
// exec to the same map.
BOOST_AUTO_TEST_CASE(emitted_program_and_defines_reassemble_and_exec) {
    const fs::path d = tmpdir();
    const std::string bin = (d / "dp.bin").string(), inc = (d / "dp.inc").string(),
                      map = (d / "map.png").string();
    const std::string synth = (d / "scene").string();
    BOOST_REQUIRE(run("synth --seed 3 --size 80x24 --out-dir " + synth).code == 0);
    const std::string images = " --left " + synth + "/left.png --right " + synth + "/right.png";
    const Result r = run("run --model core --D 12 --roi 4,2,70,20" + images + " --out " + map +
                         " --emit-program " + bin + " --emit-defines " + inc);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_REQUIRE(fs::is_regular_file(bin));
    std::ifstream in(inc);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    BOOST_TEST(text.find(".equ X0 4\n") != std::string::npos);
    BOOST_TEST(text.find(".equ D 12\n") != std::string::npos);
    // Re-assemble: the emitted source includes dp.s itself.
    const std::string frame = inc, again = (d / "again.bin").string();
    BOOST_TEST(text.find(";     imapsim asm ") != std::string::npos);
    const Result as = run("asm " + frame + " -o " + again);
    BOOST_REQUIRE_MESSAGE(as.code == 0, as.out);
    const std::string da = (d / "a.s").string(), db = (d / "b.s").string();
    BOOST_REQUIRE(run("disasm " + bin + " --no-comments -o " + da).code == 0);
    BOOST_REQUIRE(run("disasm " + again + " --no-comments -o " + db).code == 0);
    auto slurp = [](const std::string& p) {
        std::ifstream f(p);
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    };
    BOOST_TEST(slurp(da).size() > 1000u);
    BOOST_TEST((slurp(da) == slurp(db)));
    // The disassembly re-assembles too (edit, re-assemble, exec).
    const std::string edited = (d / "edited.bin").string();
    BOOST_REQUIRE_MESSAGE(run("asm " + da + " -o " + edited).code == 0, "disassembly reassembles");
    // exec with the command line the header gives: the same map.
    const size_t at = text.find(";     imapsim exec ");
    BOOST_REQUIRE(at != std::string::npos);
    std::string cmd = text.substr(at + 19, text.find('\n', at) - at - 19);
    const std::string exec_map = (d / "exec.png").string();
    auto replace = [&](const std::string& from, const std::string& to) {
        const size_t p = cmd.find(from);
        BOOST_REQUIRE_MESSAGE(p != std::string::npos, from << " in " << cmd);
        cmd.replace(p, from.size(), to);
    };
    replace(bin, edited);
    replace("--left LEFT --right RIGHT", images.substr(1));
    replace("--out-left MAP.png", "--out-left " + exec_map);
    const Result x = run("exec " + cmd + " --model core");
    BOOST_TEST_INFO(x.out);
    BOOST_REQUIRE(x.code == 0);
    BOOST_TEST((slurp(exec_map) == slurp(map)));  // PNG bytes: same pixels, same encoder

    // Issue 32 item 10: the emitted source assembles anywhere (the firmware
    // is inlined, no .include of the source tree), and exec of the source
    // itself runs it: moved to a folder of its own, the same map.
    BOOST_TEST(text.find(".include \"/") == std::string::npos, "no .include of an absolute path");
    BOOST_TEST(text.find("; ---- dp.s (inlined from firmware/asm/dp.s)") != std::string::npos);
    const fs::path moved = d / "elsewhere";
    fs::create_directories(moved);
    fs::copy_file(inc, moved / "frame.inc");
    std::string src_cmd = cmd;
    const size_t bp = src_cmd.find(edited);
    BOOST_REQUIRE(bp != std::string::npos);
    src_cmd.replace(bp, edited.size(), "frame.inc");
    const std::string src_map = (d / "src.png").string();
    const size_t mp = src_cmd.find(exec_map);
    BOOST_REQUIRE(mp != std::string::npos);
    src_cmd.replace(mp, exec_map.size(), src_map);
    const Result xs = run("exec " + src_cmd + " --model core", moved.string());
    BOOST_TEST_INFO(xs.out);
    BOOST_REQUIRE(xs.code == 0);
    BOOST_TEST((slurp(src_map) == slurp(map)));
    fs::remove_all(d);
}

// Issue 13 items 2 and 5: every output is checked before the run; the
// colour-mapped map has the raw map's occlusions in white.
BOOST_AUTO_TEST_CASE(outputs_checked_first_and_colour_map) {
    const fs::path d = tmpdir();
    fs::create_directories(d / "taken.png");
    for (const char* flag :
         {"--out", "--out-color", "--report", "--emit-program", "--emit-defines"}) {
        const Result r = run(std::string("run --model core --size 64x32 --D 8 ") + flag + " " +
                             (d / "taken.png").string());
        BOOST_TEST_CONTEXT(flag << "\n" << r.out) {
            BOOST_TEST(r.code == 2);
            BOOST_TEST(r.out.find("is a folder") != std::string::npos);
            BOOST_TEST(r.out.find("bit-exact") == std::string::npos);
        }
    }
    const Result same = run("run --size 64x32 --D 8 --out " + (d / "x.png").string() +
                            " --out-color " + (d / "x.png").string());
    BOOST_TEST(same.code == 2);
    BOOST_TEST(same.out.find("name the same file") != std::string::npos);
    const std::string raw = (d / "raw.png").string(), col = (d / "col.png").string();
    const Result r =
        run("run --model core --size 64x32 --D 8 --out " + raw + " --out-color " + col);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(fs::is_regular_file(col));
    fs::remove_all(d);
}

// Issue 32 item 6: the lockstep's report has its own fields (instructions
// retired and compared, both models' cycles) and is written on a divergence
// too, with every field of the first divergence; the RTL's report has its
// configuration and clocks.
BOOST_AUTO_TEST_CASE(lockstep_and_rtl_reports_have_their_fields) {
    const fs::path d = tmpdir();
    const std::string base = "run --pes 8 --size 32x12 --D 6 --lockstep-waves '' ";
    const std::string ok = (d / "ok.json").string(), bad = (d / "bad.json").string(),
                      rtl = (d / "rtl.json").string();
    const Result r = run(base + "--model lockstep --report " + ok);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(ok));
    const nlohmann::json& ls = j.at("lockstep");
    BOOST_TEST(ls.at("diverged") == false);
    BOOST_TEST(ls.at("instructions").get<uint64_t>() > 0u);
    BOOST_TEST(ls.at("compared").get<uint64_t>() == ls.at("instructions").get<uint64_t>());
    BOOST_TEST(ls.at("cycles_tlm") == j.at("cycles"));
    BOOST_TEST(ls.at("cycles_rtl") == j.at("cycles"));
    BOOST_TEST(ls.at("rtl_configuration").get<std::string>().find("p8_") == 0u);

    const Result x = run(base + "--model lockstep --inject-fault 20:3:r5:0x24 --report " + bad);
    BOOST_TEST_INFO(x.out);
    BOOST_TEST(x.code == 1);
    BOOST_TEST(x.out.find("imapsim: error: ") != std::string::npos);
    BOOST_REQUIRE(fs::exists(bad));
    const nlohmann::json b = nlohmann::json::parse(std::ifstream(bad));
    BOOST_TEST(b.at("model") == "lockstep");
    BOOST_TEST(b.at("bit_exact").is_null());
    const nlohmann::json& dv = b.at("lockstep").at("divergence");
    BOOST_TEST(b.at("lockstep").at("diverged") == true);
    BOOST_TEST(dv.at("pe") == 3);
    BOOST_TEST(dv.at("instruction").get<uint64_t>() >= 20u);
    for (const char* k :
         {"cycle", "pc", "word", "disassembly", "what", "tlm_value", "rtl_value", "message"})
        BOOST_TEST(dv.contains(k), k);
    BOOST_TEST(x.out.find(dv.at("message").get<std::string>()) != std::string::npos);
    BOOST_TEST(b.at("params").at("machine").at("pes") == 8);

    const Result t = run(base + "--model rtl --report " + rtl);
    BOOST_TEST_INFO(t.out);
    BOOST_REQUIRE(t.code == 0);
    const nlohmann::json rj = nlohmann::json::parse(std::ifstream(rtl));
    BOOST_TEST(rj.at("rtl").at("clocks").get<uint64_t>() >= rj.at("cycles").get<uint64_t>());
    BOOST_TEST(rj.at("rtl").at("configuration").get<std::string>().find("p8_") == 0u);
    // Energy of rtl / lockstep runs: the instruction-set model's counts of
    // the same program (docs/energy.md 5), so the core run's figures.
    const std::string core = (d / "core.json").string();
    BOOST_REQUIRE(run(base + "--model core --report " + core).code == 0);
    const nlohmann::json cj = nlohmann::json::parse(std::ifstream(core));
    BOOST_TEST(rj.at("energy").at("events") == cj.at("energy").at("events"));
    BOOST_TEST(j.at("energy").at("events") == cj.at("energy").at("events"));
    BOOST_TEST(rj.at("energy").at("phases") == cj.at("energy").at("phases"));
    BOOST_TEST(j.at("energy").at("phases") == cj.at("energy").at("phases"));
    BOOST_TEST(rj.at("energy").at("events_source").get<std::string>().find("instruction-set") ==
               0u);
    BOOST_TEST(j.at("energy").at("events_source") == "lockstep's TLM side");
    fs::remove_all(d);
}
