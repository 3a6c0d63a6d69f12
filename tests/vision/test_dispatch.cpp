// OpenCV picks SIMD kernels by CPU at run time (SSE4.1 ... AVX-512). The
// vision.*.baseline tests re-run the OpenCV-dependent suites with every
// dispatched feature switched off (OPENCV_CPU_DISABLE, the names OpenCV 4.6
// knows), as on an older CPU; this test checks that the switch took effect,
// since OpenCV only warns about a name it does not know and runs on.
#define BOOST_TEST_MODULE vision_dispatch
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <string>

BOOST_AUTO_TEST_CASE(dispatched_features_are_off_when_disabled) {
    const char* env = std::getenv("OPENCV_CPU_DISABLE");
    BOOST_TEST_MESSAGE("OpenCV CPU features: " << cv::getCPUFeaturesLine()
                                               << "; OPENCV_CPU_DISABLE="
                                               << (env ? env : "(unset)"));
    if (!env) return;  // the plain run: nothing to check
    const std::string e(env);
    const std::pair<const char*, int> features[] = {{"AVX512-SKX", CV_CPU_AVX512_SKX},
                                                    {"AVX2", CV_CPU_AVX2},
                                                    {"AVX", CV_CPU_AVX},
                                                    {"FP16", CV_CPU_FP16},
                                                    {"SSE4.2", CV_CPU_SSE4_2},
                                                    {"SSE4.1", CV_CPU_SSE4_1}};
    // Every name given must be one of OpenCV's, and switched off.
    size_t at = 0;
    while (at <= e.size()) {
        const size_t comma = e.find(',', at);
        const std::string name =
            e.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        bool known = false;
        for (const auto& [n, id] : features)
            if (name == n) {
                known = true;
                BOOST_TEST(!cv::checkHardwareSupport(id), name << " is still on");
            }
        BOOST_TEST(known, "'" << name << "' is not a feature name of OpenCV 4.6 (it stays on)");
        if (comma == std::string::npos) break;
        at = comma + 1;
    }
}
