// imapsim golden / eval / synth / run from the outside: exit codes, one-line
// errors naming the problem, no output file on error, outputs on success.
#define BOOST_TEST_MODULE cli_golden
#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "cli_test_util.hpp"

#include "imap/golden/stereo.hpp"
#include "imap/vision/colour.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/perturb.hpp"
#include "imap/vision/synth.hpp"

namespace fs = std::filesystem;

namespace {

using clitest::Result;
using clitest::run;

// A fresh folder with a synthetic pair (left.png, right.png).
struct Fixture {
    fs::path dir;
    Fixture() {
        dir = fs::temp_directory_path() /
              ("imapsim-cli-" + std::to_string(::getpid()) + "-" +
               boost::unit_test::framework::current_test_case().p_name.get());
        fs::remove_all(dir);
        fs::create_directories(dir);
        const auto sc = imap::vision::make_synth_scene(7, 96, 24);
        cv::imwrite((dir / "left.png").string(), sc.left);
        cv::imwrite((dir / "right.png").string(), sc.right);
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return (dir / name).string(); }
    std::string pair() const { return "--left " + p("left.png") + " --right " + p("right.png"); }
    // Writes the synthetic scene of `seed` (96x32, with ground truth) to
    // scene/ and returns the eval command prefix for it (D = 25).
    std::string eval_on_scene(int seed) const {
        BOOST_REQUIRE(
            run("synth --seed " + std::to_string(seed) + " --size 96x32 --out-dir " + p("scene"))
                .code == 0);
        return "eval --scene " + p("scene") + " --gt-scale 1 --D 25 ";
    }
};

void expect_input_error(const Fixture& f, const std::string& extra, const std::string& needle) {
    const std::string out = f.p("out.png");
    const Result r = run("golden " + f.pair() + " --out " + out + " " + extra);
    BOOST_TEST_CONTEXT("args: " << extra << "\noutput: " << r.out) {
        BOOST_TEST(r.code == 2);
        BOOST_TEST(r.out.find(needle) != std::string::npos);
        BOOST_TEST(r.out.find("imapsim: error:") != std::string::npos);
        BOOST_TEST(!fs::exists(out));
    }
}

}  // namespace

BOOST_FIXTURE_TEST_CASE(golden_writes_map_equal_to_library, Fixture) {
    const Result r = run("golden " + pair() + " --out " + p("d.png") + " --D 24 --roi 4,2,80,20");
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(r.out.find("golden:") == 0);
    BOOST_TEST(std::count(r.out.begin(), r.out.end(), '\n') == 1);  // one-line summary
    const cv::Mat d = cv::imread(p("d.png"), cv::IMREAD_UNCHANGED);
    BOOST_REQUIRE(!d.empty());
    BOOST_TEST(d.cols == 80);
    BOOST_TEST(d.rows == 20);
    // Same map as the library call with the same parameters.
    namespace g = imap::golden;
    const cv::Mat L = imap::vision::load_grey8(p("left.png"), "left");
    const cv::Mat R = imap::vision::load_grey8(p("right.png"), "right");
    g::Params prm;
    prm.D = 24;
    const g::DisparityMap m =
        g::compute(prm, imap::vision::view_of(L), imap::vision::view_of(R), g::Roi{4, 2, 80, 20});
    BOOST_TEST(std::equal(m.data.begin(), m.data.end(), d.data));
}

BOOST_FIXTURE_TEST_CASE(golden_existing_output_untouched_on_error, Fixture) {
    { std::ofstream(p("out.png")) << "previous"; }
    const Result r = run("golden " + pair() + " --out " + p("out.png") + " --D 0");
    BOOST_TEST(r.code == 2);
    std::ifstream in(p("out.png"));
    std::string content;
    std::getline(in, content);
    BOOST_TEST(content == "previous");
}

BOOST_FIXTURE_TEST_CASE(golden_bad_inputs, Fixture) {
    expect_input_error(*this, "--D 0", "--D");
    expect_input_error(*this, "--D 97", "D = 97");  // D > ROI width 96
    expect_input_error(*this, "--D 300", "--D");
    expect_input_error(*this, "--D abc", "'abc'");
    expect_input_error(*this, "--km -1", "--km");
    expect_input_error(*this, "--km 0 --kb 0", "km");
    expect_input_error(*this, "--gb 256", "--gb");
    expect_input_error(*this, "--Wo 5 --Wd 10", "Wo");
    expect_input_error(*this, "--mode both", "--mode");
    expect_input_error(*this, "--seed-col 0", "--seed-col");
    expect_input_error(*this, "--seed-col 96", "seed-col");
    expect_input_error(*this, "--seed-disp 99 --D 10", "seed-disp");
    expect_input_error(*this, "--vote maybe", "--vote");
    expect_input_error(*this, "--frame top", "--frame");
    expect_input_error(*this, "--roi 90,0,10,10", "ROI");
    expect_input_error(*this, "--roi 0,20,10,10", "ROI");
    expect_input_error(*this, "--roi 1,2,3", "--roi");
}

