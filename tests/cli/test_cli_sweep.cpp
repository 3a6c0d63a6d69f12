// imapsim sweep and imapsim table1 from the outside: value lists and ranges,
// does-not-fit rows, CSV / JSON / plot outputs, cycles against direct
// `imapsim run` calls of the same points, error rows, and Ctrl-C.
#define BOOST_TEST_MODULE cli_sweep
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_test_util.hpp"

extern char** environ;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using clitest::Result;
using clitest::run;

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imapsim-cli-sweep-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// Removes the test's temporary folder at the end.
struct Cleanup {
    ~Cleanup() {
        std::error_code ec;
        fs::remove_all(tmpdir(), ec);
    }
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A small RFC 4180 reader: rows of fields, quoted fields may hold commas.
using Csv = std::vector<std::vector<std::string>>;
Csv parse_csv(const std::string& text) {
    Csv rows;
    std::vector<std::string> row;
    std::string f;
    bool q = false, any = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (q) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                f += '"';
                ++i;
            } else if (c == '"') {
                q = false;
            } else {
                f += c;
            }
        } else if (c == '"') {
            q = true;
            any = true;
        } else if (c == ',') {
            row.push_back(f);
            f.clear();
            any = true;
        } else if (c == '\n') {
            row.push_back(f);
            rows.push_back(row);
            row.clear();
            f.clear();
            any = false;
        } else {
            f += c;
            any = true;
        }
    }
    if (any) {
        row.push_back(f);
        rows.push_back(row);
    }
    return rows;
}

// Rows as maps column -> value (header from the first row).
std::vector<std::map<std::string, std::string>> records(const Csv& csv) {
    std::vector<std::map<std::string, std::string>> out;
    BOOST_REQUIRE(!csv.empty());
    for (size_t r = 1; r < csv.size(); ++r) {
        BOOST_REQUIRE_EQUAL(csv[r].size(), csv[0].size());
        std::map<std::string, std::string> m;
        for (size_t c = 0; c < csv[0].size(); ++c) m[csv[0][c]] = csv[r][c];
        out.push_back(m);
    }
    return out;
}

// Cycles of a direct `imapsim run` of one synthetic point (WxH scene, whole
// image as ROI), read from its JSON report.
uint64_t direct_cycles(const std::string& args, const fs::path& report) {
    const Result r = run("run --report " + report.string() + " " + args);
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    std::ifstream in(report);
    const json j = json::parse(in);
    BOOST_REQUIRE(j.at("bit_exact").get<bool>());
    return j.at("cycles").get<uint64_t>();
}

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

