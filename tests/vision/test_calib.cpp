// Stereo calibration files (read, write, validation with one-line errors that
// name the key) and the rectifier built from a calibration.
#define BOOST_TEST_MODULE vision_calib
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "imap/vision/calib.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/sequence.hpp"
#include "test_helpers.hpp"

namespace v = imap::vision;
using vision_test::TempDir;
using vision_test::write_file;

namespace {

double max_abs_diff(const cv::Mat& a, const cv::Mat& b) {
    BOOST_REQUIRE(a.size() == b.size());
    cv::Mat da, db;
    a.convertTo(da, CV_64F);
    b.convertTo(db, CV_64F);
    return cv::norm(da, db, cv::NORM_INF);
}

void check_equal(const v::StereoCalib& a, const v::StereoCalib& b, double tol) {
    BOOST_TEST(a.size == b.size);
    BOOST_TEST(max_abs_diff(a.K1, b.K1) <= tol);
    BOOST_TEST(max_abs_diff(a.D1.reshape(1, 1), b.D1.reshape(1, 1)) <= tol);
    BOOST_TEST(max_abs_diff(a.K2, b.K2) <= tol);
    BOOST_TEST(max_abs_diff(a.D2.reshape(1, 1), b.D2.reshape(1, 1)) <= tol);
    BOOST_TEST(max_abs_diff(a.R, b.R) <= tol);
    BOOST_TEST(max_abs_diff(a.T.reshape(1, 3), b.T.reshape(1, 3)) <= tol);
}

// A YAML calibration written by hand, one line per key; `over` replaces the
// text of a key ("" drops the key).
std::string yaml(const std::map<std::string, std::string>& over = {}) {
    const std::map<std::string, std::string> base = {
        {"K1", "[[200, 0, 80], [0, 200, 60], [0, 0, 1]]"},
        {"D1", "[-0.05, 0.01, 0.001, -0.001, 0]"},
        {"K2", "[[200, 0, 79], [0, 200, 61], [0, 0, 1]]"},
        {"D2", "[-0.04, 0.008, 0, 0]"},
        {"R", "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"},
        {"T", "[-0.1, 0.001, 0.002]"},
        {"image_width", "160"},
        {"image_height", "120"}};
    std::map<std::string, std::string> m = base;
    for (const auto& [k, t] : over) m[k] = t;
    std::string s = "%YAML:1.0\n";
    for (const auto& [k, t] : m)
        if (!t.empty()) s += k + ": " + t + "\n";
    return s;
}

// Loads `text` from a file and returns the InputError message (none: "").
std::string load_error(const TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = dir.file(name);
    write_file(path, text);
    try {
        v::load_stereo_calib(path);
    } catch (const v::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

BOOST_AUTO_TEST_CASE(write_and_read_back_yaml_xml_json) {
    const TempDir dir("calib_rt");
    const v::StereoCalib c = v::make_synth_calib(cv::Size(320, 240));
    for (const char* name : {"c.yml", "c.yaml", "c.xml", "c.json", "C.YML"}) {
        BOOST_TEST_CONTEXT(name) {
            v::write_stereo_calib(dir.file(name), c);
            const v::StereoCalib r = v::load_stereo_calib(dir.file(name));
            check_equal(c, r, 1e-15);  // doubles are written with 17 significant digits
            BOOST_TEST(r.K1.type() == CV_64FC1);
            BOOST_TEST(r.T.rows == 3);
            BOOST_TEST(r.T.cols == 1);
        }
    }
    BOOST_TEST(vision_test::count_entries(dir.path()) == 5);  // no temporaries left
}

BOOST_AUTO_TEST_CASE(hand_written_files_with_aliases_and_shapes) {
    const TempDir dir("calib_alias");
    // OpenCV matrices, M1/M2 and dist_* aliases, Nx1 distortion, 1x3 T, image_size.
    const std::string text =
        "%YAML:1.0\n"
        "M1: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: f\n  data: [200, 0, 80, 0, 200, 60, 0, "
        "0, 1]\n"
        "dist_left: !!opencv-matrix\n  rows: 4\n  cols: 1\n  dt: d\n  data: [-0.05, 0.01, 0, 0]\n"
        "camera_matrix_right: [[201, 0, 79], [0, 201, 61], [0, 0, 1]]\n"
        "dist_right: [0, 0, 0, 0, 0, 0, 0, 0]\n"
        "R: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
        "T: !!opencv-matrix\n  rows: 1\n  cols: 3\n  dt: d\n  data: [-0.12, 0, 0]\n"
        "image_size: [160, 120]\n";
    write_file(dir.file("a.yml"), text);
    const v::StereoCalib c = v::load_stereo_calib(dir.file("a.yml"));
    BOOST_TEST(c.size == cv::Size(160, 120));
    BOOST_TEST(c.K1.at<double>(0, 2) == 80.0);
    BOOST_TEST(c.K2.at<double>(0, 0) == 201.0);
    BOOST_TEST(c.D1.total() == 4u);
    BOOST_TEST(c.D2.total() == 8u);
    BOOST_TEST(c.T.at<double>(0) == -0.12);

    // No "%YAML" first line (OpenCV needs it; the loader adds it), image_size as a matrix.
    write_file(
        dir.file("b.yaml"),
        yaml({{"image_width", ""},
              {"image_height", ""},
              {"image_size", "!!opencv-matrix\n  rows: 2\n  cols: 1\n  dt: i\n  data: [640, 480]"}})
            .substr(10));
    BOOST_TEST(v::load_stereo_calib(dir.file("b.yaml")).size == cv::Size(640, 480));
}

BOOST_AUTO_TEST_CASE(malformed_files_name_the_problem_on_one_line) {
    const TempDir dir("calib_bad");
    struct Case {
        std::string name, text;
        std::vector<std::string> expect;  // substrings of the message
    };
    const std::vector<Case> cases = {
        {"missing_k1.yml",
         yaml({{"K1", ""}}),
         {"missing key 'K1'", "also accepted: M1, camera_matrix_left"}},
        {"k1_2x3.yml",
         yaml({{"K1", "[[200, 0, 80], [0, 200, 60]]"}}),
         {"key 'K1': expected a 3x3 matrix, got 2x3"}},
        {"k1_opencv_2x3.yml",
         yaml({{"K1", "!!opencv-matrix\n  rows: 2\n  cols: 3\n  dt: d\n  data: [1,0,0,0,1,0]"}}),
         {"key 'K1': expected a 3x3 matrix, got 2x3"}},
        {"k1_short_data.yml",
         yaml({{"K1", "!!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: [1,0,0]"}}),
         {"key 'K1': malformed matrix (3x3 with 3 data values)"}},
        {"k1_huge.yml",
         yaml({{"K1", "!!opencv-matrix\n  rows: 100000\n  cols: 100000\n  dt: d\n  data: [1]"}}),
         {"key 'K1'", "100000x100000"}},
        {"k2_negative_f.yml",
         yaml({{"K2", "[[-200, 0, 80], [0, 200, 60], [0, 0, 1]]"}}),
         {"key 'K2': focal length fx = -200 must be > 0"}},
        {"k2_text.yml", yaml({{"K2", "hello"}}), {"key 'K2': expected a matrix"}},
        {"d1_nan.yml", yaml({{"D1", "[-0.05, 0.01, .nan, 0]"}}), {"key 'D1': value NaN at (0,2)"}},
        {"d2_three.yml",
         yaml({{"D2", "[0, 0, 0]"}}),
         {"key 'D2': expected 4, 5, 8, 12 or 14 distortion coefficients", "got 1x3"}},
        {"r_scaled.yml",
         yaml({{"R", "[[1.1, 0, 0], [0, 1.1, 0], [0, 0, 1.1]]"}}),
         {"key 'R': not a rotation matrix", "R^T R - I"}},
        {"r_reflection.yml",
         yaml({{"R", "[[-1, 0, 0], [0, 1, 0], [0, 0, 1]]"}}),
         {"key 'R': not a rotation matrix (det(R) = -1"}},
        {"t_zero.yml", yaml({{"T", "[0, 0, 0]"}}), {"key 'T': zero baseline"}},
        {"t_inf.yml", yaml({{"T", "[-.inf, 0, 0]"}}), {"key 'T': value -inf at (0,0)"}},
        {"t_four.yml", yaml({{"T", "[-0.1, 0, 0, 1]"}}), {"key 'T': expected a 3x1 or 1x3"}},
        {"no_size.yml",
         yaml({{"image_width", ""}, {"image_height", ""}}),
         {"missing image size", "image_size", "image_width", "image_height"}},
        {"no_height.yml", yaml({{"image_height", ""}}), {"missing key 'image_height'"}},
        {"size_zero.yml",
         yaml({{"image_width", "0"}}),
         {"keys 'image_width' and 'image_height': image size 0x120: expected integers in "
          "1..16384"}},
        {"size_big.yml",
         yaml({{"image_width", ""}, {"image_height", ""}, {"image_size", "[20000, 10]"}}),
         {"key 'image_size'", "1..16384"}},
        {"size_fraction.yml", yaml({{"image_height", "12.5"}}), {"image_height", "integers"}},
        {"garbage.yml",
         "this is not a calibration file at all\n",
         {"not a calibration file (cannot parse: line 1: "}},
        {"garbage2.yml", "}{][::: -- ]]\n", {"not a calibration file"}},
        {"binary.yml", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), {"not a calibration"}},
        {"empty.yml", "", {"empty file"}},
        {"blank.yml", "  \n\n", {"empty file"}},
        {"header_only.yml", "%YAML:1.0\n", {"not a calibration file"}},
        {"list.json", "[1, 2, 3]\n", {"not a calibration file"}},
        {"broken.xml",
         "<?xml version=\"1.0\"?>\n<opencv_storage>\n<K1 type_id=\"",
         {"not a calibration file (cannot parse: line 3: "}},
        {"garbage_line.yml", "\n\nK1: [1, 2\n  ]]]\n", {"cannot parse: line 4: "}},
        // Inputs that crash OpenCV 4.6's own parsers (std::terminate, null
        // pointer): the loader must refuse them before OpenCV sees them.
        {"opencv_crash_empty_key.yml",
         "%YAML:1.0\nK1:\n   rows: 3\n   : 3\n",
         {"cannot parse: line 4: empty key"}},
        {"opencv_crash_empty_key2.yml", "R: {a: 1, : 2}\n", {"line 1: empty key"}},
        {"opencv_crash_attribute.xml",
         "<?xml version=\"1.0\"?>\n<opencv_storage>\n<K1 type_id=",
         {"cannot parse: file ends inside a tag"}},
        {"other.json", "{\"a\": 1}\n", {"missing key 'K1'"}},
    };
    for (const Case& c : cases) {
        BOOST_TEST_CONTEXT(c.name) {
            const std::string msg = load_error(dir, c.name, c.text);
            BOOST_TEST_MESSAGE(msg);
            BOOST_TEST(!msg.empty());
            BOOST_TEST(msg.find("calibration '" + dir.file(c.name) + "': ") == 0u);
            BOOST_TEST(msg.find('\n') == std::string::npos);
            for (const std::string& e : c.expect) BOOST_TEST(msg.find(e) != std::string::npos, e);
        }
    }
    // The unmodified template loads (so the cases above fail for their own reason).
    BOOST_TEST(load_error(dir, "good.yml", yaml()).empty());

    const std::string missing = dir.file("nope.yml");
    BOOST_CHECK_EXCEPTION(v::load_stereo_calib(missing), v::InputError,
                          [&](const v::InputError& e) {
                              return std::string(e.what()) ==
                                     "calibration '" + missing + "': cannot read (no such file)";
                          });
    BOOST_CHECK_EXCEPTION(
        v::load_stereo_calib(dir.path().string()), v::InputError, [](const v::InputError& e) {
            return std::string(e.what()).find("is a directory") != std::string::npos;
        });
}

// Truncated, edited and byte-flipped versions of valid files: every one
// either loads or gives a one-line InputError; no other exception, no crash.
// (This is how the two OpenCV parser crashes refused above were found; 40000
// such inputs per format ran clean in a separate harness.)
BOOST_AUTO_TEST_CASE(damaged_files_never_crash) {
    const TempDir dir("calib_fuzz");
    const v::StereoCalib c = v::make_synth_calib(cv::Size(64, 48));
    uint64_t s = 12345;
    auto rnd = [&s]() {  // xorshift64
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        return s;
    };
    int loaded = 0, rejected = 0;
    for (const char* name : {"f.yml", "f.xml", "f.json"}) {
        v::write_stereo_calib(dir.file(name), c);
        const std::string good = vision_test::read_file(dir.file(name));
        for (int k = 0; k < 300; ++k) {
            std::string t = good;
            if (k % 3 == 0) {
                t.resize(rnd() % t.size());
            } else if (k % 3 == 1) {  // insert and delete characters
                const int ops = 1 + static_cast<int>(rnd() % 6);
                for (int o = 0; o < ops && !t.empty(); ++o) {
                    const size_t p = rnd() % t.size();
                    if (rnd() % 2 != 0)
                        t.erase(p, 1 + rnd() % 8);
                    else
                        t.insert(p, 1, "<>/=\"' \n:"[rnd() % 9]);
                }
            } else {
                const int flips = 1 + static_cast<int>(rnd() % 4);
                for (int f = 0; f < flips; ++f) {
                    const char pool[] = "{}[]<>:,\"'-.0123456789eE \n\t!%/?=xnan";
                    t[rnd() % t.size()] = pool[rnd() % (sizeof pool - 1)];
                }
            }
            const std::string path = dir.file(std::string("m_") + name);
            write_file(path, t);
            try {
                v::load_stereo_calib(path);
                ++loaded;
            } catch (const v::InputError& e) {
                ++rejected;
                BOOST_TEST(std::string(e.what()).find('\n') == std::string::npos, e.what());
            }
        }
    }
    BOOST_TEST_MESSAGE("damaged files: " << loaded << " loaded, " << rejected << " rejected");
    BOOST_TEST(rejected > 300);
}

BOOST_AUTO_TEST_CASE(write_refuses_bad_names_and_invalid_calibrations) {
    const TempDir dir("calib_write");
    const v::StereoCalib c = v::make_synth_calib(cv::Size(64, 48));
    BOOST_CHECK_THROW(v::write_stereo_calib(dir.file("c.txt"), c), v::InputError);
    BOOST_CHECK_THROW(v::write_stereo_calib(dir.file("c"), c), v::InputError);
    v::StereoCalib bad = c;
    bad.R = c.R * 2;
    BOOST_CHECK_THROW(v::write_stereo_calib(dir.file("c.yml"), bad), v::InputError);
    BOOST_CHECK_THROW(v::write_stereo_calib(dir.file("missing/c.yml"), c), v::InputError);
    BOOST_TEST(vision_test::count_entries(dir.path()) == 0);
}

BOOST_AUTO_TEST_CASE(rectifier_checks_frames_and_baseline) {
    const v::StereoCalib c = v::make_synth_calib(cv::Size(64, 48));
    const v::Rectifier r(c);
    BOOST_TEST(r.size() == cv::Size(64, 48));
    cv::Mat a(48, 64, CV_8UC1, cv::Scalar(100)), b(40, 64, CV_8UC1, cv::Scalar(100)), l, rr;
    BOOST_CHECK_EXCEPTION(r.rectify(a, b, &l, &rr), v::InputError, [](const v::InputError& e) {
        const std::string m = e.what();
        return m.find("right") != std::string::npos && m.find("64x40") != std::string::npos &&
               m.find("64x48") != std::string::npos;
    });
    cv::Mat colour(48, 64, CV_8UC3);
    BOOST_CHECK_THROW(r.rectify(colour, a, &l, &rr), v::InputError);
    r.rectify(a, a, &l, &rr);
    BOOST_TEST(l.type() == CV_8UC1);
    BOOST_TEST(l.size() == a.size());
    r.rectify(a, a, &a, &a);  // outputs may alias the inputs
    BOOST_TEST(a.size() == cv::Size(64, 48));

    v::StereoCalib swapped = c;
    swapped.T = -c.T;  // right camera to the left of the left one
    BOOST_CHECK_THROW(v::Rectifier{swapped}, v::InputError);
    v::StereoCalib vertical = c;
    vertical.T = (cv::Mat_<double>(3, 1) << 0.001, -0.1, 0);
    BOOST_CHECK_THROW(v::Rectifier{vertical}, v::InputError);
}

// Independent of the images: a 3-D point seen by both raw cameras (projected
// with the calibration's own model, cv::projectPoints) lands on the same
// rectified row in both views, with disparity f * |T| / Z (0 at infinity),
// (Z along the rectified optical axis), which is what CALIB_ZERO_DISPARITY
// rectification promises.
BOOST_AUTO_TEST_CASE(synthetic_calibration_rectifies_to_row_aligned_views) {
    const cv::Size size(320, 240);
    const v::StereoCalib c = v::make_synth_calib(size);
    const v::Rectifier r(c);
    const double f = r.P1().at<double>(0, 0), baseline = cv::norm(c.T);
    BOOST_TEST(std::abs(r.P2().at<double>(0, 3) + f * baseline) < 1e-9 * f);
    std::vector<cv::Point3d> world;
    for (double z : {0.5, 1.0, 3.0, 1e6})
        for (double x : {-0.15, 0.0, 0.15})
            for (double y : {-0.1, 0.0, 0.1}) world.emplace_back(x * z, y * z, z);
    std::vector<cv::Point2d> raw_l, raw_r, rect_l, rect_r;
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    cv::Mat rv;
    cv::Rodrigues(c.R, rv);
    cv::projectPoints(world, zero, zero, c.K1, c.D1, raw_l);
    cv::projectPoints(world, rv, c.T, c.K2, c.D2, raw_r);
    const cv::TermCriteria tc(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-10);
    cv::undistortPoints(raw_l, rect_l, c.K1, c.D1, r.R1(), r.P1(), tc);
    cv::undistortPoints(raw_r, rect_r, c.K2, c.D2, r.R2(), r.P2(), tc);
    for (size_t i = 0; i < world.size(); ++i) {
        BOOST_TEST_CONTEXT("point " << world[i]) {
            BOOST_TEST(std::abs(rect_l[i].y - rect_r[i].y) < 1e-3);
            // Depth along the rectified cameras' common optical axis.
            const cv::Mat xr = r.R1() * cv::Mat(cv::Vec3d(world[i].x, world[i].y, world[i].z));
            const double disp = rect_l[i].x - rect_r[i].x;
            BOOST_TEST(std::abs(disp - f * baseline / xr.at<double>(2)) < 1e-3);
        }
    }
}

// rectify(unrectify(x)) reproduces x away from the border band that the raw
// view does not cover. On a linear ramp, bilinear interpolation is exact, so
// only the 8-bit rounding of the two resamplings (<= 0.5 each) and OpenCV's
// 1/32-pixel map quantisation remain: a mean error <= 0.6 grey levels, while
// any geometric error of half a pixel or more would add >= 0.5 * slope
// (measured: 0.016 left, 0.066 right). On the textured sequence frames each
// resampling is a bilinear blur at a varying sub-pixel offset of texture that
// has pixel-scale detail (+-40 grey levels from pixel to pixel), and the
// rectified view is slightly magnified, so detail is lost: measured mean
// |diff| 8.3-8.4 grey levels (docs/calibration.md); bound 10.
BOOST_AUTO_TEST_CASE(rectify_undoes_unrectify) {
    const cv::Size size(160, 120);
    const v::Rectifier r(v::make_synth_calib(size));
    // Left ramp rising to the right, right ramp rising downwards.
    cv::Mat ramp_x(size, CV_8UC1), ramp_y(size, CV_8UC1);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            ramp_x.at<uint8_t>(y, x) = static_cast<uint8_t>(40 + x + y / 4);
            ramp_y.at<uint8_t>(y, x) = static_cast<uint8_t>(30 + 1.5 * y + x / 8);
        }
    cv::Mat raw_l, raw_r, back_l, back_r;
    v::unrectify(r, ramp_x, ramp_y, &raw_l, &raw_r);
    BOOST_TEST(cv::countNonZero(raw_l != ramp_x) > size.area() / 2);  // it did warp
    r.rectify(raw_l, raw_r, &back_l, &back_r);

    // Interior: the pixels whose round trip saw no uncovered (zero) raw pixel.
    cv::Mat white(size, CV_8UC1, cv::Scalar(255)), wl, wr, cl, cr;
    v::unrectify(r, white, white, &wl, &wr);
    r.rectify(wl, wr, &cl, &cr);
    const cv::Mat inner_l = cl == 255, inner_r = cr == 255;
    const int band = size.area() - cv::countNonZero(inner_l);
    BOOST_TEST_MESSAGE("left pixels outside the round-trip interior: " << band);
    BOOST_TEST(band < size.area() / 20);  // a thin border band only

    auto mean_err = [](const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
        cv::Mat d;
        cv::absdiff(a, b, d);
        return cv::mean(d, mask)[0];
    };
    const double el = mean_err(back_l, ramp_x, inner_l), er = mean_err(back_r, ramp_y, inner_r);
    BOOST_TEST_MESSAGE("ramp round trip: mean |diff| left " << el << ", right " << er);
    BOOST_TEST(el <= 0.6);
    BOOST_TEST(er <= 0.6);
    // The same check sees a one-pixel shift.
    cv::Mat shifted;
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 1, 0, 1, 0);
    cv::warpAffine(ramp_x, shifted, shift, size, cv::INTER_NEAREST, cv::BORDER_REPLICATE);
    BOOST_TEST(mean_err(back_l, shifted, inner_l) > 0.8);

    // Textured frames.
    for (int k : {0, 7}) {
        const v::SequenceFrame f = v::make_sequence_frame(3, size.width, size.height, k, 8);
        v::unrectify(r, f.left, f.right, &raw_l, &raw_r);
        r.rectify(raw_l, raw_r, &back_l, &back_r);
        const double tl = mean_err(back_l, f.left, inner_l),
                     tr = mean_err(back_r, f.right, inner_r);
        BOOST_TEST_MESSAGE("texture round trip frame " << k << ": mean |diff| left " << tl
                                                       << ", right " << tr);
        BOOST_TEST(tl <= 10.0);
        BOOST_TEST(tr <= 10.0);
    }
}
