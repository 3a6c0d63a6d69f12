// imapsim stream's request without a simulation: the refused flag
// combinations with imapsim's messages, the log paths defaulting into
// --out-dir, the synthetic source with the planned firmware and the log head.
#define BOOST_TEST_MODULE engine_stream_request
#include <boost/test/unit_test.hpp>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/stream_request.hpp"

namespace eng = imap::engine;
namespace es = imap::engine::stream;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

std::string error_of(const es::Request& r) {
    try {
        es::prepare(r);
    } catch (const eng::Error& e) {
        BOOST_TEST(e.code() == eng::kExitInput);
        return e.what();
    }
    return "";
}

es::Request synthetic(const char* n) {
    es::Request r;
    r.synthetic = n;
    r.size = "64x48";
    r.algo.D = "16";
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(refused_combinations) {
    es::Request r;
    BOOST_TEST(error_of(r) ==
               "give exactly one source: --frames DIR, --left-video L --right-video R, or "
               "--synthetic N");
    r.left_video = "l.avi";
    BOOST_TEST(error_of(r) == "--left-video and --right-video must be given together");
    r = synthetic("2");
    r.video = "x.mp4";
    BOOST_TEST(error_of(r) ==
               "--video 'x.mp4': the side-by-side video is Motion-JPEG in AVI: use a name "
               "ending in .avi");
    r = synthetic("2");
    r.out_color = true;
    BOOST_TEST(error_of(r) == "--out-color needs --out-dir (the maps are written there)");
    r = synthetic("2");
    r.machine.camera = "ntsc";
    r.line_us = "3";
    BOOST_TEST(error_of(r) ==
               "--line-us and a timed camera (--camera, camera_pixel_mhz) both set the line "
               "period: give one");
}

BOOST_AUTO_TEST_CASE(synthetic_source_planned) {
    es::Request r = synthetic("3");
    r.out_dir = (tmpdir() / "out").string();
    r.fps = "10";
    const es::Prepared pr = es::prepare(r);
    BOOST_TEST(pr.opened.size.width == 64);
    BOOST_TEST(pr.opened.size.height == 48);
    BOOST_TEST((pr.setup.roi.w == 64 && pr.setup.roi.h == 48));  // the whole frame
    BOOST_TEST(pr.setup.params.D == 16);
    BOOST_TEST(!pr.setup.program.code.empty());
    BOOST_TEST(pr.outputs.json_path == r.out_dir + "/stream.json");
    BOOST_TEST(pr.outputs.csv_path == r.out_dir + "/stream.csv");
    BOOST_TEST(!std::filesystem::exists(r.out_dir));  // nothing created yet
    const auto head = es::log_head(r, pr);
    BOOST_TEST(head["timing"]["fps"] == 10.0);
    BOOST_TEST(head["model"] == "tlm");
    BOOST_TEST(head["size"][0] == 64);
}
