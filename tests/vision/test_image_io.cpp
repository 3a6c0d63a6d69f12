// load_grey8 conversions and rejections; atomic writes that never clobber the
// target or leave temporaries behind.
#define BOOST_TEST_MODULE vision_image_io
#include <boost/test/unit_test.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "imap/vision/image_io.hpp"
#include "test_helpers.hpp"

namespace v = imap::vision;
using vision_test::TempDir;

namespace {

// Runs f, which must throw InputError; returns its message.
template <class F>
std::string input_error(F&& f) {
    try {
        f();
    } catch (const v::InputError& e) {
        return e.what();
    }
    BOOST_FAIL("no InputError thrown");
    return {};
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_CASE(grey_image_is_returned_unchanged) {
    TempDir t("io");
    cv::Mat g(7, 9, CV_8UC1);
    for (int y = 0; y < g.rows; ++y)
        for (int x = 0; x < g.cols; ++x) g.at<uint8_t>(y, x) = static_cast<uint8_t>(y * 30 + x);
    BOOST_REQUIRE(cv::imwrite(t.file("g.png"), g));
    const cv::Mat r = v::load_grey8(t.file("g.png"), "left image");
    BOOST_TEST(r.type() == CV_8UC1);
    BOOST_TEST(cv::countNonZero(r != g) == 0);
}

BOOST_AUTO_TEST_CASE(colour_is_converted_to_grey) {
    TempDir t("io");
    cv::Mat c(4, 5, CV_8UC3, cv::Scalar(77, 77, 77));  // grey stays exact
    c.at<cv::Vec3b>(1, 2) = cv::Vec3b(10, 200, 30);    // BGR
    BOOST_REQUIRE(cv::imwrite(t.file("c.png"), c));
    const cv::Mat r = v::load_grey8(t.file("c.png"), "left image");
    BOOST_TEST(r.type() == CV_8UC1);
    BOOST_TEST(r.rows == 4);
    BOOST_TEST(r.cols == 5);
    BOOST_TEST(int(r.at<uint8_t>(0, 0)) == 77);
    cv::Mat want;
    cv::cvtColor(c, want, cv::COLOR_BGR2GRAY);
    BOOST_TEST(int(r.at<uint8_t>(1, 2)) == int(want.at<uint8_t>(1, 2)));
    BOOST_TEST(int(r.at<uint8_t>(1, 2)) > 100);  // mostly green

    cv::Mat a(3, 3, CV_8UC4, cv::Scalar(50, 50, 50, 128));  // alpha ignored
    BOOST_REQUIRE(cv::imwrite(t.file("a.png"), a));
    const cv::Mat ra = v::load_grey8(t.file("a.png"), "right image");
    BOOST_TEST(ra.type() == CV_8UC1);
    BOOST_TEST(int(ra.at<uint8_t>(2, 2)) == 50);
}

BOOST_AUTO_TEST_CASE(sixteen_bit_and_float_are_rejected) {
    TempDir t("io");
    cv::Mat w(4, 4, CV_16UC1, cv::Scalar(1000));
    BOOST_REQUIRE(cv::imwrite(t.file("w.png"), w));
    const std::string msg = input_error([&] { v::load_grey8(t.file("w.png"), "left image"); });
    BOOST_TEST(msg == "left image '" + t.file("w.png") +
                          "': 16-bit images are not supported (need 8-bit grey or colour)");

    cv::Mat f(4, 4, CV_32FC1, cv::Scalar(0.5));
    BOOST_TEST_REQUIRE(cv::imwrite(t.file("f.tiff"), f));
    {
        const std::string fm = input_error([&] { v::load_grey8(t.file("f.tiff"), "gt"); });
        BOOST_TEST(contains(fm, "floating-point"));
        BOOST_TEST(contains(fm, "f.tiff"));
    }
}

BOOST_AUTO_TEST_CASE(file_only_formats_are_refused_without_temporary_files) {
    // OpenCV decodes PFM, Radiance HDR and OpenEXR from a file only: imdecode
    // writes the bytes to OPENCV_TEMP_PATH and leaves the file there when the
    // decoder throws (here: a PFM header past its size limits). The loader
    // refuses these float formats before decoding: nothing is left behind.
    TempDir t("io");
    TempDir ocv("ocvtmp");
    const std::string dir = ocv.path().string() + "/";
    BOOST_REQUIRE(::setenv("OPENCV_TEMP_PATH", dir.c_str(), 1) == 0);
    const struct {
        const char* name;
        std::string bytes;
        const char* format;
    } cases[] = {
        {"huge.pfm", "Pf\n99999999 99999999\n-1\n" + std::string(64, '\0'), "PFM"},
        {"small.pfm", "Pf\n2 2\n-1\n" + std::string(16, '\0'), "PFM"},
        {"colour.pfm", "PF\n1 1\n-1\n" + std::string(12, '\0'), "PFM"},
        {"sky.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n" + std::string(4, '\0'),
         "Radiance HDR"},
        {"scene.exr", std::string("\x76\x2f\x31\x01", 4) + std::string(32, '\0'), "OpenEXR"},
    };
    for (const auto& c : cases) {
        vision_test::write_file(t.file(c.name), c.bytes);
        const std::string msg = input_error([&] { v::load_grey8(t.file(c.name), "gt"); });
        BOOST_TEST_CONTEXT(c.name << ": " << msg) {
            BOOST_TEST(contains(msg, c.format));
            BOOST_TEST(contains(msg, "use PNG"));
        }
    }
    size_t left = 0;
    for (const auto& e : std::filesystem::directory_iterator(ocv.path())) {
        BOOST_TEST_MESSAGE("left behind: " << e.path());
        ++left;
    }
    ::unsetenv("OPENCV_TEMP_PATH");
    BOOST_TEST(left == 0u);
}

BOOST_AUTO_TEST_CASE(missing_garbage_empty_and_folders_are_rejected) {
    TempDir t("io");
    // Each message says which it is: missing, unreadable or not an image.
    BOOST_TEST(input_error([&] { v::load_grey8(t.file("nope.png"), "left image"); }) ==
               "left image '" + t.file("nope.png") + "': cannot read (no such file)");

    vision_test::write_file(t.file("garbage.png"), "this is not a PNG file at all\n");
    BOOST_TEST(input_error([&] { v::load_grey8(t.file("garbage.png"), "right image"); }) ==
               "right image '" + t.file("garbage.png") +
                   "': cannot read (not an image: no decoder accepts it; use PNG)");
    if (::geteuid() != 0) {  // root reads a file without read permission
        vision_test::write_file(t.file("locked.png"), "x");
        std::filesystem::permissions(t.file("locked.png"), std::filesystem::perms::none);
        const std::string l = input_error([&] { v::load_grey8(t.file("locked.png"), "mask"); });
        BOOST_TEST(contains(l, "cannot read (Permission denied; check its permissions)"), l);
    }

    // A truncated PNG: one clear message (and nothing from libpng on stderr).
    cv::Mat g(16, 16, CV_8UC1, cv::Scalar(9));
    BOOST_REQUIRE(cv::imwrite(t.file("full.png"), g));
    const std::string full = vision_test::read_file(t.file("full.png"));
    for (size_t cut : {size_t{12}, full.size() / 2, full.size() - 1}) {
        vision_test::write_file(t.file("trunc.png"), full.substr(0, cut));
        BOOST_TEST(input_error([&] { v::load_grey8(t.file("trunc.png"), "left image"); }) ==
                   "left image '" + t.file("trunc.png") +
                       "': cannot read (corrupt or truncated PNG)");
    }

    vision_test::write_file(t.file("zero.png"), "");
    const std::string z = input_error([&] { v::load_grey8(t.file("zero.png"), "left image"); });
    BOOST_TEST(contains(z, "left image '" + t.file("zero.png") + "': cannot read"));
    BOOST_TEST(contains(z, "empty file"));

    const std::string d = input_error([&] { v::load_grey8(t.path().string(), "left image"); });
    BOOST_TEST(contains(d, "is a directory"));

    // One line each.
    BOOST_TEST(!contains(z, "\n"));
    BOOST_TEST(!contains(d, "\n"));
}

BOOST_AUTO_TEST_CASE(palette_masks_read_as_grey) {
    // tsukuba/nonocc.png is a 1-bit palette PNG, all.png a palette PNG with an
    // iCCP chunk: palette indices must come out as their grey values.
    const std::string dir = std::string(IMAP_SHARED_DATA) + "/middlebury/tsukuba/";
    for (const char* name : {"nonocc.png", "all.png"}) {
        const cv::Mat m = v::load_grey8(dir + name, "mask");
        BOOST_TEST(m.type() == CV_8UC1);
        BOOST_TEST(cv::countNonZero((m != 0) & (m != 255)) == 0);
        BOOST_TEST(cv::countNonZero(m == 255) > 80000);
    }
}

BOOST_AUTO_TEST_CASE(view_of_matches_the_matrix) {
    cv::Mat big(10, 20, CV_8UC1, cv::Scalar(3));
    const cv::Mat sub = big(cv::Rect(2, 3, 5, 4));
    const auto vw = v::view_of(sub);
    BOOST_TEST(vw.width == 5);
    BOOST_TEST(vw.height == 4);
    BOOST_TEST(vw.stride == 20);
    BOOST_TEST(vw.row(1) == sub.ptr<uint8_t>(1));
    BOOST_CHECK_THROW(v::view_of(cv::Mat(2, 2, CV_8UC3)), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(write_image_atomic_writes_and_replaces) {
    TempDir t("io");
    cv::Mat a(6, 8, CV_8UC1, cv::Scalar(10)), b(6, 8, CV_8UC1, cv::Scalar(200));
    v::write_image_atomic(t.file("out.png"), a);
    v::write_image_atomic(t.file("out.png"), b);  // replaces
    const cv::Mat r = v::load_grey8(t.file("out.png"), "out");
    BOOST_TEST(cv::countNonZero(r != b) == 0);
    BOOST_TEST(vision_test::count_entries(t.path()) == 1);  // no temporaries left
}

BOOST_AUTO_TEST_CASE(failed_image_write_leaves_target_untouched) {
    TempDir t("io");
    const cv::Mat img(6, 8, CV_8UC1, cv::Scalar(10));

    // Unsupported extension: the existing file keeps its bytes.
    vision_test::write_file(t.file("out.xyz"), "OLD");
    const std::string m1 = input_error([&] { v::write_image_atomic(t.file("out.xyz"), img); });
    BOOST_TEST(contains(m1, t.file("out.xyz")));
    BOOST_TEST(vision_test::read_file(t.file("out.xyz")) == "OLD");
    BOOST_TEST(
        contains(input_error([&] { v::write_image_atomic(t.file("noext"), img); }), "noext"));

    // The temporary cannot be created (a folder is in its way): the existing
    // target keeps its bytes, the obstacle is not removed.
    vision_test::write_file(t.file("keep.png"), "OLD PNG");
    const std::string tmp = t.file(".keep.tmp-" + std::to_string(::getpid()) + ".png");
    std::filesystem::create_directory(tmp);
    const std::string m2 = input_error([&] { v::write_image_atomic(t.file("keep.png"), img); });
    BOOST_TEST(contains(m2, t.file("keep.png")));
    BOOST_TEST(contains(m2, "cannot write"));
    BOOST_TEST(vision_test::read_file(t.file("keep.png")) == "OLD PNG");
    BOOST_TEST(std::filesystem::is_directory(tmp));
    std::filesystem::remove(tmp);

    // Empty image.
    input_error([&] { v::write_image_atomic(t.file("keep.png"), cv::Mat()); });
    BOOST_TEST(vision_test::read_file(t.file("keep.png")) == "OLD PNG");

    // Target is a folder; parent is a file; parent does not exist.
    std::filesystem::create_directory(t.file("dir.png"));
    BOOST_TEST(
        contains(input_error([&] { v::write_image_atomic(t.file("dir.png"), img); }), "dir.png"));
    BOOST_TEST(std::filesystem::is_directory(t.file("dir.png")));
    BOOST_TEST(contains(
        input_error([&] { v::write_image_atomic(t.file("out.xyz") + "/x.png", img); }), "x.png"));
    BOOST_TEST(contains(
        input_error([&] { v::write_image_atomic(t.file("no/such/dir/x.png"), img); }), "x.png"));

    // Nothing but the files made above: no temporaries anywhere.
    BOOST_TEST(vision_test::count_entries(t.path()) == 3);  // out.xyz, keep.png, dir.png
}

BOOST_AUTO_TEST_CASE(write_text_atomic_writes_or_leaves_nothing) {
    TempDir t("io");
    v::write_text_atomic(t.file("a.json"), "[1]\n");
    v::write_text_atomic(t.file("a.json"), "[2]\n");
    BOOST_TEST(vision_test::read_file(t.file("a.json")) == "[2]\n");
    const std::string m = input_error([&] { v::write_text_atomic(t.file("x/a.json"), "[3]"); });
    BOOST_TEST(contains(m, t.file("x/a.json")));
    BOOST_TEST(vision_test::read_file(t.file("a.json")) == "[2]\n");
    BOOST_TEST(vision_test::count_entries(t.path()) == 1);
}