BOOST_AUTO_TEST_CASE(small_sweep_rows_csv_json_plot) {
    const fs::path d = tmpdir();
    const fs::path csv = d / "small.csv", js = d / "small.json", png = d / "small.png";
    const Result r = run("sweep --roi-size 32x16 --D 8 --pes 8,16 --mem-bytes 1024,60 -j 2 --csv " +
                         csv.string() + " --json " + js.string() + " --plot " + png.string() +
                         " --plot-size 640x480");
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);

    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 4u);  // 2 PE counts x 2 memory sizes
    const auto head = parse_csv(slurp(csv)).front();
    BOOST_TEST(head[0] == "pes");
    BOOST_TEST(head[1] == "mem_bytes");
    for (const char* c : {"cycles", "modeled_ms", "fps", "status", "message"}) {
        BOOST_TEST_INFO("column " << c);
        BOOST_TEST((std::find(head.begin(), head.end(), c) != head.end()));
    }
    BOOST_TEST((std::find(head.begin(), head.end(), "phase_forward") != head.end()));
    // Energy (docs/energy.md): the last three columns, after every older one.
    BOOST_REQUIRE(head.size() >= 3u);
    BOOST_TEST(head[head.size() - 3] == "energy_uj");
    BOOST_TEST(head[head.size() - 2] == "power_mw");
    BOOST_TEST(head[head.size() - 1] == "edp");

    // A direct run with 60 bytes of local memory is refused by the planner:
    // the sweep reports that point as a row with the same message.
    const Result refused = run("run --size 32x16 --roi 0,0,32,16 --D 8 --pes 8 --mem-bytes 60");
    BOOST_TEST_INFO(refused.out);
    BOOST_TEST(refused.code == 2);
    BOOST_TEST(refused.out.find("does not fit") != std::string::npos);

    std::set<std::string> seen;
    for (const auto& row : rows) {
        seen.insert(row.at("pes") + "/" + row.at("mem_bytes"));
        if (row.at("mem_bytes") == "60") {
            BOOST_TEST(row.at("status") == "does-not-fit");
            BOOST_TEST(row.at("message").find("does not fit: needs") != std::string::npos);
            BOOST_TEST(row.at("message").find("have 60") != std::string::npos);
            BOOST_TEST(row.at("cycles").empty());
        } else {
            BOOST_TEST(row.at("status") == "ok");
            BOOST_TEST(row.at("bit_exact") == "yes");
            // modeled time is cycles at the default 40 MHz
            const double cyc = std::stod(row.at("cycles"));
            BOOST_TEST(std::stod(row.at("modeled_ms")) == cyc / 40e3,
                       boost::test_tools::tolerance(1e-6));
            // the phases add up to the total
            uint64_t sum = 0;
            for (const auto& [k, v] : row)
                if (k.rfind("phase_", 0) == 0 && !v.empty()) sum += std::stoull(v);
            BOOST_TEST(sum == std::stoull(row.at("cycles")));
            // The machine bound (docs/firmware.md 11): every bounded phase at
            // or above its bound, the frame's bound their sum, efficiency
            // bound / cycles.
            uint64_t bsum = 0;
            for (const auto& [k, v] : row)
                if (k.rfind("bound_", 0) == 0 && k != "bound_cycles" && !v.empty()) {
                    BOOST_TEST_INFO("column " << k);
                    BOOST_TEST(std::stoull(v) > 0u);
                    BOOST_TEST(std::stoull(v) <= std::stoull(row.at("phase_" + k.substr(6))));
                    bsum += std::stoull(v);
                }
            BOOST_TEST(row.at("bound_forward") != "");
            BOOST_TEST(bsum == std::stoull(row.at("bound_cycles")));
            BOOST_TEST(std::stod(row.at("efficiency")) == double(bsum) / cyc,
                       boost::test_tools::tolerance(1e-3));
            // average power = energy / modeled time (uJ / ms = mW)
            BOOST_TEST(std::stod(row.at("energy_uj")) > 0.0);
            BOOST_TEST(std::stod(row.at("power_mw")) ==
                           std::stod(row.at("energy_uj")) / std::stod(row.at("modeled_ms")),
                       boost::test_tools::tolerance(1e-4));
        }
    }
    BOOST_TEST((seen == std::set<std::string>{"8/1024", "8/60", "16/1024", "16/60"}));

    // Independent check: cycles of the 16-PE point equal a direct run's.
    const uint64_t want = direct_cycles(
        "--size 32x16 --roi 0,0,32,16 --D 8 --pes 16 --mem-bytes 1024", d / "r16.json");
    for (const auto& row : rows)
        if (row.at("pes") == "16" && row.at("mem_bytes") == "1024")
            BOOST_TEST(std::stoull(row.at("cycles")) == want);

    // JSON: same rows plus the fixed parameters.
    std::ifstream in(js);
    const json j = json::parse(in);
    BOOST_TEST(j.at("rows").size() == 4u);
    BOOST_TEST(j.at("interrupted").get<bool>() == false);
    BOOST_TEST(j.at("fixed").at("algorithm").at("D") == 8);
    BOOST_TEST(j.at("fixed").at("roi_size") == "32x16");
    BOOST_TEST(j.at("swept").size() == 2u);
    for (const json& row : j.at("rows"))
        if (row.at("status") == "ok") {
            BOOST_TEST(row.at("energy").at("total_uj").get<double>() > 0.0);
            BOOST_TEST(row.at("energy").at("events").at("alu_lanes").get<uint64_t>() > 0u);
        }

    // Plot (gnuplot): a readable image of the requested size, not blank; its
    // script and data beside it, the data holding the two points that ran.
    const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
    BOOST_REQUIRE(!img.empty());
    BOOST_TEST(img.cols == 640);
    BOOST_TEST(img.rows == 480);
    const cv::Mat ink = img.reshape(1) != 255;
    BOOST_TEST(cv::countNonZero(ink) > 1000);
    const std::string gp = slurp(d / "small.gp"), dat = slurp(d / "small.dat");
    BOOST_TEST(gp.find("small.dat") != std::string::npos);
    BOOST_TEST(gp.find("pngcairo size 640,480") != std::string::npos);
    size_t data_lines = 0;
    std::istringstream dl(dat);
    for (std::string line; std::getline(dl, line);) data_lines += !line.empty() && line[0] != '#';
    BOOST_TEST(data_lines == 4u);  // the two points, and the machine's bound at each
    BOOST_TEST(gp.find("machine bound") != std::string::npos);
    // Every ran row names its dominant phase, one of the phase columns.
    for (const auto& row : rows)
        if (row.at("status") == "ok") {
            const std::string ph = row.at("dominant_phase");
            BOOST_TEST_INFO("dominant " << ph);
            BOOST_TEST(row.count("phase_" + ph) == 1u);
            for (const auto& [k, val] : row)
                if (k.rfind("phase_", 0) == 0)
                    BOOST_TEST(std::stoull(val) <= std::stoull(row.at("phase_" + ph)));
        }
}

