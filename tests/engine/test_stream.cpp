// The stream engine without a simulation: opening sources (the synthetic
// sequence, a limit, a folder without a usable frame), the summary, the
// per-frame logs and lines, and the side-by-side video written into place.
#define BOOST_TEST_MODULE engine_stream
#include <boost/test/unit_test.hpp>
#include <opencv2/videoio.hpp>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/stream.hpp"
#include "imap/vision/colour.hpp"

namespace es = imap::engine::stream;
namespace tb = imap::testbench;
namespace fs = std::filesystem;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

tb::FrameRecord rec(int i, const std::string& status, double compute, double done, bool met) {
    tb::FrameRecord r;
    r.index = i;
    r.name = "f" + std::to_string(i);
    r.status = status;
    r.compute_ms = compute;
    r.done_ms = done;
    r.latency_ms = done - 40.0 * i;
    r.deadline_met = met;
    r.cycles = static_cast<uint64_t>(compute * 40000);
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(synthetic_source_with_a_limit) {
    es::SourceSpec s;
    s.synthetic = 5;
    s.width = 48;
    s.height = 24;
    s.max_frames = 3;
    es::OpenedSource o = es::open_source(s);
    BOOST_TEST(o.size.width == 48);
    BOOST_TEST(o.size.height == 24);
    BOOST_TEST(o.source->count() == 3);
    tb::SourceFrame f;
    int n = 0;
    while (o.source->next(f)) {
        BOOST_TEST(f.error.empty());
        BOOST_TEST(f.index == n);  // the peeked first frame comes back first
        ++n;
    }
    BOOST_TEST(n == 3);
    BOOST_TEST(o.calib_note.find("none") == 0u);
}

BOOST_AUTO_TEST_CASE(a_source_without_a_usable_frame_is_refused) {
    const fs::path d = tmpdir() / "frames";
    fs::create_directories(d);
    std::ofstream(d / "left_0001.png") << "not a png";
    std::ofstream(d / "right_0001.png") << "not a png";
    es::SourceSpec s;
    s.frames_dir = d.string();
    try {
        es::open_source(s);
        BOOST_ERROR("accepted");
    } catch (const imap::engine::Error& e) {
        BOOST_TEST(e.code() == imap::engine::kExitInput);
        BOOST_TEST(std::string(e.what()).find("no usable frame") != std::string::npos, e.what());
    }
}

BOOST_AUTO_TEST_CASE(summary_logs_and_lines) {
    std::vector<tb::FrameRecord> rs = {rec(0, "ok", 10, 20, true), rec(1, "mismatch", 20, 70, true),
                                       rec(2, "ok", 30, 130, false)};
    tb::FrameRecord bad;
    bad.index = 3;
    bad.name = "f3";
    bad.status = "bad-frame";
    bad.error = "unreadable, \"quoted\"";
    rs.push_back(bad);
    const es::Summary s = es::summarize(rs);
    BOOST_TEST(s.frames == 4u);
    BOOST_TEST(s.ok == 2u);
    BOOST_TEST(s.mismatch == 1u);
    BOOST_TEST(s.bad == 1u);
    BOOST_TEST(s.ran == 3u);
    BOOST_TEST(s.missed == 1u);
    BOOST_TEST(s.mean_compute == 20.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s.throughput_fps == 1000.0 * 2 / 110.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s.capacity_fps == 50.0, boost::test_tools::tolerance(1e-12));
    const std::string csv = es::records_csv(rs);
    BOOST_TEST(csv.find("index,name,status,cycles,") == 0u);
    BOOST_TEST(csv.find("\"unreadable, \"\"quoted\"\"\"") != std::string::npos, csv);
    const auto j = es::log_json({{"source", "test"}}, rs, "complete");
    BOOST_TEST(j["state"] == "complete");
    BOOST_TEST(j["source"] == "test");
    BOOST_TEST(j["frames"].size() == 4u);
    BOOST_TEST(j["summary"]["missed_deadlines"] == 1);
    BOOST_TEST(es::frame_line(rs[0]).find("frame 0 f0: bit-exact, 400000 cycles") == 0u);
    BOOST_TEST(es::frame_line(rs[1]).find("MISMATCH vs golden") != std::string::npos);
    BOOST_TEST(es::frame_line(rs[2]).find("(DEADLINE MISSED)") != std::string::npos);
    BOOST_TEST(es::frame_line(bad) == "frame 3 f3: BAD FRAME: unreadable, \"quoted\"");
}

// Issue 32 item 8: the frames' finish times alone give 2 / 0.9 ms, more
// than the camera's 2000 fps delivers; the throughput is capped at the
// camera's rate, in the summary and in the log.
BOOST_AUTO_TEST_CASE(throughput_never_exceeds_the_camera) {
    std::vector<tb::FrameRecord> rs = {rec(0, "ok", 0.3, 1.0, false), rec(1, "ok", 0.3, 1.5, false),
                                       rec(2, "ok", 0.3, 1.9, false)};
    BOOST_TEST(es::summarize(rs).throughput_fps == 1000.0 * 2 / 0.9,
               boost::test_tools::tolerance(1e-9));
    BOOST_TEST(es::summarize(rs, 2000.0).throughput_fps == 2000.0);
    BOOST_TEST(es::summarize(rs, 4000.0).throughput_fps == 1000.0 * 2 / 0.9,
               boost::test_tools::tolerance(1e-9));
    const auto j = es::log_json({{"timing", {{"fps", 2000.0}}}}, rs, "complete");
    BOOST_TEST(j["summary"]["modeled_fps"].get<double>() == 2000.0);
    // A missed deadline is an exit status only when asked for.
    es::Outcome o;
    o.summary = es::summarize(rs, 2000.0);
    BOOST_TEST(o.summary.missed == 3u);
    BOOST_TEST(o.exit_code() == 0);
    BOOST_TEST(o.exit_code(true) == 5);
    o.summary.missed = 0;
    BOOST_TEST(o.exit_code(true) == 0);
}

BOOST_AUTO_TEST_CASE(side_by_side_video_is_renamed_into_place) {
    const fs::path v = tmpdir() / "sbs.avi";
    const imap::golden::Roi roi{2, 1, 16, 8};
    {
        es::SideBySide video(v.string(), 25, roi, 8);
        BOOST_TEST(!fs::exists(v));  // written under a temporary name
        const cv::Mat left(12, 24, CV_8UC1, cv::Scalar(100));
        cv::Mat disp(8, 16, CV_8UC1, cv::Scalar(3));
        disp.at<uint8_t>(0, 0) = 255;
        for (int i = 0; i < 3; ++i) video.add(left, disp);
        BOOST_TEST(video.finish() == 3);
    }
    BOOST_TEST(fs::exists(v));
    cv::VideoCapture cap(v.string());
    BOOST_REQUIRE(cap.isOpened());
    cv::Mat frame;
    BOOST_REQUIRE(cap.read(frame));
    BOOST_TEST(frame.cols == 32);
    // the ROI's rows and the legend under the map
    BOOST_TEST(frame.rows == 8 + imap::vision::legend_height());
    // Not finished: nothing is left behind.
    const fs::path w = tmpdir() / "dropped.avi";
    { es::SideBySide video(w.string(), 25, roi, 8); }
    BOOST_TEST(!fs::exists(w));
    for (const auto& e : fs::directory_iterator(tmpdir()))
        BOOST_TEST(e.path().filename().string().find(".tmp-") == std::string::npos);
    BOOST_CHECK_THROW(es::SideBySide((tmpdir() / "no" / "x.avi").string(), 25, roi, 8),
                      imap::engine::Error);
}
