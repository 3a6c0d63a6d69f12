// The stream engine end to end, one SystemC elaboration: three synthetic
// frames through the testbench with every output (PNGs, video, logs); the
// logs say complete and hold every frame, each map is bit-exact.
#define BOOST_TEST_MODULE engine_stream_run
#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "engine_test_util.hpp"
#include "imap/engine/stream.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/vision/colour.hpp"

namespace es = imap::engine::stream;
namespace tb = imap::testbench;
namespace fs = std::filesystem;
using enginetest::slurp;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

BOOST_AUTO_TEST_CASE(three_frames_with_every_output) {
    es::SourceSpec spec;
    spec.synthetic = 3;
    spec.width = 32;
    spec.height = 16;
    es::OpenedSource src = es::open_source(spec);
    tb::StreamSetup setup;
    setup.params.D = 8;
    setup.roi = {0, 0, 32, 16};
    setup.size = src.size;
    setup.machine.pes = 16;
    setup.plan = imap::firmware::plan_frame(setup.params, setup.roi, setup.machine);
    setup.program = imap::firmware::assemble_frame(setup.params, setup.plan);
    setup.timing.fps = 100;
    setup.timing.resolve(16);
    const fs::path d = tmpdir();
    const es::Outputs out{d.string(), (d / "v.avi").string(), (d / "s.json").string(),
                          (d / "s.csv").string(), true};
    std::vector<std::string> lines;
    es::Hooks hooks;
    hooks.frame = [&](const std::string& l) { lines.push_back(l); };
    const es::Outcome o = es::run(*src.source, setup, out, {{"source", "synthetic"}}, hooks);
    BOOST_TEST(!o.result.error);
    BOOST_TEST(o.state == "complete");
    BOOST_TEST(o.exit_code() == 0);
    BOOST_TEST(o.summary.ok == 3u);
    BOOST_TEST(o.video_frames == 3);
    BOOST_REQUIRE_EQUAL(lines.size(), 3u);
    BOOST_TEST(lines[0].find("bit-exact") != std::string::npos);
    for (int i = 0; i < 3; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "disp_%04d.png", i);
        BOOST_TEST(fs::exists(d / name), name);
        // --out-color: the colour map of the same disparities (issue 32 item 8)
        std::snprintf(name, sizeof name, "disp_%04d_color.png", i);
        BOOST_TEST_REQUIRE(fs::exists(d / name), name);
        std::snprintf(name, sizeof name, "disp_%04d.png", i);
        const cv::Mat grey = cv::imread((d / name).string(), cv::IMREAD_UNCHANGED);
        std::snprintf(name, sizeof name, "disp_%04d_color.png", i);
        const cv::Mat colour = cv::imread((d / name).string(), cv::IMREAD_COLOR);
        BOOST_TEST(colour.channels() == 3);
        BOOST_TEST(cv::norm(colour, imap::vision::colorize_disparity(grey, 8), cv::NORM_INF) ==
                   0.0);
    }
    const auto j = nlohmann::json::parse(slurp(d / "s.json"));
    BOOST_TEST(j["state"] == "complete");
    BOOST_TEST(j["frames"].size() == 3u);
    BOOST_TEST(j["source"] == "synthetic");
    size_t csv_lines = 0;
    std::istringstream in(slurp(d / "s.csv"));
    for (std::string l; std::getline(in, l);) ++csv_lines;
    BOOST_TEST(csv_lines == 4u);
    BOOST_TEST(fs::exists(d / "v.avi"));
}
