// Synthetic sequences: deterministic, exact ground truth in the convention of
// SPEC A.1 (left pixel x + d shows what right pixel x shows), objects moving
// on straight paths inside the view; frame-pair listing and sequence writing.
#define BOOST_TEST_MODULE vision_sequence
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <set>

#include "imap/vision/calib.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/sequence.hpp"
#include "imap/vision/synth.hpp"
#include "test_helpers.hpp"

namespace v = imap::vision;
namespace fs = std::filesystem;
using vision_test::TempDir;

namespace {

bool same(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

// Bounding box of the pixels with gt == d.
cv::Rect level_box(const cv::Mat& gt, int d) {
    std::vector<cv::Point> pts;
    cv::findNonZero(gt == d, pts);
    return pts.empty() ? cv::Rect() : cv::boundingRect(pts);
}

}  // namespace

BOOST_AUTO_TEST_CASE(same_seed_same_bytes) {
    for (int k : {0, 4, 9}) {
        const v::SequenceFrame a = v::make_sequence_frame(5, 160, 120, k, 10);
        const v::SequenceFrame b = v::make_sequence_frame(5, 160, 120, k, 10);
        BOOST_TEST(same(a.left, b.left));
        BOOST_TEST(same(a.right, b.right));
        BOOST_TEST(same(a.gt, b.gt));
        BOOST_TEST(a.max_disp == b.max_disp);
        const v::SequenceFrame c = v::make_sequence_frame(6, 160, 120, k, 10);
        BOOST_TEST(!same(a.left, c.left));
        BOOST_TEST(!same(a.gt, c.gt));
    }
}

BOOST_AUTO_TEST_CASE(generator_gives_the_same_frames) {
    const v::SequenceGenerator gen(11, 96, 64, 7);
    BOOST_TEST(gen.frames() == 7);
    BOOST_TEST(gen.max_disp() == 24);
    for (int k : {6, 0, 3}) {  // any order
        const v::SequenceFrame a = gen.frame(k), b = v::make_sequence_frame(11, 96, 64, k, 7);
        BOOST_TEST(same(a.left, b.left));
        BOOST_TEST(same(a.right, b.right));
        BOOST_TEST(same(a.gt, b.gt));
        BOOST_TEST(a.max_disp == b.max_disp);
    }
    BOOST_CHECK_THROW(gen.frame(7), std::invalid_argument);
    BOOST_CHECK_THROW(v::SequenceGenerator(1, 8, 64, 3), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(frames_differ_and_share_max_disp) {
    const int W = 160, H = 120, F = 6;
    std::vector<v::SequenceFrame> f;
    for (int k = 0; k < F; ++k) f.push_back(v::make_sequence_frame(2, W, H, k, F));
    BOOST_TEST(f[0].max_disp == std::min(W / 4, v::kSequenceMaxDisp));
    for (int k = 0; k < F; ++k) {
        BOOST_TEST_CONTEXT("frame " << k) {
            BOOST_TEST(f[k].left.type() == CV_8UC1);
            BOOST_TEST(f[k].gt.size() == cv::Size(W, H));
            BOOST_TEST(f[k].max_disp == f[0].max_disp);
            double mx = 0;
            cv::minMaxLoc(f[k].gt, nullptr, &mx);
            BOOST_TEST(static_cast<int>(mx) == f[k].max_disp);  // the nearest object is visible
            std::set<int> levels;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) levels.insert(f[k].gt.at<uint8_t>(y, x));
            BOOST_TEST(levels.count(0) == 1u);
            BOOST_TEST(levels.size() >= 3u);
            if (k > 0) {
                BOOST_TEST(!same(f[k].gt, f[k - 1].gt));  // the objects move
                BOOST_TEST(!same(f[k].left, f[k - 1].left));
            }
        }
    }
    // A frame of a one-frame sequence is valid too (static objects).
    BOOST_TEST(v::make_sequence_frame(2, W, H, 0, 1).max_disp == f[0].max_disp);
}

BOOST_AUTO_TEST_CASE(ground_truth_matches_the_views) {
    for (uint64_t seed : {1ull, 2ull, 77ull}) {
        for (int k : {0, 11, 29}) {
            BOOST_TEST_CONTEXT("seed " << seed << " frame " << k) {
                const v::SequenceFrame s = v::make_sequence_frame(seed, 200, 150, k, 30);
                vision_test::check_views_match_ground_truth(s.left, s.right, s.gt, s.max_disp,
                                                            v::kSynthNoise);
            }
        }
    }
}

// The nearest object (gt == max_disp) is never covered: its shape keeps its
// pixel count, its box moves along a straight line at a constant velocity of
// at most kSequenceMaxSpeedX/Y pixels per frame, and its texture moves with it.
// The background (gt 0 in both frames) stays where it is.
BOOST_AUTO_TEST_CASE(objects_move_on_straight_paths_with_their_texture) {
    const int W = 200, H = 150, F = 12;
    for (uint64_t seed : {1ull, 3ull, 8ull}) {
        BOOST_TEST_CONTEXT("seed " << seed) {
            std::vector<v::SequenceFrame> f;
            for (int k = 0; k < F; ++k) f.push_back(v::make_sequence_frame(seed, W, H, k, F));
            const int D = f[0].max_disp;
            const int area = cv::countNonZero(f[0].gt == D);
            std::vector<cv::Rect> box;
            for (int k = 0; k < F; ++k) {
                box.push_back(level_box(f[k].gt, D));
                BOOST_TEST(cv::countNonZero(f[k].gt == D) == area);
                BOOST_TEST(box[k].size() == box[0].size());
                BOOST_TEST(box[k].x >= D);
                BOOST_TEST(box[k].x + box[k].width <= W);
                BOOST_TEST(box[k].y + box[k].height <= H);
            }
            const int tx = box[F - 1].x - box[0].x, ty = box[F - 1].y - box[0].y;
            BOOST_TEST((tx != 0 || ty != 0));
            for (int k = 1; k < F; ++k) {
                const int dx = box[k].x - box[k - 1].x, dy = box[k].y - box[k - 1].y;
                BOOST_TEST(std::abs(dx) <= v::kSequenceMaxSpeedX);
                BOOST_TEST(std::abs(dy) <= v::kSequenceMaxSpeedY);
                // Straight line, constant velocity: within rounding of the line.
                BOOST_TEST(std::abs((box[k].x - box[0].x) * (F - 1) - tx * k) <= (F - 1) / 2);
                BOOST_TEST(std::abs((box[k].y - box[0].y) * (F - 1) - ty * k) <= (F - 1) / 2);
                // Texture: object pixel (x, y) of frame k-1 is at (x+dx, y+dy) in frame k.
                long n = 0, bad = 0;
                for (int y = box[k - 1].y; y < box[k - 1].br().y; ++y)
                    for (int x = box[k - 1].x; x < box[k - 1].br().x; ++x) {
                        if (f[k - 1].gt.at<uint8_t>(y, x) != D) continue;
                        ++n;
                        if (std::abs(f[k - 1].left.at<uint8_t>(y, x) -
                                     f[k].left.at<uint8_t>(y + dy, x + dx)) > 2 * v::kSynthNoise)
                            ++bad;
                    }
                BOOST_TEST(n == area);
                BOOST_TEST(bad == 0);
                // Background stays; its noise is drawn anew for every frame.
                long bg = 0, bg_bad = 0, bg_changed = 0;
                for (int y = 0; y < H; ++y)
                    for (int x = 0; x < W; ++x)
                        if (f[k].gt.at<uint8_t>(y, x) == 0 && f[k - 1].gt.at<uint8_t>(y, x) == 0) {
                            ++bg;
                            const int a = f[k].left.at<uint8_t>(y, x),
                                      b = f[k - 1].left.at<uint8_t>(y, x);
                            if (std::abs(a - b) > 2 * v::kSynthNoise) ++bg_bad;
                            if (a != b) ++bg_changed;
                        }
                BOOST_TEST(bg > W * H / 4);
                BOOST_TEST(bg_bad == 0);
                BOOST_TEST(bg_changed > bg / 2);
            }
        }
    }
}

BOOST_AUTO_TEST_CASE(long_sequences_stay_inside_the_view) {
    // 100000 frames: paths are shortened to fit, so motion is sub-pixel per frame.
    const int F = 100000;
    const v::SequenceFrame a = v::make_sequence_frame(4, 64, 48, 0, F);
    const v::SequenceFrame b = v::make_sequence_frame(4, 64, 48, F - 1, F);
    const v::SequenceFrame c = v::make_sequence_frame(4, 64, 48, 1, F);
    const int D = a.max_disp;
    BOOST_TEST(D == 16);
    BOOST_TEST(cv::countNonZero(a.gt == D) == cv::countNonZero(b.gt == D));
    BOOST_TEST(level_box(b.gt, D).x >= D);
    BOOST_TEST(same(a.gt, c.gt));  // no visible motion from frame 0 to frame 1
}

BOOST_AUTO_TEST_CASE(bad_arguments_are_refused) {
    BOOST_CHECK_THROW(v::make_sequence_frame(1, 15, 64, 0, 1), std::invalid_argument);
    BOOST_CHECK_THROW(v::make_sequence_frame(1, 64, 15, 0, 1), std::invalid_argument);
    BOOST_CHECK_THROW(v::make_sequence_frame(1, 64, 64, 3, 3), std::invalid_argument);
    BOOST_CHECK_THROW(v::make_sequence_frame(1, 64, 64, -1, 3), std::invalid_argument);
    BOOST_CHECK_THROW(v::make_sequence_frame(1, 64, 64, 0, 0), std::invalid_argument);
    const v::SequenceFrame s = v::make_sequence_frame(1, 16, 16, 0, 2);  // smallest size
    BOOST_TEST(s.max_disp == 4);
}

// ---------------------------------------------------------------------------
// list_frame_pairs

namespace {
void touch(const fs::path& p) {
    fs::create_directories(p.parent_path());
    vision_test::write_file(p.string(), "x");
}
std::vector<std::string> names(const std::vector<v::FramePair>& pairs) {
    std::vector<std::string> n;
    for (const auto& p : pairs) n.push_back(p.name);
    return n;
}
}  // namespace

BOOST_AUTO_TEST_CASE(pairs_by_name_ordered_by_number) {
    const TempDir d("pairs_flat");
    for (const char* n :
         {"left_10.png", "right_10.png", "left_2.png", "right_2.png", "left_0001.png",
          "right_0001.png", "f7_Left.png", "f7_Right.png", "CAM_LEFT_3.PNG", "CAM_RIGHT_3.PNG",
          "left_5.png", "gt_0001.png", "left_notes.txt", ".left_0009.tmp-12.png",
          "cleft_left_4.png", "cleft_right_4.png", "calib.yml"})
        touch(d.path() / n);
    const std::vector<v::FramePair> p = v::list_frame_pairs(d.path().string());
    const std::vector<std::string> want = {"left_0001.png",    "left_2.png", "CAM_LEFT_3.PNG",
                                           "cleft_left_4.png", "left_5.png", "f7_Left.png",
                                           "left_10.png"};
    BOOST_TEST(names(p) == want, boost::test_tools::per_element());
    for (const auto& fp : p) {
        BOOST_TEST_CONTEXT(fp.name) {
            BOOST_TEST(fp.left == (d.path() / fp.name).string());
            if (fp.name == "left_5.png") {
                BOOST_TEST(fp.right.empty());
                BOOST_TEST(fp.error.find("right_5.png") != std::string::npos);
            } else {
                BOOST_TEST(fp.error.empty());
                BOOST_TEST(fs::is_regular_file(fp.right));
            }
        }
    }
    auto right_of = [&](const std::string& name) {
        for (const auto& fp : p)
            if (fp.name == name) return fs::path(fp.right).filename().string();
        return std::string("?");
    };
    BOOST_TEST(right_of("f7_Left.png") == "f7_Right.png");
    BOOST_TEST(right_of("CAM_LEFT_3.PNG") == "CAM_RIGHT_3.PNG");
    BOOST_TEST(right_of("cleft_left_4.png") == "cleft_right_4.png");  // 2nd "left" pairs
    BOOST_TEST(right_of("left_10.png") == "right_10.png");
}

BOOST_AUTO_TEST_CASE(pairs_from_left_and_right_subfolders) {
    const TempDir d("pairs_sub");
    for (const char* n : {"Left/img10.png", "Right/img10.png", "Left/img9.png", "Right/img9.png",
                          "Left/img11.png", "Left/.hidden.png", "Right/img12.png"})
        touch(d.path() / n);
    const std::vector<v::FramePair> p = v::list_frame_pairs(d.path().string());
    const std::vector<std::string> want = {"img9.png", "img10.png", "img11.png"};
    BOOST_TEST(names(p) == want, boost::test_tools::per_element());
    BOOST_TEST(p[0].left == (d.path() / "Left" / "img9.png").string());
    BOOST_TEST(p[0].right == (d.path() / "Right" / "img9.png").string());
    BOOST_TEST(p[2].right.empty());
    BOOST_TEST(p[2].error.find("img11.png") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(folders_without_pairs_are_errors) {
    const TempDir d("pairs_none");
    auto msg = [](const std::string& dir) {
        try {
            v::list_frame_pairs(dir);
        } catch (const v::InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    BOOST_TEST(msg(d.path().string()).find("no frame pairs") != std::string::npos);  // empty
    touch(d.path() / "right_0.png");
    touch(d.path() / "scene.png");
    BOOST_TEST(msg(d.path().string()).find("no frame pairs") != std::string::npos);
    BOOST_TEST(msg((d.path() / "missing").string()).find("not a folder") != std::string::npos);
    BOOST_TEST(msg((d.path() / "scene.png").string()).find("not a folder") != std::string::npos);
    // left/ and right/ subfolders without images
    const TempDir s("pairs_none_sub");
    fs::create_directories(s.path() / "left");
    fs::create_directories(s.path() / "right");
    touch(s.path() / "right" / "img0.png");
    const std::string m = msg(s.path().string());
    BOOST_TEST(
        m.find("no image files in '" + (s.path() / "left").string() + "'") != std::string::npos, m);
    BOOST_TEST(m.find("left/ and right/ frames with equal names") != std::string::npos, m);
}

// ---------------------------------------------------------------------------
// write_sequence

BOOST_AUTO_TEST_CASE(write_sequence_rectified_and_raw) {
    const TempDir d("seq_write");
    const int W = 96, H = 64, F = 3;
    const fs::path plain = d.path() / "plain";
    BOOST_TEST(v::write_sequence(plain.string(), 9, W, H, F, "") == 24);
    BOOST_TEST(vision_test::count_entries(plain) == 3 * F);
    for (int k = 0; k < F; ++k) {
        const v::SequenceFrame f = v::make_sequence_frame(9, W, H, k, F);
        char num[16];
        std::snprintf(num, sizeof num, "%04d", k);
        const std::string n(num);
        BOOST_TEST(same(v::load_grey8((plain / ("left_" + n + ".png")).string(), "l"), f.left));
        BOOST_TEST(same(v::load_grey8((plain / ("right_" + n + ".png")).string(), "r"), f.right));
        BOOST_TEST(same(v::load_grey8((plain / ("gt_" + n + ".png")).string(), "g"), f.gt));
    }
    const auto pairs = v::list_frame_pairs(plain.string());
    BOOST_TEST(pairs.size() == static_cast<size_t>(F));

    // Raw frames + calibration: rectifying them gives back the rectified frames
    // (up to the resampling blur; see test_calib), gt is unchanged.
    const fs::path raw = d.path() / "raw";
    const std::string calib = (d.path() / "calib.yml").string();
    // The progress callback runs once per frame, after the frame's files.
    std::vector<int> calls;
    BOOST_TEST(v::write_sequence(raw.string(), 9, W, H, F, calib, [&](int done) {
                   BOOST_TEST(vision_test::count_entries(raw) == 3 * done);
                   calls.push_back(done);
               }) == 24);
    BOOST_TEST(calls == (std::vector<int>{1, 2, 3}), boost::test_tools::per_element());
    BOOST_TEST(vision_test::count_entries(raw) == 3 * F);
    const v::StereoCalib c = v::load_stereo_calib(calib);
    BOOST_TEST(c.size == cv::Size(W, H));
    const v::Rectifier r(c);
    const v::SequenceFrame f = v::make_sequence_frame(9, W, H, 1, F);
    const cv::Mat rl = v::load_grey8((raw / "left_0001.png").string(), "l");
    const cv::Mat rr = v::load_grey8((raw / "right_0001.png").string(), "r");
    BOOST_TEST(!same(rl, f.left));
    BOOST_TEST(same(v::load_grey8((raw / "gt_0001.png").string(), "g"), f.gt));
    cv::Mat bl, br, diff;
    r.rectify(rl, rr, &bl, &br);
    cv::absdiff(bl, f.left, diff);
    const cv::Rect inner(4, 4, W - 8, H - 8);
    BOOST_TEST(cv::mean(diff(inner))[0] < 10.0);
    cv::Mat raw_diff;
    cv::absdiff(rl, f.left, raw_diff);
    BOOST_TEST(cv::mean(raw_diff(inner))[0] > cv::mean(diff(inner))[0] + 5.0);

    // A bad calibration name fails before any frame is written.
    const fs::path bad = d.path() / "bad";
    BOOST_CHECK_THROW(v::write_sequence(bad.string(), 9, W, H, F, (d.path() / "c.txt").string()),
                      v::InputError);
    BOOST_TEST((!fs::exists(bad) || vision_test::count_entries(bad) == 0));
    BOOST_CHECK_THROW(v::write_sequence((d.path() / "calib.yml").string(), 9, W, H, F, ""),
                      v::InputError);  // not a folder
}
