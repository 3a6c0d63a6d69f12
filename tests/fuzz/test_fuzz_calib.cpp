// Fuzzing the stereo calibration loader (docs/testing.md): mutants of
// corpus/calib/*.yml|xml must load as a valid calibration or fail with
// InputError.
#define BOOST_TEST_MODULE fuzz_calib
#include "fuzz_test.hpp"
#include "fuzz_vision.hpp"
#include "imap/vision/calib.hpp"

using namespace imap::fuzz;

BOOST_AUTO_TEST_CASE(seeds_are_valid_calibrations) {
    const std::vector<Bytes> s = seeds("calib");
    BOOST_REQUIRE_GE(s.size(), 4u);
    for (const Bytes& b : s) {
        const Result r = check_calib(b);
        BOOST_CHECK_MESSAGE(r.outcome.rfind("loaded", 0) == 0, r.outcome);
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
    }
}

// Found by this fuzzer: OpenCV 4.6's YAML parser loops forever when, looking
// for a second document, it meets a "-" that does not start "---" (after a
// "..." end marker, or after a line indented less than the root map's first
// key). load_stereo_calib now refuses such texts before OpenCV parses them.
BOOST_AUTO_TEST_CASE(regressions) {
    const auto r = replay_regressions("calib", check_calib);
    BOOST_REQUIRE_GE(r.size(), 2u);
    for (const char* name :
         {"opencv_yaml_dash_after_document_end.yml", "opencv_yaml_dedent_dash.yml"}) {
        std::string what = "loaded";
        try {
            imap::vision::load_stereo_calib(fuzz_dir() + "/regressions/calib/" + name);
        } catch (const imap::vision::InputError& e) {
            what = e.what();
        }
        BOOST_CHECK_MESSAGE(what.find("(cannot parse: a second YAML document, or a line indented "
                                      "less than the first key)") != std::string::npos,
                            what);
    }
}

// Valid calibrations written by OpenCV itself (one document, "---" after the
// directive) still load after that check.
BOOST_AUTO_TEST_CASE(opencv_written_calibrations_still_load) {
    imap::vision::StereoCalib c;
    c.K1 = (cv::Mat_<double>(3, 3) << 100, 0, 32, 0, 100, 24, 0, 0, 1);
    c.K2 = c.K1.clone();
    c.D1 = cv::Mat::zeros(1, 5, CV_64F);
    c.D2 = c.D1.clone();
    c.R = cv::Mat::eye(3, 3, CV_64F);
    c.T = (cv::Mat_<double>(3, 1) << -0.1, 0, 0);
    c.size = cv::Size(64, 48);
    for (const char* ext : {".yml", ".xml", ".json"}) {
        const std::string path = work_dir() + "/fuzz-calib-written" + ext;
        cv::FileStorage fs(path, cv::FileStorage::WRITE);
        fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2 << "R" << c.R << "T"
           << c.T << "image_width" << c.size.width << "image_height" << c.size.height;
        fs.release();
        BOOST_CHECK_MESSAGE(check_calib(read_file(path)).outcome == "loaded, rectified", ext);
    }
}

BOOST_AUTO_TEST_CASE(fuzz) {
    run_campaign("calib", ".yml", seeds("calib"), mutate_calib, check_calib);
}