BOOST_AUTO_TEST_CASE(svg_plot_and_gnuplot_script_redraws) {
    const fs::path d = tmpdir() / "svg";
    fs::create_directories(d);
    const Result r = run("sweep --model core --roi-size 32x16 --D 8 --pes 8,16 --plot " +
                         (d / "p.svg").string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    const std::string svg = slurp(d / "p.svg");
    BOOST_TEST(svg.find("<svg") != std::string::npos);
    BOOST_TEST(svg.find("</svg>") != std::string::npos);
    // The script beside it redraws the plot on its own (into another name).
    const std::string cmd = "cd " + d.string() + " && gnuplot -e \"outfile='again.png'\" p.gp 2>&1";
    BOOST_TEST(std::system(cmd.c_str()) == 0);
    BOOST_TEST(cv::imread((d / "again.png").string()).cols == 900);
    // A plot name gnuplot cannot draw is refused before the sweep.
    const Result bad = run("sweep --dry-run --pes 8,16 --plot " + (d / "p.jpg").string());
    BOOST_TEST(bad.code == 2);
    BOOST_TEST(bad.out.find(".png or .svg") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(nothing_runs_exit_5) {
    // Every point does not fit: no point ran, which is exit 5 and said so.
    const fs::path d = tmpdir();
    const Result r =
        run("sweep --model core --roi-size 32x16 --D 8 --pes 3,4 --mem-bytes 40,60 "
            "--csv " +
            (d / "none.csv").string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 5);
    BOOST_TEST(r.out.find("0 ran") != std::string::npos);
    BOOST_TEST(r.out.find("nothing ran") != std::string::npos);
    const auto rows = records(parse_csv(slurp(d / "none.csv")));
    BOOST_TEST(rows.size() == 4u);
    // With --dry-run, no point fitting is the same answer.
    const Result dry = run("sweep --dry-run --roi-size 32x16 --D 8 --mem-bytes 40,60");
    BOOST_TEST_INFO(dry.out);
    BOOST_TEST(dry.code == 5);
    BOOST_TEST(dry.out.find("nothing fits") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(resume_of_a_local_run_refuses_slurm_options) {
    // A local run folder resumed with a Slurm option would silently run
    // locally and ignore it: refused, before anything runs.
    const fs::path d = tmpdir();
    const fs::path rd = d / "rundir";
    const Result first =
        run("sweep --roi-size 32x16 --D 8 --pes 8 --keep --run-dir " + rd.string());
    BOOST_TEST_INFO(first.out);
    BOOST_REQUIRE_EQUAL(first.code, 0);
    const Result again = run("sweep --resume " + rd.string() + " --partition debug");
    BOOST_TEST_INFO(again.out);
    BOOST_TEST(again.code == 2);
    BOOST_TEST(again.out.find("need --executor slurm") != std::string::npos);
    BOOST_TEST(again.out.find("executor is local") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(knee_is_found_and_explained) {
    // 64 -> 128 PEs on a 128-wide ROI: the DP phases stop shrinking; whatever
    // the firmware's cycle counts, the curve's slope changes there or not, and
    // a reported knee names the phases on both sides.
    const fs::path d = tmpdir();
    const fs::path js = d / "knee.json";
    const Result r =
        run("sweep --model core --roi-size 128x16 --D 16 --pes 16..512*2 -j 2 --json " +
            js.string() + " --plot " + (d / "knee.png").string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    std::ifstream in(js);
    const json j = json::parse(in);
    // Recompute the slopes from the rows and compare with what was reported.
    std::vector<std::pair<double, double>> pts;
    for (const auto& row : j.at("rows"))
        pts.push_back({std::stod(row.at("point").at("pes").get<std::string>()),
                       row.at("modeled_ms").get<double>()});
    BOOST_REQUIRE_EQUAL(pts.size(), 6u);
    double best = 0;
    size_t at = 0;
    for (size_t i = 1; i + 1 < pts.size(); ++i) {
        const double s0 =
            std::log(pts[i].second / pts[i - 1].second) / std::log(pts[i].first / pts[i - 1].first);
        const double s1 =
            std::log(pts[i + 1].second / pts[i].second) / std::log(pts[i + 1].first / pts[i].first);
        if (std::fabs(s1 - s0) > std::fabs(best)) {
            best = s1 - s0;
            at = i;
        }
    }
    const json& knees = j.at("knees");
    if (std::fabs(best) >= 0.5) {
        BOOST_REQUIRE_EQUAL(knees.size(), 1u);
        const json& k = knees[0];
        BOOST_TEST(k.at("at").get<std::string>() ==
                   std::to_string(static_cast<int>(pts[at].first)));
        const std::string e = k.at("explanation").get<std::string>();
        BOOST_TEST(e.find("knee at pes=") == 0u);
        BOOST_TEST(e.find(k.at("phase_after").get<std::string>()) != std::string::npos);
        BOOST_TEST(r.out.find(e) != std::string::npos);  // printed with the summary
        // and written on the plot, in words (issue 32 item 15)
        const std::string label = k.at("label").get<std::string>();
        BOOST_TEST(label.find(" PEs") != std::string::npos, label);
        BOOST_TEST(slurp(d / "knee.gp").find("\"" + label + "\"") != std::string::npos, label);
    } else {
        BOOST_TEST(knees.empty());
    }
}

// Issue 29 item 1: a clock sweep of a bandwidth-bound frame (pointers spilled
// over an external path of 30 MB/s and one byte per cycle) has its knee at
// the clock the parameters predict, ext_mb_s / ext_bus_bytes (computed here,
// docs/isa.md 2.4): below it the bus width limits the path and the frame's
// time halves with each doubling; above it the bandwidth does and the spill's
// cycles grow with the clock. The explanation names the spill.
BOOST_AUTO_TEST_CASE(bandwidth_bound_clock_sweep_has_its_knee_where_predicted) {
    const double mb_s = 30, bus = 1, predicted = mb_s / bus;
    std::string clocks;
    for (int k = -2; k <= 3; ++k)
        clocks += (clocks.empty() ? "" : ",") + std::to_string(predicted * std::pow(2.0, k));
    const fs::path d = tmpdir();
    const fs::path js = d / "clock.json";
    const Result r =
        run("sweep --model core --roi-size 128x128 --D 64 --mem-bytes 384 --set "
            "ext_mb_s=30 --set ext_bus_bytes=1 --clock-mhz " +
            clocks + " -j 2 --json " + js.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    std::ifstream in(js);
    const json j = json::parse(in);
    const json& knees = j.at("knees");
    BOOST_REQUIRE_EQUAL(knees.size(), 1u);
    const json& k = knees[0];
    double at = 0;
    BOOST_REQUIRE(std::sscanf(k.at("at").get<std::string>().c_str(), "%lf", &at) == 1);
    BOOST_TEST(std::fabs(at - predicted) < 1e-6);
    BOOST_TEST(k.at("phase_after").get<std::string>() == "spill");
    BOOST_TEST(r.out.find("knee at clock_mhz=") != std::string::npos);
    fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(range_syntax) {
    const fs::path d = tmpdir();
    const fs::path csv = d / "ranges.csv";
    // --dry-run plans every point without running it.
    const Result r =
        run("sweep --dry-run --roi-size 32x16 --pes 8..64*2 --D 4..6 --clock-mhz "
            "10..40:10 --csv " +
            csv.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 4u * 3u * 4u);
    std::set<std::string> pes, D, clk;
    for (const auto& row : rows) {
        pes.insert(row.at("pes"));
        D.insert(row.at("D"));
        clk.insert(row.at("clock_mhz"));
        BOOST_TEST(row.at("status") == "fits-not-run");
    }
    BOOST_TEST((pes == std::set<std::string>{"8", "16", "32", "64"}));
    BOOST_TEST((D == std::set<std::string>{"4", "5", "6"}));
    BOOST_TEST((clk == std::set<std::string>{"10", "20", "30", "40"}));

    // Bad syntax: exit 2, the flag and the accepted syntax named, nothing written.
    const std::pair<const char*, const char*> bad[] = {{"--pes 8..", "--pes"},
                                                       {"--pes 8..64*1", "--pes"},
                                                       {"--pes 64..8", "--pes"},
                                                       {"--D 4,,8", "--D"},
                                                       {"--roi-size 32y16", "--roi-size"},
                                                       {"--clock-mhz abc", "--clock-mhz"},
                                                       {"--set ring_hop=1..x", "--set ring_hop"},
                                                       {"--mode single,both", "--mode"},
                                                       {"--set nosuch=1,2", "nosuch"}};
    for (const auto& [args, flag] : bad) {
        const fs::path out = d / "bad.csv";
        const Result b = run(std::string("sweep --dry-run ") + args + " --csv " + out.string());
        BOOST_TEST_CONTEXT(args << "\n" << b.out) {
            BOOST_TEST(b.code == 2);
            BOOST_TEST(b.out.find(flag) != std::string::npos);
            BOOST_TEST(b.out.find("imapsim: error:") != std::string::npos);
            BOOST_TEST(!fs::exists(out));
        }
    }
    const Result syn = run("sweep --dry-run --pes 8..");
    BOOST_TEST(syn.out.find("A..B*F") != std::string::npos);

    // More than 10000 points are refused.
    const Result big = run("sweep --dry-run --pes 2..200 --D 1..100");
    BOOST_TEST_INFO(big.out);
    BOOST_TEST(big.code == 2);
    BOOST_TEST(big.out.find("19900 points") != std::string::npos);
    BOOST_TEST(big.out.find("10000") != std::string::npos);

    // --plot needs a swept axis; --x must name one.
    BOOST_TEST(
        run("sweep --dry-run --D 8 --roi-size 32x16 --plot " + (d / "p.png").string()).code == 2);
    const Result x = run("sweep --dry-run --pes 8,16 --roi-size 32x16 --D 8 --x D");
    BOOST_TEST(x.code == 2);
    BOOST_TEST(x.out.find("--x") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(failing_point_is_an_error_row_exit_5) {
    // A watchdog of 1000 cycles makes the run fault (exit 3 of the child);
    // the sweep goes on with the other point and exits 5. (--model core: the
    // fault is thrown out of the bare executor, not out of a SystemC thread.)
    const fs::path d = tmpdir();
    const fs::path csv = d / "err.csv";
    const Result r = run(
        "sweep --model core --roi-size 32x16 --D 8 --set watchdog_cycles=1000,2000000000 --csv " +
        csv.string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 5);
    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 2u);
    BOOST_TEST(rows[0].at("status") == "error");
    BOOST_TEST(rows[0].at("message").find("fault") != std::string::npos);
    BOOST_TEST(rows[1].at("status") == "ok");
    // The failed point's log is kept and named.
    const std::string key = "kept in ";
    const size_t k = r.out.find(key);
    BOOST_REQUIRE(k != std::string::npos);
    const fs::path logs = r.out.substr(k + key.size(), r.out.find('\n', k) - k - key.size());
    BOOST_TEST(fs::is_directory(logs));
    bool fault_logged = false;
    for (const auto& e : fs::recursive_directory_iterator(logs))
        if (e.path().extension() == ".log")
            fault_logged |= slurp(e.path()).find("watchdog") != std::string::npos;
    BOOST_TEST(fault_logged);
    std::error_code ec;
    fs::remove_all(logs, ec);
}

BOOST_AUTO_TEST_CASE(table1_grid) {
    const fs::path d = tmpdir();
    const fs::path csv = d / "t1.csv";
    const Result r = run("table1 -j 2 --csv " + csv.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    const Csv c = parse_csv(slurp(csv));
    BOOST_REQUIRE(!c.empty());
    BOOST_TEST((c[0] == std::vector<std::string>{"width", "D", "modeled_ms", "cycles",
                                                 "dominant_phase", "energy_uj"}));
    // The paper's grid: widths 32/64/128, D 16/32/64/128 with D <= width.
    std::set<std::pair<int, int>> want;
    for (int w : {32, 64, 128})
        for (int dd : {16, 32, 64, 128})
            if (dd <= w) want.insert({w, dd});
    BOOST_REQUIRE_EQUAL(want.size(), 9u);
    std::set<std::pair<int, int>> got;
    uint64_t headline = 0;
    double headline_uj = 0;
    for (size_t i = 1; i < c.size(); ++i) {
        BOOST_REQUIRE_EQUAL(c[i].size(), 6u);
        BOOST_TEST(!c[i][4].empty());
        BOOST_TEST(std::stod(c[i][5]) > 0.0);
        const int w = std::stoi(c[i][0]), dd = std::stoi(c[i][1]);
        got.insert({w, dd});
        const uint64_t cyc = std::stoull(c[i][3]);
        BOOST_TEST(std::stod(c[i][2]) == cyc / 40e3, boost::test_tools::tolerance(1e-6));
        if (w == 128 && dd == 64) headline = cyc, headline_uj = std::stod(c[i][5]);
    }
    BOOST_TEST(c.size() == 10u);
    BOOST_TEST((got == want));
    // The headline cell equals a direct run of the same point.
    BOOST_TEST(headline ==
               direct_cycles("--size 128x128 --roi 0,0,128,128 --D 64 --pes 256 --clock-mhz 40",
                             d / "headline.json"));
    // ... and its energy per frame is the one that run reports for it
    // (issue 29 item 3), beside the time in the table's second grid.
    const json hj = json::parse(slurp(d / "headline.json"));
    BOOST_TEST(headline_uj == hj.at("energy").at("total_uj").get<double>(),
               boost::test_tools::tolerance(1e-6));
    BOOST_TEST(r.out.find("Energy per frame (uJ) of the same cells") != std::string::npos);
    BOOST_TEST(r.out.find("energy uJ") != std::string::npos);
    // The stdout table shows the paper's 85 ms beside the headline cell.
    std::istringstream lines(r.out);
    std::string line;
    bool shown = false;
    while (std::getline(lines, line))
        if (line.find("[paper 85]") != std::string::npos && line.find("      128") == 0)
            shown = true;
    BOOST_TEST(shown);
}

BOOST_AUTO_TEST_CASE(ctrl_c_writes_partial_results) {
    const fs::path d = tmpdir();
    const fs::path csv = d / "int.csv", js = d / "int.json", out = d / "int.out";
    // 293 points of ~0.1 s each, one at a time: far longer than the test waits.
    std::vector<std::string> args = {IMAPSIM_EXE, "sweep",      "--roi-size", "32x16",    "--D",
                                     "8",         "--pes",      "8..300",     "-j",       "1",
                                     "--csv",     csv.string(), "--json",     js.string()};
    std::vector<char*> av;
    for (auto& a : args) av.push_back(a.data());
    av.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    posix_spawnattr_t at;
    posix_spawnattr_init(&at);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETPGROUP);  // own group, like a terminal job
    posix_spawnattr_setpgroup(&at, 0);
    pid_t pid = -1;
    BOOST_REQUIRE_EQUAL(posix_spawn(&pid, IMAPSIM_EXE, &fa, &at, av.data(), environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);

    // Wait until a few points have finished (at least ~1 s), then Ctrl-C the
    // whole group (the running child gets it too). The sweep plans all 293
    // points before it runs one (about 4 s of CPU, 40 s under ASan and more
    // on a loaded machine), so the wait may be long; it ends at the third row.
    const auto t0 = std::chrono::steady_clock::now();
    auto finished_rows = [&]() {
        const std::string s = slurp(out);
        size_t n = 0;
        for (size_t p = s.find("ok, bit-exact"); p != std::string::npos;
             p = s.find("ok, bit-exact", p + 1))
            ++n;
        return n;
    };
    while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(600)) {
        if (finished_rows() >= 3 && std::chrono::steady_clock::now() - t0 > std::chrono::seconds(1))
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    BOOST_REQUIRE(::kill(-pid, SIGINT) == 0);
    int st = 0;
    BOOST_REQUIRE_EQUAL(::waitpid(pid, &st, 0), pid);
    BOOST_TEST_INFO(slurp(out));
    BOOST_REQUIRE(WIFEXITED(st));
    BOOST_TEST(WEXITSTATUS(st) == 130);

    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE(rows.size() >= 2u);
    // finished points, then one row saying the sweep was interrupted
    const auto& last = rows.back();
    BOOST_TEST(last.at("status") == "sweep-interrupted");
    BOOST_TEST(last.at("message").find("did not run") != std::string::npos);
    size_t ok = 0;
    for (size_t i = 0; i + 1 < rows.size(); ++i) {
        const std::string& s = rows[i].at("status");
        BOOST_TEST_INFO("status " << s);
        BOOST_TEST((s == "ok" || s == "interrupted"));
        ok += s == "ok";
    }
    BOOST_TEST(ok >= 3u);
    BOOST_TEST(rows.size() - 1 < 293u);

    std::ifstream in(js);
    const json j = json::parse(in);
    BOOST_TEST(j.at("interrupted").get<bool>());
    BOOST_TEST(j.at("points_total").get<size_t>() == 293u);
    BOOST_TEST(j.at("not_run").get<size_t>() > 0u);
    BOOST_TEST(j.at("rows").size() == rows.size() - 1);
    BOOST_TEST(j.at("points_finished").get<size_t>() + j.at("not_run").get<size_t>() == 293u);
}

BOOST_AUTO_TEST_CASE(area_column_grows_with_the_pe_count) {
    // The sweep's area column: the yosys figures of the design's PE and CP
    // scaled to each point's machine (every model reports them; CI has yosys).
    const fs::path d = tmpdir() / "area";
    fs::create_directories(d);
    const fs::path csv = d / "a.csv", rep = d / "r.json";
    const Result r =
        run("sweep --model core --roi-size 32x16 --D 8 --pes 8,16 --csv " + csv.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    BOOST_TEST(r.out.find("Mcells") != std::string::npos);
    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 2u);
    BOOST_REQUIRE(!rows[0].at("area_cells").empty());
    const uint64_t c8 = std::stoull(rows[0].at("area_cells"));
    const uint64_t c16 = std::stoull(rows[1].at("area_cells"));
    const uint64_t m8 = std::stoull(rows[0].at("area_memory_bits"));
    const uint64_t m16 = std::stoull(rows[1].at("area_memory_bits"));
    // Eight more PEs: eight more PE cells, eight more PEs' registers and memory.
    const Result one =
        run("run --model core --size 32x16 --roi 0,0,32,16 --D 8 --pes 8 --report " + rep.string());
    BOOST_REQUIRE_EQUAL(one.code, 0);
    const nlohmann::json j = nlohmann::json::parse(slurp(rep));
    const uint64_t pe = j.at("area").at("pe_cells").get<uint64_t>();
    BOOST_TEST(pe > 100u);
    BOOST_TEST(j.at("area").at("cells").get<uint64_t>() == c8);
    BOOST_TEST(c16 - c8 == 8 * pe);
    BOOST_TEST(m16 - m8 == 8u * (8u * 16u + 8u * 1024u));
}

// Issue 29 item 3: --y chooses the table's extra column and the plot's y;
// --pareto lists the Pareto-optimal points and draws time against energy;
// edp = energy x modeled time; a bad --y is refused before anything runs.
BOOST_AUTO_TEST_CASE(y_metric_and_pareto_view) {
    const fs::path d = tmpdir() / "pareto";
    fs::create_directories(d);
    const fs::path csv = d / "p.csv", png = d / "p.png", never = d / "never.csv";
    const Result bad =
        run("sweep --roi-size 32x16 --D 8 --pes 8,16 --y speed --csv " + never.string());
    BOOST_TEST_INFO(bad.out);
    BOOST_TEST(bad.code == 2);
    BOOST_TEST(bad.out.find("invalid value 'speed' for --y: expected one of time, energy, power, "
                            "edp, area") != std::string::npos);
    BOOST_TEST(!fs::exists(never));

    const Result r =
        run("sweep --model core --roi-size 32x16 --D 8 --pes 8,16,32 --y energy "
            "--pareto --csv " +
            csv.string() + " --plot " + png.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    BOOST_TEST(r.out.find("energy uJ") != std::string::npos);
    BOOST_TEST(r.out.find("  least energy: pes=") != std::string::npos);
    BOOST_TEST(r.out.find("Pareto-optimal") != std::string::npos);
    BOOST_TEST(fs::exists(png));
    const std::string gp = slurp(d / "p.gp");
    BOOST_TEST(gp.find("Energy per frame vs modeled frame time") != std::string::npos);
    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 3u);
    // The Pareto set recomputed from the CSV: a point is listed exactly
    // when no other is at most as slow and at most as much energy, better in one.
    for (const auto& a : rows) {
        const double ta = std::stod(a.at("modeled_ms")), ea = std::stod(a.at("energy_uj"));
        // the CSV prints the three with 6 decimals: each within 0.5e-6
        BOOST_TEST(std::abs(std::stod(a.at("edp")) - ea * ta) <= 0.5e-6 * (1.0 + ea + ta) + 1e-12);
        bool dominated = false;
        for (const auto& b : rows) {
            const double tb = std::stod(b.at("modeled_ms")), eb = std::stod(b.at("energy_uj"));
            dominated |= tb <= ta && eb <= ea && (tb < ta || eb < ea);
        }
        const bool listed = r.out.find("    pes=" + a.at("pes") + ": ") != std::string::npos;
        BOOST_TEST(listed == !dominated, "pes=" << a.at("pes"));
    }
}

// A point runs the algorithm it was planned with: the preset and the A.9
// options reach the child `imapsim run` (they were dropped, so quality
// points were planned as quality and ran the paper's parameters in bidir).
BOOST_AUTO_TEST_CASE(a_preset_sweep_point_runs_the_preset) {
    const fs::path d = tmpdir();
    const fs::path csv = d / "quality.csv";
    const Result r =
        run("sweep --model core --preset quality --roi-size 32x16 --D 8 --pes 32 --csv " +
            csv.string());
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE_EQUAL(r.code, 0);
    const auto rows = records(parse_csv(slurp(csv)));
    BOOST_REQUIRE_EQUAL(rows.size(), 1u);
    const std::string point = "--model core --size 32x16 --roi 0,0,32,16 --D 8 --pes 32";
    const uint64_t quality = direct_cycles("--preset quality " + point, d / "quality.json");
    BOOST_TEST(std::stoull(rows[0].at("cycles")) == quality);
    BOOST_TEST(quality != direct_cycles(point, d / "paper.json"));
}
