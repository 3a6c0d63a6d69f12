// Determinism of imapsim run: two runs of the same case on the same model
// give byte-identical disparity maps, VCD and GTKWave files, and reports
// that are equal once the wall-clock fields are removed; the three models
// (core, tlm, rtl) give identical maps, cycles and phases. The same for a
// stream: per-frame maps, side-by-side video and logs.
#define BOOST_TEST_MODULE reliability_determinism
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The small synthetic case; rtl traces two PEs only to keep the VCD small.
// 8 PEs: the RTL's waves need a traced configuration (built for 8 PEs).
const char* const kCase = "--size 64x32 --D 16 --pes 8 --trace-pes 0:1";
const char* const kModels[] = {"core", "tlm", "rtl"};

// Report fields that measure the host, not the model (docs/errors.md).
const char* const kWallClockFields[] = {"wall_s", "golden_ms", "sim_cycles_per_s"};

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    BOOST_REQUIRE_MESSAGE(in.good(), "cannot read " << p);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Run {
    fs::path dir;
    clitest::Result result;
    std::string map, vcd, gtkw;
    json report;
};

// Runs the case in its own folder with relative output names, so that the
// files of two runs can be compared byte for byte (the .gtkw names the VCD).
Run run_case(const std::string& model, const std::string& tag) {
    Run r;
    r.dir = fs::temp_directory_path() /
            ("imapsim-determinism-" + std::to_string(::getpid()) + "-" + model + "-" + tag);
    fs::remove_all(r.dir);
    fs::create_directories(r.dir);
    const std::string cmd = "cd '" + r.dir.string() + "' && " + IMAPSIM_EXE + " run --model " +
                            model + " " + kCase + " --report r.json --out map.png --vcd w.vcd 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    BOOST_REQUIRE(p != nullptr);
    char buf[4096];
    size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.result.out.append(buf, n);
    const int st = pclose(p);
    r.result.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    BOOST_TEST_INFO(cmd << "\n" << r.result.out);
    BOOST_REQUIRE(r.result.code == 0);
    r.map = read_file(r.dir / "map.png");
    r.vcd = read_file(r.dir / "w.vcd");
    r.gtkw = read_file(r.dir / "w.gtkw");
    r.report = json::parse(read_file(r.dir / "r.json"));
    return r;
}

// The report without the wall-clock fields; they must be there (a renamed
// field would otherwise make the comparison pass vacuously or fail late).
json without_wall_clock(json j) {
    for (const char* f : kWallClockFields) {
        BOOST_TEST(j.contains(f), "report has " << f);
        j.erase(f);
    }
    return j;
}

std::map<std::string, Run>& first_runs() {
    static std::map<std::string, Run> runs;
    return runs;
}

}  // namespace

BOOST_AUTO_TEST_CASE(two_runs_are_identical) {
    for (const char* model : kModels) {
        BOOST_TEST_CONTEXT("model " << model) {
            Run a = run_case(model, "a");
            const Run b = run_case(model, "b");
            BOOST_TEST(a.report.at("bit_exact").get<bool>());
            BOOST_TEST(a.map == b.map, "disparity maps byte-identical");
            BOOST_TEST(a.vcd.size() > 1000u);
            BOOST_TEST(a.vcd == b.vcd, "VCD files byte-identical");
            BOOST_TEST(a.gtkw == b.gtkw, "GTKWave files byte-identical");
            const json ja = without_wall_clock(a.report), jb = without_wall_clock(b.report);
            BOOST_TEST(ja == jb, "reports equal without wall-clock fields:\n"
                                     << ja.dump(1) << "\n"
                                     << jb.dump(1));
            fs::remove_all(a.dir);
            fs::remove_all(b.dir);
            a.vcd.clear();  // keep the map and report for the cross-model test
            first_runs()[model] = std::move(a);
        }
    }
}

