// scripts/rtl_coverage_report.py (docs/rtl.md, "Code coverage") on a small
// hand-written coverage file: the per-kind figures, the bit-range waivers,
// and the two warnings that keep the waiver file honest (a waiver matching
// nothing; a waiver of a point that some run hit).
#define BOOST_TEST_MODULE rtl_coverage_report
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#ifndef IMAP_SOURCE_DIR
#error "IMAP_SOURCE_DIR must name the source tree"
#endif

namespace fs = std::filesystem;

namespace {
// One Verilator coverage point: C '<key \x02 value, joined by \x01>' count
std::string point(const char* kind, int line, const std::string& what, int count) {
    std::ostringstream s;
    s << "C '\x01"
      << "f\x02"
      << "/src/rtl_model/hdl/imap_cp.sv\x01l\x02" << line << "\x01n\x02"
      << "5\x01page\x02v_" << kind << "/imap_cp\x01o\x02" << what << "' " << count << "\n";
    return s.str();
}

struct Report {
    int status = 0;
    std::string summary;
};

Report run(const std::string& waivers) {
    const fs::path dir = fs::temp_directory_path() / ("covrep-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    {
        std::ofstream d(dir / "merged.dat");
        d << "# SystemC::Coverage-3\n";
        d << point("line", 20, "if", 3) << point("line", 21, "else", 0);
        d << point("toggle", 10, "cnt[0]", 7) << point("toggle", 10, "cnt[1]", 0)
          << point("toggle", 10, "cnt[2]", 0) << point("toggle", 10, "cnt[3]", 0)
          << point("toggle", 11, "flag", 0);
        // a point outside hdl/ is not the design's
        d << "C '\x01"
          << "f\x02/src/rtl_model/verif/imap_tb.sv\x01l\x02"
          << "1\x01n\x02"
          << "1\x01page\x02v_toggle/tb\x01o\x02x[0]' 0\n";
        std::ofstream(dir / "waivers.txt") << "# test\n" << waivers;
    }
    const std::string cmd = "python3 " IMAP_SOURCE_DIR "/scripts/rtl_coverage_report.py " +
                            (dir / "merged.dat").string() + " " + (dir / "waivers.txt").string() +
                            " " + (dir / "summary.txt").string() + " " +
                            (dir / "uncovered.txt").string() + " > " + (dir / "out.txt").string() +
                            " 2>&1";
    Report r;
    r.status = std::system(cmd.c_str());
    std::ifstream in(fs::exists(dir / "summary.txt") ? dir / "summary.txt" : dir / "out.txt");
    std::stringstream ss;
    ss << in.rdbuf();
    r.summary = ss.str();
    fs::remove_all(dir);
    return r;
}
bool has(const Report& r, const std::string& s) {
    return r.summary.find(s) != std::string::npos;
}
}  // namespace

BOOST_AUTO_TEST_CASE(figures_without_waivers) {
    const Report r = run("");
    BOOST_TEST_INFO(r.summary);
    BOOST_CHECK_EQUAL(r.status, 0);
    BOOST_CHECK(has(r, "1/2  50.0%"));  // lines
    BOOST_CHECK(has(r, "1/5  20.0%"));  // toggles (the testbench's point left out)
    BOOST_CHECK(has(r, "toggle: 20.0% (target >= 85%: NOT met)"));
}

BOOST_AUTO_TEST_CASE(a_bit_range_waives_those_bits_only) {
    const Report r = run("imap_cp.sv signal=cnt[3:2] toggle above the largest count\n");
    BOOST_TEST_INFO(r.summary);
    BOOST_CHECK_EQUAL(r.status, 0);
    BOOST_CHECK(has(r, "1/3  33.3% (2 waived)"));
    BOOST_CHECK(!has(r, "warning"));
}

BOOST_AUTO_TEST_CASE(a_waiver_of_a_hit_point_is_reported) {
    // planted: bit 0 toggled in the run, so "cannot be reached" is false
    const Report r = run("imap_cp.sv signal=cnt[1:0] toggle planted\n");
    BOOST_TEST_INFO(r.summary);
    BOOST_CHECK(has(r, "warning: waiver at line 2 waives 1 point(s) that were hit"));
}

BOOST_AUTO_TEST_CASE(a_waiver_matching_nothing_is_reported) {
    const Report r =
        run("imap_cp.sv signal=nosuch toggle gone from the design\n"
            "imap_cp.sv signal=cnt[9:8] toggle bits the signal does not have\n"
            "imap_cp.sv:21 line the else arm\n");
    BOOST_TEST_INFO(r.summary);
    BOOST_CHECK(has(r, "warning: waiver at line 2 matches no point"));
    BOOST_CHECK(has(r, "warning: waiver at line 3 matches no point"));
    BOOST_CHECK(!has(r, "waiver at line 4 matches no point"));
    BOOST_CHECK(has(r, "1/1 100.0% (1 waived)"));  // the line waived
}

BOOST_AUTO_TEST_CASE(a_malformed_waiver_is_an_error) {
    const Report r = run("imap_cp.sv signal=cnt[1:3] toggle low above high\n");
    BOOST_TEST_INFO(r.summary);
    BOOST_CHECK_NE(r.status, 0);
    BOOST_CHECK(has(r, "a signal is NAME or NAME[HI:LO] (HI >= LO)"));
}