BOOST_FIXTURE_TEST_CASE(golden_bad_files, Fixture) {
    const Result missing = run("golden --left " + p("nope.png") + " --right " + p("right.png") +
                               " --out " + p("o.png"));
    BOOST_TEST(missing.code == 2);
    BOOST_TEST(missing.out.find("nope.png") != std::string::npos);
    BOOST_TEST(!fs::exists(p("o.png")));

    cv::imwrite(p("small.png"), cv::Mat(10, 10, CV_8UC1, cv::Scalar(3)));
    const Result mismatch = run("golden --left " + p("left.png") + " --right " + p("small.png") +
                                " --out " + p("o.png"));
    BOOST_TEST(mismatch.code == 2);
    BOOST_TEST(mismatch.out.find("size") != std::string::npos);
    BOOST_TEST(!fs::exists(p("o.png")));

    const Result badext = run("golden " + pair() + " --out " + p("o.nosuchformat"));
    BOOST_TEST(badext.code == 2);
    BOOST_TEST(!fs::exists(p("o.nosuchformat")));
}

BOOST_FIXTURE_TEST_CASE(synth_then_eval_scores_the_scene, Fixture) {
    const Result s = run("synth --seed 3 --size 128x48 --out-dir " + p("scene"));
    BOOST_TEST_INFO(s.out);
    BOOST_REQUIRE(s.code == 0);
    for (const char* f : {"left.png", "right.png", "gt.png"})
        BOOST_TEST(fs::exists(p("scene/") + f));
    const Result e =
        run("eval --scene " + p("scene") + " --gt-scale 1 --D 49 --json " + p("e.json"));
    BOOST_TEST_INFO(e.out);
    BOOST_TEST(e.code == 0);
    BOOST_TEST(fs::exists(p("e.json")));
    BOOST_TEST(e.out.find("golden") != std::string::npos);
}

nlohmann::json read_json(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

BOOST_FIXTURE_TEST_CASE(presets_and_overrides, Fixture) {
    // --preset quality sets the SPEC A.9 options; a flag given overrides its
    // preset value; the golden row names the preset.
    const std::string ev = eval_on_scene(3) + "--matcher golden ";
    const Result q = run(ev + "--preset quality --json " + p("q.json"));
    BOOST_TEST_INFO(q.out);
    BOOST_REQUIRE(q.code == 0);
    BOOST_TEST(q.out.find("golden:quality") != std::string::npos);
    const auto jq = read_json(p("q.json")).at(0).at("params");
    BOOST_TEST(jq.at("mode") == "joint");
    BOOST_TEST(jq.at("kc") == 4);
    BOOST_TEST(jq.at("agg_rx") == 2);
    BOOST_TEST(jq.at("km") == 1);
    const Result o =
        run(ev + "--preset quality --mode single --kc 2 --Wo 99 --Wd 99 --json " + p("o.json"));
    BOOST_REQUIRE(o.code == 0);
    const auto jo = read_json(p("o.json")).at(0).at("params");
    BOOST_TEST(jo.at("mode") == "single");
    BOOST_TEST(jo.at("kc") == 2);
    BOOST_TEST(jo.at("Wo") == 99);
    BOOST_TEST(jo.at("ad_max") == 16);  // still the preset's
    // The paper preset is today's default: the same map as no preset, no A.9 keys.
    BOOST_REQUIRE(run(ev + "--preset paper --json " + p("a.json")).code == 0);
    BOOST_REQUIRE(run(ev + "--json " + p("b.json")).code == 0);
    const auto ja = read_json(p("a.json")).at(0), jb = read_json(p("b.json")).at(0);
    BOOST_TEST(ja.at("params") == jb.at("params"));
    BOOST_TEST(ja.at("nonocc") == jb.at("nonocc"));
    BOOST_TEST(!ja.at("params").contains("kc"));
    // golden with an explicit --mode bidir on top of the quality preset
    const Result g =
        run("golden " + pair() + " --out " + p("d.png") + " --D 16 --preset quality --mode bidir");
    BOOST_TEST_INFO(g.out);
    BOOST_TEST(g.code == 0);
    BOOST_TEST(g.out.find(" bidir ") != std::string::npos);
}

BOOST_FIXTURE_TEST_CASE(bad_presets_and_options_are_refused, Fixture) {
    expect_input_error(*this, "--preset fast", "invalid value 'fast' for --preset");
    expect_input_error(*this, "--preset quality --census 3", "--census is out of range");
    expect_input_error(*this, "--agg-rx 8", "--agg-rx is out of range (allowed: 0..7)");
    expect_input_error(*this, "--dissim sad", "invalid value 'sad' for --dissim");
    expect_input_error(*this, "--ad-max 256", "--ad-max is out of range (allowed: 0..255)");
    expect_input_error(*this, "--mode diagonal", "expected single, bidir or joint");
    expect_input_error(*this, "--km 0 --kb 0", "at least one match weight must be > 0");
}

BOOST_FIXTURE_TEST_CASE(the_firmware_refuses_a9_options, Fixture) {
    // A window wider than the firmware's copies (agg-rx > 2): a model run
    // refuses it before any work (and writes no report) instead of running
    // another algorithm against the golden.
    const Result r = run(
        "run --model core --size 64x16 --D 8 --preset quality --agg-rx 3 --report " + p("r.json"));
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("does not implement the SPEC A.9 option(s) --agg-rx 3") !=
               std::string::npos);
    BOOST_TEST(!fs::exists(p("r.json")));
}