BOOST_AUTO_TEST_CASE(models_agree) {
    for (const char* model : kModels)
        if (!first_runs().count(model)) first_runs()[model] = run_case(model, "a");
    const Run& ref = first_runs().at("core");
    json jref = without_wall_clock(ref.report);
    jref.erase("model");
    for (const char* model : {"tlm", "rtl"}) {
        BOOST_TEST_CONTEXT("core vs " << model) {
            const Run& r = first_runs().at(model);
            BOOST_TEST(r.report.at("model") == model);
            BOOST_TEST(r.map == ref.map, "same disparity map");
            BOOST_TEST(r.report.at("cycles") == ref.report.at("cycles"));
            BOOST_TEST(r.report.at("phases") == ref.report.at("phases"));
            json j = without_wall_clock(r.report);
            j.erase("model");
            // the RTL's own fields (its configuration and clocks), which
            // the other models do not have
            if (std::string(model) == "rtl") {
                BOOST_TEST(j.at("rtl").at("cycles") == ref.report.at("cycles"));
                j.erase("rtl");
                // its energy from the instruction-set model's counts of the
                // same program (docs/energy.md 5): the same figures, the
                // source named
                BOOST_TEST(j.at("energy")
                               .at("events_source")
                               .get<std::string>()
                               .find("instruction-set model") == 0u);
                j["energy"]["events_source"] = jref.at("energy").at("events_source");
            }
            BOOST_TEST(j == jref, "reports equal but for the model and wall-clock fields");
        }
    }
    for (auto& [m, r] : first_runs()) fs::remove_all(r.dir);
}

// Two runs of the same stream: byte-identical disparity maps and video, and
// logs equal once the per-frame wall time (the CSV's wall_s column, the
// JSON's frames[].wall_s, model_wall_s, golden_wall_s) is removed.
BOOST_AUTO_TEST_CASE(two_streams_are_identical) {
    struct Stream {
        fs::path dir;
        std::map<std::string, std::string> files;  // name -> bytes
        json log;
        std::vector<std::string> csv;  // rows without the wall_s field
    };
    auto stream = [](const std::string& tag) {
        Stream st;
        st.dir = fs::temp_directory_path() /
                 ("imapsim-determinism-" + std::to_string(::getpid()) + "-stream-" + tag);
        fs::remove_all(st.dir);
        fs::create_directories(st.dir);
        const clitest::Result r =
            clitest::run("stream --synthetic 3 --size 64x32 --D 8 --out-dir " +
                         (st.dir / "o").string() + " --video " + (st.dir / "o" / "v.avi").string());
        BOOST_TEST_INFO(r.out);
        BOOST_REQUIRE(r.code == 0);
        for (const auto& e : fs::directory_iterator(st.dir / "o"))
            st.files[e.path().filename().string()] = read_file(e.path());
        st.log = json::parse(st.files.at("stream.json"));
        for (json& f : st.log.at("frames")) {  // the host times: wall_s and its parts
            for (const char* k : {"wall_s", "model_wall_s", "golden_wall_s"}) {
                BOOST_TEST(f.contains(k), k);
                f.erase(k);
            }
        }
        std::istringstream csv(st.files.at("stream.csv"));
        size_t wall_col = std::string::npos;
        for (std::string line; std::getline(csv, line);) {
            std::vector<std::string> fields;
            std::istringstream ls(line);
            for (std::string f; std::getline(ls, f, ',');) fields.push_back(f);
            if (wall_col == std::string::npos) {  // the header names the column
                for (size_t i = 0; i < fields.size(); ++i)
                    if (fields[i] == "wall_s") wall_col = i;
                BOOST_REQUIRE(wall_col != std::string::npos);
            }
            BOOST_REQUIRE(wall_col < fields.size());
            fields.erase(fields.begin() + static_cast<long>(wall_col));
            std::string row;
            for (const std::string& f : fields) row += f + ",";
            st.csv.push_back(row);
        }
        return st;
    };
    const Stream a = stream("a"), b = stream("b");
    std::vector<std::string> names;
    for (const auto& [name, bytes] : a.files) names.push_back(name);
    BOOST_TEST(names == (std::vector<std::string>{"disp_0000.png", "disp_0001.png", "disp_0002.png",
                                                  "stream.csv", "stream.json", "v.avi"}),
               boost::test_tools::per_element());
    BOOST_TEST(b.files.size() == a.files.size());
    for (const char* f : {"disp_0000.png", "disp_0001.png", "disp_0002.png", "v.avi"})
        BOOST_TEST(a.files.at(f) == b.files.at(f), f << " byte-identical");
    BOOST_TEST(a.log == b.log, "stream.json equal without the wall times");
    BOOST_TEST(a.csv == b.csv, boost::test_tools::per_element());
    BOOST_TEST(a.csv.size() == 4u);
    fs::remove_all(a.dir);
    fs::remove_all(b.dir);
}
