// imapsim stream from the outside: a 30-frame synthetic sequence written as
// raw (un-rectified) frames with its calibration, rectified back in the
// stream, bit-exact on every frame and about as accurate as the directly
// rendered sequence; Ctrl-C. A corrupt frame in the middle and bad flags are
// rows of the bad-input matrix (tests/reliability/test_error_matrix.cpp).
#define BOOST_TEST_MODULE cli_stream
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "cli_test_util.hpp"
#include "imap/vision/colour.hpp"

extern char** environ;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using clitest::Result;
using clitest::run;

fs::path tmpdir(const std::string& tag) {
    fs::path d = fs::temp_directory_path() /
                 ("imapsim-cli-stream-" + tag + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

json read_json(const fs::path& p) {
    std::ifstream in(p);
    BOOST_REQUIRE_MESSAGE(in.good(), "cannot open " << p);
    return json::parse(in);
}

size_t count_lines(const fs::path& p) {
    std::ifstream in(p);
    size_t n = 0;
    for (std::string l; std::getline(in, l);) ++n;
    return n;
}

size_t count_files(const fs::path& dir, const std::string& prefix) {
    size_t n = 0;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return 0;
    for (const auto& e : fs::directory_iterator(dir))
        n += e.path().filename().string().rfind(prefix, 0) == 0;
    return n;
}

double mean_bad1(const json& log) {
    double s = 0;
    for (const auto& f : log["frames"]) s += f["bad1_percent"].get<double>();
    return s / static_cast<double>(log["frames"].size());
}

}  // namespace

// The acceptance run: 30 frames, un-rectify / rectify round trip.
BOOST_AUTO_TEST_CASE(thirty_frames_rectified_round_trip) {
    const fs::path d = tmpdir("rt");
    const std::string seq = (d / "seq").string(), out = (d / "out").string();
    const Result s = run("synth --frames 30 --size 128x96 --seed 4 --calib-out " + seq +
                         "/calib.yml --out-dir " + seq);
    BOOST_REQUIRE_MESSAGE(s.code == 0, s.out);
    const Result r = run("stream --frames " + seq + " --calib " + seq + "/calib.yml --D 33" +
                         " --out-dir " + out + " --video " + out + "/sbs.avi");
    BOOST_TEST_MESSAGE(r.out);
    BOOST_REQUIRE_MESSAGE(r.code == 0, r.out);
    BOOST_TEST(r.out.find("30 frames: 30 bit-exact") != std::string::npos);
    const json log = read_json(fs::path(out) / "stream.json");
    BOOST_TEST(log["state"] == "complete");
    BOOST_REQUIRE_EQUAL(log["frames"].size(), 30u);
    for (const auto& f : log["frames"]) {
        BOOST_TEST(f["status"] == "ok");
        BOOST_TEST(f["differing_pixels"] == 0);
        BOOST_TEST(f["latency_ms"].get<double>() > f["compute_ms"].get<double>());
    }
    BOOST_TEST(log["summary"]["ok"] == 30);
    BOOST_TEST(count_lines(fs::path(out) / "stream.csv") == 31u);
    BOOST_TEST(count_files(out, "disp_") == 30u);
    const cv::Mat m = cv::imread(out + "/disp_0029.png", cv::IMREAD_UNCHANGED);
    BOOST_TEST(m.cols == 128);
    BOOST_TEST(m.rows == 96);
    cv::VideoCapture vc(out + "/sbs.avi");
    BOOST_REQUIRE(vc.isOpened());
    BOOST_TEST(vc.get(cv::CAP_PROP_FRAME_WIDTH) == 256.0);
    // Issue 13 item 5: a legend under the map (colour bar, white occlusion box).
    BOOST_TEST(vc.get(cv::CAP_PROP_FRAME_HEIGHT) == 96.0 + imap::vision::legend_height());
    int frames = 0;
    for (cv::Mat f; vc.read(f);) {
        if (frames++ > 0) continue;
        const cv::Vec3b box = f.at<cv::Vec3b>(96 + 3, 256 - 3);  // JPEG: about white
        BOOST_TEST((box[0] > 200 && box[1] > 200 && box[2] > 200));
        const cv::Vec3b bar0 = f.at<cv::Vec3b>(96 + 3, 128 + 3);  // disparity 0: dark blue
        BOOST_TEST((bar0[0] > 100 && bar0[2] < 60));
    }
    BOOST_TEST(frames == 30);

    // The same sequence rendered directly as rectified pairs.
    const std::string out2 = (d / "direct").string();
    const Result r2 =
        run("stream --synthetic 30 --size 128x96 --seed 4 --D 33 --json " + out2 + ".json");
    BOOST_REQUIRE_MESSAGE(r2.code == 0, r2.out);
    const json direct = read_json(out2 + ".json");
    const double rt = mean_bad1(log), dir = mean_bad1(direct);
    BOOST_TEST_MESSAGE("mean bad-1: direct " << dir << " %, rectify round trip " << rt << " %");
    // Tolerance as in vision.rectify_accuracy (docs/calibration.md): the
    // two bilinear resamplings of the round trip blur fine texture, which
    // costs a few points of bad-1 at object edges (measured +3 to +4.5);
    // a one-row rectification error costs about +20.
    BOOST_TEST(dir < 15.0);
    BOOST_TEST(rt <= dir + 6.5);
}

// Output names without a folder ("n1.avi") are files in the current folder,
// beside --out-dir or not (issue: "cannot make absolute path", exit 4).
BOOST_AUTO_TEST_CASE(bare_output_file_names) {
    const fs::path d = tmpdir("bare");
    const Result r =
        run("stream --synthetic 3 --size 64x48 --D 8 --out-dir n1 --video n1.avi --json n7.json "
            "--csv n7.csv",
            d.string());
    BOOST_TEST_MESSAGE(r.out);
    BOOST_REQUIRE_MESSAGE(r.code == 0, r.out);
    BOOST_TEST(fs::is_regular_file(d / "n1.avi"));
    BOOST_TEST(fs::is_regular_file(d / "n7.json"));
    BOOST_TEST(fs::is_regular_file(d / "n7.csv"));
    BOOST_TEST(count_files(d / "n1", "disp_") == 3u);
    BOOST_TEST(read_json(d / "n7.json")["summary"]["ok"] == 3);
    // A bare name given for the folder's own log is the same as the default.
    const Result r2 = run("stream --synthetic 2 --size 64x48 --D 8 --out-dir . --json s.json",
                          (d / "n1").string());
    BOOST_REQUIRE_MESSAGE(r2.code == 0, r2.out);
    BOOST_TEST(fs::is_regular_file(d / "n1" / "s.json"));
    BOOST_TEST(fs::is_regular_file(d / "n1" / "stream.csv"));
    // A folder name with a trailing '/' (as shell completion writes it) is
    // created like the name without it, for stream and synth alike.
    const Result r3 = run("stream --synthetic 1 --size 64x48 --D 8 --out-dir fresh/", d.string());
    BOOST_REQUIRE_MESSAGE(r3.code == 0, r3.out);
    BOOST_TEST(count_files(d / "fresh", "disp_") == 1u);
    const Result r4 = run("synth --seed 1 --size 64x48 --out-dir scene/", d.string());
    BOOST_REQUIRE_MESSAGE(r4.code == 0, r4.out);
    BOOST_TEST(fs::is_regular_file(d / "scene" / "left.png"));
    fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(ctrl_c_leaves_consistent_partial_logs) {
    const fs::path d = tmpdir("int");
    const std::string out = (d / "out").string();
    const std::string exe = IMAPSIM_EXE;
    std::vector<std::string> args = {exe,     "stream", "--synthetic", "100000",    "--size",
                                     "64x32", "--D",    "16",          "--out-dir", out};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, (d / "stdout.txt").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid = 0;
    BOOST_REQUIRE(posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&fa);
    // Wait until some frames are done (the log exists), then interrupt.
    const auto t0 = std::chrono::steady_clock::now();
    while (count_files(out, "disp_") < 3 &&
           std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    BOOST_REQUIRE(::kill(pid, SIGINT) == 0);
    int st = 0;
    BOOST_REQUIRE(waitpid(pid, &st, 0) == pid);
    BOOST_REQUIRE(WIFEXITED(st));
    BOOST_TEST(WEXITSTATUS(st) == 130);
    const json log = read_json(fs::path(out) / "stream.json");
    BOOST_TEST(log["state"] == "interrupted");
    const size_t n = log["frames"].size();
    BOOST_TEST(n >= 3u);
    BOOST_TEST(n < 100000u);
    BOOST_TEST(log["summary"]["frames"] == n);
    BOOST_TEST(count_lines(fs::path(out) / "stream.csv") == n + 1);
    BOOST_TEST(count_files(out, "disp_") == n);
    BOOST_TEST(count_files(out, ".") == 0u);  // no temporary files left
    for (size_t k = 0; k < n; ++k) BOOST_TEST(log["frames"][k]["index"] == k);
}