BOOST_FIXTURE_TEST_CASE(eval_tradeoff_table_json_and_plot, Fixture) {
    const std::string ev = eval_on_scene(5);
    const Result t = run(ev + "--tradeoff --json " + p("t.json") + " --plot " + p("t.png"));
    BOOST_TEST_INFO(t.out);
    BOOST_REQUIRE(t.code == 0);
    BOOST_TEST(fs::exists(p("t.png")));
    // drawn by gnuplot, with its script and data beside it
    BOOST_TEST(fs::exists(p("t.gp")));
    BOOST_TEST(fs::exists(p("t.dat")));
    const auto rows = read_json(p("t.json"));
    bool quality = false, five = false, paper = false, sgbm = false;
    for (const auto& r : rows) {
        const std::string name = r.at("variant");
        BOOST_TEST(t.out.find(name) != std::string::npos);
        if (name == "quality") {
            quality = true;
            // the budget, all of it measured: the firmware runs the preset
            BOOST_TEST(r.at("modeled_ms").get<double>() <= 40.0);
            BOOST_TEST(r.at("a9_cycles_estimate").get<int64_t>() == 0);
            BOOST_TEST(r.at("fw_cycles_measured").get<int64_t>() > 0);
        }
        if (name == "quality-5x1") {
            five = true;  // the horizontal window alone: measured as well
            BOOST_TEST(r.at("a9_cycles_estimate").get<int64_t>() == 0);
            BOOST_TEST(r.at("fw_cycles_measured").get<int64_t>() > 0);
        }
        if (name == "paper") {
            paper = true;
            BOOST_TEST(r.at("a9_cycles_estimate").get<int64_t>() == 0);
            // Energy beside time (issue 29 item 3): the headline case as
            // imapsim run reports it for the same point (the default scene
            // and ROI, D = 64, the cyclopean frame the firmware runs).
            const Result h = run("run --model core --preset paper --D 64 --frame cyc --report " +
                                 p("paper.json"));
            BOOST_TEST_INFO(h.out);
            BOOST_REQUIRE(h.code == 0);
            const auto hj = read_json(p("paper.json"));
            BOOST_TEST(r.at("fw_cycles_measured").get<int64_t>() == hj.at("cycles").get<int64_t>());
            BOOST_TEST(
                r.at("fw_energy_uj").get<double>() == hj.at("energy").at("total_uj").get<double>(),
                boost::test_tools::tolerance(1e-12));
            char uj[32];
            std::snprintf(uj, sizeof uj, "%.3f", r.at("fw_energy_uj").get<double>());
            BOOST_TEST(t.out.find(uj) != std::string::npos, uj);
        }
        if (name == "opencv-sgbm") {
            // present and scored, but never pinned (OpenCV's kernels vary by CPU)
            sgbm = true;
            BOOST_TEST(r.at("nonocc").get<double>() >= 0.0);
            BOOST_TEST(!r.contains("modeled_ms"));
        }
    }
    BOOST_TEST((quality && five && paper && sgbm));
    // refused combinations
    const Result a = run(ev + "--tradeoff --km 3");
    BOOST_TEST(a.code == 2);
    BOOST_TEST(a.out.find("drop --km") != std::string::npos);
    const Result b = run(ev + "--plot " + p("x.png"));
    BOOST_TEST(b.code == 2);
    BOOST_TEST(b.out.find("--plot needs --tradeoff") != std::string::npos);
    BOOST_TEST(!fs::exists(p("x.png")));
}

