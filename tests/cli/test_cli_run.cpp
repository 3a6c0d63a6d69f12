// imapsim run from the outside: the firmware on the default model over the
// shared Middlebury scenes (ROIs and whole images), the JSON report, and the
// machine-flag errors.
#define BOOST_TEST_MODULE cli_run
#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_util.hpp"

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
    BOOST_TEST(j.at("params").at("machine").at("pes") == "256");
    BOOST_TEST(j.at("params").at("algorithm").at("D") == 64);
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
        {"--ext-bytes 0", "does not fit"},
        {"--set ring_hop=0", "ring_hop"},
        {"--set nosuch=3", "nosuch"},
        {"--set indirect=off", "indirect"},
        {"--model nosuch", "--model"},
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

BOOST_AUTO_TEST_CASE(tlm_and_core_agree_on_cycles_and_phases) {
    const fs::path d = tmpdir();
    const char* configs[] = {
        "",
        "--mode single --D 32 --vote off --frame left",
        "--pes 64 --D 24 --seed-disp 3 --frame right",
        "--pes 8 --size 40x30 --D 12 --set ring_hop=2 --set xfer_setup=20",
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
        }
    }
    fs::remove_all(d);
}