BOOST_FIXTURE_TEST_CASE(eval_param_sets, Fixture) {
    const std::string ev = eval_on_scene(4);
    {
        std::ofstream f(p("sets.txt"));
        f << "# two sets\n--preset paper\n\n--preset quality --kc 2 --Wo 300 --Wd 300\n";
    }
    const Result r = run(ev + "--param-sets " + p("sets.txt") + " --json " + p("s.json"));
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const auto rows = read_json(p("s.json"));
    BOOST_REQUIRE(rows.size() == 2u);
    BOOST_TEST(rows[0].at("line") == 2);
    BOOST_TEST(rows[1].at("line") == 4);
    BOOST_TEST(rows[1].at("params").at("kc") == 2);
    BOOST_TEST(rows[1].at("params").at("Wo") == 300);
    // the same score as a plain eval with those flags
    BOOST_REQUIRE(run(ev + "--matcher golden --preset paper --json " + p("e.json")).code == 0);
    BOOST_TEST(read_json(p("e.json")).at(0).at("nonocc") == rows[0].at("nonocc"));
    {
        std::ofstream f(p("bad.txt"));
        f << "--preset quality\n--kc many\n";
    }
    const Result b = run(ev + "--param-sets " + p("bad.txt") + " --json " + p("b.json"));
    BOOST_TEST(b.code == 2);
    BOOST_TEST(b.out.find("bad.txt:2: invalid value 'many' for --kc") != std::string::npos, b.out);
    BOOST_TEST(!fs::exists(p("b.json")));
    const Result c = run(ev + "--param-sets " + p("sets.txt") + " --km 2");
    BOOST_TEST(c.code == 2);
    BOOST_TEST(c.out.find("drop --km") != std::string::npos);
}

BOOST_FIXTURE_TEST_CASE(eval_perturb, Fixture) {
    const std::string ev = eval_on_scene(6);
    const std::string spec = "gain=0.8,offset=10,noise=3,seed=4";
    const Result r = run(ev + "--matcher all --perturb " + spec + " --json " + p("p.json"));
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(r.out.find("perturbation: gain=0.8,offset=10,image=right,noise=3,"
                          "noise-image=both,seed=4") == 0);
    const auto rows = read_json(p("p.json"));
    BOOST_REQUIRE(rows.size() == 3u);  // golden and both OpenCV matchers, all perturbed
    for (const auto& row : rows)
        BOOST_TEST(row.at("perturb").get<std::string>().find("seed=4") != std::string::npos);

    // The same scores as an unperturbed eval of a folder holding the pair
    // perturbed by the library: the perturbation reaches the matchers.
    fs::copy(p("scene"), p("pert"));
    cv::Mat L = imap::vision::load_grey8(p("pert/left.png"), "left");
    cv::Mat R = imap::vision::load_grey8(p("pert/right.png"), "right");
    imap::vision::perturb_pair(L, R, imap::vision::parse_perturbation(spec));
    cv::imwrite(p("pert/left.png"), L);
    cv::imwrite(p("pert/right.png"), R);
    const Result e = run("eval --scene " + p("pert") + " --gt-scale 1 --D 25 --matcher golden " +
                         "--json " + p("e.json"));
    BOOST_REQUIRE(e.code == 0);
    BOOST_TEST(read_json(p("e.json")).at(0).at("nonocc") == rows.at(0).at("nonocc"));

    // The identity perturbation scores exactly as no perturbation; a change
    // of the gain changes the golden's score on this scene.
    BOOST_REQUIRE(run(ev + "--matcher golden --json " + p("a.json")).code == 0);
    BOOST_REQUIRE(
        run(ev + "--matcher golden --perturb gain=1,image=both,seed=9 --json " + p("b.json"))
            .code == 0);
    BOOST_REQUIRE(
        run(ev + "--matcher golden --perturb gain=0.5,offset=-30 --json " + p("c.json")).code == 0);
    const double plain = read_json(p("a.json")).at(0).at("nonocc");
    BOOST_TEST(read_json(p("b.json")).at(0).at("nonocc").get<double>() == plain);
    BOOST_TEST(read_json(p("c.json")).at(0).at("nonocc").get<double>() != plain);
}

BOOST_FIXTURE_TEST_CASE(eval_perturb_bad_specs, Fixture) {
    const std::string ev = eval_on_scene(6) + "--json " + p("x.json") + " ";
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"gain=0", "'gain=0' for --perturb: expected a number > 0 and <= 16"},
        {"gain=-0.5", "'gain=-0.5' for --perturb: expected a number > 0"},
        {"gain=inf", "'gain=inf' for --perturb: expected a number > 0"},
        {"noise=-1", "'noise=-1' for --perturb: expected a standard deviation in 0..64"},
        {"offset=999", "'offset=999' for --perturb: expected a number in -255..255"},
        {"seed=x", "'seed=x' for --perturb: expected an integer"},
        {"image=top", "'image=top' for --perturb: expected left, right or both"},
        {"blur=1", "'blur=1' for --perturb: unknown key 'blur'"},
        {"gain0.8", "'gain0.8' for --perturb: expected key=value"},
        {"noise=1,noise=2", "'noise=2' for --perturb: 'noise' given twice"},
    };
    for (const auto& [spec, needle] : bad) {
        const Result r = run(ev + "--perturb " + spec);
        BOOST_TEST_CONTEXT("spec " << spec << "\noutput: " << r.out) {
            BOOST_TEST(r.code == 2);
            BOOST_TEST(r.out.find("imapsim: error: invalid value " + needle) != std::string::npos);
            BOOST_TEST(r.out.find("bad>1") == std::string::npos);  // refused before any work
            BOOST_TEST(!fs::exists(p("x.json")));
        }
    }
}

BOOST_FIXTURE_TEST_CASE(eval_robustness, Fixture) {
    const std::string ev = eval_on_scene(6) + "--matcher golden ";
    const Result r = run(ev + "--preset quality --robustness --json " + p("r.json"));
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const auto rows = read_json(p("r.json"));
    BOOST_REQUIRE(rows.size() == 6u);
    BOOST_TEST(r.out.find("golden:quality") != std::string::npos);
    // each condition scores as eval --perturb with its SPEC
    for (const auto& row : rows) {
        std::string extra;
        if (!row.at("perturb").is_null())
            extra = "--perturb " + row.at("perturb").get<std::string>();
        BOOST_TEST_CONTEXT(row.at("condition")) {
            const Result e = run(ev + "--preset quality " + extra + " --json " + p("e.json"));
            BOOST_REQUIRE(e.code == 0);
            BOOST_TEST(read_json(p("e.json")).at(0).at("nonocc") ==
                       row.at("nonocc").at("golden:quality"));
        }
    }
    const Result a = run(ev + "--robustness --perturb noise=2");
    BOOST_TEST(a.code == 2);
    BOOST_TEST(a.out.find("drop --perturb") != std::string::npos);
    const Result b = run(ev.substr(0, ev.find("--matcher")) + "--robustness --tradeoff");
    BOOST_TEST(b.code == 2);
    BOOST_TEST(b.out.find("--robustness") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(main_job_without_arguments) {
    const Result r = run("");
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(r.out.find("synthetic scene") != std::string::npos);
    BOOST_TEST(r.out.find("bad-1") != std::string::npos);
}

// Issue 13 item 5: --out-color writes the map colour-mapped: each pixel the
// colour of the raw map's value, occluded (255) white.
BOOST_FIXTURE_TEST_CASE(colour_mapped_map, Fixture) {
    const Result r =
        run("golden " + pair() + " --D 16 --out " + p("raw.png") + " --out-color " + p("col.png"));
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const cv::Mat raw = cv::imread(p("raw.png"), cv::IMREAD_UNCHANGED);
    const cv::Mat col = cv::imread(p("col.png"), cv::IMREAD_UNCHANGED);
    BOOST_REQUIRE(col.type() == CV_8UC3);
    BOOST_REQUIRE(col.size() == raw.size());
    int occluded = 0;
    for (int y = 0; y < raw.rows; ++y)
        for (int x = 0; x < raw.cols; ++x) {
            const int d = raw.at<uint8_t>(y, x);
            occluded += d == 255;
            BOOST_TEST((col.at<cv::Vec3b>(y, x) == imap::vision::disparity_colour(d, 16)));
        }
    BOOST_TEST(occluded > 0);  // the unfilled map has occlusions to show
    BOOST_TEST(
        run("golden " + pair() + " --out " + p("a.png") + " --out-color " + p("c.txt")).code == 2);
    BOOST_TEST(!fs::exists(p("a.png")));
}
